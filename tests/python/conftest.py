"""Shared problems of the Python tests.

Run through ctest (python_tests), which sets PYTHONPATH to build/python,
SNH_PYTHON_CROSSCHECK to the C++ program that solves the same problem and
SNH_CLI to the snh command line.
"""

import math
import os

import pytest

import snh


def twisted_bar(element_type="hex8", precision="double"):
    """The problem tests/python_crosscheck.cpp solves, built through Python."""
    if element_type == "tet4":
        bar = snh.make_tet_box(4, 2, 2, 0.25)
    else:
        bar = snh.make_box_lattice(4, 2, 2, 0.25)
    e = 1e-9
    held = snh.ConstraintSet("held", snh.vertices_in_box(bar, (-e, -1, -1), (e, 2, 2)))
    end = snh.ConstraintSet(
        "end",
        snh.vertices_in_box(bar, (1 - e, -1, -1), (1 + e, 2, 2)),
        motion=lambda t: snh.RigidTransform.rotation_about((1, 0, 0), t * math.pi / 2, (1, 0.25, 0.25)),
    )
    options = snh.SolveOptions(precision=precision, load_steps=2, body_force=(0, 0, -100))
    material = snh.Material.from_youngs_modulus(1e4, 0.45)
    return bar, material, [held, end], options


@pytest.fixture
def bar_problem():
    return twisted_bar()


@pytest.fixture
def crosscheck_program():
    path = os.environ.get("SNH_PYTHON_CROSSCHECK")
    if not path or not os.path.exists(path):
        pytest.skip("SNH_PYTHON_CROSSCHECK is not set (run through ctest)")
    return path


@pytest.fixture
def cli_program():
    path = os.environ.get("SNH_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("SNH_CLI is not set (run through ctest)")
    return path


def status_name(status):
    """A step's status as its name, (a StepStatus; str() gives its name)."""
    return status if isinstance(status, str) else str(status)
