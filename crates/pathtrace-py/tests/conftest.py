"""Shared helpers for the pathtrace module's tests: the repository, the CLI binary, PFM reading."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[3]
CORNELL_TOML = REPO / "scenes" / "cornell-box.toml"


def cli_binary() -> Path:
    """The `pathtrace` CLI to compare with: $PATHTRACE_CLI, else one cargo built in the target
    directory ($CARGO_TARGET_DIR or target/; release first, then the test profile's), else PATH."""
    given = os.environ.get("PATHTRACE_CLI")
    if given:
        return Path(given)
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    for profile in ("release", "debug"):
        candidate = target / profile / "pathtrace"
        if candidate.is_file():
            return candidate
    found = shutil.which("pathtrace")
    if found:
        return Path(found)
    raise FileNotFoundError(
        "no pathtrace CLI found: set PATHTRACE_CLI, or build it (cargo build --release) first"
    )


@pytest.fixture(scope="session")
def cli() -> Path:
    return cli_binary()


def read_pfm(path: Path) -> np.ndarray:
    """A colour PFM as float32 (H, W, 3), row 0 at the top (PFM stores the bottom row first)."""
    data = path.read_bytes()
    header_end = 0
    for _ in range(3):
        header_end = data.index(b"\n", header_end) + 1
    kind, size, scale = data[:header_end].decode("ascii").split("\n")[:3]
    assert kind == "PF", kind
    width, height = (int(v) for v in size.split())
    dtype = "<f4" if float(scale) < 0 else ">f4"
    pixels = np.frombuffer(data[header_end:], dtype=dtype, count=width * height * 3)
    return pixels.reshape(height, width, 3)[::-1].astype(np.float32)
