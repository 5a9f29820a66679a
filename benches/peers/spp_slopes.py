#!/usr/bin/env python3
"""Cost per sample of our renders and Mitsuba 3's, without the fixed costs.

Renders each scene at two sample counts with our binaries and with Mitsuba (`llvm_ad_rgb`),
interleaved round by round, and fits time = fixed + slope · spp through the two medians. The
slope, as core-nanoseconds per sample (× threads / pixels), is what the per-sample work costs:
the sampler, camera rays, traversal, shading and the film, without loading, the BVH build,
kernel compilation or output.

    .venv-peers/bin/python benches/peers/spp_slopes.py --scene teapot=../shared/scenes/teapot-simple/simple.xml \\
        --pathtrace old/pathtrace --pathtrace target/release/pathtrace --spp 64,256 --runs 7
"""

import argparse
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cornell_mitsuba as cm  # noqa: E402  (find_libllvm)
import suite_mitsuba as sm  # noqa: E402


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", action="append", required=True, metavar="LABEL=PATH", help="a scene (repeat)")
    p.add_argument("--pathtrace", action="append", required=True, metavar="BIN", help="our binary (repeat)")
    p.add_argument("--spp", default="64,256", help="the two sample counts")
    p.add_argument("--runs", type=int, default=5, help="interleaved rounds")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant timed")
    args = p.parse_args(argv)
    try:
        low, high = (int(v) for v in args.spp.split(","))
    except ValueError:
        p.error(f"--spp {args.spp!r}: give two sample counts, as in --spp 64,256")
    if not 0 < low < high:
        p.error(f"--spp {args.spp!r}: the counts must be positive and increasing (the fit needs two)")
    scenes = {}
    for s in args.scene:
        label, sep, path = s.partition("=")
        if not sep or not label or not path:
            p.error(f"--scene {s!r}: give LABEL=PATH, as in --scene teapot=../shared/scenes/teapot-simple/simple.xml")
        if not os.path.isfile(path):
            p.error(f"--scene {s!r}: {path}: no such file")
        scenes[label] = path
    for binary in args.pathtrace:
        if not os.access(binary, os.X_OK):
            p.error(f"--pathtrace {binary}: not an executable file")
    if "llvm" in args.variant and "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = cm.find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib
    import drjit as dr
    import mitsuba as mi
    import numpy as np

    tmp = tempfile.mkdtemp()
    peers = {label: sm.Mitsuba(mi, dr, args.variant, path, {}) for label, path in scenes.items()}
    for m in peers.values():  # compile and cache Mitsuba's kernels before timing
        for spp in (low, high):
            m.render(np, spp, 0)
    times = {}
    for r in range(args.runs):
        for label, path in scenes.items():
            for spp in (low, high):
                for k, binary in enumerate(args.pathtrace):
                    t, _ = sm.ours(np, binary, path, {}, spp, r, args.threads, tmp)
                    times.setdefault((f"pathtrace[{k}]", label, spp), []).append(t)
                t, _ = peers[label].render(np, spp, r)
                times.setdefault(("mitsuba", label, spp), []).append(t)
    print(f"{'renderer':14} {'scene':10} {'spp':>5} {'median s':>9}  runs")
    for (who, label, spp), ts in sorted(times.items()):
        print(f"{who:14} {label:10} {spp:5} {statistics.median(ts):9.4f}  " + " ".join(f"{t:.3f}" for t in ts))
    print(f"\n{'renderer':14} {'scene':10} {'fixed s':>8} {'ns/sample (core)':>17}")
    for who in [f"pathtrace[{k}]" for k in range(len(args.pathtrace))] + ["mitsuba"]:
        for label in scenes:
            m = peers[label]
            pixels = m.size[0] * m.size[1]
            a, b = (statistics.median(times[(who, label, s)]) for s in (low, high))
            slope = (b - a) / (high - low)
            print(f"{who:14} {label:10} {a - slope * low:8.4f} {slope * args.threads / pixels * 1e9:17.1f}")


if __name__ == "__main__":
    main()
