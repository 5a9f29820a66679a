"""Writes the glTF texture test scenes and their Mitsuba 3 twins, built from the same data, into
crates/pathtrace-scene/tests/data/maps/ (plain Python, no dependencies):

- emissive.gltf + emissive.bin + emissive.png: a Lambertian floor (KHR_materials_specular
  specularFactor 0) lit only by a standing panel whose emission is emissiveTexture (a 4 × 4
  sRGB image, bilinear) × emissiveFactor × KHR_materials_emissive_strength; the camera sees
  the panel and the floor it lights. emissive.glb holds the same document with the buffer and the
  image in its binary chunk (the image in a buffer view), emissive_data.gltf the same with the
  buffer and the image as base64 `data:` URIs.
  Twin emissive.xml + emissive_floor.obj + emissive_panel.obj: the same triangles and uv, a
  `diffuse` floor, and an `area` emitter whose radiance is a `bitmap` of emissive_radiance.pfm,
  the image sRGB-decoded and multiplied by factor × strength here (Mitsuba's bitmap has no scale).
- metal_rough.gltf + metal_rough.bin + metal_rough.png: a metal floor (metallicFactor 1, base
  colour factor) whose roughness is the metallicRoughnessTexture's green channel (4 × 4, nearest,
  linear) × roughnessFactor, lit by a standing panel of constant emission.
  Twin metal_rough.xml: a `roughconductor` (`none` metal, GGX, specular_reflectance = the base
  colour: our mapping of glTF's metal, see crates/pathtrace-scene/src/gltf/material.rs) whose
  `alpha` is a nearest `bitmap` of metal_rough_alpha.pfm, α = (roughnessFactor · G)² per texel
  (with nearest lookups squaring per texel equals squaring after the lookup), and an `area`
  emitter of the panel's radiance.
- metallic.gltf + metallic.bin + metallic.png: the same floor, metallicFactor 0.9 and a
  metallicRoughnessTexture (4 × 4, nearest, linear) whose blue channel (metallic) varies per
  texel and whose green is metal_rough.png's roughness; KHR_materials_specular specularFactor 0,
  so glTF's dielectric is Lambertian. Our import: a `blend` of a `lambertian` and a
  `rough_conductor` weighted by 0.9 × blue.
  Twin metallic.xml: a `twosided` `blendbsdf` whose `weight` is a nearest `bitmap` of
  metallic_weight.pfm (0.9 × blue per texel), `bsdf_0` a `diffuse` and `bsdf_1` the
  metal_rough.xml `roughconductor` (α from metal_rough_alpha.pfm), both of the base colour.
- basecolor.gltf + basecolor.bin + basecolor.png: a Lambertian floor (specularFactor 0) whose
  base colour is baseColorTexture (a 4 × 4 sRGB RGBA image, bilinear) × a non-white
  baseColorFactor, alphaMode BLEND with opacity = baseColorFactor's alpha × the texture's alpha
  (glTF 2.0 §3.9.2), lit by the standing panel of constant emission.
  Twin basecolor.xml: a `mask` whose `opacity` is a `bitmap` of basecolor_alpha.pfm (factor ×
  alpha per texel) around a `diffuse` whose `reflectance` is a `bitmap` of basecolor_albedo.pfm
  (the texels sRGB-decoded and multiplied by the factor here: Mitsuba's bitmap has no scale;
  bilinear filtering is linear, so scaling the texels equals scaling the filtered value), with
  `volpath` and unlimited depth as cutout.xml (crates/pathtrace-scene/tests/gltf_base_colour.rs).

    python3 benches/peers/make_gltf_texture_assets.py
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(__file__))
from make_gltf_assets import YFOV, FLOOR_COLOUR, col_major, look_at, mitsuba_sensor, rgb, srgb_decode  # noqa: E402

OUT = os.path.join(os.path.dirname(__file__), "../../crates/pathtrace-scene/tests/data/maps")

FLOOR_P = [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]]
FLOOR_UV = [[(p[0] + 2) / 4, (p[2] + 2) / 4] for p in FLOOR_P]  # the whole image over the floor
FLOOR_I = [0, 2, 1, 0, 3, 2]  # faces +y
PANEL_P = [[-1.2, 0.1, 1.2], [1.2, 0.1, 1.2], [1.2, 1.5, 1.2], [-1.2, 1.5, 1.2]]
PANEL_UV = [[(p[0] + 1.2) / 2.4, (1.5 - p[1]) / 1.4] for p in PANEL_P]  # the image's top at the top
PANEL_I = [0, 2, 1, 0, 3, 2]  # faces −z, towards the camera
CAMERA = look_at([0.0, 1.6, -3.2], [0, 0.5, 0.8], [0, 1, 0])

# emissive.png, sRGB bytes, first row at the top.
EMISSIVE_SRGB = [
    [(255, 40, 40), (255, 200, 60), (60, 255, 60), (40, 120, 255)],
    [(255, 255, 255), (20, 20, 20), (200, 60, 255), (255, 140, 0)],
    [(0, 200, 200), (255, 255, 120), (90, 90, 90), (255, 0, 128)],
    [(128, 255, 0), (0, 0, 0), (255, 220, 200), (60, 60, 255)],
]
EMISSIVE_FACTOR, EMISSIVE_STRENGTH = [1.0, 0.8, 0.9], 6.0

# metal_rough.png: R unused (occlusion's channel), G roughness, B metallic (1).
ROUGHNESS = [[0.35, 0.5, 0.65, 0.8], [0.9, 0.4, 0.6, 0.45], [0.55, 0.75, 0.38, 0.85], [0.7, 0.42, 0.95, 0.5]]
ROUGHNESS_FACTOR = 0.9
METAL_COLOUR = [0.9, 0.7, 0.5]
PANEL_RADIANCE = 5.0


def png(rows, channels):
    """PNG bytes of `rows` (lists of byte values, first row at the top), 8-bit grey/RGB/RGBA."""
    height, width = len(rows), len(rows[0]) // channels
    colour = {1: 0, 3: 2, 4: 6}[channels]
    raw = b"".join(b"\0" + bytes(r) for r in rows)

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def write_pfm(path, rows):
    """A colour PFM of `rows` (lists of (r, g, b) floats, first row at the top): PFM stores the
    bottom row first, little-endian (negative scale)."""
    height, width = len(rows), len(rows[0])
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        for row in reversed(rows):
            for c in row:
                f.write(struct.pack("<3f", *c))


def write_obj(path, positions, uvs, indices):
    with open(path, "w") as f:
        for p in positions:
            f.write("v %.9g %.9g %.9g\n" % tuple(p))
        for t in uvs:
            f.write("vt %.9g %.9g\n" % tuple(t))
        for i in range(0, len(indices), 3):
            f.write("f %d/%d %d/%d %d/%d\n" % tuple(x + 1 for j in indices[i:i + 3] for x in (j, j)))


def geometry():
    """The buffer (floor and panel positions and uvs, then their u16 indices), its views and
    accessors 0-5: floor POSITION, TEXCOORD_0, indices, panel POSITION, TEXCOORD_0, indices."""
    data, views, accessors = b"", [], []
    bounds = lambda ps: {"min": [min(p[k] for p in ps) for k in range(3)], "max": [max(p[k] for p in ps) for k in range(3)]}
    for positions, uvs, indices in ((FLOOR_P, FLOOR_UV, FLOOR_I), (PANEL_P, PANEL_UV, PANEL_I)):
        for blob, acc in (
            (b"".join(struct.pack("<3f", *p) for p in positions),
             dict({"componentType": 5126, "count": len(positions), "type": "VEC3"}, **bounds(positions))),
            (b"".join(struct.pack("<2f", *t) for t in uvs), {"componentType": 5126, "count": len(uvs), "type": "VEC2"}),
            (b"".join(struct.pack("<H", i) for i in indices),
             {"componentType": 5123, "count": len(indices), "type": "SCALAR"}),
        ):
            views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(blob)})
            accessors.append(dict({"bufferView": len(views) - 1}, **acc))
            data += blob
    return data, views, accessors


def document(name, data, views, accessors, panel_material, image, extra_materials=None, sampler=None):
    lambert = {"extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
    floor = extra_materials or dict({"pbrMetallicRoughness": {"baseColorFactor": FLOOR_COLOUR + [1.0],
                                                               "metallicFactor": 0.0}}, **lambert)
    doc = {
        "asset": {"version": "2.0", "generator": "pathtrace benches/peers/make_gltf_texture_assets.py"},
        "extensionsUsed": ["KHR_materials_specular", "KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "floor", "mesh": 0}, {"name": "panel", "mesh": 1},
                  {"name": "camera", "camera": 0, "matrix": col_major(CAMERA)}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": YFOV, "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 3, "TEXCOORD_0": 4}, "indices": 5, "material": 1}]}],
        "materials": [floor, dict(panel_material, **{"extensions": dict(
            panel_material.get("extensions", {}), **lambert["extensions"])})],
        "textures": [dict({"source": 0}, **({"sampler": 0} if sampler else {}))],
        "images": [image],
        "buffers": [{"uri": name + ".bin", "byteLength": len(data)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    if sampler:
        doc["samplers"] = [sampler]
    return doc


def glb(doc, data):
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    bin_ = data + b"\0" * (-len(data) % 4)
    out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(bin_))
    return out + struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_), 0x004E4942) + bin_


PATH_DEPTH_4 = """    <integrator type="path">
        <integer name="max_depth" value="4"/>
    </integrator>
"""
# Mitsuba's `path` counts a pass through a `mask` as a bounce and stops shadow rays at masked
# surfaces; `volpath` passes them, as ours do (tests load the twin with -D integrator=path).
VOLPATH_UNLIMITED = """    <default name="integrator" value="volpath"/>
    <integrator type="$integrator">
        <integer name="max_depth" value="-1"/>
    </integrator>
"""


def twin(title, shapes, pfm_note, test="gltf_textures.rs", integrator=PATH_DEPTH_4):
    return f"""<?xml version="1.0"?>
<!-- The Mitsuba 3 twin of {title}, written by benches/peers/make_gltf_texture_assets.py
     ({pfm_note}). Used by crates/pathtrace-scene/tests/{test}. -->
<scene version="3.0.0">
{integrator}{mitsuba_sensor(CAMERA)}{shapes}</scene>
"""


def write_emissive():
    data, views, accessors = geometry()
    rows = [[c for texel in row for c in texel] for row in EMISSIVE_SRGB]
    image = png(rows, 3)
    with open(os.path.join(OUT, "emissive.png"), "wb") as f:
        f.write(image)
    with open(os.path.join(OUT, "emissive.bin"), "wb") as f:
        f.write(data)
    panel = {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
             "emissiveTexture": {"index": 0}, "emissiveFactor": EMISSIVE_FACTOR,
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": EMISSIVE_STRENGTH}}}
    doc = document("emissive", data, views, accessors, panel, {"uri": "emissive.png"})
    with open(os.path.join(OUT, "emissive.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    # The same document with everything inside: .glb (image in a buffer view after the geometry)…
    packed = data + b"\0" * (-len(data) % 4)
    views_glb = views + [{"buffer": 0, "byteOffset": len(packed), "byteLength": len(image)}]
    doc_glb = dict(doc, bufferViews=views_glb, images=[{"bufferView": len(views), "mimeType": "image/png"}],
                   buffers=[{"byteLength": len(packed) + len(image)}])
    with open(os.path.join(OUT, "emissive.glb"), "wb") as f:
        f.write(glb(doc_glb, packed + image))
    # … and .gltf with data: URIs.
    b64 = lambda b: base64.b64encode(b).decode()
    doc_data = dict(doc, images=[{"uri": "data:image/png;base64," + b64(image)}],
                    buffers=[{"uri": "data:application/octet-stream;base64," + b64(data), "byteLength": len(data)}])
    with open(os.path.join(OUT, "emissive_data.gltf"), "w") as f:
        json.dump(doc_data, f, indent=1)
    # The twin.
    write_obj(os.path.join(OUT, "emissive_floor.obj"), FLOOR_P, FLOOR_UV, FLOOR_I)
    write_obj(os.path.join(OUT, "emissive_panel.obj"), PANEL_P, PANEL_UV, PANEL_I)
    scale = [EMISSIVE_STRENGTH * f for f in EMISSIVE_FACTOR]
    radiance = [[tuple(srgb_decode(texel[k] / 255) * scale[k] for k in range(3)) for texel in row]
                for row in EMISSIVE_SRGB]
    write_pfm(os.path.join(OUT, "emissive_radiance.pfm"), radiance)
    shapes = f"""    <shape type="obj">
        <string name="filename" value="emissive_floor.obj"/>
        <boolean name="face_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="{rgb(FLOOR_COLOUR)}"/></bsdf>
    </shape>
    <shape type="obj">
        <string name="filename" value="emissive_panel.obj"/>
        <boolean name="face_normals" value="true"/>
        <boolean name="flip_tex_coords" value="false"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
        <emitter type="area">
            <texture name="radiance" type="bitmap">
                <string name="filename" value="emissive_radiance.pfm"/>
            </texture>
        </emitter>
    </shape>
"""
    with open(os.path.join(OUT, "emissive.xml"), "w") as f:
        f.write(twin("emissive.gltf (same floor, panel, uv, emission, camera)", shapes,
                     "emissive_radiance.pfm: emissive.png sRGB-decoded × emissiveFactor × emissiveStrength"))


def constant_panel():
    """The twins' panel of constant radiance PANEL_RADIANCE (metal_rough, metallic, basecolor)."""
    return f"""    <shape type="obj">
        <string name="filename" value="emissive_panel.obj"/>
        <boolean name="face_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="{rgb([PANEL_RADIANCE] * 3)}"/></emitter>
    </shape>
"""


def write_metal_rough():
    data, views, accessors = geometry()
    with open(os.path.join(OUT, "metal_rough.bin"), "wb") as f:
        f.write(data)
    rows = [[c for r in row for c in (0, int(round(r * 255)), 255)] for row in ROUGHNESS]
    with open(os.path.join(OUT, "metal_rough.png"), "wb") as f:
        f.write(png(rows, 3))
    metal = {"pbrMetallicRoughness": {"baseColorFactor": METAL_COLOUR + [1.0], "metallicFactor": 1.0,
                                      "roughnessFactor": ROUGHNESS_FACTOR, "metallicRoughnessTexture": {"index": 0}}}
    panel = {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
             "emissiveFactor": [1.0, 1.0, 1.0],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": PANEL_RADIANCE}}}
    nearest = {"magFilter": 9728, "minFilter": 9728}
    doc = document("metal_rough", data, views, accessors, panel, {"uri": "metal_rough.png"}, metal, nearest)
    with open(os.path.join(OUT, "metal_rough.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    alpha = [[((ROUGHNESS_FACTOR * round(r * 255) / 255) ** 2,) * 3 for r in row] for row in ROUGHNESS]
    write_pfm(os.path.join(OUT, "metal_rough_alpha.pfm"), alpha)
    shapes = f"""    <shape type="obj">
        <string name="filename" value="emissive_floor.obj"/>
        <boolean name="face_normals" value="true"/>
        <boolean name="flip_tex_coords" value="false"/>
        <bsdf type="roughconductor">
            <string name="material" value="none"/>
            <string name="distribution" value="ggx"/>
            <texture name="alpha" type="bitmap">
                <string name="filename" value="metal_rough_alpha.pfm"/>
                <string name="filter_type" value="nearest"/>
            </texture>
            <rgb name="specular_reflectance" value="{rgb(METAL_COLOUR)}"/>
        </bsdf>
    </shape>
{constant_panel()}"""
    with open(os.path.join(OUT, "metal_rough.xml"), "w") as f:
        f.write(twin("metal_rough.gltf (same floor, uv, roughness texels, panel, camera)", shapes,
                     "metal_rough_alpha.pfm: α = (roughnessFactor × the texture's green)² per texel"))


# metallic.png's blue channel (its green is ROUGHNESS): metallic per texel, times METALLIC_FACTOR.
METALLIC = [[0.0, 0.25, 0.5, 1.0], [1.0, 0.75, 0.1, 0.0], [0.6, 0.0, 1.0, 0.3], [0.2, 0.9, 0.45, 0.8]]
METALLIC_FACTOR = 0.9


def write_metallic():
    data, views, accessors = geometry()
    with open(os.path.join(OUT, "metallic.bin"), "wb") as f:
        f.write(data)
    rows = [[c for r, m in zip(rrow, mrow) for c in (0, int(round(r * 255)), int(round(m * 255)))]
            for rrow, mrow in zip(ROUGHNESS, METALLIC)]
    with open(os.path.join(OUT, "metallic.png"), "wb") as f:
        f.write(png(rows, 3))
    floor = {"pbrMetallicRoughness": {"baseColorFactor": METAL_COLOUR + [1.0], "metallicFactor": METALLIC_FACTOR,
                                      "roughnessFactor": ROUGHNESS_FACTOR, "metallicRoughnessTexture": {"index": 0}},
             "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
    panel = {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
             "emissiveFactor": [1.0, 1.0, 1.0],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": PANEL_RADIANCE}}}
    nearest = {"magFilter": 9728, "minFilter": 9728}
    doc = document("metallic", data, views, accessors, panel, {"uri": "metallic.png"}, floor, nearest)
    with open(os.path.join(OUT, "metallic.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    weight = [[(METALLIC_FACTOR * round(m * 255) / 255,) * 3 for m in row] for row in METALLIC]
    write_pfm(os.path.join(OUT, "metallic_weight.pfm"), weight)
    shapes = f"""    <shape type="obj">
        <string name="filename" value="emissive_floor.obj"/>
        <boolean name="face_normals" value="true"/>
        <boolean name="flip_tex_coords" value="false"/>
        <bsdf type="twosided">
            <bsdf type="blendbsdf">
                <texture name="weight" type="bitmap">
                    <string name="filename" value="metallic_weight.pfm"/>
                    <string name="filter_type" value="nearest"/>
                </texture>
                <bsdf type="diffuse">
                    <rgb name="reflectance" value="{rgb(METAL_COLOUR)}"/>
                </bsdf>
                <bsdf type="roughconductor">
                    <string name="material" value="none"/>
                    <string name="distribution" value="ggx"/>
                    <texture name="alpha" type="bitmap">
                        <string name="filename" value="metal_rough_alpha.pfm"/>
                        <string name="filter_type" value="nearest"/>
                    </texture>
                    <rgb name="specular_reflectance" value="{rgb(METAL_COLOUR)}"/>
                </bsdf>
            </bsdf>
        </bsdf>
    </shape>
{constant_panel()}"""
    with open(os.path.join(OUT, "metallic.xml"), "w") as f:
        f.write(twin("metallic.gltf (same floor, uv, metallic and roughness texels, panel, camera)", shapes,
                     "metallic_weight.pfm: metallicFactor × the texture's blue per texel; metal_rough_alpha.pfm: "
                     "α = (roughnessFactor × green)²"))


# basecolor.png, sRGB bytes (RGBA, first row at the top), and the factor (RGB, alpha).
BASE_SRGBA = [
    [(230, 200, 90, 255), (90, 160, 230, 204), (200, 90, 140, 153), (250, 250, 250, 255)],
    [(120, 230, 120, 128), (240, 140, 60, 255), (60, 60, 60, 230), (180, 210, 240, 179)],
    [(255, 255, 255, 179), (150, 90, 200, 255), (220, 180, 130, 102), (90, 200, 190, 255)],
    [(200, 60, 60, 255), (130, 130, 220, 153), (245, 225, 170, 255), (160, 240, 90, 204)],
]
BASE_FACTOR = [0.9, 0.6, 0.3, 0.7]


def write_basecolor():
    data, views, accessors = geometry()
    with open(os.path.join(OUT, "basecolor.bin"), "wb") as f:
        f.write(data)
    with open(os.path.join(OUT, "basecolor.png"), "wb") as f:
        f.write(png([[c for texel in row for c in texel] for row in BASE_SRGBA], 4))
    floor = {"pbrMetallicRoughness": {"baseColorFactor": BASE_FACTOR, "metallicFactor": 0.0,
                                      "baseColorTexture": {"index": 0}},
             "alphaMode": "BLEND",
             "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
    panel = {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
             "emissiveFactor": [1.0, 1.0, 1.0],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": PANEL_RADIANCE}}}
    doc = document("basecolor", data, views, accessors, panel, {"uri": "basecolor.png"}, floor)
    with open(os.path.join(OUT, "basecolor.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    albedo = [[tuple(srgb_decode(t[k] / 255) * BASE_FACTOR[k] for k in range(3)) for t in row] for row in BASE_SRGBA]
    write_pfm(os.path.join(OUT, "basecolor_albedo.pfm"), albedo)
    alpha = [[(BASE_FACTOR[3] * t[3] / 255,) * 3 for t in row] for row in BASE_SRGBA]
    write_pfm(os.path.join(OUT, "basecolor_alpha.pfm"), alpha)
    shapes = f"""    <shape type="obj">
        <string name="filename" value="emissive_floor.obj"/>
        <boolean name="face_normals" value="true"/>
        <boolean name="flip_tex_coords" value="false"/>
        <bsdf type="mask">
            <texture name="opacity" type="bitmap">
                <string name="filename" value="basecolor_alpha.pfm"/>
            </texture>
            <bsdf type="diffuse">
                <texture name="reflectance" type="bitmap">
                    <string name="filename" value="basecolor_albedo.pfm"/>
                </texture>
            </bsdf>
        </bsdf>
    </shape>
{constant_panel()}"""
    with open(os.path.join(OUT, "basecolor.xml"), "w") as f:
        f.write(twin("basecolor.gltf (same floor, uv, base colour and alpha texels × factor, panel, camera)", shapes,
                     "basecolor_albedo.pfm: basecolor.png sRGB-decoded × baseColorFactor.rgb; basecolor_alpha.pfm: "
                     "baseColorFactor.a × the texture's alpha", "gltf_base_colour.rs", VOLPATH_UNLIMITED))


def main():
    os.makedirs(OUT, exist_ok=True)
    write_emissive()
    write_metal_rough()
    write_metallic()
    write_basecolor()


if __name__ == "__main__":
    main()
