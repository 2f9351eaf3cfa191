"""topple.plot returns figures; the examples run headless and write theirs."""
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

import topple  # noqa: E402
import topple.plot  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def motion():
    return topple.synth(pga_g=0.5, freq_hz=2.0, duration_s=15.0, seed=11)


def test_sliding_and_rocking_figures(motion, tmp_path):
    for result in (topple.slide(motion, mu=0.2), topple.slide(motion, mu=0.3, mode="one-way", slope_deg=5.0),
                   topple.rock(motion, topple.Block(width=0.1, height=0.4))):
        fig = topple.plot.response(motion, result)
        assert isinstance(fig, Figure) and len(fig.axes) == 3
        fig.savefig(tmp_path / "f.png")
        assert (tmp_path / "f.png").stat().st_size > 10_000


def test_figure_needs_a_history(motion):
    with pytest.raises(ValueError, match="history=True"):
        topple.plot.sliding(motion, topple.slide(motion, mu=0.2, history=False))


def test_sliding_spectrum(motion, tmp_path):
    with pytest.warns(DeprecationWarning):  # the old call computing the spectrum itself still works
        fig = topple.plot.sliding_spectrum(motion, np.linspace(0.05, 0.5, 10))
    fig.savefig(tmp_path / "s.png")
    assert isinstance(fig, Figure)
    spec = topple.slide_spectrum(motion, [0.1, 0.2])
    assert spec["max_abs_displacement_m"][0] == topple.slide(motion, mu=0.1, history=False).max_abs_displacement_m


def test_inversion_map(tmp_path):
    from test_cli_equivalence import SURVEY

    survey = tmp_path / "survey.toml"
    survey.write_text(SURVEY)
    fig = topple.plot.inversion_map(topple.invert(str(survey), threads=2))
    fig.savefig(tmp_path / "map.png")
    assert isinstance(fig, Figure)


@pytest.mark.parametrize("script,figures", [
    ("slammer_analysis.py", ["slammer_displacements.png", "slammer_history.png"]),
    ("rocking_objects.py", ["rocking_objects.png", "rocking_history.png"]),
])
@pytest.mark.parametrize("data", ["default", "synthetic"])
def test_examples_run_headless(tmp_path, script, figures, data):
    args = [sys.executable, str(ROOT / "examples" / "python" / script), str(tmp_path)]
    if data == "synthetic":  # what a clone without ../shared gets
        args += ["--records" if script.startswith("slammer") else "--record", str(tmp_path / "absent")]
    elif script.startswith("slammer"):
        args += ["--max-records", "4"]
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run(args, capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "figures written" in proc.stdout
    for name in figures:
        assert (tmp_path / name).stat().st_size > 10_000
