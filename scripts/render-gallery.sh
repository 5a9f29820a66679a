#!/usr/bin/env bash
# Renders every scene in scenes/gallery/ into docs/images/gallery/ and rewrites docs/gallery.md
# with each picture, the command that made it and the time it took.
# Usage: scripts/render-gallery.sh   (from anywhere; builds the release binary first)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=target/release/pathtrace
out=docs/images/gallery
mkdir -p "$out"
stats=$(mktemp)
trap 'rm -f "$stats"' EXIT

{
    echo "# Gallery"
    echo
    echo "The teaching sequence of the design document, as scene files in \`scenes/gallery/\`, rendered"
    echo "by \`scripts/render-gallery.sh\` on the project's 2-core machine (2 threads)."
    echo
} > docs/gallery.md.new

for scene in scenes/gallery/*.toml; do
    name=$(basename "$scene" .toml)
    image="$out/$name.png"
    "$bin" render "$scene" -o "$image" --quiet --stats-json "$stats"
    seconds=$(sed -n 's/.*"render_seconds": \([0-9.]*\).*/\1/p' "$stats")
    spp=$(sed -n 's/^  "spp": \([0-9]*\).*/\1/p' "$stats")
    size=$(sed -n 's/^  "width": \([0-9]*\).*/\1/p' "$stats")x$(sed -n 's/^  "height": \([0-9]*\).*/\1/p' "$stats")
    # The scene file's own comment says what the picture shows.
    caption=$(sed -n 's/^# \{0,1\}//p; /^$/q' "$scene" | tr '\n' ' ')
    {
        echo "## $name"
        echo
        echo "![$name](images/gallery/$name.png)"
        echo
        echo "$caption"
        echo
        echo "\`pathtrace render $scene -o $image\` — $size, $spp spp, $(printf '%.1f' "$seconds") s."
        echo
    } >> docs/gallery.md.new
    echo "rendered $image (${seconds}s)"
done
# Keep the hand-written sections (public scenes rendered with their own commands) after the marker.
marker='<!-- Sections below this line are written by hand'
if grep -q "$marker" docs/gallery.md; then
    echo >> docs/gallery.md.new
    sed -n "/$marker/,\$p" docs/gallery.md >> docs/gallery.md.new
fi
mv docs/gallery.md.new docs/gallery.md
