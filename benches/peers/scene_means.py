"""Mean pixel value per channel of Mitsuba 3 XML scenes, rendered by Mitsuba 3 (and by pathtrace).

Two uses, chosen by whether a scene file is named:

1. Reference means of the shared test scenes (no SCENE argument). The reference numbers in
   crates/pathtrace-scene/tests/mitsuba_means.rs come from this mode:

       bash benches/peers/setup.sh
       .venv-peers/bin/python benches/peers/scene_means.py --size 64 --spp 4096

   Each scene is loaded as written except for the film size (width and height are replaced in the
   XML text, so `$res` defaults and fixed sizes alike become SIZE × SIZE) and the sample count
   (`--spp`, default 4096, through the sampler's `sample_count`); `<include>`d files are inlined
   first so a film defined in one is resized too. The scene's own integrator, depth,
   filter and emitters are kept. `--only TEXT` renders only scenes whose path contains TEXT.

2. Mitsuba against pathtrace on one scene (SCENE.xml given). Renders the same XML file with both
   renderers at the same settings and prints the image means (R, G, B), their ratio
   ours / Mitsuba, and a standard error of each mean estimated from independent renders with
   different seeds (so "agrees within noise" can be judged):

       .venv-peers/bin/python benches/peers/scene_means.py SCENE.xml --pathtrace target/release/pathtrace \
           [--spp 256] [--runs 2] [-D name=value ...]

   `-D name=value` sets a scene `<default>` for both (e.g. `-D resx=320 -D resy=180 -D integrator=path`).
   Without `--pathtrace` only Mitsuba's mean is printed. `--spp` defaults to 256 here.

Nothing of Mitsuba's is written to the repository or the scenes' folders: images of the second
mode go to a temporary directory.
"""
import argparse
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time

SCENES = [
    "cbox/cbox.xml",
    "cornell-box-bitterli/scene_v3.xml",
    "teapot-simple/simple.xml",
    "cbox-classic/docs/scenes/integrator_depth_inf.xml",
    "matpreview/docs/scenes/bsdf_diffuse_plain.xml",
    "matpreview/docs/scenes/bsdf_plastic_shiny.xml",
    "matpreview/docs/scenes/bsdf_roughconductor_copper.xml",
    "matpreview/docs/scenes/bsdf_dielectric_glass.xml",
    "bunny/docs/scenes/shape_ply_bunny.xml",
]


def inline_includes(text, folder):
    """Replaces each `<include filename="F"/>` by F's body (its <scene> wrapper removed), so that
    the film-size substitution also reaches a film defined in an included file. Relative paths in
    an included file resolve against the including scene's folder and `<path>`s, as Mitsuba does."""
    def body(m):
        inner = open(os.path.join(folder, m.group(1))).read()
        inner = re.sub(r"<\?xml[^>]*\?>", "", inner)
        inner = re.sub(r"<scene[^>]*>", "", inner, count=1)
        return inline_includes(re.sub(r"</scene>\s*$", "", inner.strip()), folder)
    return re.sub(r'<include\s+filename="([^"]*)"\s*/>', body, text)


def image_mean(np, img):
    a = np.array(img, dtype=np.float64)[..., :3]
    return a.reshape(-1, 3).mean(axis=0)


def mean_and_se(np, means):
    m = np.mean(means, axis=0)
    se = np.std(means, axis=0, ddof=1) / np.sqrt(len(means)) if len(means) > 1 else np.full(3, np.nan)
    return m, se


DIGITS = 4


def fmt(v):
    return "(" + ", ".join(f"{x:.{DIGITS}f}" for x in v) + ")"


def reference_means(a, mi, np):
    """Mode 1: the shared test scenes at SIZE × SIZE."""
    spp = a.spp or 4096
    for rel in SCENES:
        if a.only and a.only not in rel:
            continue
        path = os.path.abspath(os.path.join(a.scenes, rel))
        text = inline_includes(open(path).read(), os.path.dirname(path))
        for axis in ("width", "height"):
            text = re.sub(rf'(<integer\s+name="{axis}"\s+value=")[^"]*(")', rf"\g<1>{a.size}\g<2>", text)
        # Resolve relative paths (meshes, <path>) as if the text were the file itself.
        resolver = mi.file_resolver()
        resolver.prepend(os.path.dirname(path))
        cwd = os.getcwd()
        os.chdir(os.path.dirname(path))
        try:
            scene = mi.load_string(text)
        finally:
            os.chdir(cwd)
        t0 = time.time()
        img = mi.render(scene, spp=spp, seed=a.seed)
        elapsed = time.time() - t0
        means = image_mean(np, img)
        print(f"{rel}: mean = [{means[0]:.5f}, {means[1]:.5f}, {means[2]:.5f}]  ({a.size}², {spp} spp, {elapsed:.1f} s)")
    return 0


def compare(a, mi, np):
    """Mode 2: one scene, Mitsuba against pathtrace, with standard errors from repeated runs."""
    spp = a.spp or 256
    defines = dict(d.split("=", 1) for d in a.defines)
    scene = mi.load_file(a.scene, **defines)
    theirs = []
    for run in range(a.runs):
        img = mi.render(scene, spp=spp, seed=run)
        theirs.append(image_mean(np, img))
    m, se = mean_and_se(np, theirs)
    print(f"mitsuba  {a.variant}  {spp} spp x {a.runs}: mean {fmt(m)}  s.e. {fmt(se)}")

    if not a.pathtrace:
        return 0
    ours = []
    with tempfile.TemporaryDirectory() as tmp:
        for run in range(a.runs):
            out = os.path.join(tmp, f"ours{run}.exr")
            stats = os.path.join(tmp, f"stats{run}.json")
            cmd = shlex.split(a.pathtrace) + ["render", a.scene, "--spp", str(spp), "--seed", str(run + 1),
                                              "--threads", str(a.threads), "--quiet",
                                              "--stats-json", stats, "-o", out]
            for d in a.defines:
                cmd += ["-D", d]
            subprocess.run(cmd, check=True)
            bmp = mi.Bitmap(out).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
            ours.append(image_mean(np, bmp))
            seconds = json.load(open(stats)).get("render_seconds")
            print(f"pathtrace run {run}: {seconds:.1f} s")
    o, ose = mean_and_se(np, ours)
    print(f"pathtrace           {spp} spp x {a.runs}: mean {fmt(o)}  s.e. {fmt(ose)}")
    ratio = o / m
    z = (o - m) / np.sqrt(se ** 2 + ose ** 2)
    print(f"ours / mitsuba: {fmt(ratio)}   z: {fmt(z)}")
    return 0


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene", nargs="?", help="one XML scene to compare with pathtrace (mode 2); "
                   "without it, the shared test scenes' reference means (mode 1)")
    p.add_argument("--spp", type=int, default=None, help="samples per pixel (default 4096 in mode 1, 256 in mode 2)")
    p.add_argument("--variant", default="scalar_rgb")
    # Mode 1.
    p.add_argument("--scenes", default=os.path.join(os.path.dirname(__file__), "../../../shared/scenes"))
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--only", default=None, help="render only scenes whose path contains this text")
    # Mode 2.
    p.add_argument("--pathtrace", metavar="BIN", help="our binary (split like a shell command line)")
    p.add_argument("--runs", type=int, default=2, help="renders per renderer (different seeds), for the s.e.")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME=VALUE")
    p.add_argument("--digits", type=int, default=4, help="decimals printed for means (mode 2)")
    a = p.parse_args(argv)
    global DIGITS
    DIGITS = a.digits

    import numpy as np
    import mitsuba as mi

    mi.set_variant(a.variant)
    if a.scene is None:
        return reference_means(a, mi, np)
    import drjit as dr

    mi.set_log_level(mi.LogLevel.Error)
    dr.set_thread_count(a.threads)
    return compare(a, mi, np)


if __name__ == "__main__":
    sys.exit(main())
