"""Rendering one image on a Ray cluster: the render is cut into sample ranges ("chunks"), each a
Ray task, and the films are added as they finish. The film sums are exact integers, so the result
is bit for bit the film ``pathtrace.render`` gives on one machine, whatever the number of
workers, the order chunks finish in, or which chunks were re-run after a worker died.

Install with ``pip install 'pathtrace[ray]'``. See docs/distributed.md.
"""

from __future__ import annotations

import os
import tempfile
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import pathtrace

from . import _core

__all__ = ["render"]

Range = Tuple[int, int]

# Scenes built in this (worker) process, by their pickled source: a worker builds each scene's
# BVH once, however many chunks it renders.
_SCENES: Dict[Any, "pathtrace.Scene"] = {}


def _scene_in_worker(source: Tuple[str, str, str, List[Tuple[str, str]]]) -> "pathtrace.Scene":
    kind, first, second, defines = source
    key = (kind, first, second, tuple(map(tuple, defines)))
    scene = _SCENES.get(key)
    if scene is None:
        scene = _core._rebuild_scene(kind, first, second, [tuple(d) for d in defines])
        _SCENES[key] = scene
    return scene


def _render_chunk(source: Any, start: int, end: int, options: Dict[str, Any]) -> bytes:
    """One Ray task: samples ``start..end`` of every pixel, as film bytes."""
    scene = _scene_in_worker(source)
    film = pathtrace.render(scene, sample_range=(start, end), **options)
    return film.to_bytes()


def _split(ranges: List[Range], chunks: int) -> List[Range]:
    """Cuts ``ranges`` into ``chunks`` pieces whose lengths differ by at most one (the first
    ``total % chunks`` one longer), in order; a piece that would span two ranges is cut in two."""
    total = sum(b - a for a, b in ranges)
    parts = max(1, min(chunks, total))
    sizes = [total // parts + (1 if i < total % parts else 0) for i in range(parts)]
    out: List[Range] = []
    pending = list(ranges)
    for size in sizes:
        while size > 0 and pending:
            a, b = pending[0]
            take = min(size, b - a)
            out.append((a, a + take))
            size -= take
            pending[0] = (a + take, b)
            if a + take == b:
                pending.pop(0)
    return out


def _write_atomically(path: Union[str, "os.PathLike[str]"], data: bytes) -> None:
    folder = os.path.dirname(os.fspath(path)) or "."
    fd, temp = tempfile.mkstemp(prefix=".pathtrace-checkpoint.", dir=folder)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(temp, path)
    except BaseException:
        if os.path.exists(temp):
            os.remove(temp)
        raise


def _load_checkpoint(path: Union[str, "os.PathLike[str]"], key: str) -> Optional["pathtrace.Film"]:
    if not os.path.exists(path):
        return None
    with open(path, "rb") as f:
        data = f.read()
    try:
        film = pathtrace.Film.from_bytes(data)
    except ValueError as e:
        raise ValueError(f"{os.fspath(path)}: {e}") from None
    if film.key != key:
        raise ValueError(
            f"{os.fspath(path)}: the checkpoint belongs to another scene or other settings; "
            "delete it or give another checkpoint path"
        )
    return film


def render(
    scene: "pathtrace.Scene",
    *,
    spp: int,
    seed: int = 0,
    chunks: Optional[int] = None,
    max_retries: int = 3,
    address: Optional[str] = None,
    progress: Optional[Callable[[int, int], Any]] = None,
    checkpoint: Optional[Union[str, "os.PathLike[str]"]] = None,
    **settings: Any,
) -> "pathtrace.Film":
    """Renders ``scene`` on a Ray cluster and returns the film ``pathtrace.render(scene,
    spp=spp, seed=seed, **settings)`` returns, bit for bit.

    ``settings`` are :func:`pathtrace.render`'s options (``width``, ``height``, ``max_depth``,
    ``sampler``, …); ``threads`` (default 1) is each task's thread count, and each task asks Ray
    for that many CPUs. ``chunks`` is the number of sample ranges (default: twice the cluster's
    CPUs, at most ``spp``). ``address=None`` uses the Ray instance this process already
    initialised, else starts a local one; otherwise ``ray.init(address=address)``.

    The scene is shipped once (``ray.put`` of its source; each worker process builds it once).
    A chunk whose worker dies is re-run by Ray up to ``max_retries`` times; when a chunk is
    still missing after that, :class:`pathtrace.DistributedRenderError` names the missing
    ranges and carries the film of the chunks that arrived. ``progress(done, total)`` is called
    with samples per pixel merged so far. With ``checkpoint`` (a file path), the film so far is
    saved after every chunk and a later call with the same arguments renders only the ranges the
    file lacks.
    """
    try:
        import ray
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("pathtrace.distributed needs Ray: pip install 'pathtrace[ray]'") from e
    if spp < 1:
        raise ValueError("spp must be at least 1")
    if max_retries < 0:
        raise ValueError("max_retries must be 0 or more")
    options = dict(settings, spp=spp, seed=seed)
    options.setdefault("threads", 1)
    key = _core.render_key(scene, **options)

    if address is not None:
        if not ray.is_initialized():
            ray.init(address=address)
    elif not ray.is_initialized():
        ray.init()

    film: Optional[pathtrace.Film] = None
    if checkpoint is not None:
        film = _load_checkpoint(checkpoint, key)
    todo: List[Range] = [(0, spp)] if film is None else list(film.missing_ranges)
    if chunks is None:
        chunks = 2 * max(1, int(ray.cluster_resources().get("CPU", 1)))
    pieces = _split(todo, chunks)

    source_ref = ray.put(scene.__reduce__()[1])
    task = ray.remote(_render_chunk).options(
        num_cpus=max(1, int(options["threads"]) or 1), max_retries=max_retries, retry_exceptions=False
    )
    pending = {task.remote(source_ref, a, b, options): (a, b) for a, b in pieces}
    done = spp - sum(b - a for a, b in todo)
    lost: List[Range] = []
    last_error: Optional[BaseException] = None
    if progress is not None:
        progress(done, spp)
    try:
        while pending:
            ready, _ = ray.wait(list(pending), num_returns=1)
            for ref in ready:
                chunk = pending.pop(ref)
                try:
                    part = pathtrace.Film.from_bytes(ray.get(ref))
                except ray.exceptions.RayError as e:
                    lost.append(chunk)
                    last_error = e
                    continue
                film = part if film is None else film + part
                done += chunk[1] - chunk[0]
                if checkpoint is not None:
                    _write_atomically(checkpoint, film.to_bytes())
                if progress is not None:
                    progress(done, spp)
    except BaseException:
        for ref in pending:
            ray.cancel(ref, force=True)
        raise
    if lost:
        lost.sort()
        names = ", ".join(f"{a}..{b}" for a, b in lost)
        raise pathtrace.DistributedRenderError(
            f"{len(lost)} chunks were lost after {max_retries} retries (samples {names}); last error: "
            f"{type(last_error).__name__}: {last_error}".splitlines()[0],
            lost,
            film,
        )
    assert film is not None and film.complete, "every chunk arrived"
    return film
