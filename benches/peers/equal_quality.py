#!/usr/bin/env python3
"""Equal-quality comparison on the Cornell box: time to relative MSE 1e-2, Mitsuba 3 vs pathtrace.

Both renderers render the identical Cornell box (the scene of cornell_mitsuba.py) at the size of
the stored reference benches/references/cornell-d8.exr (rendered by `pathtrace bench
--make-references`, 8192 spp), max depth 8, box filter, with sample counts 1, 4, 16, 64, ...
(powers of 4 suit every Mitsuba sampler: stratified and multijitter want squares, ldsampler powers
of two). Each render's time (Mitsuba: the render call; pathtrace: its own render_seconds) and
relative MSE against the reference, mean over pixels and channels of (a - b)^2 / (b^2 + 0.01), give
a curve; the time at which it crosses the target is interpolated in log-log. Rounds interleave
every configuration so all see the same machine load; medians over rounds are reported with the
ratios "Mitsuba's best / ours" (> 1: we are faster).

    .venv-peers/bin/python benches/peers/equal_quality.py --pathtrace target/release/pathtrace

See docs/benchmarks.md for the measured numbers.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cornell_mitsuba as cm  # noqa: E402  (the scene, shared with the samples/s benchmark)

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def rel_mse(np, img, ref):
    """pathtrace's relative MSE (metrics/error.rs): mean of (a - b)^2 / (b^2 + 0.01)."""
    return float(np.mean((img - ref) ** 2 / (ref * ref + 0.01)))


def run_pathtrace(np, cmd, stats, out):
    """Runs a `pathtrace render` command that writes `--stats-json stats` and `-o out` (a PFM);
    returns its render_seconds and the image. Exits with its stderr if it fails."""
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"pathtrace failed: {' '.join(cmd)}\n{proc.stderr}")
    with open(stats) as fh:
        seconds = float(json.load(fh)["render_seconds"])
    return seconds, load_pfm(np, out)


def load_pfm(np, path):
    """A colour PFM as written by pathtrace: header, then rows bottom to top, little-endian f32."""
    with open(path, "rb") as fh:
        if fh.readline().strip() != b"PF":
            sys.exit(f"{path}: not a colour PFM")
        width, height = (int(v) for v in fh.readline().split())
        scale = float(fh.readline())
        data = np.frombuffer(fh.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1].astype(np.float64)


def crossing(curve, target):
    """Time at which (time, error) points first reach target, log-log interpolated; None if never."""
    for i, (t, e) in enumerate(curve):
        if e <= target:
            if i == 0:
                return t
            t0, e0 = curve[i - 1]
            if e0 <= e or t0 <= 0:
                return t
            f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e))
            return math.exp(math.log(t0) + f * (math.log(t) - math.log(t0)))
    return None


def timed_render(mi, dr, np, variant, scene, spp, seed):
    """Mitsuba's render call, timed until the image exists (llvm variants evaluate lazily):
    (seconds, linear RGB as float64, row 0 at the top)."""
    mi.set_variant(variant)
    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    if variant.startswith("llvm"):
        dr.eval(img)
        dr.sync_thread()
    seconds = time.perf_counter() - t0
    return seconds, np.array(img, dtype=np.float64)[:, :, :3]


class Mitsuba:
    def __init__(self, mi, dr, variant, sampler, args):
        self.mi, self.dr, self.variant, self.sampler = mi, dr, variant, sampler
        self.name = f"mitsuba {variant} {sampler}"
        mi.set_variant(variant)
        d = cm.scene_dict(mi, args.size, 1, args.max_depth, 0)
        d["sensor"]["sampler"] = {"type": sampler, "sample_count": 1}
        self.scene = mi.load_dict(d)

    def render(self, np, spp, seed, _tmp):
        return timed_render(self.mi, self.dr, np, self.variant, self.scene, spp, seed)


class Pathtrace:
    def __init__(self, binary, sampler, args, mi):
        self.binary, self.sampler, self.args, self.mi = binary, sampler, args, mi
        self.name = f"pathtrace {sampler}"

    def render(self, np, spp, seed, tmp):
        a = self.args
        # PFM, read by numpy alone: loading an EXR through mi.Bitmap wakes Dr.Jit's worker
        # threads, which keep spinning for a while and took the CPUs from our next render
        # (a 128x128, 16-spp render measured 0.034 s after an mi.Bitmap load instead of 0.023 s
        # back to back; docs/benchmarks.md).
        out, stats = os.path.join(tmp, "pt.pfm"), os.path.join(tmp, "pt.json")
        cmd = shlex.split(self.binary) + [
            "render", "cornell-box", "--size", f"{a.size}x{a.size}", "--spp", str(spp),
            "--max-depth", str(a.max_depth), "--strategy", "mis", "--sampler", self.sampler,
            "--filter", "box", "--threads", str(a.threads), "--seed", str(seed), "--quiet",
            "--stats-json", stats, "-o", out]
        return run_pathtrace(np, cmd, stats, out)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--pathtrace", required=True, metavar="BIN", help="our binary")
    p.add_argument("--reference", default=os.path.join(REPO, "benches/references/cornell-d8.exr"))
    p.add_argument("--variant", action="append", choices=cm.VARIANTS,
                   help="Mitsuba variant, repeatable (default: both)")
    p.add_argument("--mitsuba-samplers", default="independent,stratified,multijitter,ldsampler")
    p.add_argument("--samplers", default="independent,stratified,sobol", help="ours")
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--runs", type=int, default=3, help="interleaved rounds")
    p.add_argument("--target", type=float, default=1e-2, help="relative MSE to reach")
    p.add_argument("--max-spp", type=int, default=4096)
    args = p.parse_args(argv)
    variants = list(dict.fromkeys(args.variant or list(cm.VARIANTS)))
    if any(v.startswith("llvm") for v in variants) and "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = cm.find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib

    import numpy as np
    import drjit as dr
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Warn)
    dr.set_thread_count(args.threads)
    ref = cm.load_exr(mi, np, args.reference)[:, :, :3]
    if ref.shape[0] != ref.shape[1]:
        sys.exit("the reference must be square")
    args.size = ref.shape[0]
    print(f"mitsuba {mi.__version__}, {args.size}x{args.size}, max depth {args.max_depth}, "
          f"{args.threads} threads, target relative MSE {args.target:g}, reference {args.reference}")

    configs = [Mitsuba(mi, dr, v, s, args) for v in variants for s in args.mitsuba_samplers.split(",")]
    configs += [Pathtrace(args.pathtrace, s, args, mi) for s in args.samplers.split(",")]
    ladder = [4 ** k for k in range(16) if 4 ** k <= args.max_spp]
    times = {c.name: [] for c in configs}
    with tempfile.TemporaryDirectory(prefix="eq-") as tmp:
        for c in configs:  # warm-up: llvm compiles its kernels, files get cached
            c.render(np, 4, 0, tmp)
        for run in range(args.runs):
            for c in configs:
                curve = []
                for spp in ladder:
                    seconds, img = c.render(np, spp, 1000 * run + spp, tmp)
                    curve.append((seconds, rel_mse(np, img, ref)))
                    if curve[-1][1] < 0.5 * args.target:
                        break
                t = crossing(curve, args.target)
                times[c.name].append(t)
                pts = " ".join(f"{s}:{e:.3g}@{t_:.3f}s" for s, (t_, e) in zip(ladder, curve))
                shown = f"{t:.3f} s" if t is not None else "not reached"
                print(f"round {run + 1}/{args.runs} {c.name:<36} {shown:>12}   spp:relMSE@time {pts}")

    def med(name):
        ts = times[name]
        return statistics.median(ts) if ts and all(t is not None for t in ts) else None

    print()
    print(f"time to relative MSE {args.target:g} (median of {args.runs}):")
    for c in configs:
        m = med(c.name)
        print(f"  {c.name:<36} {('%.3f s' % m) if m else 'not reached':>12}   runs "
              + " ".join("%.3f" % t if t else "-" for t in times[c.name]))
    ours = {c.name: med(c.name) for c in configs if isinstance(c, Pathtrace) and med(c.name)}
    if not ours:
        return 1
    ours_best = min(ours, key=ours.get)
    for v in variants:
        theirs = {c.name: med(c.name) for c in configs
                  if isinstance(c, Mitsuba) and c.variant == v and med(c.name)}
        if theirs:
            best = min(theirs, key=theirs.get)
            print(f"equal-quality time ratio, {best} / {ours_best}: {theirs[best] / ours[ours_best]:.3f}"
                  f"  (ours / theirs = {ours[ours_best] / theirs[best]:.3f}; target <= 0.5)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
