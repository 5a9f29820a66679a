#!/usr/bin/env bash
# Set up the Python environment used by the Mitsuba 3 peer benchmark.
#
#   benches/peers/setup.sh            # .venv-peers with mitsuba 3.9.x + numpy
#   benches/peers/setup.sh --llvm     # ... and libllvm19 for the llvm_ad_rgb variant
#
# Idempotent: re-running only installs what is missing. The venv lives at the
# repository root (.venv-peers, gitignored).
set -euo pipefail

want_llvm=0
for arg in "$@"; do
    case "$arg" in
        --llvm) want_llvm=1 ;;
        -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
        *) echo "setup.sh: unknown option: $arg" >&2; exit 2 ;;
    esac
done

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
venv="$repo_root/.venv-peers"
python="${PYTHON:-python3}"

if [ ! -x "$venv/bin/python" ]; then
    echo "creating $venv"
    "$python" -m venv "$venv"
fi

if "$venv/bin/python" - <<'PY' 2>/dev/null
import importlib.metadata as md, sys
v = md.version("mitsuba")
md.version("numpy")
sys.exit(0 if v.startswith("3.9.") else 1)
PY
then
    echo "mitsuba 3.9.x and numpy already installed in $venv"
else
    "$venv/bin/pip" install --quiet --upgrade pip
    "$venv/bin/pip" install --quiet "mitsuba==3.9.*" numpy
fi
"$venv/bin/python" -c 'import mitsuba, drjit, numpy; print("mitsuba", mitsuba.__version__, "| drjit", drjit.__version__, "| numpy", numpy.__version__)'

if [ "$want_llvm" = 1 ]; then
    # Debian's default LLVM 14 aborts on Dr.Jit's first kernel; LLVM 19 works.
    lib="$(ls /usr/lib/llvm-19/lib/libLLVM*.so* /usr/lib/*-linux-gnu/libLLVM*19*.so* 2>/dev/null | head -n1 || true)"
    if [ -z "$lib" ]; then
        sudo=""
        [ "$(id -u)" = 0 ] || sudo="sudo"
        $sudo apt-get update -qq
        $sudo apt-get install -y -qq libllvm19
        lib="$(ls /usr/lib/llvm-19/lib/libLLVM*.so* /usr/lib/*-linux-gnu/libLLVM*19*.so* 2>/dev/null | head -n1 || true)"
    fi
    if [ -z "$lib" ]; then
        echo "setup.sh: libllvm19 installed but no libLLVM*.so found" >&2
        exit 1
    fi
    echo "for llvm_ad_rgb use:"
    echo "export DRJIT_LIBLLVM_PATH=$lib"
fi
