#!/usr/bin/env bash
# Every copy of the SIMD render loop in one release binary gives the same film, byte for byte:
# `--kernel wide` (32 lanes with AVX-512, else 16), `--kernel wide8` (the AVX2 kernel: 16 lanes),
# and with PATHTRACE_NO_AVX2=1 the portable 8-lane copy, each against `--kernel scalar` (one lane).
# `cargo test` cannot check this: builds with debug assertions compile only the portable copy
# (crates/pathtrace/src/render/tile.rs). Usage: benches/kernels_agree.sh BIN [SCENES_DIR]
# SCENES_DIR defaults to ../shared/scenes beside the repository. Exit 1 on any difference.
set -euo pipefail
bin=$1
scenes=${2:-$(cd "$(dirname "$0")/../.." && pwd)/shared/scenes}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail=0

# check NAME SCENE [render options...]
check() {
    local name=$1 scene=$2
    shift 2
    local common=(render "$scene" --spp 4 --seed 3 --threads 2 --quiet "$@")
    "$bin" "${common[@]}" --kernel scalar -o "$out/scalar.pfm" --film-out "$out/scalar.ptfilm" >/dev/null
    for variant in wide wide8 portable; do
        local kernel=$variant env=()
        if [ "$variant" = portable ]; then kernel=wide env=(PATHTRACE_NO_AVX2=1); fi
        env "${env[@]}" "$bin" "${common[@]}" --kernel "$kernel" -o "$out/$variant.pfm" \
            --film-out "$out/$variant.ptfilm" >/dev/null
        if cmp -s "$out/scalar.ptfilm" "$out/$variant.ptfilm" && cmp -s "$out/scalar.pfm" "$out/$variant.pfm"; then
            echo "same  $name $variant"
        else
            echo "DIFF  $name $variant (against --kernel scalar)"
            fail=1
        fi
    done
}

check cornell-box "$(dirname "$0")/../scenes/cornell-box.toml"
check cbox "$scenes/cbox/cbox.xml" --sampler sobol
check teapot "$scenes/teapot-simple/simple.xml" --sampler stratified --filter gaussian
check veach-mis "$scenes/veach-mis/docs/scenes/integrator_direct_both.xml"
check veach-mis-bitterli "$scenes/veach-mis-bitterli/scene_v3.xml"
check copper "$scenes/matpreview/docs/scenes/bsdf_roughconductor_copper.xml"
check bunny "$scenes/bunny/docs/scenes/shape_ply_bunny.xml"
exit $fail
