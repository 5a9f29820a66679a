#!/usr/bin/env python3
"""Any Mitsuba 3 scene files, timed against Mitsuba 3 and compared by image mean: a screen for
scenes the suite (suite_mitsuba.py) does not hold.

Issue 14 asks that scenes we do not have be rendered and timed the way the suite's are. This
renders each given file (or every *.xml directly inside a given folder) as it is, at its own film
size, integrator and filter, with only the sample count set, `--runs` interleaved rounds of one
Mitsuba render and one of ours (different seeds per round, the same seed for both):

- speed: Mitsuba's render call after a warm-up render (its llvm variant compiles kernels on first
  use) against our own `render_seconds`, medians over the rounds; the ratio is Mitsuba's time ÷
  ours (above 1: we are faster);
- agreement: the mean over the image and its channels, ours ÷ Mitsuba's, and a z-score of the
  difference from the spread of the rounds' means (with `--runs` ≥ 2). Means only: a screen, not
  the per-block z-tests of the scene tests;
- our warnings: a scene that uses a plugin we skip or replace (a projector emitter, a curve, a
  polarised BSDF) prints a located warning. Its image is not Mitsuba's, and it is left out of the
  summary's speed ratios and disagreements.

A file Mitsuba cannot load as it is (most need a folder the docs' own script adds to its file
resolver) is reported and skipped; so is a file we refuse, with our error.

    bash benches/peers/setup.sh --llvm
    .venv-peers/bin/python benches/peers/screen_mitsuba.py --pathtrace target/release/pathtrace \\
        --spp 4 --runs 2 path/to/mitsuba-data/docs/scenes

The summary line gives the geometric mean and the least of the speed ratios, and the files whose
means differ by more than `--z` standard errors.
"""

from __future__ import annotations

import argparse
import glob
import json
import math
import os
import shlex
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cornell_mitsuba as cm  # noqa: E402  (find_libllvm)
from equal_quality import load_pfm  # noqa: E402
from suite_mitsuba import Mitsuba  # noqa: E402


def scene_files(paths):
    """(label, path) of the files named (labelled as given) and of the *.xml files directly inside
    the folders named (labelled by file name), sorted per folder."""
    out = []
    for p in paths:
        if os.path.isdir(p):
            out += [(os.path.basename(f), f) for f in sorted(glob.glob(os.path.join(p, "*.xml")))]
        else:
            out.append((p, p))
    return out


def ours(np, binary, path, spp, seed, threads, tmp):
    """One render of ours: (render_seconds, image, warnings) or an error message."""
    out, stats = os.path.join(tmp, "pt.pfm"), os.path.join(tmp, "pt.json")
    cmd = shlex.split(binary) + ["render", path, "--spp", str(spp), "--seed", str(seed),
                                 "--threads", str(threads), "--quiet", "--stats-json", stats, "-o", out]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    if proc.returncode != 0:
        return next((ln for ln in lines if ln.startswith("error")), f"exit status {proc.returncode}")
    with open(stats) as fh:
        seconds = float(json.load(fh)["render_seconds"])
    return seconds, load_pfm(np, out), [ln for ln in lines if ln.startswith("warning")]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--pathtrace", required=True, metavar="BIN", help="our binary")
    p.add_argument("--spp", type=int, default=4, help="samples per pixel of every render")
    p.add_argument("--runs", type=int, default=2, help="interleaved rounds per file")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant timed")
    p.add_argument("--z", type=float, default=4.0, help="means further apart than this many "
                   "standard errors are listed as disagreeing")
    p.add_argument("paths", nargs="+", metavar="FILE_OR_FOLDER")
    args = p.parse_args(argv)
    if args.spp < 1 or args.runs < 1 or args.threads < 1:
        p.error("--spp, --runs and --threads must be positive")
    files = scene_files(args.paths)
    if not files:
        p.error("no scene files found")
    if "llvm" in args.variant and "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = cm.find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib
    import numpy as np
    import drjit as dr
    import mitsuba as mi
    mi.set_variant(args.variant)
    dr.set_thread_count(args.threads)
    print(f"mitsuba {mi.__version__} {args.variant} vs {args.pathtrace}, {args.spp} spp, "
          f"{args.threads} threads, {args.runs} rounds", flush=True)
    tmp = tempfile.mkdtemp()
    ratios, disagree, skipped = {}, [], []
    for name, path in files:
        try:
            theirs = Mitsuba(mi, dr, args.variant, path, {})
            theirs.render(np, args.spp, 1)
        except Exception as e:  # Mitsuba's loader raises RuntimeError and others
            skipped.append(name)
            print(f"{name}: Mitsuba cannot load it: {str(e).strip().splitlines()[-1][:160]}", flush=True)
            continue
        times_m, times_o, means_m, means_o, warnings, error = [], [], [], [], [], None
        for r in range(args.runs):
            seconds, img = theirs.render(np, args.spp, 2 + r)
            times_m.append(seconds)
            means_m.append(float(img.mean()))
            got = ours(np, args.pathtrace, path, args.spp, 2 + r, args.threads, tmp)
            if isinstance(got, str):
                error = got
                break
            seconds, img, warnings = got
            times_o.append(seconds)
            means_o.append(float(img.mean()))
        if error:
            skipped.append(name)
            print(f"{name}: we refuse it: {error}", flush=True)
            continue
        speed = statistics.median(times_m) / statistics.median(times_o)
        mean_m, mean_o = statistics.fmean(means_m), statistics.fmean(means_o)
        z = float("nan")
        if args.runs >= 2:
            se = math.hypot(statistics.stdev(means_m), statistics.stdev(means_o)) / math.sqrt(args.runs)
            z = (mean_o - mean_m) / se if se > 0 else (0.0 if mean_o == mean_m else math.inf)
        ratio = mean_o / mean_m if mean_m else float("nan")
        note = f"  {len(warnings)} warning(s), first: {warnings[0][:120]}" if warnings else ""
        print(f"{name}: Mitsuba {statistics.median(times_m):.3f} s, ours {statistics.median(times_o):.3f} s, "
              f"speed {speed:.2f}x; mean ours/Mitsuba {ratio:.4f} (z {z:+.1f}){note}", flush=True)
        if warnings:
            continue
        ratios[name] = speed
        if abs(z) > args.z:
            disagree.append(f"{name} ({ratio:.4f}, z {z:+.1f})")
    if ratios:
        geo = math.exp(statistics.fmean(math.log(v) for v in ratios.values()))
        low = min(ratios, key=ratios.get)
        print(f"\n{len(ratios)} files without warnings: speed geometric mean {geo:.2f}x, "
              f"least {ratios[low]:.2f}x ({low}); {sum(v < 1 for v in ratios.values())} below 1x")
    print(f"means beyond {args.z} standard errors: {', '.join(disagree) if disagree else 'none'}")
    print(f"not rendered by both: {len(skipped)}")


if __name__ == "__main__":
    main()
