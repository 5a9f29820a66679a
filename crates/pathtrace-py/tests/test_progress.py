"""Progress, cancel, background jobs, the GIL released while rendering, and Ctrl-C."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import pathtrace

# Far more samples than a test waits for: these renders end only when cancelled.
ENDLESS = dict(spp=1_000_000, width=64, height=64)


def test_progress_is_reported_on_the_calling_thread() -> None:
    seen: list[pathtrace.Progress] = []
    caller = threading.get_ident()
    threads: set[int] = set()

    def progress(p: pathtrace.Progress) -> None:
        seen.append(p)
        threads.add(threading.get_ident())

    film = pathtrace.render(pathtrace.builtin(), spp=256, width=128, height=128, progress=progress)
    assert threads == {caller}
    assert len(seen) >= 2, "reports while rendering and once at the end"
    assert [p.spp_done for p in seen] == sorted(p.spp_done for p in seen)
    last = seen[-1]
    assert last.finished and not last.cancelled
    assert (last.spp_done, last.spp_target, last.fraction) == (256, 256, 1.0)
    assert last.samples == 256 * 128 * 128 and last.samples_per_second > 0
    assert last.error_estimate == pytest.approx(film.relative_error_estimate)


def test_an_exception_in_progress_cancels_and_propagates() -> None:
    class Stop(Exception):
        pass

    def progress(p: pathtrace.Progress) -> None:
        if p.spp_done >= 2:
            raise Stop

    began = time.monotonic()
    with pytest.raises(Stop):
        pathtrace.render(pathtrace.builtin(), progress=progress, **ENDLESS)
    assert time.monotonic() - began < 30


def test_a_cancelled_job_returns_a_partial_film_with_its_real_spp() -> None:
    job = pathtrace.start(pathtrace.builtin(), **ENDLESS)
    while job.progress().spp_done < 4:
        time.sleep(0.01)
    snapshot = job.snapshot()
    assert snapshot.shape == (64, 64, 3) and snapshot.dtype == np.float32 and snapshot.any()
    job.cancel()
    film = job.wait()
    assert film is not None and job.done()
    counts = film.counts()
    assert 4 <= film.spp < ENDLESS["spp"]
    assert film.spp == counts.min()
    p = job.progress()
    # Whole waves the session recorded; a wave that ended just as the cancel came is in the
    # film's counts but may not be in spp_done.
    assert p.cancelled and 4 <= p.spp_done <= film.spp
    # Waiting again gives the same film.
    np.testing.assert_array_equal(job.wait().image(), film.image())


def test_wait_with_timeout_and_context_manager() -> None:
    with pathtrace.start(pathtrace.builtin(), **ENDLESS) as job:
        began = time.monotonic()
        assert job.wait(timeout=0.2) is None
        assert 0.15 < time.monotonic() - began < 5
        assert not job.done()
    # Leaving the block cancelled the render and waited for it.
    assert job.done() and job.progress().cancelled
    finished = pathtrace.start(pathtrace.builtin(), spp=2, width=16, height=16).wait(timeout=60)
    assert finished is not None and finished.spp == 2


def test_other_python_threads_run_while_rendering() -> None:
    ticks = 0
    stop = threading.Event()

    def count() -> None:
        nonlocal ticks
        while not stop.is_set():
            ticks += 1

    counter = threading.Thread(target=count)
    counter.start()
    try:
        # The counter's free speed, while this thread sleeps (which releases the GIL).
        before = ticks
        time.sleep(0.3)
        free_rate = (ticks - before) / 0.3
        # One render thread, so the counter is not also starved of CPU by the render; 128 spp so
        # that even a fast machine renders for about a second (32 spp took 0.21 s on an idle one).
        before, began = ticks, time.monotonic()
        pathtrace.render(pathtrace.builtin(), spp=128, width=192, height=192, threads=1)
        took, during = time.monotonic() - began, ticks - before
    finally:
        stop.set()
        counter.join()
    assert took > 0.3, "the render must last long enough to tell"
    # Were the GIL held through the render, the counter could not run at all (it would get at
    # most a switch interval, 5 ms); released, it runs at a good part of its free speed even on
    # a loaded machine.
    assert during > 0.05 * free_rate * took, (during, free_rate, took)


CHILD = textwrap.dedent(
    """
    import sys, pathtrace
    def progress(p):
        if p.spp_done >= 1:
            print("rendering", flush=True)
    try:
        pathtrace.render(pathtrace.builtin(), spp=1_000_000, width=64, height=64, progress=progress)
    except KeyboardInterrupt:
        print("interrupted", flush=True)
        sys.exit(3)
    print("finished", flush=True)
    """
)


@pytest.mark.skipif(os.name != "posix", reason="sends SIGINT")
def test_ctrl_c_cancels_and_raises_keyboard_interrupt() -> None:
    child = subprocess.Popen([sys.executable, "-c", CHILD], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout is not None
        assert child.stdout.readline().strip() == "rendering"
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=30)
    finally:
        child.kill()
    assert child.returncode == 3
    assert "interrupted" in out and "finished" not in out
