"""The Python examples run and write what they say."""

import os
import pathlib
import subprocess
import sys

import pytest

import snh

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"


def run(script, *args):
    return subprocess.run(
        [sys.executable, str(EXAMPLES / script), *args], check=True, env=os.environ, capture_output=True, text=True
    ).stdout


def test_twist(tmp_path):
    run("twist.py", str(tmp_path / "twist.vtu"))
    assert (tmp_path / "twist.vtu").stat().st_size > 0


def test_flex(tmp_path):
    pytest.importorskip("matplotlib")
    run("flex.py", str(tmp_path / "flex.png"))
    assert (tmp_path / "flex.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_character(tmp_path):
    out = run("character.py", str(tmp_path / "arm.pc2"), "--resolution", "16")
    assert "3 of 3 frames converged" in out
    assert snh.read_pc2(str(tmp_path / "arm.pc2")).samples.shape == (3, 359, 3)
