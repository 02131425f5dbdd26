"""Stable Neo-Hookean flesh simulation on OpenCL devices.

The engine is the snh C++ library; this package binds its public API
(include/snh/) with NumPy arrays in and out. See docs/python.md.
"""

from ._snh import *  # noqa: F401,F403
from ._snh import Error  # noqa: F401
from ._meshio import from_meshio, to_meshio, to_pyvista  # noqa: F401

__version__ = "0.1.0"
