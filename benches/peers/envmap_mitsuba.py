"""Checks pathtrace's environment-map conventions against Mitsuba 3: the museum map of the
shared matpreview scenes (its own to_world and scale 3), seen directly by a camera in several
directions (no surfaces in view, so only the map lookup and orientation matter).

    bash benches/peers/setup.sh
    .venv-peers/bin/python benches/peers/envmap_mitsuba.py --out /tmp/envmap-check

writes /tmp/envmap-check/view{K}.xml and prints Mitsuba's mean RGB per view; render the same
files with `pathtrace render /tmp/envmap-check/view{K}.xml --spp 64 -o /tmp/envmap-check/ours{K}.exr`
and compare the printed means (docs/sampling.md has the numbers). Nothing of Mitsuba's is kept.
"""
import argparse
import os

import mitsuba as mi
import numpy as np

VIEWS = [(0, 0, 1), (1, 0.2, 0.3), (-1, 0.5, -0.2), (0.2, -0.6, -1), (0.3, 1, 0.1)]

SCENE = """<scene version="3.0.0">
  <integrator type="path"/>
  <sensor type="perspective">
    <float name="fov" value="70"/>
    <transform name="to_world"><lookat origin="0, 0, 0" target="{tx}, {ty}, {tz}" up="{ux}, {uy}, {uz}"/></transform>
    <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
    <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="32"/>
      <rfilter type="box"/></film>
  </sensor>
  <emitter type="envmap">
    <string name="filename" value="{exr}"/>
    <transform name="to_world">
      <rotate y="1" angle="-180"/>
      <matrix value="-0.224951 -0.000001 -0.974370 0.000000 -0.974370 0.000000 0.224951 0.000000 0.000000 1.000000 -0.000001 8.870000 0.000000 0.000000 0.000000 1.000000 "/>
    </transform>
    <float name="scale" value="3"/>
  </emitter>
  <shape type="sphere"><point name="center" x="0" y="-1000" z="0"/><float name="radius" value="0.01"/></shape>
</scene>
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", default=os.path.join(os.path.dirname(__file__), "../../../shared/scenes"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--spp", type=int, default=64)
    a = ap.parse_args()
    mi.set_variant("scalar_rgb")
    exr = os.path.abspath(os.path.join(a.scenes, "matpreview/common/textures/museum.exr"))
    os.makedirs(a.out, exist_ok=True)
    for k, (tx, ty, tz) in enumerate(VIEWS):
        up = (0, 0, 1) if abs(ty) > 0.9 else (0, 1, 0)
        text = SCENE.format(tx=tx, ty=ty, tz=tz, ux=up[0], uy=up[1], uz=up[2], spp=a.spp, exr=exr)
        path = os.path.join(a.out, f"view{k}.xml")
        with open(path, "w") as f:
            f.write(text)
        img = np.array(mi.render(mi.load_file(path), seed=k))
        print(f"view{k} target ({tx}, {ty}, {tz}): Mitsuba mean {img.reshape(-1, img.shape[-1])[:, :3].mean(0)}")


if __name__ == "__main__":
    main()
