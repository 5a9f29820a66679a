#!/bin/bash
# A/B of pathtrace builds by their own `render_seconds` (loading and the BVH build excluded):
# one render thread, builds alternating within each round, the times of each build sorted.
#
#   benches/render_ab.sh SCENE SPP ROUNDS BINARY...
#   benches/render_ab.sh ../shared/scenes/cbox/cbox.xml 128 9 old/pathtrace target/release/pathtrace
set -euo pipefail
scene=$1 spp=$2 rounds=$3
shift 3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for _ in $(seq "$rounds"); do
    for b in "$@"; do
        "$b" render "$scene" --spp "$spp" --threads 1 -o "$tmp/x.exr" --quiet --stats-json "$tmp/s.json" >/dev/null 2>&1
        echo "$b $(python3 -c 'import json, sys; print(round(json.load(open(sys.argv[1]))["render_seconds"], 3))' "$tmp/s.json")"
    done
done | sort -k1,1 -k2,2n | awk '{ t[$1] = t[$1] " " $2 } END { for (b in t) print b ":" t[b] }'
