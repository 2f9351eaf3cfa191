"""matplotlib figures of what the ``topple`` command line draws (needs the ``[plot]`` extra: matplotlib).

Every function returns a :class:`matplotlib.figure.Figure` built without pyplot (no global state, works headless);
save it with ``fig.savefig("name.png")``. Values are plotted in the units their names say.
"""
from __future__ import annotations

import math
from typing import Any, Mapping, Optional, Sequence

import numpy as np
from matplotlib.figure import Figure

from . import GroundMotion, RockingResult, SlidingResult, slide_spectrum

__all__ = ["response", "sliding", "rocking", "sliding_spectrum", "inversion_map"]


def _need_history(result: Any) -> None:
    if len(result.time_s) == 0:
        raise ValueError("this result has no time history: run it with history=True (the default)")


def _record_panel(ax, motion: GroundMotion, g_m_s2: float, thresholds: Sequence[tuple[float, str]]) -> None:
    ax.plot(motion.time_s, motion.accel_m_s2 / g_m_s2, color="0.25", lw=0.7, label="ground")
    for value, label in thresholds:
        ax.axhline(value, color="tab:red", lw=0.9, ls="--", label=label)  # "" : no legend entry
    ax.set_ylabel("ground accel. (g)")
    ax.legend(loc="upper right", fontsize="small")
    ax.grid(alpha=0.3)


def sliding(motion: GroundMotion, result: SlidingResult, title: Optional[str] = None) -> Figure:
    """Record with its yield accelerations (g), then displacement (m) and velocity (m/s), on a shared time axis (s)."""
    _need_history(result)
    fig = Figure(figsize=(9, 7), layout="constrained")
    ax = fig.subplots(3, 1, sharex=True)
    lines = [(result.yield_down_g, f"yield +{result.yield_down_g:.3g} g")]
    if result.yield_up_g is not None:
        lines.append((result.yield_up_g, f"yield {result.yield_up_g:.3g} g"))
    _record_panel(ax[0], motion, result.g_m_s2, lines)
    ax[1].plot(result.time_s, result.displacement_m, color="tab:blue")
    ax[1].set_ylabel("displacement (m)")
    ax[2].plot(result.time_s, result.velocity_m_s, color="tab:green")
    ax[2].set_ylabel("rel. velocity (m/s)")
    ax[2].set_xlabel("time (s)")
    for a in ax[1:]:
        a.grid(alpha=0.3)
    fig.suptitle(title or f"Sliding block, mu = {result.mu_static:g} ({result.mode}): {motion.name or 'record'}")
    return fig


def rocking(motion: GroundMotion, result: RockingResult, title: Optional[str] = None) -> Figure:
    """Record with the uplift thresholds +-g tan(alpha), then theta/alpha and theta' (rad/s) on a shared time axis."""
    _need_history(result)
    fig = Figure(figsize=(9, 7), layout="constrained")
    ax = fig.subplots(3, 1, sharex=True)
    tan_alpha = math.tan(result.alpha_rad)
    _record_panel(ax[0], motion, result.g_m_s2, [(tan_alpha, f"±g tan(alpha) = ±{tan_alpha:.3g} g"), (-tan_alpha, "")])
    ax[1].plot(result.time_s, np.asarray(result.theta_rad) / result.alpha_rad, color="tab:blue")
    for level in (1.0, -1.0):
        ax[1].axhline(level, color="tab:red", lw=0.8, ls=":")
    ax[1].set_ylabel("theta / alpha")
    ax[2].plot(result.time_s, result.theta_dot_rad_s, color="tab:green")
    ax[2].set_ylabel("theta' (rad/s)")
    ax[2].set_xlabel("time (s)")
    for a in ax[1:]:
        a.grid(alpha=0.3)
    verdict = "overturned" if result.overturned else f"max |theta| = {result.max_rotation_over_alpha:.3g} alpha"
    fig.suptitle(title or f"Rocking {result.body!r}: {verdict}: {motion.name or 'record'}")
    return fig


def response(motion: GroundMotion, result: Any, title: Optional[str] = None) -> Figure:
    """sliding() or rocking(), by the type of result."""
    if isinstance(result, SlidingResult):
        return sliding(motion, result, title)
    if isinstance(result, RockingResult):
        return rocking(motion, result, title)
    raise TypeError(f"expected a SlidingResult or RockingResult, got {type(result).__name__}")


def sliding_spectrum(motion: GroundMotion, mu: Optional[Sequence[float]] = None, *, slope_deg: float = 0.0,
                     mode: str = "two-way", g: float = 9.80665, title: Optional[str] = None) -> Figure:
    """Maximum |displacement| (m) against the friction coefficient mu (default: 60 values from 2 % to 120 % of PGA/g)."""
    if mu is None:
        pga_g = float(motion.pga_m_s2) / g
        mu = np.linspace(0.02 * pga_g, 1.2 * pga_g, 60)
    spec = slide_spectrum(motion, np.asarray(mu, dtype=np.float64), slope_deg=slope_deg, mode=mode, g=g)
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.subplots()
    ax.plot(spec["mu"], spec["max_abs_displacement_m"], marker=".", label="max |displacement|")
    ax.plot(spec["mu"], np.abs(spec["residual_displacement_m"]), ls="--", label="|residual|")
    ax.set_yscale("symlog", linthresh=1e-4)
    ax.set_xlabel("friction coefficient mu")
    ax.set_ylabel("displacement (m)")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title(title or f"Sliding spectrum ({mode}, slope {slope_deg:g} deg): {motion.name or 'record'}")
    return fig


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges of a log-spaced grid at the geometric midpoints (as the inversion spreads a cell's mass)."""
    v = np.asarray(values, dtype=np.float64)
    mid = np.sqrt(v[:-1] * v[1:])
    return np.concatenate(([v[0] ** 2 / mid[0]], mid, [v[-1] ** 2 / mid[-1]]))


def inversion_map(site: Mapping[str, Any], title: Optional[str] = None) -> Figure:
    """Posterior over PGA (g) x predominant frequency (Hz) from one site's dict of topple.invert, with the best cell,
    the 68 % / 95 % intervals and the static bounds."""
    if "sites" in site:
        raise ValueError("this survey has several sites: pass one of result['sites']")
    pga = np.asarray(site["grid"]["pga_g"])
    freq = np.asarray(site["grid"]["freq_hz"])
    post = np.asarray(site["posterior_grid"])
    fig = Figure(figsize=(7.5, 5.5), layout="constrained")
    ax = fig.subplots()
    mesh = ax.pcolormesh(_edges(freq), _edges(pga), post, cmap="viridis", shading="flat")
    fig.colorbar(mesh, ax=ax, label="posterior probability")
    ax.set_xscale("log")
    ax.set_yscale("log")
    best = site["best_cell"]
    ax.plot([best["freq_hz"]], [best["pga_g"]], marker="*", ms=14, color="white", mec="black", label="best")
    for key, ls in (("ci68", "-"), ("ci95", ":")):
        for v in site["pga_g"][key]:
            if v is not None:
                ax.axhline(v, color="white", ls=ls, lw=0.9)
        for v in site["freq_hz"][key]:
            if v is not None:
                ax.axvline(v, color="white", ls=ls, lw=0.9)
    low, high = site["static_bounds_pga_g"]
    for v, label in ((low, "static lower bound"), (high, "static upper bound")):
        if v is not None:
            ax.axhline(v, color="tab:red", ls="--", lw=1.0, label=label)
    ax.set_xlabel("predominant frequency (Hz)")
    ax.set_ylabel("PGA (g)")
    ax.legend(loc="lower right", fontsize="small")
    ax.set_title(title or f"Inversion: {site['site']}")
    return fig
