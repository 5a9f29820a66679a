#!/usr/bin/env bash
# Re-makes the measured figures of docs/sampling.md: the Cornell-box convergence study, the
# balance-vs-power comparison on scenes/converge/veach-mis.toml and adaptive vs uniform sampling
# on the glass Cornell box. Each `converge` run writes its CSV, plots (SVG and PNG), table and
# reference into target/sampling-figures/NAME; the plots and renders are copied into docs/images/.
# The tables in docs/sampling.md are copied by hand from the printed tables.
# Usage: scripts/sampling-figures.sh   (from anywhere; builds the release binary first; ~10 minutes
# on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p pathtrace-cli
bin=${CARGO_TARGET_DIR:-target}/release/pathtrace
work=target/sampling-figures
img=docs/images
mkdir -p "$work" "$img"

copy_plots() { # converge output folder → docs/images/convergence-NAME-{spp,time}.{svg,png}
    for k in spp time; do
        for ext in svg png; do cp "$work/$1/error-vs-$k.$ext" "$img/convergence-$2-$k.$ext"; done
    done
}

"$bin" converge --size 128x128 --max-spp 256 --reference-spp 4096 --max-depth 8 \
    --strategies bsdf,mixture,mis --samplers independent,stratified,sobol -o "$work/cornell"
copy_plots cornell cornell

"$bin" render scenes/converge/veach-mis.toml --size 384x256 --spp 64 -o "$img/veach-mis.png" --quiet
"$bin" converge scenes/converge/veach-mis.toml --size 192x128 --max-spp 256 --reference-spp 4096 \
    --strategies bsdf,light,mis-balance,mis --samplers independent -o "$work/veach"
copy_plots veach veach-mis

"$bin" converge scenes/gallery/07-cornell-glass.toml --size 128x128 --max-spp 256 --reference-spp 4096 \
    --strategies mis --samplers independent,sobol --sampling uniform,adaptive -o "$work/glass"
copy_plots glass glass-adaptive
"$bin" render scenes/gallery/07-cornell-glass.toml --size 128x128 --spp 64 --seed 1 \
    -o "$img/adaptive-glass-uniform.png"
"$bin" render scenes/gallery/07-cornell-glass.toml --size 128x128 --spp 64 --seed 1 --adaptive \
    -o "$img/adaptive-glass-adaptive.png" --spp-image "$img/adaptive-glass-spp.png"
