"""Relative MSE per render of Mitsuba's samplers and ours, estimated from the spread over seeds
(no reference image): the mean over pixels and channels of the seeds' variance ÷ (mean² + 0.01),
the expected relMSE of one render (pathtrace's metric, without the bias term; mean² estimated
without the seeds' own noise).

    .venv-peers/bin/python benches/peers/seed_spread.py --pathtrace target/release/pathtrace \\
        ../shared/scenes/bunny/docs/scenes/shape_ply_bunny.xml --seeds 4 --spp 4,16 --max-depth 2,-1

Compares how each sampler's error falls with the sample count, for scenes whose files take a
`max_depth` define (`--max-depth` values are passed to both renderers as `-D max_depth=...`).
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cornell_mitsuba as cm  # noqa: E402  (find_libllvm)
import suite_mitsuba as sm  # noqa: E402


def spread(np, images):
    """The seeds' variance over an unbiased estimate of the true mean's square: the square of
    the seeds' mean exceeds it by var / K on average, which would read low for noisy renders."""
    a = np.stack(images)
    mean, var = a.mean(0), a.var(0, ddof=1)
    mean_sq = np.maximum(mean * mean - var / len(images), 0.0)
    return float((var / (mean_sq + 0.01)).mean())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene")
    p.add_argument("--pathtrace", required=True, metavar="BIN")
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--spp", default="4,16", help="comma-separated sample counts")
    p.add_argument("--max-depth", default="", help="comma-separated max_depth defines (none: the file's)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--mitsuba-samplers", default="independent,multijitter,ldsampler")
    p.add_argument("--samplers", default="independent,sobol")
    args = p.parse_args(argv)
    if args.seeds < 2:
        p.error("--seeds: at least 2 (the estimate is their variance)")
    if "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = cm.find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib
    import numpy as np
    import drjit as dr
    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    dr.set_thread_count(args.threads)
    with tempfile.TemporaryDirectory(prefix="spread-") as tmp:
        for depth in sm.split(args.max_depth) or [None]:
            defines = {} if depth is None else {"max_depth": depth}
            theirs = [(f"mitsuba {n}", sm.Mitsuba(mi, dr, "llvm_ad_rgb", args.scene, defines, n))
                      for n in sm.split(args.mitsuba_samplers)]
            for spp in (int(x) for x in sm.split(args.spp)):
                row = [(name, spread(np, [m.render(np, spp, s)[1] for s in range(args.seeds)])) for name, m in theirs]
                for name in sm.split(args.samplers):
                    images = [sm.ours(np, args.pathtrace, args.scene, defines, spp, s, args.threads, tmp,
                                      ["--sampler", name])[1] for s in range(args.seeds)]
                    row.append((f"ours {name}", spread(np, images)))
                print(f"max_depth {depth or 'of the file'}, {spp} spp: "
                      + "  ".join(f"{n} {e:.4f}" for n, e in row), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
