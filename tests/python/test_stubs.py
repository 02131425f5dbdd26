"""The committed type stubs match the built module (where pybind11-stubgen is installed)."""

import pathlib
import subprocess
import sys

import pytest

STUB = pathlib.Path(__file__).resolve().parents[2] / "python" / "snh" / "_snh.pyi"


def test_stubs_are_current(tmp_path):
    pytest.importorskip("pybind11_stubgen")
    command = [sys.executable, "-m", "pybind11_stubgen", "snh._snh", "-o", str(tmp_path)]
    for enum in ("Barrier", "MaterialModel"):
        command += ["--enum-class-locations", f"{enum}:snh._snh"]
    subprocess.run(command, check=True, capture_output=True)
    generated = (tmp_path / "snh" / "_snh.pyi").read_text()
    assert generated == STUB.read_text(), "python/snh/_snh.pyi is stale: regenerate it (docs/python.md)"
