#!/usr/bin/env bash
# Regenerates docs/images/viewer.png: the viewer window mid-render (8 of 64 spp), captured from
# its own framebuffer under a virtual X server with Mesa's software OpenGL.
# Needs: the release binary (cargo build --release) and xvfb-run (Debian: xvfb xauth).
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${CARGO_TARGET_DIR:-target}/release/pathtrace"
LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 1024x768x24" \
    "$bin" view cornell-box --size 512x512 --spp 64 --seed 1 \
    --screenshot docs/images/viewer.png --screenshot-at-spp 8 --screenshot-window --exit-when-done
