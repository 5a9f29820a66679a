#!/bin/bash
# A/B of pathtrace builds by their own `render_seconds` (loading and the BVH build excluded),
# one render thread (or --threads N), builds alternating within each round.
#
#   benches/render_ab.sh SCENE SPP ROUNDS BINARY...
#       each build's times, sorted
#   benches/render_ab.sh --paired SCENE SPP ROUNDS BINARY_A BINARY_B
#       both medians, and the median and quartiles of the per-round ratio B/A with the number of
#       rounds in which B was faster (a sign test: 29 of 41 is p ≈ 0.01 two-sided); the order of
#       the two alternates between rounds, so a slow spell of the machine hits both
#
#   --threads N (before the other arguments) renders on N threads instead of one, for changes
#   that only show when the threads share work (the suite renders on 2)
#
#   benches/render_ab.sh ../shared/scenes/cbox/cbox.xml 128 9 old/pathtrace target/release/pathtrace
#   benches/render_ab.sh --paired ../shared/scenes/teapot-simple/simple.xml 64 41 old/pathtrace target/release/pathtrace
set -euo pipefail
paired=0 threads=1
while [ $# -gt 0 ]; do
    case "$1" in
        --paired) paired=1; shift ;;
        --threads)
            [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || { echo "render_ab.sh: --threads needs a thread count (a positive integer)" >&2; exit 2; }
            threads=$2; shift 2 ;;
        *) break ;;
    esac
done
if [ $# -lt 4 ] || { [ $paired = 1 ] && [ $# -ne 5 ]; }; then
    sed -n '4,16p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
scene=$1 spp=$2 rounds=$3
shift 3
for b in "$@"; do
    [ -x "$b" ] || { echo "render_ab.sh: $b: not an executable file" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# One render's `render_seconds`.
seconds() {
    "$1" render "$scene" --spp "$spp" --threads "$threads" -o "$tmp/x.pfm" --quiet --stats-json "$tmp/s.json" >/dev/null 2>&1
    python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["render_seconds"])' "$tmp/s.json"
}
if [ $paired = 0 ]; then
    for _ in $(seq "$rounds"); do
        for b in "$@"; do
            echo "$b $(seconds "$b")"
        done
    done | awk '{ printf "%s %.3f\n", $1, $2 }' | sort -k1,1 -k2,2n | awk '{ t[$1] = t[$1] " " $2 } END { for (b in t) print b ":" t[b] }'
    exit
fi
A=$1 B=$2
for r in $(seq "$rounds"); do
    if [ $((r % 2)) = 0 ]; then a=$(seconds "$A"); b=$(seconds "$B"); else b=$(seconds "$B"); a=$(seconds "$A"); fi
    echo "$a $b"
done | python3 -c '
import sys, statistics as st
p = [tuple(map(float, l.split())) for l in sys.stdin]
a = [x for x, _ in p]; b = [y for _, y in p]; r = sorted(y / x for x, y in p)
n = len(r)
print(f"A median {st.median(a):.4f}  B median {st.median(b):.4f}  ratio B/A median {st.median(r):.3f}  "
      f"(quartiles {r[n // 4]:.3f}-{r[3 * n // 4]:.3f}, B faster in {sum(1 for x in r if x < 1)}/{n})")'
