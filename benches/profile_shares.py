#!/usr/bin/env python3
"""Shares of a `perf record` profile by function, counting inlined frames.

The render loop is one function after inlining (`render_tile_avx512`), so
`perf report --sort sym` puts nearly every sample there. This script maps each
sampled address of the binary through `addr2line -i` to its whole chain of
inlined frames and counts a sample towards every pattern that matches any frame
of its chain (inclusive shares: nested matches overlap).

    perf record -q -o prof.data -F 2000 target/release/pathtrace render SCENE \
        --spp 64 --threads 1 -o /tmp/x.exr --quiet
    benches/profile_shares.py prof.data target/release/pathtrace intersect_opaque occluded_opaque
    benches/profile_shares.py prof.data target/release/pathtrace --hot 30

Patterns are Python regular expressions searched in the demangled frame names.
`--hot N` lists the N most sampled innermost frames with their source lines; with
`--within PATTERN`, only those of samples whose chain has a frame matching PATTERN
(`--hot 25 --within surface_unless` breaks one inlined function down by line).
The binary must be the one recorded, with line tables (the release profile keeps them).
"""

import argparse
import collections
import os
import re
import subprocess


def sampled_addresses(data):
    """Counts of (address, object) samples, the objects' mappings, and the sample total."""
    script = subprocess.run(
        ["perf", "script", "-i", data, "-F", "ip,dso", "--show-mmap-events"],
        capture_output=True, text=True, check=True,
    ).stdout
    mappings = {}  # object path -> (mapped start, file offset)
    counts = collections.Counter()
    total = 0
    mmap = re.compile(r"\[(0x[0-9a-f]+)\((0x[0-9a-f]+)\) @ (0x[0-9a-f]+|0) .*?\]: [rx-]+p? (\S+)")
    for line in script.splitlines():
        if "PERF_RECORD_MMAP" in line:
            m = mmap.search(line)
            if m:
                mappings[m.group(4)] = (int(m.group(1), 16), int(m.group(3), 16))
            continue
        fields = line.split()
        if len(fields) < 2:
            continue
        total += 1
        counts[(int(fields[0], 16), fields[1].strip("()"))] += 1
    return counts, mappings, total


def text_bias(binary):
    """Virtual address minus file offset of the executable segment."""
    headers = subprocess.run(["readelf", "-lW", binary], capture_output=True, text=True, check=True).stdout
    for line in headers.splitlines():
        fields = line.split()
        if fields and fields[0] == "LOAD" and "R E" in line:
            return int(fields[2], 16) - int(fields[1], 16)
    return 0


def inline_chains(data, binary):
    """[(samples, [(function, file:line), innermost first])] for the binary's addresses,
    the sample counts of other objects, and the total."""
    counts, mappings, total = sampled_addresses(data)
    name = os.path.basename(os.path.realpath(binary))
    bias = text_bias(binary)
    own = collections.Counter()
    others = collections.Counter()
    for (ip, obj), n in counts.items():
        if os.path.basename(obj) == name and obj in mappings:
            start, offset = mappings[obj]
            own[ip - start + offset + bias] += n
        else:
            others[os.path.basename(obj)] += n
    addresses = sorted(own)
    lines = subprocess.run(
        ["addr2line", "-e", binary, "-a", "-i", "-f", "-C"],
        input="\n".join(hex(a) for a in addresses), capture_output=True, text=True, check=True,
    ).stdout.splitlines()
    chains = collections.defaultdict(list)
    current = None
    i = 0
    while i < len(lines):
        if lines[i].startswith("0x"):
            current = int(lines[i], 16)
            i += 1
            continue
        location = lines[i + 1] if i + 1 < len(lines) else ""
        chains[current].append((lines[i], location))
        i += 2
    return [(own[a], chains[a]) for a in addresses], others, total


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("data", help="perf.data file")
    parser.add_argument("binary", help="the profiled executable")
    parser.add_argument("patterns", nargs="*", help="regular expressions over frame names")
    parser.add_argument("--hot", type=int, default=0, help="list the N hottest innermost frames")
    parser.add_argument("--within", metavar="PATTERN", help="--hot counts only samples with a frame matching PATTERN")
    args = parser.parse_args()
    for path in (args.data, args.binary):
        if not os.path.isfile(path):
            raise SystemExit(f"{path}: no such file")
    patterns = []
    for pattern in args.patterns:
        try:
            patterns.append((pattern, re.compile(pattern)))
        except re.error as e:
            raise SystemExit(f"pattern {pattern!r}: {e}")
    try:
        samples, others, total = inline_chains(args.data, args.binary)
    except FileNotFoundError as e:
        raise SystemExit(f"{e.filename}: not installed (needs perf, readelf and addr2line)")
    except subprocess.CalledProcessError as e:
        raise SystemExit(f"{e.cmd[0]} failed on {args.data} / {args.binary}: {e.stderr.strip()}")
    if total == 0:
        raise SystemExit(f"{args.data}: no samples")
    for pattern, r in patterns:
        n = sum(c for c, chain in samples if any(r.search(f) for f, _ in chain))
        print(f"{100 * n / total:5.1f}% {pattern}")
    if args.hot:
        hot = collections.Counter()
        within = re.compile(args.within) if args.within else None
        for c, chain in samples:
            if chain and (within is None or any(within.search(f) for f, _ in chain)):
                function, location = chain[0]
                hot[f"{re.sub(r'<.*>', '<>', function)[:90]} @{os.path.basename(location)}"] += c
        for key, c in hot.most_common(args.hot):
            print(f"{100 * c / total:5.1f}% {key}")
        for obj, c in others.most_common(5):
            print(f"{100 * c / total:5.1f}% [{obj}]")


if __name__ == "__main__":
    main()
