"""topple: earthquake response of free-standing rigid objects, from Python.

The functions and types come from topple's C++ library (extension ``topple._core``): the same solvers, readers,
validation and JSON summaries as the ``topple`` command line, so results are bit for bit those of the CLI.
Units are SI and every name says its unit (``accel_m_s2``, ``dt_s``, ``residual_displacement_m``); lengths are plain
floats in metres. See ``__init__.pyi`` for the documented signatures and ``topple.plot`` for matplotlib figures.

Array inputs: a numpy array must be float64 (``TypeError`` otherwise: int or float32 data is never cast silently)
and 1-D; a strided (non-contiguous) float64 array is accepted and copied; a list or tuple of numbers is converted.
Bad values (NaN, Inf, dt <= 0, an unknown unit ...) raise ``topple.InputError`` (a ``ValueError``) with the CLI's
message and attributes ``file``, ``line``, ``field``, ``problem``.
"""
from ._core import (
    STANDARD_GRAVITY,
    Block,
    Cylinder,
    General,
    GroundMotion,
    InputError,
    RockingBody,
    RockingResult,
    SlidingResult,
    intensity,
    invert,
    read,
    rock,
    slide,
    slide_spectrum,
    synth,
)

__version__ = "0.1.0"

__all__ = [
    "STANDARD_GRAVITY",
    "Block",
    "Cylinder",
    "General",
    "GroundMotion",
    "InputError",
    "RockingBody",
    "RockingResult",
    "SlidingResult",
    "intensity",
    "invert",
    "read",
    "rock",
    "slide",
    "slide_spectrum",
    "synth",
]
