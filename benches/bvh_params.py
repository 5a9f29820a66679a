#!/usr/bin/env python3
"""Leaf size and bin count of the SAH build, measured: runs `pathtrace bench bvh --json` for
each setting (round robin, so every setting sees the same machine load), and prints the
medians of build time, memory and single-thread rays/s (thread CPU time, `--cpu-time`) as a
Markdown table for docs/bvh.md.

    python3 benches/bvh_params.py --pathtrace target/release/pathtrace [--rounds 2]
"""

import argparse
import json
import shlex
import statistics
import subprocess
from collections import defaultdict

SETTINGS = [(4, 8), (8, 8), (16, 8), (32, 8), (16, 1), (16, 4), (16, 16)]  # (bins, max leaf)
METRICS = [
    ("build_sah_serial_ms", "build ms (1 thread)", 0),
    ("bytes_per_tri", "bytes/tri", 0),
    ("sah_incoherent_closest_1t", "incoherent Mrays/s", 2),
    ("sah_incoherent_any_1t", "incoherent any-hit Mrays/s", 2),
    ("sah_coherent_closest_1t", "camera Mrays/s", 2),
]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--pathtrace", default="target/release/pathtrace")
    p.add_argument("--rounds", type=int, default=2)
    p.add_argument("--scenes", default="sphere,bunny")
    # 10^5.5 = 316,228 triangles for the sphere, 4 × 69,451 = 277,804 for the bunny.
    p.add_argument("--size-args", default="--min-tris 2.5e5 --max-tris 3.2e5 --steps-per-decade 2")
    a = p.parse_args()
    results = defaultdict(list)  # (scene, triangles, bins, leaf, metric) -> values
    for _ in range(a.rounds):
        for bins, leaf in SETTINGS:
            cmd = shlex.split(a.pathtrace) + ["bench", "bvh", "--json", "--scenes", a.scenes, "--bins", str(bins),
                                              "--max-leaf", str(leaf), "--runs", "3", "--brute-max", "1", "--cpu-time"]
            cmd += shlex.split(a.size_args)
            out = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
            for row in out["rows"]:
                for m, _, _ in METRICS:
                    results[(row["scene"], row["triangles"], bins, leaf, m)].append(row[m])
    scenes = sorted({(k[0], k[1]) for k in results})
    print("| mesh | bins | max leaf | " + " | ".join(label for _, label, _ in METRICS) + " |")
    print("|---|---:|---:|" + "---:|" * len(METRICS))
    for scene, tris in scenes:
        for bins, leaf in SETTINGS:
            cells = []
            for m, _, prec in METRICS:
                cells.append(f"{statistics.median(results[(scene, tris, bins, leaf, m)]):.{prec}f}")
            print(f"| {scene} {tris} | {bins} | {leaf} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
