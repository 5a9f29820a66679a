"""Block means of a Mitsuba 3 render, with standard errors, for block-by-block z-tests.

Renders one XML scene (resized to SIZE x SIZE the way scene_means.py resizes, `<include>`s
inlined) RUNS times with different seeds, splits each image into BLOCK x BLOCK-pixel blocks and
prints, per block and channel, the mean over runs and its standard error (from the spread of the
runs), as Rust constants for crates/pathtrace-scene/tests/mitsuba_blocks.rs:

    .venv-peers/bin/python benches/peers/block_means.py bunny/docs/scenes/shape_ply_bunny.xml \
        --size 64 --block 8 --spp 512 --runs 16 --name BUNNY

Scene paths are relative to --scenes (default ../shared/scenes). `-D name=value` sets a scene
parameter. Nothing is written to disk.
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(__file__))
from scene_means import inline_includes  # noqa: E402


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene")
    p.add_argument("--scenes", default=os.path.join(os.path.dirname(__file__), "../../../shared/scenes"))
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--block", type=int, default=8)
    p.add_argument("--spp", type=int, default=512)
    p.add_argument("--runs", type=int, default=16)
    p.add_argument("--name", default="BLOCKS")
    p.add_argument("--variant", default="scalar_rgb")
    p.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME=VALUE")
    a = p.parse_args(argv)

    import numpy as np
    import mitsuba as mi

    mi.set_variant(a.variant)
    mi.set_log_level(mi.LogLevel.Error)
    path = os.path.abspath(os.path.join(a.scenes, a.scene))
    folder = os.path.dirname(path)
    text = inline_includes(open(path).read(), folder)
    for axis in ("width", "height"):
        text = re.sub(rf'(<integer\s+name="{axis}"\s+value=")[^"]*(")', rf"\g<1>{a.size}\g<2>", text)
    defines = dict(d.split("=", 1) for d in a.defines)
    mi.file_resolver().prepend(folder)
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        scene = mi.load_string(text, **defines)
    finally:
        os.chdir(cwd)
    n = a.size // a.block
    runs = []
    for seed in range(a.runs):
        img = np.array(mi.render(scene, spp=a.spp, seed=seed), dtype=np.float64)[..., :3]
        runs.append(img.reshape(n, a.block, n, a.block, 3).mean(axis=(1, 3)).reshape(-1, 3))
    runs = np.array(runs)
    mean = runs.mean(axis=0)
    se = runs.std(axis=0, ddof=1) / np.sqrt(a.runs)
    print(f"// {a.scene}: Mitsuba {mi.__version__} {a.variant}, {a.size}², {a.block}² blocks (row-major), "
          f"{a.runs} runs x {a.spp} spp; mean {mean.mean(axis=0)}")
    rows = lambda v: ",\n".join("    [" + ", ".join(f"{x:.6e}" for x in b) + "]" for b in v)
    print(f"const {a.name}_MEAN: [[f64; 3]; {n * n}] = [\n{rows(mean)},\n];")
    print(f"const {a.name}_SE: [[f64; 3]; {n * n}] = [\n{rows(se)},\n];")
    return 0


if __name__ == "__main__":
    sys.exit(main())
