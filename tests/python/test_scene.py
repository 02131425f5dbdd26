"""Built-in scenes and scene files from Python."""

import pathlib

import pytest

import snh

SCENES = pathlib.Path(__file__).resolve().parents[2] / "data" / "scenes"


def test_built_in_scene():
    assert "stretch" in snh.scene_names()
    parameters = snh.scene_defaults("stretch")
    parameters.resolution = 2
    parameters.steps = 2
    scene = snh.make_scene("stretch", parameters)
    assert scene.mesh.element_count > 0 and scene.constraints
    result = scene.simulation().solve()
    assert len(result.steps) == 2


def test_scene_file_runs_with_changed_options(tmp_path):
    file = snh.load_scene(str(SCENES / "flex.json"))
    assert file.scene.name == "flex"
    assert file.bones is None and file.surface is None
    options = file.scene.options
    options.load_steps = 2
    seen = []
    run = snh.run_scene(file, options, progress=seen.append, vtu_dir=str(tmp_path / "vtu"))
    assert run.converged
    assert [p.index for p in seen] == [1, 2]
    assert len(run.steps) == 2 and run.steps[-1].reactions is not None
    assert (tmp_path / "vtu").is_dir() and any((tmp_path / "vtu").iterdir())
    snh.write_scene_json(str(tmp_path / "run.json"), file, run)
    assert (tmp_path / "run.json").stat().st_size > 0


def test_bad_scene_file_is_an_error(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"name": "x", "no_such_key": 1}')
    with pytest.raises(snh.Error):
        snh.load_scene(str(path))
