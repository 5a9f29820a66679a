"""RGB (eta, k) of Fe and Ti, converted from measured spectra exactly as Mitsuba 3 converts its
own named conductors in RGB mode.

Mitsuba 3's data/ior folder has no iron or titanium. Their optical constants here are the
measurements of P. B. Johnson and R. W. Christy, "Optical constants of transition metals: Ti, V,
Cr, Mn, Fe, Co, Ni, and Pd", Phys. Rev. B 9, 5056-5070 (1974), as tabulated (wavelength in µm,
n, k; room temperature) in the refractiveindex.info database, files
database/data/main/Fe/nk/Johnson.yml and database/data/main/Ti/nk/Johnson.yml (public domain,
CC0). Only the numbers are used.

Method: the spectra are written as Mitsuba .spd files (wavelength in nm, value) under
TMP/data/ior/NAME.{eta,k}.spd, TMP is put first on Mitsuba's file resolver, and a `conductor`
with `material = NAME` is loaded in `scalar_rgb`: the same code path (complex_ior_from_file and its
spectrum-to-sRGB conversion) as benches/peers/metal_table.py uses for Mitsuba's own metals. To
show the path is the same, Mitsuba's own Cr spectra are first copied under a new name and must
give Cr's RGB values exactly. Run:
    .venv-peers/bin/python benches/peers/metal_table_jc.py
Its rows are the Fe and Ti entries of crates/pathtrace/src/material/metals.rs.
"""
import os
import shutil
import sys
import tempfile

import mitsuba as mi

# Johnson & Christy (1974): wavelength (µm), n, k.
FE = """
0.188 1.29 1.35
0.192 1.35 1.37
0.195 1.42 1.39
0.199 1.45 1.40
0.203 1.47 1.40
0.207 1.49 1.41
0.212 1.47 1.43
0.216 1.47 1.44
0.221 1.47 1.47
0.226 1.47 1.49
0.231 1.48 1.53
0.237 1.48 1.57
0.243 1.50 1.61
0.249 1.51 1.66
0.255 1.53 1.70
0.262 1.56 1.75
0.269 1.59 1.79
0.276 1.62 1.84
0.284 1.64 1.88
0.292 1.65 1.94
0.301 1.67 2.00
0.311 1.69 2.06
0.320 1.74 2.12
0.332 1.78 2.19
0.342 1.85 2.27
0.354 1.93 2.35
0.368 2.02 2.43
0.381 2.12 2.50
0.397 2.24 2.58
0.413 2.35 2.65
0.431 2.48 2.71
0.451 2.59 2.77
0.471 2.67 2.82
0.496 2.74 2.88
0.521 2.86 2.91
0.549 2.95 2.93
0.582 2.94 2.99
0.617 2.88 3.05
0.659 2.92 3.10
0.704 2.86 3.19
0.756 2.87 3.28
0.821 2.94 3.39
0.892 2.96 3.56
0.984 2.92 3.79
1.088 2.97 4.06
1.216 3.03 4.39
1.393 3.09 4.83
1.610 3.11 5.39
1.937 3.17 6.12
"""

TI = """
0.188 1.10 1.62
0.192 1.16 1.64
0.195 1.22 1.66
0.199 1.25 1.68
0.203 1.27 1.69
0.207 1.31 1.69
0.212 1.31 1.68
0.216 1.32 1.67
0.221 1.32 1.66
0.226 1.32 1.66
0.231 1.31 1.68
0.237 1.30 1.72
0.243 1.28 1.77
0.249 1.27 1.83
0.255 1.26 1.91
0.262 1.27 1.99
0.269 1.27 2.07
0.276 1.30 2.17
0.284 1.35 2.26
0.292 1.40 2.36
0.301 1.45 2.46
0.311 1.50 2.57
0.320 1.55 2.66
0.332 1.61 2.74
0.342 1.72 2.82
0.354 1.82 2.87
0.368 1.90 2.90
0.381 1.99 2.93
0.397 2.08 2.95
0.413 2.14 2.98
0.431 2.21 3.01
0.451 2.27 3.04
0.471 2.32 3.10
0.496 2.36 3.19
0.521 2.44 3.30
0.549 2.54 3.43
0.582 2.60 3.58
0.617 2.67 3.72
0.659 2.76 3.84
0.704 2.86 3.96
0.756 3.00 4.01
0.821 3.21 4.01
0.892 3.29 3.96
0.984 3.35 3.97
1.088 3.50 4.02
1.216 3.62 4.15
1.393 3.67 4.37
1.610 3.69 4.70
1.937 3.51 5.19
"""


def rgb(value):
    return [float(value[i]) for i in range(3)]


def conductor_rgb(name):
    params = mi.traverse(mi.load_dict({"type": "conductor", "material": name}))
    return rgb(params["eta.value"]), rgb(params["k.value"])


def write_spd(path, rows, column):
    with open(path, "w") as f:
        for lam_um, n, k in rows:
            f.write(f"{lam_um * 1000.0:.1f} {(n, k)[column]}\n")


def main():
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    tmp = tempfile.mkdtemp()
    try:
        ior = os.path.join(tmp, "data", "ior")
        os.makedirs(ior)
        mi.file_resolver().prepend(tmp)
        # Check: Mitsuba's own Cr under another name gives Cr's numbers.
        own = os.path.join(os.path.dirname(mi.__file__), "data", "ior")
        for part in ("eta", "k"):
            shutil.copy(os.path.join(own, f"Cr.{part}.spd"), os.path.join(ior, f"CrCopy.{part}.spd"))
        if conductor_rgb("CrCopy") != conductor_rgb("Cr"):
            print("the temporary-file path does not reproduce Mitsuba's Cr", file=sys.stderr)
            return 1
        print(f"# check: Cr via a copied .spd = Mitsuba's Cr {conductor_rgb('Cr')}", file=sys.stderr)
        for name, table in (("Fe", FE), ("Ti", TI)):
            rows = [tuple(float(x) for x in line.split()) for line in table.strip().splitlines()]
            write_spd(os.path.join(ior, f"{name}.eta.spd"), rows, 0)
            write_spd(os.path.join(ior, f"{name}.k.spd"), rows, 1)
            eta, k = conductor_rgb(name)
            print(f'    ("{name}", [{eta[0]:.6}, {eta[1]:.6}, {eta[2]:.6}], [{k[0]:.6}, {k[1]:.6}, {k[2]:.6}]),')
    finally:
        shutil.rmtree(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
