"""The same problem through Python and C++ gives the same bits."""

import subprocess

import numpy as np
import pytest

import snh
from conftest import twisted_bar


@pytest.mark.parametrize("element_type,precision", [("hex8", "double"), ("tet4", "double"), ("hex8", "float")])
def test_positions_match_cpp_bitwise(tmp_path, crosscheck_program, element_type, precision):
    out = tmp_path / "positions.bin"
    subprocess.run([crosscheck_program, "solve", str(out), precision, element_type], check=True)
    cpp = np.fromfile(out, dtype=np.float64).reshape(-1, 3)

    mesh, material, sets, options = twisted_bar(element_type, precision)
    sim = snh.Simulation(mesh, material, sets, options)
    result = sim.solve()
    assert result.converged
    assert sim.positions.shape == cpp.shape
    assert np.array_equal(sim.positions.view(np.uint64), cpp.view(np.uint64))
    assert np.array_equal(result.positions, sim.positions)


def test_error_carries_cpp_message(crosscheck_program):
    expected = subprocess.run([crosscheck_program, "error"], check=True, capture_output=True, text=True).stdout
    assert expected
    with pytest.raises(snh.Error) as info:
        snh.Material.from_youngs_modulus(-1.0, 0.3)
    assert str(info.value) == expected
    assert isinstance(info.value, RuntimeError)
