#!/usr/bin/env python3
"""Stand-in for the pathtrace binary, to test cornell_mitsuba.py --pathtrace.

Accepts the benchmark's command line

    fake_pathtrace.py render cornell-box --size WxH --spp N --max-depth D
        --strategy mis --threads T --seed S --quiet --stats-json STATS.json -o OUT.exr

renders the box with Mitsuba (scalar_rgb) so that OUT.exr is a real image,
and writes STATS.json with the contract's fields. Not a benchmark of anything.
"""
import argparse
import json
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
try:
    import mitsuba as mi
except ImportError:  # re-run with the peers venv's interpreter
    py = os.path.join(here, "..", "..", ".venv-peers", "bin", "python")
    os.execv(py, [py, os.path.abspath(__file__)] + sys.argv[1:])

sys.path.insert(0, here)
import cornell_mitsuba  # noqa: E402

p = argparse.ArgumentParser()
p.add_argument("command", choices=["render"])
p.add_argument("scene", choices=["cornell-box"])
p.add_argument("--size", required=True)
p.add_argument("--spp", type=int, required=True)
p.add_argument("--max-depth", type=int, required=True)
p.add_argument("--strategy", required=True)
p.add_argument("--threads", type=int, required=True)
p.add_argument("--seed", type=int, required=True)
p.add_argument("--quiet", action="store_true")
p.add_argument("--stats-json", required=True)
p.add_argument("-o", dest="out", required=True)
a = p.parse_args()
w, h = (int(x) for x in a.size.split("x"))
assert w == h, "the fake renders square images only"

import drjit as dr  # noqa: E402
mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Warn)
dr.set_thread_count(a.threads)
scene = mi.load_dict(cornell_mitsuba.scene_dict(mi, w, a.spp, a.max_depth, a.seed + 1))
t0 = time.perf_counter()
img = mi.render(scene, spp=a.spp, seed=a.seed + 1)
seconds = time.perf_counter() - t0
mi.util.write_bitmap(a.out, img)
with open(a.stats_json, "w") as fh:
    json.dump({"width": w, "height": h, "spp": a.spp, "render_seconds": seconds,
               "samples_per_second": w * h * a.spp / seconds}, fh)
