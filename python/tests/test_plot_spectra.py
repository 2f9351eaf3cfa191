"""topple.plot figures of spectra, overturning maps and fragility curves (Agg backend, no display)."""
import math

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

import topple  # noqa: E402
import topple.plot  # noqa: E402


@pytest.fixture(scope="module")
def motion():
    return topple.synth(pga_g=0.5, freq_hz=2.0, duration_s=10.0, seed=3)


def saved(fig, tmp_path):
    fig.savefig(tmp_path / "f.png")
    return (tmp_path / "f.png").stat().st_size > 10_000


def test_response_spectrum_figure(motion, tmp_path):
    spec = topple.response_spectrum(motion)
    fig = topple.plot.response_spectrum(spec, tp_s=topple.intensity(motion)["tp_s"])
    assert isinstance(fig, Figure) and len(fig.axes) == 1
    ax = fig.axes[0]
    assert ax.get_xlabel() == "period (s)" and ax.get_ylabel() == "PSA (g)" and ax.get_xscale() == "log"
    assert saved(fig, tmp_path)
    fig = topple.plot.response_spectrum(motion, units="m/s2")
    assert fig.axes[0].get_ylabel() == "PSA (m/s²)"
    with pytest.raises(ValueError):
        topple.plot.response_spectrum(spec, units="furlongs")


def test_fourier_spectrum_figure(motion, tmp_path):
    fig = topple.plot.fourier_spectrum(topple.fourier_spectrum(motion))
    ax = fig.axes[0]
    assert ax.get_xlabel() == "frequency (Hz)" and ax.get_ylabel() == "Fourier amplitude (m/s)"
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert saved(fig, tmp_path)
    assert isinstance(topple.plot.fourier_spectrum(motion), Figure)


def test_overturning_map_figure(motion, tmp_path):
    omap = topple.overturning_map(motion, alpha_rad=math.atan(0.2), heights_m=[0.3, 0.6, 1.2],
                                  pga_g=np.linspace(0.1, 1.0, 6), threads=2)
    fig = topple.plot.overturning_map(omap)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "PGA (g)" and ax.get_ylabel() == "body height (m)"
    assert saved(fig, tmp_path)


def test_fragility_figure(tmp_path):
    fit_result = {"im": "pga", "im_unit": "g", "curves": [{
        "name": "overturn", "im": np.array([0.1, 0.2, 0.4, 0.8]), "fraction": np.array([0.0, 0.25, 0.6, 1.0]),
        "fit": topple.fragility_fit([0.1, 0.2, 0.4, 0.8], [20] * 4, [0, 5, 12, 20])}]}
    fig = topple.plot.fragility(fit_result)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "PGA (g)" and ax.get_ylabel() == "probability of failure"
    assert saved(fig, tmp_path)
