"""topple: earthquake response of free-standing rigid objects, from Python.

The functions and types come from topple's C++ library (extension ``topple._core``): the same solvers, readers,
validation and JSON summaries as the ``topple`` command line, so results are bit for bit those of the CLI.
Units are SI and every name says its unit (``accel_m_s2``, ``dt_s``, ``residual_displacement_m``); lengths are plain
floats in metres. See ``__init__.pyi`` for the documented signatures and ``topple.plot`` for matplotlib figures.

Array inputs: a numpy array must be float64 (``TypeError`` otherwise: int or float32 data is never cast silently)
and 1-D; a strided (non-contiguous) float64 array is accepted and copied; a list or tuple of numbers is converted.
Bad values (NaN, Inf, dt <= 0, an unknown unit ...) raise ``topple.InputError`` (a ``ValueError``) with the CLI's
message and attributes ``file``, ``line``, ``field``, ``problem``; a file that does not exist raises
``topple.MissingFileError``, which is both an ``InputError`` and a ``FileNotFoundError``.

Every public function and class has a numpy-style docstring with units: ``help(topple.slide)``.
The distribution on PyPI is ``topple-quake`` (``pip install topple-quake[plot]``); the import name is ``topple``.
"""
import math as _math
import numbers as _numbers
import os as _os
import re as _re
from typing import Any as _Any, Mapping as _Mapping, Optional as _Optional, Union as _Union

from . import _core
from ._core import (
    STANDARD_GRAVITY,
    Block,
    Cylinder,
    FragilityFit,
    General,
    GeneralAsymmetric,
    GroundMotion,
    InputError,
    MissingFileError,
    MotionSet,
    RockingBody,
    RockingResult,
    SlideRockResult,
    Sliding2dResult,
    SlidingResult,
    fourier_spectrum,
    fragility,
    fragility_fit,
    intensity,
    overturning_map,
    read,
    response_spectrum,
    rock,
    rock3d,
    rock_oriented,
    rotd,
    slide,
    slide_2d,
    slide_flexible,
    slide_rock,
    slide_spectrum,
    slide_spectrum_2d,
    synth,
)

__version__ = "0.1.0"

__all__ = [
    "STANDARD_GRAVITY",
    "Block",
    "Cylinder",
    "FragilityFit",
    "General",
    "GeneralAsymmetric",
    "GroundMotion",
    "InputError",
    "MissingFileError",
    "MotionSet",
    "RockingBody",
    "RockingResult",
    "SlideRockResult",
    "Sliding2dResult",
    "SlidingResult",
    "SweepTable",
    "fourier_spectrum",
    "fragility",
    "fragility_fit",
    "intensity",
    "invert",
    "invert_region",
    "overturning_map",
    "read",
    "response_spectrum",
    "rock",
    "rock3d",
    "rock_oriented",
    "rotd",
    "slide",
    "slide_2d",
    "slide_flexible",
    "slide_rock",
    "slide_spectrum",
    "slide_spectrum_2d",
    "survey_toml",
    "sweep",
    "synth",
]


class SweepTable(dict):
    """The table of a sweep (the result of topple.sweep): column name -> values, in the CSV's column order.

    ``topple sweep`` writes the same rows. Numeric columns (numbers and true/false) are float64 numpy arrays, NaN
    where the CSV cell is empty (the value does not apply to the row, e.g. a rocking column on a sliding row); text
    columns are lists of str (None where empty). Units are in the column names (``max_abs_displacement_m`` in m,
    ``pga_g`` in g).

    Attributes
    ----------
    columns : list of str
        Column names, in order.
    n_rows : int
        Number of rows (runs).
    """

    @property
    def columns(self) -> list:
        """Column names, in order."""
        return list(self.keys())

    @property
    def n_rows(self) -> int:
        """Number of rows (runs)."""
        return len(next(iter(self.values()))) if self else 0

    def to_pandas(self):
        """The table as a pandas DataFrame (pandas is not a dependency of topple).

        Returns
        -------
        pandas.DataFrame
            One column per sweep column, one row per run.

        Raises
        ------
        ImportError
            When pandas is not installed.
        """
        try:
            import pandas
        except ImportError as err:
            raise ImportError("SweepTable.to_pandas needs pandas (pip install pandas)") from err
        return pandas.DataFrame(dict(self))


def sweep(path, threads: int = 0) -> SweepTable:
    """Run a sweep file (TOML, docs/sweeps.md) in memory, as ``topple sweep`` does, and return its table.

    Relative record globs are anchored at the file's directory. Its [output] section is ignored: nothing is
    written. The GIL is released while the runs compute.

    Parameters
    ----------
    path : str or os.PathLike
        The sweep file. A missing file raises topple.MissingFileError (a FileNotFoundError); a bad one
        topple.InputError naming the file, line and key.
    threads : int
        Worker threads, 0 = every core this process may use.

    Returns
    -------
    SweepTable
        Column name -> values, the rows of the CSV ``topple sweep`` writes.
    """
    return SweepTable(_core._sweep(_os.fspath(path), threads=threads))


_BARE_KEY = _re.compile(r"^[A-Za-z0-9_-]+$")


def _toml_key(key: str) -> str:
    if not isinstance(key, str):
        raise TypeError(f"survey keys must be str, got {type(key).__name__} ({key!r})")
    return key if _BARE_KEY.match(key) else _toml_string(key)


def _toml_string(text: str) -> str:
    # TOML basic strings share JSON's escapes (\", \\, \n, \uXXXX); control characters are escaped.
    out = []
    for ch in text:
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _toml_value(value: _Any, where: str) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, _numbers.Integral):
        return str(int(value))
    if isinstance(value, _numbers.Real):
        v = float(value)
        if _math.isnan(v):
            return "nan"
        if _math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, (str, _os.PathLike)):
        return _toml_string(_os.fspath(value))
    if isinstance(value, (list, tuple)) or (hasattr(value, "tolist") and hasattr(value, "ndim")):
        items = value.tolist() if hasattr(value, "tolist") else value
        return "[" + ", ".join(_toml_value(v, where) for v in items) + "]"
    if value is None:
        raise TypeError(f"survey: {where} is None: leave the key out for its default")
    raise TypeError(f"survey: {where} has type {type(value).__name__}: use str, numbers, bools or lists of them")


def _is_table_array(value: _Any) -> bool:
    return isinstance(value, (list, tuple)) and len(value) > 0 and all(isinstance(v, _Mapping) for v in value)


def _toml_table(table: _Mapping, prefix: str, lines: list) -> None:
    """Plain keys first, then sub-tables [prefix.key], then arrays of tables [[prefix.key]] (TOML's order rule)."""
    for key, value in table.items():
        if not isinstance(value, _Mapping) and not _is_table_array(value):
            lines.append(f"{_toml_key(key)} = {_toml_value(value, prefix + str(key))}")
    for key, value in table.items():
        name = prefix + _toml_key(key)
        if isinstance(value, _Mapping):
            lines.append(f"\n[{name}]")
            _toml_table(value, name + ".", lines)
    for key, value in table.items():
        name = prefix + _toml_key(key)
        if _is_table_array(value):
            for item in value:
                lines.append(f"\n[[{name}]]")
                _toml_table(item, name + ".", lines)


def survey_toml(survey: _Mapping[str, _Any]) -> str:
    """The TOML text of a survey built in Python (the structure of a survey file, docs/survey.md).

    Useful to save a survey that topple.invert was given as a dict: the file gives the same inversion.

    Parameters
    ----------
    survey : dict
        Tables as dicts ("site", "inversion", "event"), arrays of tables as lists of dicts ("object", "sites"),
        values as str (lengths with their unit, e.g. "8cm"), numbers, bools or lists of them.

    Returns
    -------
    str
        The survey as TOML.

    Raises
    ------
    TypeError
        For a value TOML cannot hold (None, an object) or a key that is not a str.
    """
    if not isinstance(survey, _Mapping):
        raise TypeError(f"survey must be a dict, got {type(survey).__name__}")
    lines: list = []
    _toml_table(survey, "", lines)
    return "\n".join(lines).lstrip("\n") + "\n"


def invert(survey: _Union[str, "_os.PathLike[str]", _Mapping[str, _Any]], *, threads: int = 0,
           report_dir: _Optional[_Union[str, "_os.PathLike[str]"]] = None,
           base_dir: _Optional[_Union[str, "_os.PathLike[str]"]] = None) -> dict:
    """Estimate the PGA (g) and predominant frequency (Hz) of the shaking from a survey, as ``topple invert --json``.

    Parameters
    ----------
    survey : str, os.PathLike or dict
        A survey file (TOML, docs/survey.md), or a survey built in Python: a dict with the file's structure, e.g.
        ``{"site": {"name": "Kitchen"}, "inversion": {"pga_g": [0.05, 2.0, 20]}, "object": [{"id": "vase",
        "shape": "cylinder", "diameter": "8cm", "height": "40cm", "mu": 0.5, "outcome": "overturned"}]}``
        (lengths are strings with their unit; the library validates it exactly as a file, with the same messages
        naming the object and field). A missing file raises topple.MissingFileError (a FileNotFoundError).
    threads : int
        Worker threads, 0 = every core.
    report_dir : str or os.PathLike, optional
        Also write the HTML report there, as ``topple invert --report DIR`` (DIR/index.html and its figures; with
        several sites DIR/site1, DIR/site2 ...). The folder is made when missing.
    base_dir : str or os.PathLike, optional
        For a dict survey: the folder that relative record paths resolve against (default: the current folder).

    Returns
    -------
    dict
        One site's result (several sites: ``{"sites": [...]}``) with the keys of ``topple invert --json``:
        pga_g (g) and freq_hz (Hz) estimates (median, ci68, ci95, best), static_bounds_pga_g (g), objects,
        notes, grid (pga_g in g, freq_hz in Hz), prior, likelihood (the objects' own estimates, without the prior),
        pga_given_freq (per frequency column, the PGA in g the objects need there; median_g None where negligible),
        next_objects (household objects ranked by the bits one more observation adds); and beyond the CLI's JSON: posterior_grid and log_likelihood_grid
        (numpy, rows = PGA, columns = frequency) and each object's probability_grid (P(observation | cell)),
        for topple.plot.inversion_map.
    """
    report = None if report_dir is None else _os.fspath(report_dir)
    if isinstance(survey, _Mapping):
        base = _os.fspath(base_dir) if base_dir is not None else _os.getcwd()
        return _core._invert_text(survey_toml(survey), name="<survey dict>", base_dir=base, threads=threads,
                                  report_dir=report)
    if base_dir is not None:
        raise TypeError("base_dir applies to a dict survey; a file's records resolve against its own folder")
    return _core._invert_file(_os.fspath(survey), threads=threads, report_dir=report)


def invert_region(survey: _Union[str, "_os.PathLike[str]", _Mapping[str, _Any]], *, threads: int = 0,
                  base_dir: _Optional[_Union[str, "_os.PathLike[str]"]] = None) -> dict:
    """The regional joint inversion of a multi-site survey: the attenuation relation and every site pooled through it.

    What ``topple invert --json`` gives as ``region`` (docs/method.md, "Regional joint inversion"): every site with
    objects inverted on its own, then ln PGA = c0 - c1 ln sqrt(R^2 + c2^2) + delta fitted to all of them by grid
    integration, with the predominant frequency's relation ln f = d0 + d1 ln sqrt(R^2 + c2^2) + eps when the data
    support it (Bayes factor against a constant frequency of at least 3).

    Parameters
    ----------
    survey : str, os.PathLike or dict
        A regional survey file (TOML, docs/survey.md: ``[event] epicentre``, at least 3 sites with lat/lon; stations
        with ``pga_g`` or ``record``), or the same as a dict (see topple.invert).
    threads : int
        Worker threads for the sites' inversions, 0 = every core.
    base_dir : str or os.PathLike, optional
        For a dict survey: the folder that relative record paths resolve against (default: the current folder).

    Returns
    -------
    dict
        ``relation`` (c0_ln_g, c1, tau_ln, pga_at_reference_g: each {median, ci68, ci95}; c2_km fixed,
        reference_distance_km), ``frequency_relation`` (None, or d0_ln_hz, d1, tau_f_ln, ln_bayes_factor, supported,
        ...), ``sites`` (per located site: hypocentral_distance_km, pooled_pga_g (g), relation_pga_g (g),
        independent_pga_g (g), pooled_freq_hz (Hz, None unless the frequency relation is supported),
        independent_freq_hz (Hz), calibration), ``priors``, ``contour_levels_g`` (g), ``notes``; and beyond the
        CLI's ``region``: ``region_notes`` and ``site_results`` (each survey site's own inversion as topple.invert
        gives it, None for a station without objects).

    Raises
    ------
    topple.InputError
        For a survey that gets no regional fit (no epicentre, fewer than 3 located sites), naming the reason; and for
        a bad survey, as topple.invert.
    """
    if isinstance(survey, _Mapping):
        base = _os.fspath(base_dir) if base_dir is not None else _os.getcwd()
        return _core._invert_region_text(survey_toml(survey), name="<survey dict>", base_dir=base, threads=threads)
    if base_dir is not None:
        raise TypeError("base_dir applies to a dict survey; a file's records resolve against its own folder")
    return _core._invert_region_file(_os.fspath(survey), threads=threads)
