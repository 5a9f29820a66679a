"""Mean pixel value per channel of a Mitsuba 3 XML scene: Mitsuba 3 (scalar_rgb) vs pathtrace.

Renders the same XML file with both renderers at the same settings and prints the image means
(R, G, B), their ratio ours / Mitsuba, and a standard error of each mean estimated from
independent renders with different seeds (so "agrees within noise" can be judged).

    .venv-peers/bin/python benches/peers/scene_means.py SCENE.xml --pathtrace target/release/pathtrace \
        [--spp 256] [--runs 2] [-D name=value ...]

`-D name=value` sets a scene `<default>` for both (e.g. `-D resx=320 -D resy=180 -D integrator=path`).
Nothing of Mitsuba's is written to the repository: images go to a temporary directory.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import tempfile


def image_mean(np, img):
    a = np.array(img, dtype=np.float64)[..., :3]
    return a.reshape(-1, 3).mean(axis=0)


def mean_and_se(np, means):
    m = np.mean(means, axis=0)
    se = np.std(means, axis=0, ddof=1) / np.sqrt(len(means)) if len(means) > 1 else np.full(3, np.nan)
    return m, se


def fmt(v):
    return "(" + ", ".join(f"{x:.4f}" for x in v) + ")"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene")
    p.add_argument("--pathtrace", metavar="BIN", help="our binary (split like a shell command line)")
    p.add_argument("--spp", type=int, default=256, help="samples per pixel of each render")
    p.add_argument("--runs", type=int, default=2, help="renders per renderer (different seeds), for the s.e.")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME=VALUE")
    args = p.parse_args(argv)

    import numpy as np
    import mitsuba as mi
    import drjit as dr

    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    dr.set_thread_count(args.threads)
    defines = dict(d.split("=", 1) for d in args.defines)

    scene = mi.load_file(args.scene, **defines)
    theirs = []
    for run in range(args.runs):
        img = mi.render(scene, spp=args.spp, seed=run)
        theirs.append(image_mean(np, img))
    m, se = mean_and_se(np, theirs)
    print(f"mitsuba  scalar_rgb  {args.spp} spp x {args.runs}: mean {fmt(m)}  s.e. {fmt(se)}")

    if not args.pathtrace:
        return 0
    ours = []
    with tempfile.TemporaryDirectory() as tmp:
        for run in range(args.runs):
            out = os.path.join(tmp, f"ours{run}.exr")
            stats = os.path.join(tmp, f"stats{run}.json")
            cmd = shlex.split(args.pathtrace) + ["render", args.scene, "--spp", str(args.spp), "--seed", str(run + 1),
                                                 "--threads", str(args.threads), "--quiet",
                                                 "--stats-json", stats, "-o", out]
            for d in args.defines:
                cmd += ["-D", d]
            subprocess.run(cmd, check=True)
            bmp = mi.Bitmap(out).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
            ours.append(image_mean(np, bmp))
            seconds = json.load(open(stats)).get("render_seconds")
            print(f"pathtrace run {run}: {seconds:.1f} s")
    o, ose = mean_and_se(np, ours)
    print(f"pathtrace           {args.spp} spp x {args.runs}: mean {fmt(o)}  s.e. {fmt(ose)}")
    ratio = o / m
    z = (o - m) / np.sqrt(se ** 2 + ose ** 2)
    print(f"ours / mitsuba: {fmt(ratio)}   z: {fmt(z)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
