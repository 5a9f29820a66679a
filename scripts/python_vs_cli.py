#!/usr/bin/env python3
"""Times the Python module against the CLI on the same render, interleaved (CLI, Python, Python,
CLI, ...), and prints each time and the medians. Used for docs/python.md.

    python scripts/python_vs_cli.py --cli target/release/pathtrace --runs 7

Two measures for each side, scene loading excluded from the engine's:
- engine: the render session's own elapsed time (start to last tile), which the CLI writes to
  `--stats-json` (`render_seconds`) and Python reports in the last `Progress` it passes to
  the callback: the same clock on both sides;
- wall: the CLI process from exec to exit (start-up, scene build, render, PFM write) against the
  wall time of the `pathtrace.render(...)` call (start, wait, film copy);
- cpu: CPU seconds (user + system, all threads) of the CLI process against those this process
  spends in `pathtrace.render(...)`: insensitive to how much of a loaded machine each one got.
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import pathtrace


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", required=True, help="the pathtrace binary (a release build)")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--size", type=int, default=512)
    args = ap.parse_args()

    scene = pathtrace.builtin("cornell-box")
    cli_times, py_times, cli_wall, py_wall, cli_cpu, py_cpu = [], [], [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        stats, out = Path(tmp) / "stats.json", Path(tmp) / "out.pfm"
        size = f"{args.size}x{args.size}"

        def children_cpu() -> float:
            usage = resource.getrusage(resource.RUSAGE_CHILDREN)
            return usage.ru_utime + usage.ru_stime

        def run_cli() -> None:
            cpu = children_cpu()
            began = time.perf_counter()
            subprocess.run(
                [args.cli, "render", "cornell-box", "--spp", str(args.spp), "--size", size, "--quiet",
                 "-o", str(out), "--stats-json", str(stats)],
                check=True,
            )
            cli_wall.append(time.perf_counter() - began)
            cli_cpu.append(children_cpu() - cpu)
            cli_times.append(json.loads(stats.read_text())["render_seconds"])

        def run_python() -> None:
            last: list[pathtrace.Progress] = []
            cpu = time.process_time()
            began = time.perf_counter()
            pathtrace.render(scene, spp=args.spp, width=args.size, height=args.size, progress=last.append)
            py_wall.append(time.perf_counter() - began)
            py_cpu.append(time.process_time() - cpu)
            py_times.append(last[-1].elapsed)

        for run in range(args.runs):
            # Alternate which goes first, so a load that rises or falls in step does not favour one.
            for measure in (run_cli, run_python) if run % 2 == 0 else (run_python, run_cli):
                measure()
            print(
                f"run {run + 1}: engine CLI {cli_times[-1]:.3f} s, Python {py_times[-1]:.3f} s; "
                f"wall CLI process {cli_wall[-1]:.3f} s, Python render() {py_wall[-1]:.3f} s; "
                f"cpu CLI {cli_cpu[-1]:.3f} s, Python {py_cpu[-1]:.3f} s",
                flush=True,
            )
    for name, c, p in (("engine", cli_times, py_times), ("wall", cli_wall, py_wall), ("cpu", cli_cpu, py_cpu)):
        cm, pm = statistics.median(c), statistics.median(p)
        print(f"median of {args.runs} ({name}): CLI {cm:.3f} s, Python {pm:.3f} s, Python/CLI = {pm / cm:.3f}")


if __name__ == "__main__":
    main()
