"""matplotlib figures of topple's results (needs the ``plot`` extra: ``pip install "topple-quake[plot]"``).

Naming scheme: each function is named after what it draws and takes the result of the topple function that
computes it (the history figures also take the motion, which they draw)::

    topple.slide(motion, ...)     -> plot.sliding(motion, result)
    topple.rock(motion, ...)      -> plot.rocking(motion, result)     (either: plot.response(motion, result))
    topple.slide_spectrum(...)    -> plot.sliding_spectrum(spec)
    topple.response_spectrum(...) -> plot.response_spectrum(spec)
    topple.fourier_spectrum(...)  -> plot.fourier_spectrum(fas)
    topple.overturning_map(...)   -> plot.overturning_map(omap)
    topple.fragility(...)         -> plot.fragility(result)
    topple.invert(...)            -> plot.inversion_map(result)

The three spectrum figures also accept a GroundMotion, computed with the defaults. Every function draws into
``ax=`` (a matplotlib Axes; single-panel figures) or ``fig=`` (a Figure or SubFigure; the three-panel histories)
when given, else into a new Figure built without pyplot (no global state, works headless), and returns the Figure:
save it with ``fig.savefig("name.png")``. Values are plotted in the units their names say. Titles name the analysis
(the record's file name without its folders, the parameters); ``title=`` replaces it.

Deprecated names (they warn with a DeprecationWarning and will be removed): ``plot.slide_spectrum`` (the compute
function, which is ``topple.slide_spectrum``) and ``plot.sliding_spectrum(motion, mu, slope_deg=, mode=, g=)``
computing the spectrum itself (compute with topple.slide_spectrum and pass its result).
"""
from __future__ import annotations

import math
import os
import textwrap
import warnings
from typing import Any, Mapping, Optional, Sequence

import numpy as np

try:
    from matplotlib import patheffects
    from matplotlib.figure import Figure
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
except ImportError as _err:  # pragma: no cover - exercised by a subprocess test
    raise ImportError("topple.plot needs matplotlib, which the plot extra installs: "
                      "pip install \"topple-quake[plot]\" (from a checkout: pip install \".[plot]\"; "
                      "or pip install matplotlib)") from _err

from . import GroundMotion, RockingResult, SlidingResult
from . import fourier_spectrum as _fourier_spectrum
from . import response_spectrum as _response_spectrum
from . import slide_spectrum as _slide_spectrum

__all__ = ["response", "sliding", "rocking", "sliding_spectrum", "inversion_map", "response_spectrum",
           "fourier_spectrum", "overturning_map", "fragility"]

_TITLE_WIDTH = 80  # characters per title line: longer titles wrap instead of running off the figure


# ---- helpers ----

def _root_figure(fig_or_subfig: Any) -> Figure:
    """The top-level Figure of a Figure or SubFigure."""
    try:
        return fig_or_subfig.get_figure(root=True)  # matplotlib >= 3.10
    except (TypeError, AttributeError):
        while not isinstance(fig_or_subfig, Figure):
            fig_or_subfig = fig_or_subfig.figure  # a SubFigure's .figure is the root Figure before 3.10
        return fig_or_subfig


def _single_axes(ax: Any, figsize: tuple) -> tuple:
    """(figure to return, axes to draw into): the caller's axes, or a new constrained-layout figure."""
    if ax is None:
        fig = Figure(figsize=figsize, layout="constrained")
        return fig, fig.subplots()
    return _root_figure(ax.figure), ax


def _wrap(title: str) -> str:
    return "\n".join(textwrap.wrap(title, _TITLE_WIDTH)) if len(title) > _TITLE_WIDTH else title


def _record_label(name: Optional[str]) -> str:
    """A record's name for a title: a file's base name (never its folders: an absolute path says nothing and runs off
    the figure), else the description (synthetic motions)."""
    if not name:
        return "record"
    # A description may hold a slash ("PGA 2.9 m/s2"): only a name that is a path loses its folders.
    if os.path.isabs(name) or os.path.exists(name) or (os.sep in name and " " not in name):
        return os.path.basename(name) or name
    return name


def _log_axis_125(axis: Any) -> None:
    """Log axis labelled at 1, 2, 5 x 10^k with plain numbers (0.2, 0.5, 1, 2 ...), not 10^-1."""
    axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def _need_history(result: Any) -> None:
    if len(result.time_s) == 0:
        raise ValueError("this result has no time history: run it with history=True (the default)")


def _history_panels(fig: Any, motion: GroundMotion, result: Any, thresholds: Sequence[tuple], middle: tuple,
                    bottom: tuple) -> tuple:
    """Three panels sharing the time axis, in the caller's figure or subfigure or a new one: the record with its
    threshold lines, then `middle` and `bottom` = (values, y label, colour). Returns (figure, target, axes)."""
    _need_history(result)
    if fig is None:
        fig = Figure(figsize=(9, 7), layout="constrained")
    ax = fig.subplots(3, 1, sharex=True)
    _record_panel(ax[0], motion, result.g_m_s2, thresholds)
    for a, (values, label, color) in zip(ax[1:], (middle, bottom)):
        a.plot(result.time_s, values, color=color)
        a.set_ylabel(label)
        a.grid(alpha=0.3)
    ax[2].set_xlabel("time (s)")
    return _root_figure(fig), fig, ax


def _record_panel(ax: Any, motion: GroundMotion, g_m_s2: float, thresholds: Sequence[tuple]) -> None:
    ax.plot(motion.time_s, motion.accel_m_s2 / g_m_s2, color="0.25", lw=0.7, label="ground")
    for value, label in thresholds:
        ax.axhline(value, color="tab:red", lw=0.9, ls="--", label=label)  # "" : no legend entry
    ax.set_ylabel("ground accel. (g)")
    ax.legend(loc="upper right", fontsize="small")
    ax.grid(alpha=0.3)


# ---- histories ----

def sliding(motion: GroundMotion, result: SlidingResult, title: Optional[str] = None, *,
            fig: Any = None) -> Figure:
    """Sliding history: the record with its yield accelerations, displacement and velocity on one time axis.

    Parameters
    ----------
    motion : GroundMotion
        The ground motion the block was run on (accelerations drawn in g).
    result : SlidingResult
        The result of topple.slide(motion, ...), run with history=True.
    title : str, optional
        Figure title (default: mu, mode, slope and the record's file name).
    fig : matplotlib.figure.Figure or SubFigure, optional
        Draw the three panels into it (it should be empty); default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        Panels: ground acceleration (g) with the yield accelerations (g), relative displacement (m), relative
        velocity (m/s), against time (s).
    """
    lines = [(result.yield_down_g, f"yield +{result.yield_down_g:.3g} g")]
    if result.yield_up_g is not None:
        lines.append((result.yield_up_g, f"yield {result.yield_up_g:.3g} g"))
    root, target, _ = _history_panels(fig, motion, result, lines,
                                      (result.displacement_m, "displacement (m)", "tab:blue"),
                                      (result.velocity_m_s, "rel. velocity (m/s)", "tab:green"))
    mu = f"mu = {result.mu_static:g}"
    if result.mu_kinetic != result.mu_static:
        mu += f", mu_k = {result.mu_kinetic:g}"
    target.suptitle(_wrap(title or f"Sliding block, {mu}, {result.mode}, slope {result.slope_deg:g} deg: "
                                   f"{_record_label(motion.name)}"))
    return root


def rocking(motion: GroundMotion, result: RockingResult, title: Optional[str] = None, *,
            fig: Any = None) -> Figure:
    """Rocking history: the record with the uplift thresholds +-g tan(alpha), theta/alpha and theta'.

    Parameters
    ----------
    motion : GroundMotion
        The ground motion the body was run on (accelerations drawn in g).
    result : RockingResult
        The result of topple.rock(motion, ...), run with history=True.
    title : str, optional
        Figure title (default: the body, e, the verdict and the record's file name).
    fig : matplotlib.figure.Figure or SubFigure, optional
        Draw the three panels into it (it should be empty); default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        Panels: ground acceleration (g) with +-tan(alpha) (g), rotation theta / alpha (dimensionless), angular
        velocity theta' (rad/s), against time (s).
    """
    _need_history(result)  # before dividing by alpha: an empty history is the caller's mistake, said plainly
    tan_alpha = math.tan(result.alpha_rad)
    root, target, ax = _history_panels(fig, motion, result,
                                       [(tan_alpha, f"±g tan(alpha) = ±{tan_alpha:.3g} g"), (-tan_alpha, "")],
                                       (np.asarray(result.theta_rad) / result.alpha_rad, "theta / alpha", "tab:blue"),
                                       (result.theta_dot_rad_s, "theta' (rad/s)", "tab:green"))
    for level in (1.0, -1.0):
        ax[1].axhline(level, color="tab:red", lw=0.8, ls=":")
    verdict = "overturned" if result.overturned else f"max |theta| = {result.max_rotation_over_alpha:.3g} alpha"
    target.suptitle(_wrap(title or f"Rocking {result.body!r}, e = {result.e:.3g} ({result.e_mode}): {verdict}: "
                                   f"{_record_label(motion.name)}"))
    return root


def response(motion: GroundMotion, result: Any, title: Optional[str] = None, *, fig: Any = None) -> Figure:
    """The history figure of a sliding or rocking result: sliding() or rocking(), by the type of result.

    Parameters
    ----------
    motion : GroundMotion
        The ground motion the object was run on.
    result : SlidingResult or RockingResult
        The result of topple.slide or topple.rock.
    title : str, optional
        Figure title.
    fig : matplotlib.figure.Figure or SubFigure, optional
        Draw into it; default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        As sliding() or rocking().
    """
    if isinstance(result, SlidingResult):
        return sliding(motion, result, title, fig=fig)
    if isinstance(result, RockingResult):
        return rocking(motion, result, title, fig=fig)
    raise TypeError(f"expected a SlidingResult or RockingResult, got {type(result).__name__}")


# ---- spectra ----

def sliding_spectrum(spec: Any, mu: Optional[Sequence[float]] = None, *, title: Optional[str] = None,
                     ax: Any = None, slope_deg: Optional[float] = None, mode: Optional[str] = None,
                     g: Optional[float] = None) -> Figure:
    """Sliding displacement spectrum: maximum |displacement| and |residual| against the friction coefficient.

    Parameters
    ----------
    spec : dict or GroundMotion
        The result of topple.slide_spectrum(motion, mu, ...); or a GroundMotion, computed two-way on a level plane
        for 60 values of mu from 2 % to 120 % of PGA / g.
    mu : sequence of float, optional
        Deprecated (DeprecationWarning): friction coefficients (dimensionless) to compute the spectrum of a motion
        at; compute with topple.slide_spectrum instead.
    title : str, optional
        Title (default: mode, slope and the record's file name).
    ax : matplotlib.axes.Axes, optional
        Draw into it; default a new Figure.
    slope_deg, mode, g : optional
        Deprecated (DeprecationWarning), with a motion: plane inclination (deg), sliding mode, gravity (m/s^2).

    Returns
    -------
    matplotlib.figure.Figure
        Displacement (m, symlog axis) against mu (dimensionless).
    """
    if isinstance(spec, GroundMotion):
        legacy = {k: v for k, v in (("slope_deg", slope_deg), ("mode", mode), ("g", g)) if v is not None}
        if mu is not None or legacy:
            warnings.warn("topple.plot.sliding_spectrum(motion, mu, slope_deg=, mode=, g=) is deprecated: compute "
                          "spec = topple.slide_spectrum(motion, mu, ...) and call topple.plot.sliding_spectrum(spec)",
                          DeprecationWarning, stacklevel=2)
        gravity = legacy.get("g", 9.80665)
        if mu is None:
            pga_g = float(spec.pga_m_s2) / gravity
            mu = np.linspace(0.02 * pga_g, 1.2 * pga_g, 60)
        spec = _slide_spectrum(spec, np.asarray(mu, dtype=np.float64), slope_deg=legacy.get("slope_deg", 0.0),
                               mode=legacy.get("mode", "two-way"), g=gravity)
    elif mu is not None or slope_deg is not None or mode is not None or g is not None:
        raise TypeError("mu, slope_deg, mode and g apply only when a GroundMotion is passed (deprecated); the "
                        "spectrum from topple.slide_spectrum already holds them")
    fig, ax = _single_axes(ax, (7, 4.5))
    ax.plot(spec["mu"], spec["max_abs_displacement_m"], marker=".", label="max |displacement|")
    ax.plot(spec["mu"], np.abs(spec["residual_displacement_m"]), ls="--", label="|residual|")
    ax.set_yscale("symlog", linthresh=1e-4)
    ax.set_xlabel("friction coefficient mu")
    ax.set_ylabel("displacement (m)")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title(_wrap(title or f"Sliding spectrum ({spec['mode']}, slope {spec['slope_deg']:g} deg, PGA "
                                f"{spec['pga_g']:.3g} g): {_record_label(spec.get('motion'))}"))
    return fig


def response_spectrum(spec: Any, title: Optional[str] = None, *, units: str = "g",
                      tp_s: Optional[float] = None, ax: Any = None) -> Figure:
    """Pseudo-spectral acceleration against period (log axis).

    Parameters
    ----------
    spec : dict or GroundMotion
        The result of topple.response_spectrum; or a GroundMotion (its 5 %-damped spectrum on the default periods).
    title : str, optional
        Title (default: the damping and the record's file name).
    units : {"g", "m/s2"}
        Unit of the PSA axis.
    tp_s : float, optional
        A period to mark, s (e.g. topple.intensity(motion)["tp_s"]).
    ax : matplotlib.axes.Axes, optional
        Draw into it; default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        PSA (g or m/s^2) against period (s).
    """
    if isinstance(spec, GroundMotion):
        spec = _response_spectrum(spec)
    if units not in ("g", "m/s2"):
        raise ValueError(f"units must be 'g' or 'm/s2', got {units!r}")
    psa = np.asarray(spec["psa_g"] if units == "g" else spec["psa_m_s2"])
    fig, ax = _single_axes(ax, (7, 4.5))
    ax.plot(spec["period_s"], psa, color="tab:blue", label=f"PSA, {100 * spec['damping']:g} % damping")
    if tp_s is not None:
        ax.axvline(tp_s, color="tab:orange", ls="--", lw=1.0, label=f"Tp = {tp_s:.3f} s")
    ax.set_xscale("log")
    _log_axis_125(ax.xaxis)
    ax.set_xlabel("period (s)")
    ax.set_ylabel("PSA (g)" if units == "g" else "PSA (m/s²)")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    ax.set_title(_wrap(title or f"Response spectrum, {100 * spec['damping']:g} % damping: "
                                f"{_record_label(spec.get('motion'))}"))
    return fig


def fourier_spectrum(fas: Any, title: Optional[str] = None, *, ax: Any = None) -> Figure:
    """Fourier amplitude against frequency, log-log: the FAS, its Konno-Ohmachi smoothing, the predominant frequency.

    Parameters
    ----------
    fas : dict or GroundMotion
        The result of topple.fourier_spectrum; or a GroundMotion (smoothing b = 40).
    title : str, optional
        Title (default: the record's file name).
    ax : matplotlib.axes.Axes, optional
        Draw into it; default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        Fourier amplitude (m/s) against frequency (Hz).
    """
    if isinstance(fas, GroundMotion):
        fas = _fourier_spectrum(fas)
    f = np.asarray(fas["freq_hz"])
    a = np.asarray(fas["amplitude_m_s"])
    keep = f > 0  # log axis
    fig, ax = _single_axes(ax, (7, 4.5))
    ax.plot(f[keep], a[keep], color="0.7", lw=0.6, label="FAS")
    if fas.get("smoothed_amplitude_m_s") is not None:
        ax.plot(fas["smoothed_freq_hz"], fas["smoothed_amplitude_m_s"], color="tab:blue", lw=1.5,
                label=f"Konno-Ohmachi, b = {fas['smoothing_b']:g}")
    fp = fas.get("predominant_frequency_hz")
    if fp is not None:
        ax.axvline(fp, color="tab:red", ls="--", lw=1.0, label=f"f_p = {fp:.3g} Hz")
    ax.set_xscale("log")
    ax.set_yscale("log")
    _log_axis_125(ax.xaxis)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("Fourier amplitude (m/s)")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    ax.set_title(_wrap(title or f"Fourier amplitude spectrum: {_record_label(fas.get('motion'))}"))
    return fig


# ---- object spectra, fragility ----

def overturning_map(omap: Mapping[str, Any], title: Optional[str] = None, *, ax: Any = None) -> Figure:
    """Overturned (dark) or standing against PGA and body height, with each size's first-overturn PGA.

    Parameters
    ----------
    omap : dict
        The result of topple.overturning_map.
    title : str, optional
        Title (default: shape, alpha and the record's file name).
    ax : matplotlib.axes.Axes, optional
        Draw into it; default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        Cells over PGA (g) x body height (m), the first-overturn PGA (g) per height and the uplift threshold
        PGA = g tan(alpha).
    """
    pga = np.asarray(omap["pga_g"], dtype=np.float64)
    height = np.asarray(omap["height_m"], dtype=np.float64)
    order = np.argsort(height)
    fell = np.asarray(omap["overturned"], dtype=np.float64)[order]
    h = height[order]

    def edges(v: np.ndarray) -> np.ndarray:
        if len(v) == 1:
            return np.array([v[0] * 0.9, v[0] * 1.1])
        mid = 0.5 * (v[:-1] + v[1:])
        return np.concatenate(([v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]))

    fig, ax = _single_axes(ax, (7.5, 5))
    ax.pcolormesh(edges(pga), edges(h), fell, cmap="Greys", vmin=0.0, vmax=1.6, shading="flat")
    first = np.asarray(omap["first_overturn_pga_g"], dtype=np.float64)[order]
    ax.plot(first, h, marker="o", color="tab:red", lw=1.0, label="first-overturn PGA")
    ax.axvline(omap["uplift_pga_g"], color="tab:blue", ls="--", lw=1.0, label="uplift: PGA = g tan(alpha)")
    ax.set_xlabel("PGA (g)")
    ax.set_ylabel("body height (m)")
    ax.legend(loc="upper left", fontsize="small")
    ax.set_title(_wrap(title or f"Overturning map, {omap['shape']}, alpha = {math.degrees(omap['alpha_rad']):.3g} "
                                f"deg: {_record_label(omap.get('motion'))}"))
    return fig


def fragility(result: Mapping[str, Any], title: Optional[str] = None, *, level: float = 0.95,
              ax: Any = None) -> Figure:
    """Probability of failure against the intensity measure: observed fractions, lognormal fits and their bands.

    Parameters
    ----------
    result : dict
        The result of topple.fragility, or one of its curves.
    title : str, optional
        Title (default: what was analysed: mu and threshold, the body, the number of motions, the band level).
    level : float
        Confidence level of the delta-method band (0 to 1).
    ax : matplotlib.axes.Axes, optional
        Draw into it; default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        Probability against the IM in its unit (g for PGA, m/s for PGV and CAV, m for PGD), log axis.
    """
    curves = result["curves"] if "curves" in result else [result]
    im = result.get("im", "im")
    unit = result.get("im_unit", "")
    fig, ax = _single_axes(ax, (7, 4.5))
    for k, curve in enumerate(curves):
        color = f"C{k}"
        x = np.asarray(curve["im"], dtype=np.float64)
        ax.plot(x, curve["fraction"], ls="none", marker="o", color=color, label=f"{curve['name']}: observed")
        fit = curve.get("fit")
        if fit is not None:
            xs = np.geomspace(x.min() / 1.5, x.max() * 1.5, 200)
            bound = " (at its bound)" if fit.beta_at_bound else ""
            ax.plot(xs, fit.probability(xs), color=color,
                    label=f"{curve['name']}: theta = {fit.theta:.3g} {unit}, beta = {fit.beta:.2f}{bound}")
            lower, upper = fit.band(xs, level)
            ax.fill_between(xs, lower, upper, color=color, alpha=0.2, lw=0)
    ax.set_xscale("log")
    _log_axis_125(ax.xaxis)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(f"{str(im).upper()} ({unit})" if unit else str(im))
    ax.set_ylabel("probability of failure")
    ax.grid(alpha=0.3, which="both")
    # Below the axes: a long label ("... beta = 0.35") never runs off the figure or covers the curves.
    ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=1, frameon=False)
    if title is None:
        what = []
        if result.get("mu") is not None:
            what.append(f"sliding mu = {result['mu']:g}, d > {result['threshold_m']:g} m")
        if result.get("body") is not None:
            what.append(f"overturning of {result['body']!r}")
        motions = f", {result['motions']} motions" if result.get("motions") else ""
        title = f"Fragility{': ' + '; '.join(what) if what else ''}{motions} ({100 * level:g} % band)"
    ax.set_title(_wrap(title))
    return fig


# ---- inversion ----

def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges of a log-spaced grid at the geometric midpoints (as the inversion spreads a cell's mass)."""
    v = np.asarray(values, dtype=np.float64)
    if len(v) == 1:
        return np.array([v[0] / 1.1, v[0] * 1.1])
    mid = np.sqrt(v[:-1] * v[1:])
    return np.concatenate(([v[0] ** 2 / mid[0]], mid, [v[-1] ** 2 / mid[-1]]))


def _credible_levels(posterior: np.ndarray, masses: Sequence[float]) -> list:
    """Posterior values whose super-level sets hold `masses` of the probability (highest-posterior-density
    regions): the cells sorted by posterior, the smallest value kept when the cumulative mass first reaches m."""
    p = np.sort(np.asarray(posterior, dtype=np.float64).ravel())[::-1]
    cum = np.cumsum(p) / p.sum()
    return [float(p[min(int(np.searchsorted(cum, m)), len(p) - 1)]) for m in masses]


def inversion_map(result: Mapping[str, Any], title: Optional[str] = None, *, ax: Any = None) -> Figure:
    """The inversion's map, on the report's axes: posterior over log PGA x log frequency with its credible regions.

    Drawn: the posterior per cell (colour), the 68 % and 95 % highest-posterior-density regions (white, solid and
    dashed), the median (PGA, frequency), the static bounds on PGA (red vertical lines), and for every object the
    line where its observation has probability 0.5 (labelled with the object's id; an object whose probability is
    above or below 0.5 on the whole grid has no line and its legend entry says so).

    Parameters
    ----------
    result : dict
        The result of topple.invert for one site (a multi-site result: pass one of result["sites"]).
    title : str, optional
        Title (default: the site and the number of objects).
    ax : matplotlib.axes.Axes, optional
        Draw into it (the colour bar takes space from it); default a new Figure.

    Returns
    -------
    matplotlib.figure.Figure
        PGA (g, log axis labelled at 1-2-5) against predominant frequency (Hz, log axis).
    """
    if "sites" in result:
        raise ValueError("this survey has several sites: pass one of result['sites']")
    pga = np.asarray(result["grid"]["pga_g"], dtype=np.float64)
    freq = np.asarray(result["grid"]["freq_hz"], dtype=np.float64)
    post = np.asarray(result["posterior_grid"], dtype=np.float64)  # rows PGA, columns frequency
    fig, ax = _single_axes(ax, (9, 6))
    # The report's axes: PGA across, frequency up; the grids' rows are PGA, so they are drawn transposed.
    mesh = ax.pcolormesh(_edges(pga), _edges(freq), post.T, cmap="viridis", shading="flat")
    ax.figure.colorbar(mesh, ax=ax, label="posterior probability per cell", pad=0.01)
    ax.set_xscale("log")
    ax.set_yscale("log")
    _log_axis_125(ax.xaxis)
    _log_axis_125(ax.yaxis)
    handles = []
    edge = [patheffects.Stroke(linewidth=2.8, foreground="black"), patheffects.Normal()]
    if len(pga) > 1 and len(freq) > 1 and post.max() > 0:
        l68, l95 = _credible_levels(post, (0.68, 0.95))
        for level, ls, name in ((l95, "--", "95 % credible region"), (l68, "-", "68 % credible region")):
            if 0 < level < post.max():
                # White with a black edge: visible on the dark map and in the light legend alike.
                cs = ax.contour(pga, freq, post.T, levels=[level], colors="white", linestyles=ls, linewidths=1.3)
                cs.set(path_effects=edge)
                handles.append(ax.plot([], [], color="white", ls=ls, lw=1.3, label=name, path_effects=edge)[0])
    med_pga = result["pga_g"].get("median")
    med_freq = result["freq_hz"].get("median")
    if med_pga is not None and med_freq is not None:
        handles.append(ax.plot([med_pga], [med_freq], marker="o", ms=8, color="white", mec="black", ls="none",
                               label=f"median: {med_pga:.3g} g, {med_freq:.3g} Hz")[0])
    # Static thresholds are hard (PGA > g b/h, mu g for an object that moved) or soft (mu g for an object that did not
    # slide visibly: it may slip below the visibility threshold); only a hard one is called a bound.
    low, high = result["static_bounds_pga_g"]
    hard_low, hard_high = result.get("static_bounds_hard_pga_g", [None, None])
    for v, hard, side, ls in ((low, hard_low, "lower", ":"), (high, hard_high, "upper", "-.")):
        if v is not None:
            kind = "hard" if hard is not None and abs(hard - v) <= 1e-12 * abs(v) else "soft"
            handles.append(ax.axvline(v, color="tab:red", ls=ls, lw=1.4,
                                      label=f"static {side} threshold ({kind}) {v:.3g} g"))
    styles = ["-", "--", ":", "-."]
    for k, obj in enumerate(result.get("objects", [])):
        color = f"C{k % 10}"
        ls = styles[(k // 10) % len(styles)]
        label = f"{obj['id']} ({obj['outcome']})"
        grid = obj.get("probability_grid")
        if grid is None:
            continue
        grid = np.asarray(grid, dtype=np.float64)
        if len(pga) > 1 and len(freq) > 1 and grid.min() < 0.5 < grid.max():
            cs = ax.contour(pga, freq, grid.T, levels=[0.5], colors=[color], linestyles=ls, linewidths=1.6)
            ax.clabel(cs, fmt={0.5: str(obj["id"])}, fontsize="x-small", inline=True)
            handles.append(ax.plot([], [], color=color, ls=ls, lw=1.6, label=f"{label}: P(observation) = 0.5")[0])
        else:
            side = "> 0.5" if grid.min() >= 0.5 else "< 0.5"
            handles.append(ax.plot([], [], color=color, ls="none", marker="x",
                                   label=f"{label}: no line, P(observation) {side} everywhere")[0])
    ax.set_xlabel("PGA (g)")
    ax.set_ylabel("predominant frequency (Hz)")
    # Legend below the axes, in columns: it never covers the map or the axis labels.
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2, fontsize="small",
              frameon=False)
    n = len(result.get("objects", []))
    ax.set_title(_wrap(title or f"Inversion: {result['site']}: PGA and predominant frequency from {n} objects"))
    return fig


def __getattr__(name: str) -> Any:
    """Deprecated names of this module (PEP 562): they warn and forward."""
    if name == "slide_spectrum":
        warnings.warn("topple.plot.slide_spectrum is deprecated: it is the compute function topple.slide_spectrum "
                      "(draw its result with topple.plot.sliding_spectrum)", DeprecationWarning, stacklevel=2)
        return _slide_spectrum
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
