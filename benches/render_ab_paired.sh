#!/bin/bash
# Paired A/B of two pathtrace builds by their own `render_seconds`, one render thread: each round
# renders with both builds (the order alternating between rounds), so a slow spell of the machine
# hits both; prints both medians and the median and quartiles of the per-round ratio B/A, and in
# how many rounds B was faster (a sign test: 29 of 41 is p ≈ 0.01 two-sided).
#
#   benches/render_ab_paired.sh SCENE SPP ROUNDS BINARY_A BINARY_B
#   benches/render_ab_paired.sh ../shared/scenes/teapot-simple/simple.xml 64 41 old/pathtrace target/release/pathtrace
set -euo pipefail
scene=$1 spp=$2 rounds=$3 A=$4 B=$5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
t() { "$1" render "$scene" --spp "$spp" --threads 1 -o "$tmp/x.pfm" --quiet --stats-json "$tmp/s.json" >/dev/null 2>&1; python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["render_seconds"])' "$tmp/s.json"; }
for r in $(seq "$rounds"); do
  if [ $((r % 2)) = 0 ]; then a=$(t "$A"); b=$(t "$B"); else b=$(t "$B"); a=$(t "$A"); fi
  echo "$a $b"
done | python3 -c '
import sys, statistics as st
p=[tuple(map(float,l.split())) for l in sys.stdin]
a=[x for x,_ in p]; b=[y for _,y in p]; r=sorted(y/x for x,y in p)
n=len(r)
print(f"A median {st.median(a):.4f}  B median {st.median(b):.4f}  ratio B/A median {st.median(r):.3f}  (quartiles {r[n//4]:.3f}-{r[3*n//4]:.3f}, B faster in {sum(1 for x in r if x<1)}/{n})")'
