#!/usr/bin/env python3
"""Our BVH against Embree on the same triangles and the same incoherent rays.

    benches/peers/bvh_embree_setup.sh                 # .venv-embree with embreex + numpy
    .venv-embree/bin/python benches/peers/bvh_embree.py --pathtrace target/release/pathtrace

Each run asks `pathtrace bench bvh --export FILE` to generate the mesh (default: the Stanford
bunny subdivided to 1.1M triangles), build its BVH, trace the incoherent rays on one thread
(closest hit) and write triangles, rays and its hit distances to FILE; then this script loads
the same triangles into Embree (embreex, one rtcIntersect1 per ray on one thread), times the
scene commit (the build) and the same rays, and checks that both agree on hit/miss and on t.
Runs alternate between the two so both see the same machine load; medians are printed with
the ratio ours / Embree. Nothing of Embree's is committed: it comes from PyPI into a venv.
"""

import argparse
import json
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

try:
    import embreex
    from embreex import rtcore_scene, mesh_construction
except ImportError:
    sys.exit("embreex is missing: run benches/peers/bvh_embree_setup.sh, then use .venv-embree/bin/python")


def read_export(path):
    """Triangles (T, 3, 3), origins (R, 3), directions (R, 3) and our distances (R,)."""
    raw = Path(path).read_bytes()
    if raw[:8] != b"PTBVHEX1":
        sys.exit(f"{path}: not a pathtrace BVH export")
    tris, rays = np.frombuffer(raw, dtype="<u8", count=2, offset=8)
    at = 24
    v = np.frombuffer(raw, dtype="<f4", count=int(tris) * 9, offset=at).reshape(-1, 3, 3)
    at += int(tris) * 36
    r = np.frombuffer(raw, dtype="<f4", count=int(rays) * 6, offset=at).reshape(-1, 6)
    at += int(rays) * 24
    t = np.frombuffer(raw, dtype="<f4", count=int(rays), offset=at)
    return v, np.ascontiguousarray(r[:, :3]), np.ascontiguousarray(r[:, 3:]), t


# CPU-time clocks by default (the machine is shared): the tracing thread's CPU time for rays,
# the whole process's CPU time for Embree's (multi-threaded) build. --wall uses wall clocks.
TRACE_CLOCK = time.thread_time
BUILD_CLOCK = time.process_time


def run_ours(cmd, mesh, tris, rays, out):
    args = cmd + ["bench", "bvh", "--export", str(out), "--scenes", mesh, "--max-tris", str(tris),
                  "--rays", str(rays), "--runs", "1", "--threads", "1"]
    if TRACE_CLOCK is time.thread_time:
        args.append("--cpu-time")
    done = subprocess.run(args, check=True, capture_output=True, text=True)
    return json.loads(done.stdout)


def run_embree(v, origins, dirs):
    scene = rtcore_scene.EmbreeScene()
    mesh_construction.TriangleMesh(scene, v.astype(np.float32))
    # embreex commits the scene (builds its BVH) on the first query.
    start = BUILD_CLOCK()
    scene.run(origins[:1], dirs[:1])
    build = BUILD_CLOCK() - start
    start = TRACE_CLOCK()
    scene.run(origins, dirs)
    trace = TRACE_CLOCK() - start
    t = scene.run(origins, dirs, output=1)["tfar"]
    return build, len(origins) / trace, np.where(np.isfinite(t) & (t < 1e30), t, np.inf)


def embree_call_rate(origins, dirs):
    """Rays/s of embreex on one triangle that every ray misses at the root: the cost of
    embreex's per-ray wrapping (array handling, one rtcIntersect1 call per ray), not of Embree's
    traversal. Reported so the ratio can be read both ways."""
    far = np.array([[[1e6, 1e6, 1e6], [1e6 + 1, 1e6, 1e6], [1e6, 1e6 + 1, 1e6]]], dtype=np.float32)
    scene = rtcore_scene.EmbreeScene()
    mesh_construction.TriangleMesh(scene, far)
    scene.run(origins[:1], dirs[:1])
    start = TRACE_CLOCK()
    scene.run(origins, dirs)
    return len(origins) / max(TRACE_CLOCK() - start, 1e-9)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--pathtrace", default="target/release/pathtrace", help="our binary (split like a shell line)")
    p.add_argument("--mesh", default="bunny", choices=["bunny", "sphere", "soup"])
    p.add_argument("--tris", default="1e6", help="triangle count (the bunny: the first 69,451·4^k ≥ it)")
    p.add_argument("--rays", default="1e6", help="incoherent rays")
    p.add_argument("--runs", type=int, default=3, help="alternating runs of each; medians are printed")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--wall", action="store_true", help="time by wall clocks instead of CPU time")
    a = p.parse_args()
    if a.wall:
        global TRACE_CLOCK, BUILD_CLOCK
        TRACE_CLOCK = BUILD_CLOCK = time.perf_counter

    cmd = shlex.split(a.pathtrace)
    ours_rate, ours_build, embree_rate, embree_build, call_rate = [], [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "bvh-export.bin"
        for run in range(a.runs):
            info = run_ours(cmd, a.mesh, a.tris, a.rays, out)
            ours_rate.append(info["closest_mrays_per_s_1t"] * 1e6)
            ours_build.append(info["build_ms"] / 1e3)
            v, origins, dirs, ours_t = read_export(out)
            build, rate, embree_t = run_embree(v, origins, dirs)
            embree_rate.append(rate)
            embree_build.append(build)
            call_rate.append(embree_call_rate(origins, dirs))
            print(f"run {run + 1}/{a.runs}: ours {ours_rate[-1] / 1e6:.3f} M rays/s, "
                  f"Embree {rate / 1e6:.3f} M rays/s", file=sys.stderr)

    ours_hit, embree_hit = np.isfinite(ours_t), np.isfinite(embree_t)
    both = ours_hit & embree_hit
    rel = np.abs(ours_t[both] - embree_t[both]) / np.maximum(np.abs(embree_t[both]), 1e-30)
    summary = {
        "embreex": getattr(embreex, "__version__", "?"),
        "mesh": a.mesh,
        "triangles": int(len(v)),
        "rays": int(len(origins)),
        "threads": 1,
        "hit_fraction_ours": float(ours_hit.mean()),
        "hit_fraction_embree": float(embree_hit.mean()),
        "hit_miss_agreement": float((ours_hit == embree_hit).mean()),
        "t_agreement_1e-4": float((rel <= 1e-4).mean()) if both.any() else 1.0,
        "ours_mrays_per_s": statistics.median(ours_rate) / 1e6,
        "embree_mrays_per_s": statistics.median(embree_rate) / 1e6,
        "ratio_ours_over_embree": statistics.median(ours_rate) / statistics.median(embree_rate),
        "embreex_call_overhead_mrays_per_s": statistics.median(call_rate) / 1e6,
        "embree_traversal_only_mrays_per_s": 1e-6
        / max(1 / statistics.median(embree_rate) - 1 / statistics.median(call_rate), 1e-12),
        "ours_build_s": statistics.median(ours_build),
        "embree_build_s": statistics.median(embree_build),
        "runs": a.runs,
        "clock": "wall" if a.wall else "cpu",
    }
    if a.json:
        print(json.dumps(summary, indent=2))
        return
    print(f"{summary['mesh']}: {summary['triangles']} triangles, {summary['rays']} incoherent rays, 1 thread, "
          f"median of {a.runs} alternating runs, {summary['clock']} time")
    print(f"hits: ours {summary['hit_fraction_ours']:.4f}, Embree {summary['hit_fraction_embree']:.4f}; "
          f"hit/miss agree on {summary['hit_miss_agreement']:.5f} of rays, "
          f"t within 1e-4 on {summary['t_agreement_1e-4']:.5f} of common hits")
    print(f"closest hit   ours {summary['ours_mrays_per_s']:.3f} M rays/s   Embree {summary['embree_mrays_per_s']:.3f} "
          f"M rays/s   ratio {summary['ratio_ours_over_embree']:.2f}")
    print(f"embreex alone (every ray misses one far triangle): {summary['embreex_call_overhead_mrays_per_s']:.3f} "
          f"M rays/s; Embree without that overhead: {summary['embree_traversal_only_mrays_per_s']:.3f} M rays/s, "
          f"ratio {summary['ours_mrays_per_s'] / summary['embree_traversal_only_mrays_per_s']:.2f}")
    print(f"build         ours {summary['ours_build_s']:.3f} s (our SAH, 1 thread)   "
          f"Embree {summary['embree_build_s']:.3f} s (its default build; CPU time summed over its threads)")


if __name__ == "__main__":
    main()
