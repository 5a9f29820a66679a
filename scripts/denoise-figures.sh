#!/usr/bin/env bash
# The pictures and error table of docs/denoising.md: the Cornell box at 256² rendered at 1, 4 and 16
# spp, noisy and denoised (Open Image Denoise with the albedo and normal buffers), its feature
# buffers, and each image's relative MSE against a 2048-spp reference (`pathtrace compare`).
# Needs a release build, OIDN_DIR (docs/denoising.md) and, to turn the EXR buffers into PNGs,
# Mitsuba's Python package (benches/peers: .venv-peers).
# Usage: scripts/denoise-figures.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BIN="${CARGO_TARGET_DIR:-target}/release/pathtrace"
PY="${PEERS_PYTHON:-.venv-peers/bin/python}"
OUT=docs/images/denoise
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"
common=(cornell-box --size 256x256 --quiet)
# The reference takes another seed: the noisy images' samples are not among its own.
"$BIN" render "${common[@]}" --seed 2 --spp 2048 -o "$TMP/ref.exr"
relmse() { "$BIN" compare "$1" "$TMP/ref.exr" --json | python3 -c 'import json,sys; print("%.5f" % json.load(sys.stdin)["relative_mse"])'; }
echo "| spp | relative MSE, noisy | relative MSE, denoised | ratio |"
echo "| ---: | ---: | ---: | ---: |"
for spp in 1 4 16; do
    "$BIN" render "${common[@]}" --seed 1 --spp "$spp" --denoise --keep-noisy -o "$OUT/cornell-${spp}spp.png"
    "$BIN" render "${common[@]}" --seed 1 --spp "$spp" --denoise --keep-noisy --aov albedo,normal -o "$TMP/cb-${spp}.exr"
    noisy=$(relmse "$TMP/cb-${spp}.noisy.exr")
    denoised=$(relmse "$TMP/cb-${spp}.exr")
    echo "| $spp | $noisy | $denoised | $(python3 -c "print(f'{$noisy/$denoised:.1f}x')") |"
done
mv "$OUT/cornell-4spp.noisy.png" "$OUT/cornell-4spp-noisy.png"
rm -f "$OUT"/cornell-1spp.noisy.png "$OUT"/cornell-16spp.noisy.png
"$BIN" render "${common[@]}" --seed 2 --spp 2048 -o "$OUT/cornell-reference.png"
# The 4-spp buffers as pictures: albedo as is, normals mapped from [-1, 1] to [0, 1].
"$PY" - "$TMP/cb-4.exr" "$OUT" <<'PYEOF'
import sys
import numpy as np
import mitsuba as mi
mi.set_variant("scalar_rgb")
bitmap = mi.Bitmap(sys.argv[1])
names = [f.name for f in bitmap.struct_()]
data = np.array(bitmap)
channel = lambda n: data[:, :, names.index(n)]
albedo = np.stack([channel("albedo." + c) for c in "RGB"], -1)
normal = np.stack([channel("N." + c) for c in "XYZ"], -1) * 0.5 + 0.5
for name, img in [("albedo", albedo), ("normal", normal)]:
    out = mi.Bitmap(np.ascontiguousarray(img, dtype=np.float32))
    out.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, name == "albedo").write(f"{sys.argv[2]}/cornell-4spp-{name}.png")
PYEOF
ls -la "$OUT"
