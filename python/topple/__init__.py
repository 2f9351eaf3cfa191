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
import os as _os

from . import _core
from ._core import (
    STANDARD_GRAVITY,
    Block,
    Cylinder,
    FragilityFit,
    General,
    GroundMotion,
    InputError,
    RockingBody,
    RockingResult,
    SlidingResult,
    fourier_spectrum,
    fragility,
    fragility_fit,
    intensity,
    invert,
    overturning_map,
    read,
    response_spectrum,
    rock,
    slide,
    slide_flexible,
    slide_spectrum,
    synth,
)

__version__ = "0.1.0"

__all__ = [
    "STANDARD_GRAVITY",
    "Block",
    "Cylinder",
    "FragilityFit",
    "General",
    "GroundMotion",
    "InputError",
    "RockingBody",
    "RockingResult",
    "SlidingResult",
    "SweepTable",
    "fourier_spectrum",
    "fragility",
    "fragility_fit",
    "intensity",
    "invert",
    "overturning_map",
    "read",
    "response_spectrum",
    "rock",
    "slide",
    "slide_flexible",
    "slide_spectrum",
    "sweep",
    "synth",
]


class SweepTable(dict):
    """The table of a sweep: column name -> values, in the CSV's column order (``topple sweep`` writes the same rows).

    Numeric columns (numbers and true/false) are float64 numpy arrays, NaN where the CSV cell is empty (the value
    does not apply to the row, e.g. a rocking column on a sliding row); text columns are lists of str (None where
    empty). Units are in the column names (``max_abs_displacement_m``, ``pga_g``)."""

    @property
    def columns(self) -> list:
        """Column names, in order."""
        return list(self.keys())

    @property
    def n_rows(self) -> int:
        """Number of rows (runs)."""
        return len(next(iter(self.values()))) if self else 0

    def to_pandas(self):
        """A pandas.DataFrame of the table (pandas is not a dependency of topple: ImportError when absent)."""
        try:
            import pandas
        except ImportError as err:
            raise ImportError("SweepTable.to_pandas needs pandas (pip install pandas)") from err
        return pandas.DataFrame(dict(self))


def sweep(path, threads: int = 0) -> SweepTable:
    """Run a sweep file (TOML, docs/sweeps.md) in memory, as ``topple sweep`` does, and return its table.

    path: the sweep file (str or path-like); relative record globs are anchored at its directory. Its [output]
    section is ignored: nothing is written. threads: worker threads, 0 = every core this process may use. The GIL is
    released while the runs compute. Bad files raise topple.InputError naming the file, line and key."""
    return SweepTable(_core._sweep(_os.fspath(path), threads=threads))
