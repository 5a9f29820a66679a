"""Each loader gives the same scene; bad input raises SceneError at the CLI's location."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import pathtrace
from conftest import CORNELL_TOML

SMALL = dict(spp=4, seed=1, width=40, height=30)


def test_file_dict_and_builtin_render_the_same_film() -> None:
    tomllib = pytest.importorskip("tomllib")
    as_dict = tomllib.loads(CORNELL_TOML.read_text())
    scenes = [
        pathtrace.load_file(CORNELL_TOML),
        pathtrace.load_dict(as_dict),
        pathtrace.builtin("cornell-box"),
        pathtrace.builtin(),
    ]
    images = [pathtrace.render(s, **SMALL).image() for s in scenes]
    assert images[0].any(), "the Cornell box renders something"
    for image in images[1:]:
        np.testing.assert_array_equal(image, images[0])


def test_json_file_loads_like_its_dict(tmp_path: Path) -> None:
    scene = {
        "render": {"width": 24, "height": 16, "spp": 2},
        "camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov": 40},
        "materials": {"grey": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
                      "lamp": {"type": "emissive", "radiance": [4, 4, 4]}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"},
                    {"type": "sphere", "center": [0, 3, 2], "radius": 0.5, "material": "lamp"}],
    }
    path = tmp_path / "spheres.json"
    path.write_text(json.dumps(scene))
    from_file = pathtrace.load_file(path)
    from_dict = pathtrace.load_dict(scene)
    assert (from_file.width, from_file.height, from_file.spp) == (24, 16, 2)
    np.testing.assert_array_equal(pathtrace.render(from_file).image(), pathtrace.render(from_dict).image())


MITSUBA = """<scene version="3.0.0">
  <default name="res" value="32"/>
  <sensor type="perspective">
    <float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
  </sensor>
  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5"/></bsdf>
  <shape type="sphere"><ref id="grey"/></shape>
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>
"""


def test_mitsuba_xml_with_defines(tmp_path: Path) -> None:
    path = tmp_path / "sphere.xml"
    path.write_text(MITSUBA)
    assert pathtrace.load_file(path).width == 32
    scene = pathtrace.load_file(path, defines={"res": 12})
    assert (scene.width, scene.height) == (12, 12)
    image = pathtrace.render(scene, spp=2).image()
    assert image.shape == (12, 12, 3)
    # A grey sphere under a white sky: the corners see the sky (radiance 1, as the importer
    # converts Mitsuba's RGB: within 1%), the centre sees the sphere (darker).
    corners = image[[0, 0, -1, -1], [0, -1, 0, -1]]
    assert np.all(np.abs(corners - 1) < 0.01), corners
    assert image[6, 6].max() < 0.9


def bad_toml(tmp_path: Path) -> Path:
    text = CORNELL_TOML.read_text().replace('type = "lambertian"', 'type = "lambertan"', 1)
    path = tmp_path / "bad.toml"
    path.write_text(text)
    return path


def test_scene_error_carries_the_cli_location(tmp_path: Path, cli: Path) -> None:
    path = bad_toml(tmp_path)
    with pytest.raises(pathtrace.SceneError) as caught:
        pathtrace.load_file(path)
    e = caught.value
    assert isinstance(e, ValueError)
    expected_line = next(i for i, l in enumerate(path.read_text().splitlines(), 1) if "lambertan" in l)
    assert (Path(e.path), e.line) == (path, expected_line)
    assert e.column >= 1 and "lambertan" in e.message
    assert str(e) == f"{e.path}:{e.line}:{e.column}: {e.message}"
    run = subprocess.run([cli, "render", path, "--quiet", "-o", tmp_path / "x.png"], capture_output=True, text=True)
    assert run.returncode == 2
    assert run.stderr.strip() == f"error: {e}"
    assert not (tmp_path / "x.png").exists()


def test_dict_errors_point_into_the_indented_json() -> None:
    scene = {"camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0], "vfov": "wide"}}
    with pytest.raises(pathtrace.SceneError) as caught:
        pathtrace.load_dict(scene, name="my-scene")
    e = caught.value
    assert e.path == "my-scene"
    lines = json.dumps(scene, indent=2).splitlines()
    assert "vfov" in lines[e.line - 1], (e.line, lines)


def test_missing_file_and_unknown_builtin(tmp_path: Path) -> None:
    with pytest.raises(pathtrace.SceneError) as caught:
        pathtrace.load_file(tmp_path / "nope.toml")
    assert (caught.value.line, caught.value.column) == (1, 1)
    assert "cannot read" in caught.value.message
    with pytest.raises(pathtrace.SceneError):
        pathtrace.load_file(CORNELL_TOML, defines={"spp": 4})
    with pytest.raises(ValueError, match="cornell-box"):
        pathtrace.builtin("no-such-scene")
    assert "cornell-box" in pathtrace.builtin_names()
