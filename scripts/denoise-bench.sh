#!/usr/bin/env bash
# The numbers of docs/denoising.md: the cost of the feature buffers (samples/s of the Cornell box at
# 512², 64 spp, with and without --aov, interleaved runs) and the time of the denoise step at 512²
# and 1920×1080. Needs a release build and Open Image Denoise (OIDN_DIR, see docs/denoising.md).
# Usage: scripts/denoise-bench.sh [RUNS]   (default 5)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN="${CARGO_TARGET_DIR:-target}/release/pathtrace"
RUNS="${1:-5}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
rate() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["samples_per_second"])' "$1"; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in $(seq "$RUNS"); do
    "$BIN" render cornell-box --size 512x512 --spp 64 --quiet -o "$TMP/plain.exr" --stats-json "$TMP/plain.json"
    rate "$TMP/plain.json" >> "$TMP/plain.txt"
    "$BIN" render cornell-box --size 512x512 --spp 64 --quiet --aov albedo,normal,depth -o "$TMP/aov.exr" \
        --stats-json "$TMP/aov.json"
    rate "$TMP/aov.json" >> "$TMP/aov.txt"
done
plain=$(median < "$TMP/plain.txt")
aov=$(median < "$TMP/aov.txt")
echo "cornell-box 512x512 64 spp, median of $RUNS: without --aov $plain samples/s, with --aov $aov samples/s" \
    "($(python3 -c "print(f'{100*(1-$aov/$plain):.1f}')")% slower)"
for size in 512x512 1920x1080; do
    for i in $(seq "$RUNS"); do
        "$BIN" render cornell-box --size "$size" --spp 4 --denoise -o "$TMP/d.exr" 2>&1 \
            | sed -n 's/.*denoised in \([0-9.]*\) s.*/\1/p' >> "$TMP/denoise-$size.txt"
    done
    echo "denoise step at $size, median of $RUNS: $(median < "$TMP/denoise-$size.txt") s"
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
