"""matplotlib figures of what the ``topple`` command line draws (needs the ``[plot]`` extra: matplotlib).

Every function returns a :class:`matplotlib.figure.Figure` built without pyplot (no global state, works headless);
save it with ``fig.savefig("name.png")``. Values are plotted in the units their names say.
"""
from __future__ import annotations

import math
from typing import Any, Mapping, Optional, Sequence

import numpy as np
from matplotlib.figure import Figure

from . import GroundMotion, RockingResult, SlidingResult, fourier_spectrum as _fourier_spectrum, slide_spectrum
from . import response_spectrum as _response_spectrum

__all__ = ["response", "sliding", "rocking", "sliding_spectrum", "inversion_map", "response_spectrum", "fourier_spectrum",
           "overturning_map", "fragility"]


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


def response_spectrum(spec: Any, title: Optional[str] = None, *, units: str = "g",
                      tp_s: Optional[float] = None) -> Figure:
    """Pseudo-spectral acceleration against period (s, log axis), in g (units="g") or m/s^2 (units="m/s2").

    spec: the dict of topple.response_spectrum, or a GroundMotion (its 5 %-damped spectrum on the Tp periods).
    tp_s: mark a period (s), e.g. topple.intensity(motion)["tp_s"]."""
    if isinstance(spec, GroundMotion):
        spec = _response_spectrum(spec)
    if units not in ("g", "m/s2"):
        raise ValueError(f"units must be 'g' or 'm/s2', got {units!r}")
    psa = np.asarray(spec["psa_g"] if units == "g" else spec["psa_m_s2"])
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.subplots()
    ax.plot(spec["period_s"], psa, color="tab:blue", label=f"PSA, {100 * spec['damping']:g} % damping")
    if tp_s is not None:
        ax.axvline(tp_s, color="tab:orange", ls="--", lw=1.0, label=f"Tp = {tp_s:.3f} s")
    ax.set_xscale("log")
    ax.set_xlabel("period (s)")
    ax.set_ylabel("PSA (g)" if units == "g" else "PSA (m/s²)")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    ax.set_title(title or f"Response spectrum: {spec.get('motion') or 'record'}")
    return fig


def fourier_spectrum(fas: Any, title: Optional[str] = None) -> Figure:
    """Fourier amplitude (m/s) against frequency (Hz), log-log: the FAS, its Konno-Ohmachi smoothing and the
    predominant frequency. fas: the dict of topple.fourier_spectrum, or a GroundMotion (b = 40)."""
    if isinstance(fas, GroundMotion):
        fas = _fourier_spectrum(fas)
    f = np.asarray(fas["freq_hz"])
    a = np.asarray(fas["amplitude_m_s"])
    keep = f > 0  # log axis
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.subplots()
    ax.plot(f[keep], a[keep], color="0.7", lw=0.6, label="FAS")
    if fas.get("smoothed_amplitude_m_s") is not None:
        ax.plot(fas["smoothed_freq_hz"], fas["smoothed_amplitude_m_s"], color="tab:blue", lw=1.5,
                label=f"Konno-Ohmachi, b = {fas['smoothing_b']:g}")
    fp = fas.get("predominant_frequency_hz")
    if fp is not None:
        ax.axvline(fp, color="tab:red", ls="--", lw=1.0, label=f"f_p = {fp:.3g} Hz")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("Fourier amplitude (m/s)")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    ax.set_title(title or f"Fourier amplitude spectrum: {fas.get('motion') or 'record'}")
    return fig


def overturning_map(omap: Mapping[str, Any], title: Optional[str] = None) -> Figure:
    """Overturned (dark) or standing against PGA (g) and body height (m), from the dict of topple.overturning_map,
    with each size's first-overturn PGA and the uplift threshold PGA = g tan(alpha)."""
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

    fig = Figure(figsize=(7.5, 5), layout="constrained")
    ax = fig.subplots()
    ax.pcolormesh(edges(pga), edges(h), fell, cmap="Greys", vmin=0.0, vmax=1.6, shading="flat")
    first = np.asarray(omap["first_overturn_pga_g"], dtype=np.float64)[order]
    ax.plot(first, h, marker="o", color="tab:red", lw=1.0, label="first-overturn PGA")
    ax.axvline(omap["uplift_pga_g"], color="tab:blue", ls="--", lw=1.0, label="uplift: PGA = g tan(alpha)")
    ax.set_xlabel("PGA (g)")
    ax.set_ylabel("body height (m)")
    ax.legend(loc="upper left", fontsize="small")
    ax.set_title(title or f"Overturning map, {omap['shape']}, alpha = {math.degrees(omap['alpha_rad']):.3g} deg: "
                          f"{omap.get('motion') or 'record'}")
    return fig


def fragility(result: Mapping[str, Any], title: Optional[str] = None, *, level: float = 0.95) -> Figure:
    """Probability of failure against the intensity measure: observed fractions (markers), the lognormal fit and its
    delta-method band at `level`, for each curve of the dict of topple.fragility (or one of its curves)."""
    curves = result["curves"] if "curves" in result else [result]
    im = result.get("im", "im")
    unit = result.get("im_unit", "")
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.subplots()
    for k, curve in enumerate(curves):
        color = f"C{k}"
        x = np.asarray(curve["im"], dtype=np.float64)
        ax.plot(x, curve["fraction"], ls="none", marker="o", color=color, label=f"{curve['name']}: observed")
        fit = curve.get("fit")
        if fit is not None:
            xs = np.geomspace(x.min() / 1.5, x.max() * 1.5, 200)
            ax.plot(xs, fit.probability(xs), color=color,
                    label=f"{curve['name']}: theta = {fit.theta:.3g} {unit}, beta = {fit.beta:.2f}")
            lower, upper = fit.band(xs, level)
            ax.fill_between(xs, lower, upper, color=color, alpha=0.2, lw=0)
    ax.set_xscale("log")
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(f"{im.upper()} ({unit})" if unit else str(im))
    ax.set_ylabel("probability of failure")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize="small")
    ax.set_title(title or f"Fragility ({100 * level:g} % band)")
    return fig
