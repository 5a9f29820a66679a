#!/usr/bin/env python3
"""Every suite scene rendered by Mitsuba 3 and by pathtrace, interleaved: samples/s and the
estimated time to relative MSE 1e-2, with the ratio ours / Mitsuba.

Each scene is the same Mitsuba 3 XML file for both renderers, at its own film size, with its own
integrator, depth and filter; only the sample count is set (Mitsuba: `mi.render(spp=...)`;
pathtrace: `--spp`). Mitsuba's time is its render call after a warm-up render (the llvm variant
compiles kernels on first use); ours is pathtrace's own `render_seconds` (both exclude loading).
Rounds interleave the two renderers scene by scene, so both see the same machine load; medians
over rounds are reported.

Time to relative MSE 1e-2: each renderer's images are compared with a reference rendered once by
Mitsuba at `--ref-spp` samples (cached under target/bench-references/, keyed by scene and size),
with pathtrace's relative MSE, mean of (a - b)^2 / (b^2 + 0.01). For an unbiased estimator at
fixed settings the error falls as 1/spp and the time grows as spp, so time x relMSE is a constant
of the renderer and scene: the estimate is time_to_target = time x relMSE / target, from the same
renders that give samples/s. (The reference's own error, 1/ref-spp of the relMSE at 1 spp, adds
to both renderers alike.)

    bash benches/peers/setup.sh --llvm
    .venv-peers/bin/python benches/peers/suite_mitsuba.py --pathtrace target/release/pathtrace

The media scenes (`--only media`) are the repository's own (crates/pathtrace-scene/tests/data/media).
The 1M-triangle scene is generated (a displaced grid of 1,000,000 triangles, PLY, under a quad
light) into target/bench-scenes/, and so is teapot-zoomed (teapot-simple through a 12-degree
field of view, so the teapot fills the frame). See docs/benchmarks.md for the measured table.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import re
import shlex
import statistics
import struct
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cornell_mitsuba as cm  # noqa: E402  (find_libllvm)
from equal_quality import rel_mse, run_pathtrace, timed_render  # noqa: E402
from scene_means import inline_includes  # noqa: E402

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SHARED = os.path.abspath(os.path.join(REPO, "..", "shared", "scenes"))

# (label, XML path under ../shared/scenes or "mesh-1m", defines, spp per timed render)
SCENES = (
    ("cornell-box-bitterli", "cornell-box-bitterli/scene_v3.xml", {}, 16),
    ("cbox", "cbox/cbox.xml", {}, 64),
    ("cbox-classic", "cbox-classic/docs/scenes/integrator_depth_inf.xml", {}, 16),
    ("veach-mis", "veach-mis/docs/scenes/integrator_direct_both.xml", {}, 16),
    ("veach-mis-bitterli", "veach-mis-bitterli/scene_v3.xml", {"integrator": "path"}, 8),
    ("matpreview-copper", "matpreview/docs/scenes/bsdf_roughconductor_copper.xml", {}, 4),
    ("matpreview-glass", "matpreview/docs/scenes/bsdf_dielectric_glass.xml", {}, 4),
    ("matpreview-plastic", "matpreview/docs/scenes/bsdf_plastic_shiny.xml", {}, 4),
    ("matpreview-diffuse", "matpreview/docs/scenes/bsdf_diffuse_plain.xml", {}, 4),
    ("bunny", "bunny/docs/scenes/shape_ply_bunny.xml", {}, 4),
    ("teapot-simple", "teapot-simple/simple.xml", {}, 64),
    ("teapot-zoomed", "teapot-zoomed", {}, 64),
    ("mesh-1m", "mesh-1m", {}, 16),
    # Participating media (issue #19): the repository's own test scenes (64 x 64 films).
    ("media-fog-shafts", "repo:crates/pathtrace-scene/tests/data/media/fog_shafts.xml", {}, 256),
    ("media-jelly-sphere", "repo:crates/pathtrace-scene/tests/data/media/jelly_sphere.xml", {}, 128),
)


def mesh_1m_scene(folder):
    """A 708 x 707-cell displaced grid (1,000,000+ triangles, no normals: face normals in both
    renderers) on the floor of an open box, lit by one quad light; written once."""
    os.makedirs(folder, exist_ok=True)
    ply, xml = os.path.join(folder, "grid.ply"), os.path.join(folder, "mesh-1m.xml")
    if os.path.exists(xml):
        return xml
    nx, nz = 708, 707
    verts = []
    for j in range(nz + 1):
        for i in range(nx + 1):
            x, z = i / nx * 2 - 1, j / nz * 2 - 1
            y = 0.15 * math.sin(7 * x) * math.cos(5 * z) + 0.05 * math.sin(31 * x + 17 * z)
            verts.append((x, y, z))
    faces = []
    for j in range(nz):
        for i in range(nx):
            a = j * (nx + 1) + i
            faces.append((a, a + nx + 1, a + 1))
            faces.append((a + 1, a + nx + 1, a + nx + 2))
    with open(ply, "wb") as fh:
        fh.write(("ply\nformat binary_little_endian 1.0\n"
                  f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
                  f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        fh.write(b"".join(struct.pack("<3f", *v) for v in verts))
        fh.write(b"".join(struct.pack("<B3i", 3, *f) for f in faces))
    with open(xml, "w") as fh:
        fh.write("""<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="8"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, 2.2, 3.2" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
        <film type="hdrfilm"><integer name="width" value="512"/><integer name="height" value="512"/>
            <rfilter type="box"/></film>
    </sensor>
    <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf>
    <shape type="ply"><string name="filename" value="grid.ply"/><boolean name="face_normals" value="true"/>
        <ref id="grey"/></shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate value="0, 2, 0"/></transform>
        <emitter type="area"><rgb name="radiance" value="20, 20, 20"/></emitter>
    </shape>
</scene>
""")
    return xml


def teapot_zoomed_scene(scenes, folder):
    """teapot-simple seen through a 12-degree field of view: the teapot fills the frame, so every
    sample is a mesh hit shaded by the two point lights (79% of teapot-simple's frame is
    background, whose misses are cheap for us). Written from the shared file each time, with the
    mesh's path made absolute; None without the shared scenes."""
    source = os.path.join(scenes, "teapot-simple", "simple.xml")
    if not os.path.exists(source):
        return None
    with open(source) as fh:
        xml = fh.read()
    sensor, mesh = '<sensor type="perspective" id="sensor">', 'value="meshes/teapot.ply"'
    if xml.count(sensor) != 1 or xml.count(mesh) != 1:
        sys.exit(f"{source}: not the teapot-simple scene teapot-zoomed is derived from")
    xml = xml.replace(sensor, sensor + '<float name="fov" value="12"/>')
    xml = xml.replace(mesh, f'value="{os.path.join(scenes, "teapot-simple", "meshes", "teapot.ply")}"')
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "teapot-zoomed.xml")
    with open(path, "w") as fh:
        fh.write(xml)
    return path


def scene_path(rel, args):
    if rel == "mesh-1m":
        return mesh_1m_scene(os.path.join(REPO, "target", "bench-scenes"))
    if rel == "teapot-zoomed":
        path = teapot_zoomed_scene(os.path.abspath(args.scenes), os.path.join(REPO, "target", "bench-scenes"))
        return path or os.path.join(args.scenes, "teapot-simple", "simple.xml")
    if rel.startswith("repo:"):
        return os.path.join(REPO, rel[len("repo:"):])
    return os.path.join(args.scenes, rel)


MITSUBA_SAMPLERS = ("independent", "stratified", "multijitter", "orthogonal", "ldsampler")
OUR_SAMPLERS = ("independent", "stratified", "sobol")


def split(names):
    """The names of a comma-separated list (none for an empty one)."""
    return [n for n in (names or "").split(",") if n]


class Mitsuba:
    def __init__(self, mi, dr, variant, path, defines, sampler=None):
        self.mi, self.dr, self.variant = mi, dr, variant
        mi.set_variant(variant)
        if sampler is None:
            self.scene = mi.load_file(path, **defines)
        else:
            # The scene's text (includes inlined) with every sampler's type replaced, loaded from
            # the scene's folder so that relative paths resolve as for the file itself.
            folder = os.path.dirname(os.path.abspath(path))
            text = inline_includes(open(path).read(), folder)
            text = re.sub(r'(<sampler\s+type=")[^"]*"', rf'\g<1>{sampler}"', text)
            # The folder is searched first for this load only: left in the global resolver, it
            # would shadow the next scene's files of the same relative name.
            resolver = mi.file_resolver()
            saved = [str(resolver[i]) for i in range(len(resolver))]
            resolver.prepend(folder)
            cwd = os.getcwd()
            os.chdir(folder)
            try:
                self.scene = mi.load_string(text, **defines)
            finally:
                os.chdir(cwd)
                resolver.clear()
                for entry in saved:
                    resolver.append(entry)
        film = self.scene.sensors()[0].film()
        self.size = tuple(int(v) for v in film.crop_size())

    def render(self, np, spp, seed):
        return timed_render(self.mi, self.dr, np, self.variant, self.scene, spp, seed)


def ours(np, binary, path, defines, spp, seed, threads, tmp, extra=()):
    out, stats = os.path.join(tmp, "pt.pfm"), os.path.join(tmp, "pt.json")
    cmd = shlex.split(binary) + ["render", path, "--spp", str(spp), "--seed", str(seed),
                                 "--threads", str(threads), "--quiet", "--stats-json", stats, "-o", out]
    cmd += list(extra)
    for k, v in defines.items():
        cmd += ["-D", f"{k}={v}"]
    return run_pathtrace(np, cmd, stats, out)


def reference(np, mi, dr, label, path, defines, args):
    """A high-spp Mitsuba render of the scene, cached by (scene, defines, spp)."""
    key = hashlib.sha1(json.dumps([label, defines, args.ref_spp, os.path.getmtime(path)]).encode()).hexdigest()[:12]
    cache = os.path.join(REPO, "target", "bench-references", f"{label}-{key}.npy")
    if os.path.exists(cache):
        return np.load(cache)
    m = Mitsuba(mi, dr, args.ref_variant, path, defines)
    t0 = time.time()
    _, img = m.render(np, args.ref_spp, 12345)
    os.makedirs(os.path.dirname(cache), exist_ok=True)
    np.save(cache, img)
    print(f"  reference {label}: {args.ref_spp} spp by {args.ref_variant} in {time.time() - t0:.0f} s", flush=True)
    return img


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--pathtrace", required=True, metavar="BIN", help="our binary")
    p.add_argument("--scenes", default=SHARED, help="the shared scenes folder")
    p.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant timed")
    p.add_argument("--ref-variant", default="llvm_ad_rgb", help="Mitsuba variant of the references")
    p.add_argument("--ref-spp", type=int, default=1024)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--runs", type=int, default=3, help="interleaved rounds")
    p.add_argument("--target", type=float, default=1e-2, help="relative MSE to reach")
    p.add_argument("--only", default=None, help="only scenes whose label contains this text")
    p.add_argument("--spp-scale", type=float, default=1.0, help="multiply every scene's spp")
    p.add_argument("--json", metavar="FILE", help="also write the table as JSON")
    p.add_argument("--mitsuba-samplers", default="", metavar="LIST",
                   help="comma-separated Mitsuba samplers also timed to the target error (e.g. "
                        "stratified,multijitter,ldsampler; the scene file's sampler is always timed); the "
                        "table's last column compares each renderer's best")
    p.add_argument("--samplers", default="", metavar="LIST",
                   help="comma-separated samplers of ours also timed to the target error (e.g. sobol)")
    p.add_argument("--adaptive", type=int, default=None, metavar="MIN_SPP",
                   help="also time ours with adaptive sampling (--adaptive --min-spp MIN_SPP) at the same "
                        "average spp, with the scene's sampler and with each of --samplers; it counts as one "
                        "of our samplers in the best-sampler column")
    p.add_argument("--pathtrace-arg", action="append", default=[], metavar="ARG",
                   help="an extra argument for our renders (repeat for several), e.g. "
                        "--pathtrace-arg=--light-selection --pathtrace-arg=power")
    args = p.parse_args(argv)
    for option, names, known in (("--mitsuba-samplers", args.mitsuba_samplers, MITSUBA_SAMPLERS),
                                 ("--samplers", args.samplers, OUR_SAMPLERS)):
        unknown = [n for n in split(names) if n not in known]
        if unknown:
            p.error(f"{option}: unknown sampler {', '.join(unknown)} (expected some of: {', '.join(known)})")
    if "llvm" in args.variant + args.ref_variant and "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = cm.find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib

    import numpy as np
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(args.variant)
    mi.set_log_level(mi.LogLevel.Error)
    dr.set_thread_count(args.threads)
    print(f"mitsuba {mi.__version__} {args.variant} vs {args.pathtrace}, {args.threads} threads, "
          f"{args.runs} interleaved rounds, target relative MSE {args.target:g}", flush=True)

    rows = []
    with tempfile.TemporaryDirectory(prefix="suite-") as tmp:
        for label, rel, defines, spp in SCENES:
            if args.only and args.only not in label:
                continue
            path = scene_path(rel, args)
            if not os.path.exists(path):
                print(f"{label}: {path} is absent, skipped")
                continue
            spp = max(1, round(spp * args.spp_scale))

            def ours_with(extra, path=path, defines=defines):
                return lambda np, spp, seed: ours(np, args.pathtrace, path, defines, spp, seed, args.threads, tmp,
                                                  list(args.pathtrace_arg) + extra)
            ref = reference(np, mi, dr, label, path, defines, args)
            theirs = Mitsuba(mi, dr, args.variant, path, defines)
            w, h = theirs.size
            theirs.render(np, spp, 0)  # warm-up: kernels compiled, files cached
            ours_with([])(np, 1, 0)
            # The other samplers, for time to the target error only: (who, sampler, render).
            others = [("mitsuba", name, Mitsuba(mi, dr, args.variant, path, defines, name).render)
                      for name in split(args.mitsuba_samplers)]
            others += [("ours", name, ours_with(["--sampler", name])) for name in split(args.samplers)]
            if args.adaptive is not None:
                adaptive = ["--adaptive", "--min-spp", str(args.adaptive)]
                others += [("ours", f"{name}+adaptive" if name else "adaptive", ours_with((["--sampler", name] if name else []) + adaptive))
                           for name in [""] + split(args.samplers)]
            for _, _, render in others:
                render(np, spp, 0)  # warm-up
            r = {"scene": label, "size": f"{w}x{h}", "spp": spp, "mitsuba": [], "ours": [],
                 "samplers": {f"{who} {name}": [] for who, name, _ in others}}

            def measure(render, run):
                seconds, img = render(np, spp, 1 + run)
                err = rel_mse(np, img, ref)
                return {"seconds": seconds, "samples_per_s": w * h * spp / seconds, "rel_mse": err,
                        "time_to_target": seconds * err / args.target}

            for run in range(args.runs):
                r["mitsuba"].append(measure(theirs.render, run))
                r["ours"].append(measure(ours_with([]), run))
                for who, name, render in others:
                    r["samplers"][f"{who} {name}"].append(measure(render, run))
            rows.append(r)
            med = {who: {k: statistics.median(x[k] for x in r[who]) for k in r[who][0]} for who in ("mitsuba", "ours")}
            r["median"] = med
            # Each renderer's best sampler: the scene's own or one of the others.
            best = {who: ("scene's", med[who]["time_to_target"]) for who in ("mitsuba", "ours")}
            for key, runs in r["samplers"].items():
                who, name = key.split(" ", 1)
                t = statistics.median(x["time_to_target"] for x in runs)
                print(f"  {key}: time to {args.target:g} {t:.3f} s, relMSE "
                      f"{statistics.median(x['rel_mse'] for x in runs):.4f}", flush=True)
                if t < best[who][1]:
                    best[who] = (name, t)
            r["best"] = best
            print(f"{label:<22} {w}x{h} {spp:>3} spp  samples/s: ours {med['ours']['samples_per_s'] / 1e6:7.3f} M, "
                  f"mitsuba {med['mitsuba']['samples_per_s'] / 1e6:7.3f} M, ratio "
                  f"{med['ours']['samples_per_s'] / med['mitsuba']['samples_per_s']:5.2f}x   "
                  f"time to {args.target:g}: ours {med['ours']['time_to_target']:.3f} s, "
                  f"mitsuba {med['mitsuba']['time_to_target']:.3f} s, ratio "
                  f"{med['ours']['time_to_target'] / med['mitsuba']['time_to_target']:5.2f}x   "
                  f"(best samplers: ours {best['ours'][0]}, mitsuba {best['mitsuba'][0]}, ratio "
                  f"{best['ours'][1] / best['mitsuba'][1]:5.2f}x)   "
                  f"relMSE: ours {med['ours']['rel_mse']:.4f}, mitsuba {med['mitsuba']['rel_mse']:.4f}", flush=True)

    print()
    print("| scene | size, spp | ours M samples/s | Mitsuba M samples/s | ours ÷ Mitsuba speed "
          "| time to relMSE 1e-2, ours ÷ Mitsuba | the same, best samplers (ours, Mitsuba's) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    ratios = []
    for r in rows:
        m = r["median"]
        ratio = m["ours"]["samples_per_s"] / m["mitsuba"]["samples_per_s"]
        ratios.append(ratio)
        print(f"| {r['scene']} | {r['size']}, {r['spp']} | {m['ours']['samples_per_s'] / 1e6:.3f} | "
              f"{m['mitsuba']['samples_per_s'] / 1e6:.3f} | {ratio:.2f}× | "
              f"{m['ours']['time_to_target'] / m['mitsuba']['time_to_target']:.2f}× | "
              f"{r['best']['ours'][1] / r['best']['mitsuba'][1]:.2f}× ({r['best']['ours'][0]}, "
              f"{r['best']['mitsuba'][0]}) |")
    if ratios:
        gm = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
        print(f"\ngeometric mean of the speed ratios: {gm:.2f}×  (min {min(ratios):.2f}×)")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
