"""Mean pixel value per channel of the shared Mitsuba test scenes, rendered by Mitsuba 3.

The reference numbers in crates/pathtrace-scene/tests/mitsuba_means.rs come from this script:

    bash benches/peers/setup.sh
    .venv-peers/bin/python benches/peers/scene_means.py --size 64 --spp 4096

Each scene is loaded as written except for the film size (width and height are replaced in the
XML text, so `$res` defaults and fixed sizes alike become SIZE × SIZE) and the sample count
(`--spp`, through the sampler's `sample_count`). The scene's own integrator, depth, filter and
emitters are kept. Nothing is written to the scenes' folders.
"""
import argparse
import os
import re
import time

import mitsuba as mi
import numpy as np

SCENES = [
    "cbox/cbox.xml",
    "cornell-box-bitterli/scene_v3.xml",
    "teapot-simple/simple.xml",
    "cbox-classic/docs/scenes/integrator_depth_inf.xml",
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", default=os.path.join(os.path.dirname(__file__), "../../../shared/scenes"))
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", type=int, default=4096)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--variant", default="scalar_rgb")
    ap.add_argument("--only", default=None, help="render only scenes whose path contains this text")
    a = ap.parse_args()
    mi.set_variant(a.variant)
    for rel in SCENES:
        if a.only and a.only not in rel:
            continue
        path = os.path.abspath(os.path.join(a.scenes, rel))
        text = open(path).read()
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
        img = mi.render(scene, spp=a.spp, seed=a.seed)
        elapsed = time.time() - t0
        means = np.array(img, dtype=np.float64)[:, :, :3].mean(axis=(0, 1))
        print(f"{rel}: mean = [{means[0]:.5f}, {means[1]:.5f}, {means[2]:.5f}]  ({a.size}², {a.spp} spp, {elapsed:.1f} s)")


if __name__ == "__main__":
    main()
