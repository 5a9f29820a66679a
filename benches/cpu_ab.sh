#!/bin/bash
# A/B of pathtrace builds on a busy machine: CPU seconds (user + system) of one render thread
# for HIGH spp minus LOW spp, so scene loading and the BVH build cancel out; builds alternate
# within each round.
#
#   benches/cpu_ab.sh SCENE LOW HIGH ROUNDS BINARY...
#   benches/cpu_ab.sh ../shared/scenes/teapot-simple/simple.xml 16 256 3 old/pathtrace target/release/pathtrace
set -euo pipefail
scene=$1 lo=$2 hi=$3 rounds=$4
shift 4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cpu() { # binary spp -> CPU seconds
    /usr/bin/time -o "$tmp/t" -f "%U %S" "$1" render "$scene" -D spp="$2" -o "$tmp/x.exr" --threads 1 >/dev/null 2>&1
    awk '{ print $1 + $2 }' "$tmp/t"
}
for _ in $(seq "$rounds"); do
    for b in "$@"; do
        echo "$b $(awk -v h="$(cpu "$b" "$hi")" -v l="$(cpu "$b" "$lo")" 'BEGIN { printf "%.2f", h - l }')"
    done
done
