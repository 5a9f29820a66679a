"""Throughput of pathtrace.distributed on a local Ray cluster (docs/distributed.md).

Measures, on the built-in Cornell box (default 256x256, 256 spp):
  local      pathtrace.render(threads=1)                         (one core, no Ray)
  ray-1      distributed.render on a 1-CPU local Ray cluster      (one single-threaded worker)
  ray-2      distributed.render on a 2-CPU local Ray cluster      (two single-threaded workers)
and prints ray-2 throughput / ray-1 throughput and ray-1 time / local time, checking every film
equals the local one bit for bit. Runs are interleaved (local, ray-1, ray-2, local, …) so a
change in machine load hits all three alike; medians are reported.

Run it in a loopback-only namespace, as the tests do:
  unshare -n sh -c 'ip link set lo up && RAY_AUTH_MODE=disabled python benches/distributed_throughput.py'
"""

from __future__ import annotations

import argparse
import statistics
import time

import ray

import pathtrace
from pathtrace import distributed


def timed(fn):
    t = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t


def ray_run(scene, cpus: int, chunks: int, options: dict):
    ray.init(num_cpus=cpus, include_dashboard=False, _node_ip_address="127.0.0.1", log_to_driver=False)
    try:
        # Start the workers and build the scene in them once, as a long-running farm would have.
        distributed.render(scene, chunks=cpus, **dict(options, spp=cpus, width=16, height=16))
        return timed(lambda: distributed.render(scene, chunks=chunks, **options))
    finally:
        ray.shutdown()


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--chunks", type=int, default=16)
    p.add_argument("--runs", type=int, default=3)
    a = p.parse_args()
    scene = pathtrace.builtin("cornell-box")
    options = dict(spp=a.spp, width=a.size, height=a.size, seed=0, threads=1)
    times = {"local": [], "ray-1": [], "ray-2": []}
    for run in range(a.runs):
        local, t = timed(lambda: pathtrace.render(scene, **options))
        times["local"].append(t)
        for cpus in (1, 2):
            film, t = ray_run(scene, cpus, a.chunks, options)
            assert film == local, "the distributed film differs from the local one"
            times[f"ray-{cpus}"].append(t)
        print(f"run {run + 1}: " + ", ".join(f"{k} {v[-1]:.2f} s" for k, v in times.items()), flush=True)
    med = {k: statistics.median(v) for k, v in times.items()}
    samples = a.size * a.size * a.spp
    for k, v in med.items():
        print(f"{k:6} median {v:.2f} s  ({samples / v / 1e6:.2f} M samples/s)")
    print(f"2 workers / 1 worker throughput: {med['ray-1'] / med['ray-2']:.2f}x")
    print(f"1-worker distributed time / local time: {med['ray-1'] / med['local']:.3f}")


if __name__ == "__main__":
    main()
