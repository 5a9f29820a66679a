"""The film's arrays (shapes, dtypes, meaning), writing images, and bit-identity with the CLI."""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np
import pytest

import pathtrace
from conftest import read_pfm


@pytest.fixture(scope="module")
def film() -> pathtrace.Film:
    return pathtrace.render(pathtrace.builtin(), spp=8, seed=2, width=48, height=32)


def test_shapes_and_dtypes(film: pathtrace.Film) -> None:
    image = film.image()
    assert image.shape == (32, 48, 3) and image.dtype == np.float32
    assert film.variance().shape == (32, 48, 3) and film.variance().dtype == np.float32
    counts = film.counts()
    assert counts.shape == (32, 48) and counts.dtype == np.uint32
    assert (counts == 8).all() and film.spp == 8
    assert (film.width, film.height) == (48, 32)
    np.testing.assert_array_equal(np.asarray(film), image)
    assert np.asarray(film, dtype=np.float64).dtype == np.float64
    assert film.dropped_samples == 0
    assert np.isfinite(image).all() and (image >= 0).all()
    assert (film.variance() >= 0).all() and film.variance().any()


def test_row_zero_is_the_top(film: pathtrace.Film) -> None:
    # The Cornell box's light hangs under the ceiling: the top rows are brighter than the bottom
    # rows' floor only near the light, so compare the light's own pixels: the brightest pixel
    # (the light, radiance 15) lies in the upper half.
    image = film.image()
    y, _ = np.unravel_index(np.argmax(image.sum(axis=2)), image.shape[:2])
    assert y < image.shape[0] // 2


def test_relative_error_estimate_matches_the_variance(film: pathtrace.Film) -> None:
    # The CLI's "estimated error": the RMS over pixels and channels of the relative standard
    # error, with 0.01 keeping black pixels from dominating (crates/pathtrace/src/film/noise.rs).
    mean, variance = film.image().astype(np.float64), film.variance().astype(np.float64)
    expected = np.sqrt(np.mean(variance / (mean**2 + 0.01)))
    assert film.relative_error_estimate == pytest.approx(expected, rel=1e-3)


def test_more_samples_less_variance() -> None:
    scene = pathtrace.builtin()
    few = pathtrace.render(scene, spp=4, width=32, height=32)
    many = pathtrace.render(scene, spp=64, width=32, height=32)
    assert many.relative_error_estimate < few.relative_error_estimate / 2


def test_write_png_exr_pfm(film: pathtrace.Film, tmp_path: Path) -> None:
    for name in ("out.png", "out.exr", "out.pfm"):
        film.write(tmp_path / name)
        assert (tmp_path / name).stat().st_size > 0
    np.testing.assert_array_equal(read_pfm(tmp_path / "out.pfm"), film.image())
    film.write(tmp_path / "aces.png", exposure=1.0, tonemap="aces")
    with pytest.raises(ValueError):
        film.write(tmp_path / "out.bmp")
    with pytest.raises(ValueError):
        film.write(tmp_path / "x.png", tonemap="reinhard-ish")


@pytest.mark.parametrize(
    "options, flags",
    [
        (dict(spp=16, seed=3), ["--spp", "16", "--seed", "3"]),
        (dict(spp=5, seed=7, width=70, height=40, max_depth=3, strategy="bsdf", sampler="sobol"),
         ["--spp", "5", "--seed", "7", "--size", "70x40", "--max-depth", "3", "--strategy", "bsdf",
          "--sampler", "sobol"]),
        (dict(spp=6, seed=2, width=40, height=30, max_depth=12, rr_depth=2),
         ["--spp", "6", "--seed", "2", "--size", "40x30", "--max-depth", "12", "--rr-depth", "2"]),
    ],
)
def test_bit_identical_to_the_cli(options: dict, flags: list, cli: Path, tmp_path: Path) -> None:
    out = tmp_path / "cli.pfm"
    subprocess.run([cli, "render", "cornell-box", *flags, "--quiet", "-o", out], check=True)
    image = pathtrace.render(pathtrace.builtin(), **options).image()
    cli_image = read_pfm(out)
    assert image.shape == cli_image.shape
    assert image.tobytes() == cli_image.tobytes()


def test_bad_options_raise_value_error() -> None:
    scene = pathtrace.builtin()
    for options in (dict(strategy="best"), dict(sampler="magic"), dict(spp=0), dict(width=0), dict(rr_depth=0)):
        with pytest.raises(ValueError):
            pathtrace.render(scene, **options)
        with pytest.raises(ValueError):
            pathtrace.start(scene, **options)
    with pytest.raises(TypeError, match="samples"):
        pathtrace.render(scene, samples=4)
    with pytest.raises(TypeError, match="spp"):
        pathtrace.render(scene, spp="many")


def test_feature_buffers_come_with_aov_true() -> None:
    film = pathtrace.render(pathtrace.builtin(), spp=4, seed=2, width=24, height=16, aov=True)
    albedo, normal, depth = film.albedo(), film.normal(), film.depth()
    assert albedo.shape == (16, 24, 3) and albedo.dtype == np.float32
    assert normal.shape == (16, 24, 3) and depth.shape == (16, 24)
    # Albedos are at most 1, normals at most unit; at this wide aspect the corners see past the
    # open box, where nothing is recorded.
    assert (albedo >= 0).all() and (albedo <= 1).all()
    lengths = np.linalg.norm(normal, axis=2)
    assert (lengths <= 1 + 1e-5).all() and (depth >= 0).all()
    assert (depth > 0).mean() > 0.5 and (lengths[depth == 0] == 0).all()
    # The same samples as without the buffers.
    plain = pathtrace.render(pathtrace.builtin(), spp=4, seed=2, width=24, height=16)
    np.testing.assert_array_equal(plain.image(), film.image())
    with pytest.raises(ValueError, match="aov=True"):
        plain.albedo()


def test_denoise_needs_the_library_in_ci() -> None:
    import os

    film = pathtrace.render(pathtrace.builtin(), spp=4, seed=2, width=32, height=32, aov=True)
    try:
        denoised = film.denoise()
    except RuntimeError as e:
        assert os.environ.get("CI") not in ("true", "1"), f"CI=true but denoising failed: {e}"
        assert "pyoidn" in str(e)
        pytest.skip(f"Open Image Denoise absent: {e}")
    assert denoised.shape == (32, 32, 3) and np.isfinite(denoised).all()
    # Smoother than the noisy image: neighbouring pixels differ less.
    noisy = film.image()
    assert np.abs(np.diff(denoised, axis=1)).mean() < np.abs(np.diff(noisy, axis=1)).mean()
