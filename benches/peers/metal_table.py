"""Print the RGB (eta, k) Mitsuba 3 uses for every named conductor in its RGB variants.

Mitsuba's RGB modes turn each tabulated spectrum (data/ior/*.spd) into one RGB colour when the
`conductor` plugin loads; this script loads a conductor per name in `scalar_rgb` and reads the
resulting eta/k back through `mi.traverse`. Its output is the table in
crates/pathtrace/src/material/metals.rs (regenerate with:
    .venv-peers/bin/python benches/peers/metal_table.py > /tmp/metals.txt).
"""
import os
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)  # out-of-gamut clamping notes would mix into the table

ior_dir = os.path.join(os.path.dirname(mi.__file__), "data", "ior")
names = sorted({f.split(".")[0] for f in os.listdir(ior_dir) if f.endswith(".eta.spd")})


def rgb(value):
    return [float(value[i]) for i in range(3)]


for name in names:
    try:
        bsdf = mi.load_dict({"type": "conductor", "material": name})
    except Exception as e:  # a name Mitsuba lists but refuses: report, keep going
        print(f"# {name}: {e}", file=sys.stderr)
        continue
    params = mi.traverse(bsdf)
    eta = rgb(params["eta.value"])
    k = rgb(params["k.value"])
    print(f'    ("{name}", [{eta[0]:.6}, {eta[1]:.6}, {eta[2]:.6}], [{k[0]:.6}, {k[1]:.6}, {k[2]:.6}]),')
