"""pathtrace: a physically based Monte Carlo path tracer, as a Python module.

Load a scene, render it, get numpy arrays back::

    import pathtrace
    scene = pathtrace.builtin("cornell-box")           # or load_file("scene.toml" / ".json" / ".xml")
    film = pathtrace.render(scene, spp=64, seed=3)      # blocks, with the GIL released
    image = film.image()                                # float32 (H, W, 3), linear RGB, row 0 on top
    film.write("cornell.exr")

The renderer is the same engine as the ``pathtrace`` command: ``render(scene, spp=16, seed=3)``
gives, bit for bit, the image ``pathtrace render SCENE --spp 16 --seed 3 -o out.pfm`` writes.
See docs/python.md in the repository.
"""

from __future__ import annotations

import functools
import json
import operator
import os
import warnings
from typing import TYPE_CHECKING, Any, Callable, Iterable, List, Mapping, Optional, Tuple, Union

from . import _core
from ._core import Film, Progress, RenderJob, Scene, SceneError

if TYPE_CHECKING:  # for type checkers only: the stubs' TypedDict of render options
    from typing_extensions import Unpack

    from ._core import RenderOptions

__all__ = [
    "DistributedRenderError",
    "Film",
    "Progress",
    "RenderJob",
    "Scene",
    "SceneError",
    "builtin",
    "builtin_names",
    "load_dict",
    "load_file",
    "merge",
    "render",
    "start",
]

PathLike = Union[str, "os.PathLike[str]"]


def load_file(path: PathLike, defines: Optional[Mapping[str, Any]] = None) -> Scene:
    """Loads a scene file: native ``.toml`` or ``.json`` (docs/scene-format.md) or a Mitsuba 3
    ``.xml`` scene, whose ``<default>`` parameters ``defines`` overrides (as the CLI's
    ``-D NAME=VALUE``; values are converted with ``str``).

    Raises :class:`SceneError` (a ``ValueError``) with ``.path``, ``.line``, ``.column`` and
    ``.message`` for a bad file. Mitsuba features the importer substitutes are reported with
    ``warnings.warn``.
    """
    pairs = [(str(name), str(value)) for name, value in (defines or {}).items()]
    scene, import_warnings = _core.load_file(os.fspath(path), pairs)
    for message in import_warnings:
        warnings.warn(message, stacklevel=2)
    return scene


def load_dict(d: Mapping[str, Any], name: str = "<dict>") -> Scene:
    """Builds a scene from a dict in the native schema (the JSON scene format as Python
    objects; docs/scene-format.md). Relative mesh paths resolve against the current directory.

    The dict is written as indented JSON, so a :class:`SceneError`'s ``.line`` and ``.column``
    point into ``json.dumps(d, indent=2)`` and ``.path`` is ``name``.
    """
    return _core.load_json(json.dumps(d, indent=2), name)


def builtin(name: str = "cornell-box") -> Scene:
    """A scene bundled with the renderer (see :func:`builtin_names`); ``ValueError`` for an
    unknown name."""
    return _core.builtin(name)


def builtin_names() -> list[str]:
    """The names :func:`builtin` accepts."""
    return _core.builtin_names()


def render(
    scene: Scene,
    *,
    progress: Optional[Callable[[Progress], Any]] = None,
    **options: Unpack[RenderOptions],
) -> Film:
    """Renders ``scene`` and returns its :class:`Film`. Blocks, with the GIL released, while
    the engine's worker threads render, so other Python threads keep running.

    Options (keyword only): ``spp=None``, ``seed=0``, ``width=None``, ``height=None``,
    ``max_depth=None``, ``strategy=None``, ``sampler=None``, ``threads=0``,
    ``sample_range=None``. Each left at
    ``None`` takes the scene file's ``[render]`` value, else the engine's default, exactly as
    the CLI's options do (``seed=None`` takes the scene's seed; the default ``seed=0`` is the
    CLI's default seed). ``strategy`` is ``"mis"``, ``"bsdf"``, ``"mixture"`` or ``"light"``;
    ``sampler`` is ``"independent"``, ``"stratified"`` or ``"sobol"``; ``max_depth`` counts path
    segments (-1: unlimited); ``threads=0`` uses one per core. A bad value is a ``ValueError``.
    ``aov=True`` also accumulates the feature buffers over the same samples: the film's
    ``albedo()``, ``normal()`` and ``depth()`` arrays, and ``denoise()`` (Intel Open Image
    Denoise 2, found at run time: see docs/denoising.md).

    ``sample_range=(a, b)`` renders only samples ``a`` to ``b - 1`` of every pixel of the
    ``spp`` render: films of ranges that cover ``0..spp``, added with ``+`` or :func:`merge` in
    any order, equal the film of rendering everything at once, bit for bit
    (docs/distributed.md) — with ``aov=True``, their feature buffers too (every part must then
    have them).

    ``progress(p)`` is called on the calling thread about ten times a second and once at the
    end with a :class:`Progress` (``spp_done``, ``spp_target``, ``samples_per_second``,
    ``error_estimate``, …). An exception raised in it cancels the render and propagates;
    Ctrl-C cancels the render and raises ``KeyboardInterrupt``.
    """
    return _core.render(scene, progress=progress, **options)


def start(scene: Scene, **options: Unpack[RenderOptions]) -> RenderJob:
    """Starts rendering ``scene`` in the background (options as :func:`render`) and returns a
    :class:`RenderJob`: ``.progress()``, ``.snapshot()`` (the image so far, numpy),
    ``.cancel()``, ``.done()`` and ``.wait(timeout=None)`` (the :class:`Film`, or ``None`` if the
    timeout passes first). As a context manager, leaving the block cancels the render if it is
    still running.
    """
    return _core.start(scene, **options)


def merge(films: Iterable[Film]) -> Film:
    """Adds films of sample ranges of one render (``film_a + film_b + …``): exact, so the order
    does not change a bit. ``ValueError`` if a film belongs to another scene, other settings or
    another engine build, or repeats samples another film holds; :attr:`Film.missing_ranges`
    says what is still to render."""
    films = list(films)
    if not films:
        raise ValueError("merge: no films given")
    return functools.reduce(operator.add, films)


class DistributedRenderError(RuntimeError):
    """A distributed render (:func:`pathtrace.distributed.render`) lost chunks after every retry.

    ``missing`` lists the sample ranges ``(start, end)`` no worker delivered; ``film`` is the
    film of the chunks that did arrive (``None`` if none did): render the missing ranges later
    (``render(..., sample_range=r)``) and add them, or pass a ``checkpoint`` file so that a
    restarted driver renders only what is missing.
    """

    def __init__(self, message: str, missing: List[Tuple[int, int]], film: Optional[Film]) -> None:
        super().__init__(message)
        self.missing = missing
        self.film = film
