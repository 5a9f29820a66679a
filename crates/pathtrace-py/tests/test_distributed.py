"""``pathtrace.distributed.render`` on a local Ray cluster: the same film as a local render, bit for
bit, even when a worker is killed mid-chunk; with no retries left the error names the lost range.

The cluster must stay on the loopback interface: these tests run only in a network namespace
whose one interface is ``lo`` (CI: ``unshare -n`` then ``ip link set lo up``, with one
``RAY_AUTH_MODE`` exported for every Ray process; see .ci/run) and are skipped elsewhere.
"""

from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path
from typing import List, Optional

import numpy as np
import pytest

import pathtrace

# CI sets PATHTRACE_RAY_TESTS=required: there a missing Ray or network namespace fails the
# tests instead of skipping them.
REQUIRED = os.environ.get("PATHTRACE_RAY_TESTS") == "required"
if not REQUIRED:
    pytest.importorskip("ray")
import ray  # noqa: E402
from pathtrace import distributed  # noqa: E402  (needs ray)


def _interfaces() -> List[str]:
    """This network namespace's interfaces (/proc/net/dev is per namespace; /sys/class/net is
    not remounted by ``unshare -n``)."""
    try:
        lines = Path("/proc/net/dev").read_text().splitlines()[2:]
    except OSError:
        return []
    return sorted(line.split(":")[0].strip() for line in lines)


if REQUIRED:
    assert _interfaces() == ["lo"], f"the Ray tests need a namespace with only lo, not {_interfaces()}"
pytestmark = pytest.mark.skipif(
    _interfaces() != ["lo"],
    reason="Ray tests run only in a network namespace with nothing but lo (unshare -n; see .ci/run)",
)

SMALL = dict(spp=12, seed=7, width=32, height=24, max_depth=6)


@pytest.fixture(scope="module")
def cluster():
    ray.init(num_cpus=2, include_dashboard=False, _node_ip_address="127.0.0.1", log_to_driver=False)
    yield
    ray.shutdown()


@pytest.fixture(scope="module")
def scene() -> pathtrace.Scene:
    return pathtrace.builtin()


@pytest.mark.parametrize("sampler", ["independent", "stratified", "sobol"])
def test_distributed_equals_local(cluster, scene: pathtrace.Scene, sampler: str) -> None:
    seen = []
    film = distributed.render(scene, chunks=5, sampler=sampler, progress=lambda d, t: seen.append((d, t)), **SMALL)
    local = pathtrace.render(scene, sampler=sampler, **SMALL)
    assert film == local
    np.testing.assert_array_equal(film.image(), local.image())
    assert seen[0] == (0, 12) and seen[-1] == (12, 12) and len(seen) == 6


def _chunk_workers() -> List[int]:
    """PIDs of Ray workers running a chunk now (Ray titles a busy worker ``ray::<task>``)."""
    pids = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            cmdline = Path(f"/proc/{entry}/cmdline").read_bytes()
        except OSError:
            continue
        if cmdline.startswith(b"ray::_render_chunk"):
            pids.append(int(entry))
    return pids


def _render_killing_one_worker(scene: pathtrace.Scene, **kwargs):
    """Runs a distributed render in a thread, SIGKILLs the first worker seen rendering a chunk,
    and returns (film or exception, killed pid)."""
    result: dict = {}

    def run() -> None:
        try:
            result["film"] = distributed.render(scene, **kwargs)
        except BaseException as e:  # noqa: BLE001 - handed to the test
            result["error"] = e

    thread = threading.Thread(target=run)
    thread.start()
    killed: Optional[int] = None
    deadline = time.monotonic() + 120
    while killed is None and thread.is_alive() and time.monotonic() < deadline:
        pids = _chunk_workers()
        if pids:
            # Let the chunk get going, so the kill lands mid-render.
            time.sleep(0.2)
            if pids[0] in _chunk_workers():
                os.kill(pids[0], signal.SIGKILL)
                killed = pids[0]
        time.sleep(0.02)
    thread.join(timeout=600)
    return result, killed


# Chunks long enough to be killed in the middle: about 6M samples each, over a second on one core
# of a 2-core machine (at 96² × 32 spp the release build finished a chunk in about 20 ms, before
# the test could see it running).
HEAVY = dict(spp=512, seed=3, width=256, height=192, max_depth=8)
QUARTER = HEAVY["spp"] // 4


def test_a_killed_worker_costs_time_not_samples(cluster, scene: pathtrace.Scene) -> None:
    result, killed = _render_killing_one_worker(scene, chunks=4, max_retries=3, **HEAVY)
    assert killed is not None, "no chunk was seen running"
    assert "error" not in result, result.get("error")
    assert result["film"] == pathtrace.render(scene, **HEAVY)


def test_lost_chunk_without_retries_is_named_and_a_checkpoint_resumes(
    cluster, scene: pathtrace.Scene, tmp_path: Path
) -> None:
    checkpoint = tmp_path / "render.ptfilm"
    result, killed = _render_killing_one_worker(scene, chunks=4, max_retries=0, checkpoint=checkpoint, **HEAVY)
    assert killed is not None, "no chunk was seen running"
    error = result.get("error")
    assert isinstance(error, pathtrace.DistributedRenderError), result
    chunks = [(k * QUARTER, (k + 1) * QUARTER) for k in range(4)]
    assert error.missing and all(r in chunks for r in error.missing), error.missing
    assert any(f"{a}..{b}" in str(error) for a, b in error.missing), str(error)
    if error.film is not None:
        assert error.film.missing_ranges == error.missing
        assert pathtrace.Film.from_bytes(checkpoint.read_bytes()) == error.film
    # A restarted driver renders only what is missing, and the result is the whole film.
    seen = []
    film = distributed.render(scene, chunks=4, checkpoint=checkpoint, progress=lambda d, t: seen.append(d), **HEAVY)
    missing_spp = sum(b - a for a, b in error.missing)
    assert seen[0] == HEAVY["spp"] - missing_spp
    assert film == pathtrace.render(scene, **HEAVY)
