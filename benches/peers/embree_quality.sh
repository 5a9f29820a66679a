#!/usr/bin/env bash
# Embree's BVH at build quality MEDIUM against HIGH (spatial splits; Mitsuba 3's choice) on the
# same triangles and rays, one thread: how much Mitsuba's mesh scenes gain from spatial splits.
#
#   benches/peers/bvh_embree_setup.sh        # once: .venv-embree with embreex's libembree4
#   benches/peers/embree_quality.sh [--pathtrace BIN] [--runs N] [--rays N] [MESH...]
#
# MESH: bunny, sphere or soup (exported by `BIN bench bvh --export`, 10⁶ triangles, its
# incoherent rays), or grid (the suite's mesh-1m grid with diffuse bounce rays:
# benches/peers/grid_export.py). Default: bunny grid. Prints embree_quality.c's JSON lines.
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=target/release/pathtrace runs=3 rays=1000000
meshes=()
while [ $# -gt 0 ]; do
    case "$1" in
        --pathtrace) bin=$2; shift 2 ;;
        --runs) runs=$2; shift 2 ;;
        --rays) rays=$2; shift 2 ;;
        -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        bunny|sphere|soup|grid) meshes+=("$1"); shift ;;
        *) echo "embree_quality.sh: unknown argument: $1 (see --help)" >&2; exit 2 ;;
    esac
done
[ ${#meshes[@]} -gt 0 ] || meshes=(bunny grid)
lib=$(find .venv-embree -name 'libembree4*.so*' 2>/dev/null | head -n1)
[ -n "$lib" ] || { echo "embree_quality.sh: no libembree4 in .venv-embree: run benches/peers/bvh_embree_setup.sh" >&2; exit 1; }
out=target/embree-quality
mkdir -p "$out"
gcc -O2 -Wall -Wextra benches/peers/embree_quality.c -o "$out/embree_quality" \
    -L"$(dirname "$lib")" -l:"$(basename "$lib")" -Wl,-rpath,"$(realpath "$(dirname "$lib")")"
for mesh in "${meshes[@]}"; do
    if [ "$mesh" = grid ]; then
        .venv-embree/bin/python benches/peers/grid_export.py "$out/grid.bin" --rays "$rays"
    else
        "$bin" bench bvh --export "$out/$mesh.bin" --scenes "$mesh" --max-tris 1e6 --rays "$rays" --runs 1 --threads 1 >/dev/null
    fi
    echo "# $mesh"
    "$out/embree_quality" "$out/$mesh.bin" "$runs"
done
