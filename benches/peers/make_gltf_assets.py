"""Writes the glTF test scene and its Mitsuba 3 twin, built from the same data, into
crates/pathtrace-scene/tests/data/gltf/:

- scene.gltf + scene.bin, and scene.glb (the same document with the buffer embedded): a floor
  quad and a cube placed through a two-level node hierarchy (translation, then rotation + scale),
  both with KHR_materials_specular specularFactor 0 (glTF's BRDF is then pure Lambertian), the
  cube without NORMAL (flat normals, as glTF requires); a perspective camera and a
  KHR_lights_punctual directional light, each placed by a node matrix.
- scene.xml + floor.obj + cube.obj: the same triangles (world positions computed here from the
  same node transforms), `diffuse` BSDFs of the same base colours, `face_normals`, the same
  camera (fov on the y axis) and a `directional` emitter of the same irradiance and direction.

- ../maps/normal_map.gltf + normal_map.bin and its twin normal_map.xml + normal_floor.obj: a
  Lambertian floor with TEXCOORD_0 and a normalTexture (../maps/normal.png, from
  make_map_assets.py) under a KHR_lights_punctual directional light; the twin wraps the same
  `diffuse` in a `normalmap` without the terminator shadowing (glTF has none) and reads the OBJ's
  texture coordinates unflipped. The uv layout is not mirrored (−∂p/∂v along n × ∂p/∂u), where
  glTF's tangent space and Mitsuba's agree.
- ../maps/normal_map_tangents.gltf: normal_map.gltf with a TANGENT attribute (a second buffer, a
  data: URI) turned 30° about the normal from +x, bitangent sign w = -1: the estimator's lanes
  test (lanes_exact.rs) renders it.

- ../maps/cutout.gltf + cutout.bin and its twin cutout.xml + cutout_card.obj: a floor and a
  standing card whose base colour texture (../maps/cutout.png, from make_map_assets.py) has the
  cut-out in its alpha, alphaMode BLEND (alpha as opacity, bilinear, as Mitsuba's `mask`; MASK's
  hard edges at alphaCutoff cannot match it block by block), under a directional light; the twin
  wraps a two-sided `diffuse` of the texture's (sRGB-decoded) colour in a `mask` of the grey
  mask.png (the same 0/1 alpha), rendered with `volpath` (shadow rays pass masks).

    python3 benches/peers/make_gltf_assets.py
"""
import json
import math
import os
import struct

OUT = os.path.join(os.path.dirname(__file__), "../../crates/pathtrace-scene/tests/data/gltf")


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    n = math.sqrt(sum(x * x for x in a))
    return [x / n for x in a]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def apply(m, p):
    return [sum(m[i][k] * (p[k] if k < 3 else 1.0) for k in range(4)) for i in range(3)]


def col_major(m):
    return [m[r][c] for c in range(4) for r in range(4)]


def look_at(eye, target, up):
    """A node matrix (rows) whose −z looks from eye to target (glTF cameras and lights)."""
    z = norm(sub(eye, target))
    x = norm(cross(up, z))
    y = cross(z, x)
    return [[x[0], y[0], z[0], eye[0]], [x[1], y[1], z[1], eye[1]], [x[2], y[2], z[2], eye[2]], [0, 0, 0, 1]]


# Geometry in mesh space.
FLOOR_P = [[-3, 0, -3], [3, 0, -3], [3, 0, 3], [-3, 0, 3]]
FLOOR_I = [0, 2, 1, 0, 3, 2]  # faces +y
CUBE_P, CUBE_I = [], []
for axis in range(3):
    for sign in (-1, 1):
        n = [0, 0, 0]
        n[axis] = sign
        u = [0, 0, 0]
        u[(axis + 1) % 3] = 1
        v = cross(n, u)
        base = len(CUBE_P)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            CUBE_P.append([0.5 * (n[k] + su * u[k] + sv * v[k]) for k in range(3)])
        CUBE_I += [base, base + 1, base + 2, base, base + 2, base + 3]

# The hierarchy: cube = parent (translation) × child (rotation about y by 30°, scale 1.2).
PARENT = [[1, 0, 0, 0.4], [0, 1, 0, 0.6], [0, 0, 1, 0.3], [0, 0, 0, 1]]
c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
CHILD = [[1.2 * c, 0, 1.2 * s, 0], [0, 1.2, 0, 0], [-1.2 * s, 0, 1.2 * c, 0], [0, 0, 0, 1]]
CUBE_WORLD = matmul(PARENT, CHILD)
CAMERA = look_at([0.5, 3.0, -5.0], [0.2, 0.4, 0.3], [0, 1, 0])
LIGHT = look_at([2.0, 4.0, -1.0], [0, 0, 0], [0, 1, 0])
YFOV = math.radians(38.0)
FLOOR_COLOUR = [0.6, 0.55, 0.5]
CUBE_COLOUR = [0.2, 0.4, 0.7]
LIGHT_COLOUR, LIGHT_INTENSITY = [1.0, 0.9, 0.8], 3.0


def buffer_and_accessors():
    data = b""
    views, accessors = [], []

    def add(values, fmt, comp, kind, target, minmax=False):
        nonlocal data
        while len(data) % 4:
            data += b"\0"
        blob = b"".join(struct.pack("<" + fmt, *v) if isinstance(v, list) else struct.pack("<" + fmt, v) for v in values)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(blob), "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": len(values), "type": kind}
        if minmax:
            acc["min"] = [min(v[k] for v in values) for k in range(3)]
            acc["max"] = [max(v[k] for v in values) for k in range(3)]
        accessors.append(acc)
        data += blob
        return len(accessors) - 1

    floor_p = add(FLOOR_P, "3f", 5126, "VEC3", 34962, True)
    floor_n = add([[0, 1, 0]] * 4, "3f", 5126, "VEC3", 34962)
    floor_i = add(FLOOR_I, "H", 5123, "SCALAR", 34963)
    cube_p = add(CUBE_P, "3f", 5126, "VEC3", 34962, True)
    cube_i = add(CUBE_I, "I", 5125, "SCALAR", 34963)
    return data, views, accessors, (floor_p, floor_n, floor_i, cube_p, cube_i)


def document(data, views, accessors, ids, uri):
    floor_p, floor_n, floor_i, cube_p, cube_i = ids

    def lambert(name, colour):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": colour + [1.0], "metallicFactor": 0.0,
                                                        "roughnessFactor": 0.5},
                "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}

    buffer = {"byteLength": len(data)}
    if uri:
        buffer["uri"] = uri
    return {
        "asset": {"version": "2.0", "generator": "pathtrace benches/peers/make_gltf_assets.py"},
        "extensionsUsed": ["KHR_materials_specular", "KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "color": LIGHT_COLOUR, "intensity": LIGHT_INTENSITY}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 3, 4]}],
        "nodes": [
            {"name": "floor", "mesh": 0},
            {"name": "cube-parent", "translation": PARENT[0][3:4] + PARENT[1][3:4] + PARENT[2][3:4], "children": [2]},
            {"name": "cube", "mesh": 1, "matrix": col_major(CHILD)},
            {"name": "camera", "camera": 0, "matrix": col_major(CAMERA)},
            {"name": "sun", "matrix": col_major(LIGHT), "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"name": "main", "type": "perspective",
                     "perspective": {"yfov": YFOV, "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": [
            {"name": "floor", "primitives": [{"attributes": {"POSITION": floor_p, "NORMAL": floor_n},
                                              "indices": floor_i, "material": 0}]},
            {"name": "cube", "primitives": [{"attributes": {"POSITION": cube_p}, "indices": cube_i, "material": 1}]},
        ],
        "materials": [lambert("floor", FLOOR_COLOUR), lambert("cube", CUBE_COLOUR)],
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": accessors,
    }


def write_obj(path, positions, indices):
    with open(path, "w") as f:
        for p in positions:
            f.write("v %.9g %.9g %.9g\n" % tuple(p))
        for i in range(0, len(indices), 3):
            f.write("f %d %d %d\n" % (indices[i] + 1, indices[i + 1] + 1, indices[i + 2] + 1))


MAPS = os.path.join(os.path.dirname(__file__), "../../crates/pathtrace-scene/tests/data/maps")
NFLOOR_P = [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]]
NFLOOR_UV = [[(p[0] + 2) / 2, (p[2] + 2) / 2] for p in NFLOOR_P]  # u along +x, v along +z
NFLOOR_I = [0, 2, 1, 0, 3, 2]  # faces +y
NCAMERA = look_at([0.3, 2.5, -3.5], [0, 0, 0.3], [0, 1, 0])
NLIGHT = look_at([-2.0, 2.0, -1.0], [0, 0, 0], [0, 1, 0])


def rgb(c):
    """Numbers as Mitsuba XML writes a colour or a point: comma separated, 9 significant digits."""
    return ", ".join("%.9g" % x for x in c)


def mitsuba_sensor(camera):
    """The twins' sensor: glTF's camera (node matrix `camera`, looking along −z, +y up, YFOV)
    as a 64 × 64 Mitsuba perspective sensor with a box filter and 64 independent samples."""
    eye = [camera[i][3] for i in range(3)]
    fwd = [-camera[i][2] for i in range(3)]
    up = [camera[i][1] for i in range(3)]
    return f"""    <sensor type="perspective">
        <string name="fov_axis" value="y"/>
        <float name="fov" value="{math.degrees(YFOV):.9g}"/>
        <transform name="to_world">
            <lookat origin="{rgb(eye)}" target="{rgb([eye[k] + fwd[k] for k in range(3)])}" up="{rgb(up)}"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="64"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="64"/>
            <integer name="height" value="64"/>
            <rfilter type="box"/>
        </film>
    </sensor>
"""


def write_normal_map_twin():
    data = b"".join(struct.pack("<3f", *p) for p in NFLOOR_P)
    data += b"".join(struct.pack("<3f", 0, 1, 0) for _ in NFLOOR_P)
    data += b"".join(struct.pack("<2f", *t) for t in NFLOOR_UV)
    data += b"".join(struct.pack("<H", i) for i in NFLOOR_I)
    with open(os.path.join(MAPS, "normal_map.bin"), "wb") as f:
        f.write(data)
    n = len(NFLOOR_P)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n}, {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
             {"buffer": 0, "byteOffset": 24 * n, "byteLength": 8 * n}, {"buffer": 0, "byteOffset": 32 * n, "byteLength": 12}]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
         "min": [min(p[k] for p in NFLOOR_P) for k in range(3)], "max": [max(p[k] for p in NFLOOR_P) for k in range(3)]},
        {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ]
    doc = {
        "asset": {"version": "2.0", "generator": "pathtrace benches/peers/make_gltf_assets.py"},
        "extensionsUsed": ["KHR_materials_specular", "KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "color": LIGHT_COLOUR, "intensity": LIGHT_INTENSITY}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "floor", "mesh": 0}, {"name": "camera", "camera": 0, "matrix": col_major(NCAMERA)},
                  {"name": "sun", "matrix": col_major(NLIGHT), "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": YFOV, "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": FLOOR_COLOUR + [1.0], "metallicFactor": 0.0},
                       "normalTexture": {"index": 0, "scale": 1.0},
                       "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "normal.png"}],
        "buffers": [{"uri": "normal_map.bin", "byteLength": len(data)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(os.path.join(MAPS, "normal_map.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    with open(os.path.join(MAPS, "normal_floor.obj"), "w") as f:
        for p in NFLOOR_P:
            f.write("v %.9g %.9g %.9g\n" % tuple(p))
        for t in NFLOOR_UV:
            f.write("vt %.9g %.9g\n" % tuple(t))
        for i in range(0, 6, 3):
            f.write("f %d/%d %d/%d %d/%d\n" % tuple(x + 1 for j in NFLOOR_I[i:i + 3] for x in (j, j)))
    camera = NCAMERA
    direction = [-NLIGHT[i][2] for i in range(3)]
    xml = f"""<?xml version="1.0"?>
<!-- The Mitsuba 3 twin of normal_map.gltf (same floor, uv, normal map, camera and light), written
     by benches/peers/make_gltf_assets.py. Used by crates/pathtrace-scene/tests/gltf.rs. -->
<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="4"/>
    </integrator>
{mitsuba_sensor(camera)}    <shape type="obj">
        <string name="filename" value="normal_floor.obj"/>
        <boolean name="face_normals" value="true"/>
        <boolean name="flip_tex_coords" value="false"/>
        <bsdf type="normalmap">
            <texture name="normalmap" type="bitmap">
                <string name="filename" value="normal.png"/>
                <boolean name="raw" value="true"/>
            </texture>
            <boolean name="use_shadowing_function" value="false"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="{rgb(FLOOR_COLOUR)}"/></bsdf>
        </bsdf>
    </shape>
    <emitter type="directional">
        <vector name="direction" value="{rgb(direction)}"/>
        <rgb name="irradiance" value="{rgb([LIGHT_INTENSITY * c for c in LIGHT_COLOUR])}"/>
    </emitter>
</scene>
"""
    with open(os.path.join(MAPS, "normal_map.xml"), "w") as f:
        f.write(xml)


CARD_P = [[-0.6, 0.1, 0.3], [0.6, 0.1, 0.3], [0.6, 1.3, 0.3], [-0.6, 1.3, 0.3]]
CARD_UV = [[(p[0] + 0.6) / 1.2, (1.3 - p[1]) / 1.2] for p in CARD_P]  # the image's top at the top
CARD_I = [0, 1, 2, 0, 2, 3]
CFLOOR_P = [[-2.5, 0, -2.5], [2.5, 0, -2.5], [2.5, 0, 2.5], [-2.5, 0, 2.5]]
CCAMERA = look_at([0.4, 1.8, -3.0], [0, 0.5, 0.3], [0, 1, 0])
CLIGHT = look_at([-1.0, 3.0, 3.0], [0, 0, 0], [0, 1, 0])
CARD_SRGB = [200, 120, 60]


def write_tangent_variant():
    """normal_map.gltf plus tangents of w = -1 turned 30 degrees from +x about the floor's +y."""
    import base64
    with open(os.path.join(MAPS, "normal_map.gltf")) as f:
        doc = json.load(f)
    a = math.radians(30.0)
    tangent = [math.cos(a), 0.0, -math.sin(a), -1.0]
    data = b"".join(struct.pack("<4f", *tangent) for _ in NFLOOR_P)
    doc["buffers"].append({"uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode(),
                           "byteLength": len(data)})
    doc["bufferViews"].append({"buffer": 1, "byteOffset": 0, "byteLength": len(data)})
    doc["accessors"].append({"bufferView": len(doc["bufferViews"]) - 1, "componentType": 5126,
                             "count": len(NFLOOR_P), "type": "VEC4"})
    doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = len(doc["accessors"]) - 1
    with open(os.path.join(MAPS, "normal_map_tangents.gltf"), "w") as f:
        json.dump(doc, f, indent=1)


def srgb_decode(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def write_cutout_twin():
    data = b"".join(struct.pack("<3f", *p) for p in CFLOOR_P + CARD_P)
    data += b"".join(struct.pack("<2f", *t) for t in CARD_UV)
    data += b"".join(struct.pack("<H", i) for i in FLOOR_I + CARD_I)
    with open(os.path.join(MAPS, "cutout.bin"), "wb") as f:
        f.write(data)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
             {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12},
             {"buffer": 0, "byteOffset": 140, "byteLength": 12}]
    bounds = lambda ps: {"min": [min(p[k] for p in ps) for k in range(3)], "max": [max(p[k] for p in ps) for k in range(3)]}
    accessors = [
        dict({"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"}, **bounds(CFLOOR_P)),
        dict({"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"}, **bounds(CARD_P)),
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
        {"bufferView": 4, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ]
    lambert = {"extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
    doc = {
        "asset": {"version": "2.0", "generator": "pathtrace benches/peers/make_gltf_assets.py"},
        "extensionsUsed": ["KHR_materials_specular", "KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "color": LIGHT_COLOUR, "intensity": LIGHT_INTENSITY}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"name": "floor", "mesh": 0}, {"name": "card", "mesh": 1},
                  {"name": "camera", "camera": 0, "matrix": col_major(CCAMERA)},
                  {"name": "sun", "matrix": col_major(CLIGHT), "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": YFOV, "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 3, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 1, "TEXCOORD_0": 2}, "indices": 4, "material": 1}]}],
        "materials": [
            dict({"pbrMetallicRoughness": {"baseColorFactor": FLOOR_COLOUR + [1.0], "metallicFactor": 0.0}}, **lambert),
            dict({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0},
                  "alphaMode": "BLEND", "doubleSided": True}, **lambert)],
        "textures": [{"source": 0}],
        "images": [{"uri": "cutout.png"}],
        "buffers": [{"uri": "cutout.bin", "byteLength": len(data)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(os.path.join(MAPS, "cutout.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    write_obj(os.path.join(MAPS, "cutout_floor.obj"), CFLOOR_P, FLOOR_I)
    with open(os.path.join(MAPS, "cutout_card.obj"), "w") as f:
        for p in CARD_P:
            f.write("v %.9g %.9g %.9g\n" % tuple(p))
        for t in CARD_UV:
            f.write("vt %.9g %.9g\n" % tuple(t))
        for i in range(0, 6, 3):
            f.write("f %d/%d %d/%d %d/%d\n" % tuple(x + 1 for j in CARD_I[i:i + 3] for x in (j, j)))
    camera = CCAMERA
    direction = [-CLIGHT[i][2] for i in range(3)]
    card = [srgb_decode(c / 255) for c in CARD_SRGB]
    xml = f"""<?xml version="1.0"?>
<!-- The Mitsuba 3 twin of cutout.gltf (same floor, card, uv, cut-out, camera and light), written
     by benches/peers/make_gltf_assets.py. `volpath` lets shadow rays pass the mask, as ours do;
     our tests load it with -D integrator=path. Used by crates/pathtrace-scene/tests/gltf_maps.rs. -->
<scene version="3.0.0">
    <default name="integrator" value="volpath"/>
    <integrator type="$integrator">
        <integer name="max_depth" value="-1"/>
    </integrator>
{mitsuba_sensor(camera)}    <shape type="obj">
        <string name="filename" value="cutout_floor.obj"/>
        <boolean name="face_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="{rgb(FLOOR_COLOUR)}"/></bsdf>
    </shape>
    <shape type="obj">
        <string name="filename" value="cutout_card.obj"/>
        <boolean name="face_normals" value="true"/>
        <boolean name="flip_tex_coords" value="false"/>
        <bsdf type="mask">
            <texture name="opacity" type="bitmap">
                <string name="filename" value="mask.png"/>
                <boolean name="raw" value="true"/>
            </texture>
            <bsdf type="twosided">
                <bsdf type="diffuse"><rgb name="reflectance" value="{rgb(card)}"/></bsdf>
            </bsdf>
        </bsdf>
    </shape>
    <emitter type="directional">
        <vector name="direction" value="{rgb(direction)}"/>
        <rgb name="irradiance" value="{rgb([LIGHT_INTENSITY * c for c in LIGHT_COLOUR])}"/>
    </emitter>
</scene>
"""
    with open(os.path.join(MAPS, "cutout.xml"), "w") as f:
        f.write(xml)


def main():
    os.makedirs(OUT, exist_ok=True)
    write_normal_map_twin()
    write_tangent_variant()
    write_cutout_twin()
    data, views, accessors, ids = buffer_and_accessors()
    with open(os.path.join(OUT, "scene.bin"), "wb") as f:
        f.write(data)
    with open(os.path.join(OUT, "scene.gltf"), "w") as f:
        json.dump(document(data, views, accessors, ids, "scene.bin"), f, indent=1)
    # GLB: header, JSON chunk (padded with spaces), BIN chunk (padded with zeros).
    js = json.dumps(document(data, views, accessors, ids, None)).encode()
    js += b" " * (-len(js) % 4)
    bin_ = data + b"\0" * (-len(data) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(bin_))
    glb += struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_), 0x004E4942) + bin_
    with open(os.path.join(OUT, "scene.glb"), "wb") as f:
        f.write(glb)
    write_obj(os.path.join(OUT, "floor.obj"), FLOOR_P, FLOOR_I)
    write_obj(os.path.join(OUT, "cube.obj"), [apply(CUBE_WORLD, p) for p in CUBE_P], CUBE_I)
    camera = CAMERA
    direction = [-LIGHT[i][2] for i in range(3)]
    xml = f"""<?xml version="1.0"?>
<!-- The Mitsuba 3 twin of scene.gltf (same triangles, colours, camera and light), written by
     benches/peers/make_gltf_assets.py. Used by crates/pathtrace-scene/tests/gltf.rs. -->
<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="4"/>
    </integrator>
{mitsuba_sensor(camera)}    <shape type="obj">
        <string name="filename" value="floor.obj"/>
        <boolean name="face_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="{rgb(FLOOR_COLOUR)}"/></bsdf>
    </shape>
    <shape type="obj">
        <string name="filename" value="cube.obj"/>
        <boolean name="face_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="{rgb(CUBE_COLOUR)}"/></bsdf>
    </shape>
    <emitter type="directional">
        <vector name="direction" value="{rgb(direction)}"/>
        <rgb name="irradiance" value="{rgb([LIGHT_INTENSITY * c for c in LIGHT_COLOUR])}"/>
    </emitter>
</scene>
"""
    with open(os.path.join(OUT, "scene.xml"), "w") as f:
        f.write(xml)


if __name__ == "__main__":
    main()
