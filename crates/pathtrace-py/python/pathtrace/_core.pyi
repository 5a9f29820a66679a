"""Type stubs of the native core, ``pathtrace._core`` (written in Rust with PyO3)."""

from __future__ import annotations

import os
from types import TracebackType
from typing import Any, Callable, Optional, TypedDict, Union

import numpy as np
import numpy.typing as npt
from typing_extensions import Unpack

class SceneError(ValueError):
    """A scene that cannot be loaded; ``str(e)`` is the CLI's ``FILE:LINE:COL: message``."""

    path: str
    line: int
    column: int
    message: str

class Scene:
    """A built scene and the render settings its file suggests."""

    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def spp(self) -> int: ...
    @property
    def max_depth(self) -> int: ...
    @property
    def primitive_count(self) -> int: ...

class Progress:
    """How far a render is."""

    spp_done: int
    spp_target: int
    samples: int
    elapsed: float
    samples_per_second: float
    rays_per_second: float
    dropped_samples: int
    error_estimate: Optional[float]
    finished: bool
    cancelled: bool
    @property
    def fraction(self) -> float: ...

class Film:
    """A render's result: per pixel, the sample count and the running mean and variance."""

    def image(self) -> npt.NDArray[np.float32]: ...
    def variance(self) -> npt.NDArray[np.float32]: ...
    def counts(self) -> npt.NDArray[np.uint32]: ...
    def albedo(self) -> npt.NDArray[np.float32]: ...
    def normal(self) -> npt.NDArray[np.float32]: ...
    def depth(self) -> npt.NDArray[np.float32]: ...
    def denoise(self) -> npt.NDArray[np.float32]: ...
    def __array__(self, dtype: Any = None, copy: Optional[bool] = None) -> npt.NDArray[Any]: ...
    @property
    def spp(self) -> int: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def dropped_samples(self) -> int: ...
    @property
    def relative_error_estimate(self) -> Optional[float]: ...
    def write(
        self, path: Union[str, os.PathLike[str]], exposure: float = 0.0, tonemap: str = "clamp"
    ) -> None: ...

class RenderJob:
    """A render running in the background."""

    def progress(self) -> Progress: ...
    def snapshot(self) -> npt.NDArray[np.float32]: ...
    def cancel(self) -> None: ...
    def done(self) -> bool: ...
    def wait(self, timeout: Optional[float] = None) -> Optional[Film]: ...
    def __enter__(self) -> RenderJob: ...
    def __exit__(
        self,
        exc_type: Optional[type[BaseException]],
        exc: Optional[BaseException],
        traceback: Optional[TracebackType],
    ) -> bool: ...

def load_file(path: str, defines: list[tuple[str, str]] = ...) -> tuple[Scene, list[str]]: ...
def load_json(text: str, name: str) -> Scene: ...
def builtin(name: str) -> Scene: ...
def builtin_names() -> list[str]: ...
class RenderOptions(TypedDict, total=False):
    """The keyword options of ``render`` and ``start``."""

    spp: Optional[int]
    seed: Optional[int]
    width: Optional[int]
    height: Optional[int]
    max_depth: Optional[int]
    strategy: Optional[str]
    sampler: Optional[str]
    threads: int
    aov: bool

def render(
    scene: Scene, *, progress: Optional[Callable[[Progress], Any]] = None, **options: Unpack[RenderOptions]
) -> Film: ...
def start(scene: Scene, **options: Unpack[RenderOptions]) -> RenderJob: ...
