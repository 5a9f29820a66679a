#!/usr/bin/env bash
# Set up .venv-embree (repository root, gitignored) with embreex (Embree 4 for Python) and
# numpy, for benches/peers/bvh_embree.py. Idempotent.
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
venv="$repo_root/.venv-embree"
python="${PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
if ! "$venv/bin/python" -c 'import embreex, numpy' 2>/dev/null; then
    "$venv/bin/pip" install --quiet embreex numpy
fi
"$venv/bin/python" -c 'import embreex, numpy; print("embreex", getattr(embreex, "__version__", "?"), "| numpy", numpy.__version__)'
