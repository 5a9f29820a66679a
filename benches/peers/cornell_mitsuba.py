#!/usr/bin/env python3
"""Side-by-side Cornell box benchmark: Mitsuba 3 versus pathtrace.

Builds pathtrace's Cornell box with Mitsuba's dict API (mi.load_dict), renders
it, reports samples/s (median over runs, render call only, after one warm-up),
image mean RGB and region means, and optionally runs our own binary
interleaved with Mitsuba so both see the same machine load.

Run with the interpreter of the venv made by benches/peers/setup.sh:

    .venv-peers/bin/python benches/peers/cornell_mitsuba.py --size 64 --spp 16

See benches/peers/README.md for the options and the reference means.
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
import time

VARIANTS = ("scalar_rgb", "llvm_ad_rgb")

# ---------------------------------------------------------------------------
# Scene description (must match pathtrace's `cornell-box` exactly)
# ---------------------------------------------------------------------------

RED = (0.65, 0.05, 0.05)
WHITE = (0.73, 0.73, 0.73)
GREEN = (0.12, 0.45, 0.15)
LIGHT_RADIANCE = (15.0, 15.0, 15.0)

# Parallelograms: (id, Q, u, v, material). Points are Q + a*u + b*v, a,b in
# [0,1]; the geometric normal is normalize(u x v).
QUADS = (
    ("green_wall", (555, 0, 0), (0, 555, 0), (0, 0, 555), "green"),
    ("red_wall", (0, 0, 0), (0, 555, 0), (0, 0, 555), "red"),
    ("floor", (0, 0, 0), (555, 0, 0), (0, 0, 555), "white"),
    ("ceiling", (555, 555, 555), (-555, 0, 0), (0, 0, -555), "white"),
    ("back_wall", (0, 0, 555), (555, 0, 0), (0, 555, 0), "white"),
    ("light", (343, 554, 332), (-130, 0, 0), (0, 0, -105), "black"),
)

# Axis-aligned boxes (0,0,0)-(size), rotated by angle (degrees) about +y, then
# translated. Rotation: x' = x cos t + z sin t, z' = -x sin t + z cos t.
BOXES = (
    ("tall_box", (165, 330, 165), 15.0, (265, 0, 295)),
    ("short_box", (165, 165, 165), -18.0, (130, 0, 65)),
)

CAMERA_FROM = (278, 278, -800)
CAMERA_AT = (278, 278, 0)
CAMERA_UP = (0, 1, 0)
CAMERA_VFOV = 40.0

# Regions for cross-checking renders, as fractions of (width, height) of the
# image, row 0 at the top: (name, expected shape id, x0, y0, x1, y1). Every
# primary ray through them hits the named shape (checked by --check).
REGIONS = (
    ("left wall", "green_wall", 0.06, 0.30, 0.16, 0.60),
    ("right wall", "red_wall", 0.84, 0.30, 0.94, 0.60),
    ("floor centre", "floor", 0.36, 0.88, 0.47, 0.97),
    ("ceiling light", "light", 0.43, 0.135, 0.57, 0.16),
    ("back wall", "back_wall", 0.35, 0.25, 0.65, 0.40),
)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(sum(c * c for c in a))
    return tuple(c / n for c in a)


def quad_to_world(mi, q, u, v):
    """Transform mapping Mitsuba's rectangle ([-1,1]^2 in z=0, normal +z) onto
    the parallelogram Q + a*u + b*v, with the normal along u x v."""
    n = normalize(cross(u, v))
    c = tuple(q[i] + 0.5 * u[i] + 0.5 * v[i] for i in range(3))
    m = [
        [0.5 * u[0], 0.5 * v[0], n[0], c[0]],
        [0.5 * u[1], 0.5 * v[1], n[1], c[1]],
        [0.5 * u[2], 0.5 * v[2], n[2], c[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
    return mi.ScalarTransform4f(m)


def box_to_world(mi, size, angle_deg, offset):
    """Mitsuba's cube is [-1,1]^3: scale/shift it to (0,0,0)-(size), rotate
    about +y, translate. Mitsuba's rotate() is right-handed, so rotate(+y, t)
    maps x' = x cos t + z sin t, z' = -x sin t + z cos t (checked by --check)."""
    half = [0.5 * s for s in size]
    T = mi.ScalarTransform4f
    return (T().translate(list(offset))
            .rotate([0, 1, 0], angle_deg)
            .translate(half)
            .scale(half))


def scene_dict(mi, size, spp, max_depth, seed):
    def lambert(rgb):
        # Our renderer shades both sides; Mitsuba's `diffuse` is one-sided.
        return {"type": "twosided",
                "bsdf": {"type": "diffuse",
                         "reflectance": {"type": "rgb", "value": list(rgb)}}}

    materials = {"red": RED, "white": WHITE, "green": GREEN, "black": (0.0, 0.0, 0.0)}
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": int(max_depth)},  # rr_depth: default (5)
        "sensor": {
            "type": "perspective",
            "fov": CAMERA_VFOV,
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=list(CAMERA_FROM), target=list(CAMERA_AT), up=list(CAMERA_UP)),
            "sampler": {"type": "independent", "sample_count": int(spp), "seed": int(seed)},
            "film": {
                "type": "hdrfilm",
                "width": int(size),
                "height": int(size),
                "pixel_format": "rgb",
                "component_format": "float32",
                "rfilter": {"type": "box"},
            },
        },
    }
    for name in materials:
        d["mat_" + name] = dict(lambert(materials[name]), id="mat_" + name)
    for name, q, u, v, mat in QUADS:
        shape = {"type": "rectangle", "to_world": quad_to_world(mi, q, u, v),
                 "bsdf": {"type": "ref", "id": "mat_" + mat}}
        if name == "light":
            # One-sided: emits on the side of the shape normal (u x v = -y).
            shape["emitter"] = {"type": "area",
                                "radiance": {"type": "rgb", "value": list(LIGHT_RADIANCE)}}
        d[name] = shape
    for name, size3, angle, offset in BOXES:
        d[name] = {"type": "cube", "to_world": box_to_world(mi, size3, angle, offset),
                   "bsdf": {"type": "ref", "id": "mat_white"}}
    return d


# ---------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------

def find_libllvm():
    for pattern in ("/usr/lib/llvm-19/lib/libLLVM*.so*",
                    "/usr/lib/*-linux-gnu/libLLVM-19*.so*",
                    "/usr/lib/*-linux-gnu/libLLVM.so.19*"):
        hits = sorted(glob.glob(pattern))
        if hits:
            return hits[0]
    return None


def region_pixels(region, width, height):
    _, _, fx0, fy0, fx1, fy1 = region
    x0, x1 = round(fx0 * width), round(fx1 * width)
    y0, y1 = round(fy0 * height), round(fy1 * height)
    return x0, y0, max(x1, x0 + 1), max(y1, y0 + 1)


def rgb_str(rgb):
    return "(" + ", ".join(f"{c:.4f}" for c in rgb) + ")"


def image_report(np, img, label):
    h, w = img.shape[:2]
    print(f"{label}: {w}x{h}, mean RGB {rgb_str(img.reshape(-1, 3).mean(axis=0))}")
    for region in REGIONS:
        x0, y0, x1, y1 = region_pixels(region, w, h)
        px = img[y0:y1, x0:x1, :].reshape(-1, 3)
        # Upper bound on the mean's Monte Carlo standard error: the spread of
        # pixel values also holds real shading variation across the region.
        se = px.std(axis=0, ddof=1) / np.sqrt(len(px)) if len(px) > 1 else px[0] * 0
        print(f"  {region[0]:<14} x[{x0},{x1}) y[{y0},{y1}) mean RGB {rgb_str(px.mean(axis=0))}"
              f"  (s.e. <= {max(se):.4f})")


def orientation_report(np, img):
    """Left third vs right third of the walls' rows: green must be on the left."""
    h, w = img.shape[:2]
    band = img[int(0.3 * h):int(0.6 * h)]
    left = band[:, : max(1, int(0.15 * w))].reshape(-1, 3).mean(axis=0)
    right = band[:, w - max(1, int(0.15 * w)):].reshape(-1, 3).mean(axis=0)
    ok = left[1] > left[0] and right[0] > right[1]
    print(f"orientation: left columns mean {rgb_str(left)}, right columns mean {rgb_str(right)}"
          f" -> {'green left / red right (matches pathtrace)' if ok else 'MISMATCH'}")
    return ok


def load_exr(mi, np, path):
    bmp = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32,
                                  srgb_gamma=False)
    return np.array(bmp, dtype=np.float64)


# ---------------------------------------------------------------------------
# Self-check of the scene construction (scalar variant, ray casting)
# ---------------------------------------------------------------------------

def self_check(mi, np, size):
    mi.set_variant("scalar_rgb")
    ok = True

    def report(cond, msg):
        nonlocal ok
        ok &= bool(cond)
        print(f"  [{'ok' if cond else 'FAIL'}] {msg}")

    print("self-check (scalar_rgb, ray casting):")
    # Rotation convention.
    for angle in (15.0, -18.0):
        t = math.radians(angle)
        p = mi.ScalarTransform4f().rotate([0, 1, 0], angle) @ mi.ScalarPoint3f(1.0, 2.0, 3.0)
        want = (1 * math.cos(t) + 3 * math.sin(t), 2.0, -1 * math.sin(t) + 3 * math.cos(t))
        report(max(abs(p[i] - want[i]) for i in range(3)) < 1e-4,
               f"rotate(+y, {angle:+g}) maps (1,2,3) to {tuple(round(c, 4) for c in p)}, want "
               f"{tuple(round(c, 4) for c in want)}")

    # optimize=False keeps every shape separate (by default Mitsuba merges
    # meshes sharing a BSDF, which the timed renders keep).
    scene = mi.load_dict(scene_dict(mi, size, 1, 8, 0), optimize=False)
    shapes = {s.id(): s for s in scene.shapes()}
    report(sorted(shapes) == sorted([q[0] for q in QUADS] + [b[0] for b in BOXES]),
           f"shapes {sorted(shapes)}")

    # Quads: corners, and geometric normal = normalize(u x v).
    for name, q, u, v, _ in QUADS:
        n_want = normalize(cross(u, v))
        # Aim from a point 1 unit off the quad's centre (on the -n side) at it.
        c = [q[i] + 0.37 * u[i] + 0.61 * v[i] for i in range(3)]
        o = [c[i] - 2.0 * n_want[i] for i in range(3)]
        ray = mi.Ray3f(mi.ScalarPoint3f(o), mi.ScalarVector3f(n_want))
        si = shapes[name].ray_intersect(ray)
        hit = bool(si.is_valid())
        n = si.n if hit else (0, 0, 0)
        p = si.p if hit else (0, 0, 0)
        report(hit and abs(si.t - 2.0) < 1e-3 and sum(n[i] * n_want[i] for i in range(3)) > 0.9999
               and max(abs(p[i] - c[i]) for i in range(3)) < 1e-2,
               f"{name}: hit at Q+0.37u+0.61v, normal {tuple(round(x, 4) for x in n)} "
               f"= normalize(u x v) {n_want}")
        # Just outside the parallelogram must miss.
        c2 = [q[i] + 1.01 * u[i] + 0.5 * v[i] for i in range(3)]
        o2 = [c2[i] - 2.0 * n_want[i] for i in range(3)]
        si2 = shapes[name].ray_intersect(mi.Ray3f(mi.ScalarPoint3f(o2), mi.ScalarVector3f(n_want)))
        report(not si2.is_valid(), f"{name}: misses just outside edge u")

    # Boxes: rays straight down near each corner of the rotated footprint hit
    # the box top at its height; rays just outside the footprint miss the box.
    for name, size3, angle, offset in BOXES:
        t = math.radians(angle)
        for (a, b) in ((0.05, 0.05), (0.95, 0.05), (0.05, 0.95), (0.95, 0.95)):
            for inside in (True, False):
                if inside:
                    lx, lz = size3[0] * a, size3[2] * b
                else:  # 3 units outside the corner, diagonally
                    lx = -3.0 if a < 0.5 else size3[0] + 3.0
                    lz = -3.0 if b < 0.5 else size3[2] + 3.0
                x = lx * math.cos(t) + lz * math.sin(t) + offset[0]
                z = -lx * math.sin(t) + lz * math.cos(t) + offset[2]
                # Start below the ceiling; meshes are intersected via the scene.
                ray = mi.Ray3f(mi.ScalarPoint3f(x, 550.0, z), mi.ScalarVector3f(0, -1, 0))
                si = scene.ray_intersect(ray)
                hit = bool(si.is_valid()) and si.shape.id() == name
                if inside:
                    report(hit and abs(si.p[1] - size3[1]) < 1e-2,
                           f"{name}: top hit above local ({lx:.1f},{lz:.1f})")
                else:
                    report(not hit, f"{name}: miss outside local ({lx:.1f},{lz:.1f})")

    # Camera: orientation and regions. Film position (0,0) is the top-left.
    sensor = scene.sensors()[0]

    def shape_at(fx, fy):
        ray, _ = sensor.sample_ray(0.0, 0.5, mi.ScalarPoint2f(fx, fy), mi.ScalarPoint2f(0.5, 0.5))
        si = scene.ray_intersect(ray)
        return si.shape.id() if si.is_valid() else None

    report(shape_at(0.5, 0.3) == "back_wall", "centre column, upper third sees the back wall")
    report(shape_at(0.42, 0.5) == "tall_box", "tall box left of centre")
    report(shape_at(0.62, 0.8) == "short_box", "short box right of centre, low")
    report(shape_at(0.1, 0.45) == "green_wall", "left of image sees the GREEN wall (x=555)")
    report(shape_at(0.9, 0.45) == "red_wall", "right of image sees the RED wall (x=0)")
    report(shape_at(0.5, 0.05) == "ceiling", "top of image sees the ceiling")
    # The RTIOW camera: w = normalize(from - at), u = normalize(up x w), v = w x u;
    # image x along +u, image y (downwards) along -v. Compare ray directions.
    f = CAMERA_FROM
    w_ = normalize(tuple(CAMERA_FROM[i] - CAMERA_AT[i] for i in range(3)))
    u_ = normalize(cross(CAMERA_UP, w_))
    v_ = cross(w_, u_)
    half_h = math.tan(math.radians(CAMERA_VFOV) / 2)
    worst = 0.0
    for fx, fy in ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.3, 0.8), (0.5, 0.5)):
        sx, sy = (2 * fx - 1) * half_h, (1 - 2 * fy) * half_h
        want = normalize(tuple(sx * u_[i] + sy * v_[i] - w_[i] for i in range(3)))
        ray, _ = sensor.sample_ray(0.0, 0.5, mi.ScalarPoint2f(fx, fy), mi.ScalarPoint2f(0.5, 0.5))
        worst = max(worst, max(abs(ray.d[i] - want[i]) for i in range(3)),
                    max(abs(ray.o[i] - f[i]) for i in range(3)) / 1000)
    report(worst < 1e-4, f"primary rays match the RTIOW camera (max deviation {worst:.2e})")

    for region in REGIONS:
        rname, sid = region[0], region[1]
        x0, y0, x1, y1 = region_pixels(region, size, size)
        bad = 0
        total = 0
        for py in range(y0, y1):
            for px in range(x0, x1):
                for dx, dy in ((0.01, 0.01), (0.99, 0.01), (0.01, 0.99), (0.99, 0.99), (0.5, 0.5)):
                    total += 1
                    bad += shape_at((px + dx) / size, (py + dy) / size) != sid
        report(bad == 0, f"region {rname!r} x[{x0},{x1}) y[{y0},{y1}) at {size}x{size}: "
                         f"{total - bad}/{total} primary rays hit {sid}")
    return ok


# ---------------------------------------------------------------------------
# Rendering and timing
# ---------------------------------------------------------------------------

class MitsubaRenderer:
    def __init__(self, mi, dr, variant, args):
        self.mi, self.dr, self.variant, self.args = mi, dr, variant, args
        mi.set_variant(variant)
        self.scene = mi.load_dict(scene_dict(mi, args.size, args.spp, args.max_depth, args.seed))

    def render(self, spp=None, seed=None):
        """Render and return (seconds of the render call, image)."""
        mi, dr = self.mi, self.dr
        mi.set_variant(self.variant)
        spp = self.args.spp if spp is None else spp
        seed = self.args.seed if seed is None else seed
        t0 = time.perf_counter()
        img = mi.render(self.scene, spp=spp, seed=seed)
        if self.variant.startswith(("llvm", "cuda")):
            dr.eval(img)
            dr.sync_thread()
        return time.perf_counter() - t0, img


class PathtraceRenderer:
    """Our binary, called per the benchmark contract; only its own
    render_seconds (from --stats-json) is used."""

    def __init__(self, binary, args, workdir):
        self.binary, self.args, self.workdir = binary, args, workdir
        self.last_exr = None
        self.count = 0

    def render(self):
        a = self.args
        self.count += 1
        stats = os.path.join(self.workdir, f"stats-{self.count}.json")
        out = os.path.join(self.workdir, f"pathtrace-{self.count}.exr")
        cmd = shlex.split(self.binary) + ["render", "cornell-box",
               "--size", f"{a.size}x{a.size}", "--spp", str(a.spp),
               "--max-depth", str(a.max_depth), "--strategy", "mis",
               "--threads", str(a.threads), "--seed", str(a.seed),
               "--quiet", "--stats-json", stats, "-o", out]
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if proc.returncode != 0:
            sys.exit(f"pathtrace failed (exit {proc.returncode}): {' '.join(cmd)}\n"
                     f"{proc.stdout}{proc.stderr}")
        try:
            with open(stats) as fh:
                s = json.load(fh)
        except (OSError, ValueError) as e:
            sys.exit(f"pathtrace: cannot read stats JSON {stats}: {e}")
        missing = [k for k in ("width", "height", "spp", "render_seconds", "samples_per_second")
                   if k not in s]
        if missing:
            sys.exit(f"pathtrace: stats JSON lacks {missing}: {s}")
        if (int(s["width"]), int(s["height"]), int(s["spp"])) != (a.size, a.size, a.spp):
            sys.exit(f"pathtrace: rendered {s['width']}x{s['height']} at {s['spp']} spp, "
                     f"asked for {a.size}x{a.size} at {a.spp} spp")
        seconds = float(s["render_seconds"])
        if not seconds > 0:
            sys.exit(f"pathtrace: bad render_seconds {seconds}")
        ours = a.size * a.size * a.spp / seconds
        theirs = float(s["samples_per_second"])
        if abs(theirs - ours) > 0.01 * ours:
            print(f"warning: pathtrace reports {theirs:.4g} samples/s but "
                  f"width*height*spp/render_seconds = {ours:.4g}", file=sys.stderr)
        if os.path.exists(out):
            self.last_exr = out
        return seconds


def fmt_rate(r):
    return f"{r / 1e6:.3f}"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--variant", action="append", choices=VARIANTS,
                   help="Mitsuba variant; give twice to run both (default scalar_rgb)")
    p.add_argument("--size", type=int, default=512, help="image width = height")
    p.add_argument("--spp", type=int, default=64, help="samples per pixel for timed runs")
    p.add_argument("--max-depth", type=int, default=8,
                   help="path segments (Mitsuba's max_depth: 1 = emitters only, 2 = direct)")
    p.add_argument("--threads", type=int, default=2, help="render threads (dr.set_thread_count)")
    p.add_argument("--runs", type=int, default=3, help="timed runs per renderer (0: no timing)")
    p.add_argument("--seed", type=int, default=0, help="sampler seed (same for every run)")
    p.add_argument("--out-exr", metavar="PATH",
                   help="write Mitsuba's image (reference render if --reference-spp, else "
                        "the last timed run); with two variants the variant is appended")
    p.add_argument("--pathtrace", metavar="BIN",
                   help="our binary (a command, split like a shell would), run interleaved "
                        "with Mitsuba; see fake_pathtrace.py for the contract")
    p.add_argument("--reference-spp", type=int, metavar="N",
                   help="render once more at N spp (untimed) for the means / --out-exr")
    p.add_argument("--compare-exr", metavar="PATH",
                   help="an EXR of ours to compare means with (default: pathtrace's last "
                        "output when --pathtrace is given)")
    p.add_argument("--check", action="store_true",
                   help="verify the scene construction, camera and regions by ray casting")
    p.add_argument("--verbose", action="store_true", help="keep Mitsuba's log output")
    args = p.parse_args(argv)
    variants = list(dict.fromkeys(args.variant or ["scalar_rgb"]))
    if args.size < 1 or args.spp < 1 or args.runs < 0 or args.threads < 1:
        p.error("size, spp and threads must be >= 1, runs >= 0")

    if any(v.startswith("llvm") for v in variants) and "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib  # read when the LLVM backend starts
        else:
            print("warning: no libLLVM 19 found (benches/peers/setup.sh --llvm); Dr.Jit will "
                  "try the system default, and LLVM 14 is known to abort", file=sys.stderr)

    import numpy as np
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(variants[0])
    if not args.verbose:
        mi.set_log_level(mi.LogLevel.Warn)
    dr.set_thread_count(args.threads)
    print(f"mitsuba {mi.__version__}, drjit {dr.__version__}, variants {', '.join(variants)}, "
          f"threads {dr.thread_count()}, {args.size}x{args.size}, {args.spp} spp, "
          f"max depth {args.max_depth}, seed {args.seed}"
          + (f", reference {args.reference_spp} spp" if args.reference_spp else "")
          + (f", DRJIT_LIBLLVM_PATH={os.environ['DRJIT_LIBLLVM_PATH']}"
             if "DRJIT_LIBLLVM_PATH" in os.environ else ""))

    if args.check and not self_check(mi, np, args.size):
        sys.exit("self-check FAILED")

    renderers = [MitsubaRenderer(mi, dr, v, args) for v in variants]
    times = {v: [] for v in variants}
    cpu = {v: [] for v in variants}
    images = {}
    ours_times = []
    with tempfile.TemporaryDirectory(prefix="peers-") as tmp:
        ours = PathtraceRenderer(args.pathtrace, args, tmp) if args.pathtrace else None
        if args.runs > 0:
            # Warm-up (the llvm variant compiles and caches its kernels here).
            for r in renderers:
                t, _ = r.render()
                print(f"warm-up mitsuba {r.variant}: {t:.3f} s")
            if ours:
                print(f"warm-up pathtrace: {ours.render():.3f} s")
            # Interleaved timed runs: each round runs every renderer once.
            for i in range(args.runs):
                for r in renderers:
                    c0 = time.process_time()
                    t, img = r.render()
                    cpu[r.variant].append((time.process_time() - c0) / t)
                    times[r.variant].append(t)
                    images[r.variant] = img
                    print(f"run {i + 1}/{args.runs} mitsuba {r.variant}: {t:.3f} s "
                          f"({fmt_rate(args.size ** 2 * args.spp / t)} M samples/s, "
                          f"~{cpu[r.variant][-1]:.1f} cores busy)")
                if ours:
                    t = ours.render()
                    ours_times.append(t)
                    print(f"run {i + 1}/{args.runs} pathtrace: {t:.3f} s "
                          f"({fmt_rate(args.size ** 2 * args.spp / t)} M samples/s)")

            n = args.size * args.size * args.spp
            rows = [("mitsuba", v, [n / t for t in times[v]]) for v in variants]
            if ours:
                rows.append(("pathtrace", "mis", [n / t for t in ours_times]))
            print()
            print(f"samples/s, {args.size}x{args.size}, {args.spp} spp, max depth "
                  f"{args.max_depth}, {args.threads} threads (M samples/s):")
            print(f"{'renderer':<10} {'variant':<12} {'median':>8}  runs")
            for name, var, rates in rows:
                print(f"{name:<10} {var:<12} {fmt_rate(statistics.median(rates)):>8}  "
                      + " ".join(fmt_rate(x) for x in rates))
            if ours:
                ours_med = statistics.median(rows[-1][2])
                for name, var, rates in rows[:-1]:
                    print(f"ratio pathtrace / mitsuba {var}: "
                          f"{ours_med / statistics.median(rates):.3f}")
            print()

        # Image statistics: reference render, else the last timed one.
        for r in renderers:
            if args.reference_spp or r.variant not in images:
                spp = args.reference_spp or args.spp
                t, img = r.render(spp=spp)
                print(f"mitsuba {r.variant} image render: {spp} spp in {t:.1f} s")
                images[r.variant] = img
        stats_spp = args.reference_spp or args.spp
        arrays = {}
        for v in variants:
            mi.set_variant(v)
            arr = np.array(images[v], dtype=np.float64)
            if arr.ndim != 3 or arr.shape[2] < 3:
                sys.exit(f"unexpected image shape {arr.shape}")
            arrays[v] = arr[:, :, :3]
            image_report(np, arrays[v], f"mitsuba {v} image ({stats_spp} spp)")
            orientation_report(np, arrays[v])
            if args.out_exr:
                path = args.out_exr
                if len(variants) > 1:
                    root, ext = os.path.splitext(path)
                    path = f"{root}-{v}{ext or '.exr'}"
                mi.util.write_bitmap(path, images[v])
                print(f"wrote {path}")

        compare = args.compare_exr or (ours.last_exr if ours else None)
        if compare:
            mi.set_variant(variants[0])
            theirs = arrays[variants[0]]
            mine = load_exr(mi, np, compare)[:, :, :3]
            print()
            image_report(np, mine, f"pathtrace image {compare}")
            if mine.shape != theirs.shape:
                print(f"note: sizes differ ({mine.shape[1]}x{mine.shape[0]} vs "
                      f"{theirs.shape[1]}x{theirs.shape[0]}); regions are in fractions of the image")
            print(f"{'region':<14} {'pathtrace mean RGB':<28} {'mitsuba mean RGB':<28} "
                  f"ratio pathtrace / mitsuba")
            regions = [("whole image", None)] + [(r[0], r) for r in REGIONS]
            for name, region in regions:
                def mean(a):
                    if region is None:
                        return a.reshape(-1, 3).mean(axis=0)
                    x0, y0, x1, y1 = region_pixels(region, a.shape[1], a.shape[0])
                    return a[y0:y1, x0:x1].reshape(-1, 3).mean(axis=0)
                m_ours, m_mi = mean(mine), mean(theirs)
                ratio = [a / b if b > 0 else float("nan") for a, b in zip(m_ours, m_mi)]
                print(f"{name:<14} {rgb_str(m_ours):<28} {rgb_str(m_mi):<28} {rgb_str(ratio)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
