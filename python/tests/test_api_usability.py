"""What a notebook user expects of the API (issue 13, "Python"): surveys built in Python, the report from Python,
FileNotFoundError for a missing file, a clear ImportError without matplotlib, a warning for a fragility fit at its
beta bound, plot functions that draw into given axes and return the figure, titles without folders, deprecated
names that warn."""
import copy
import math
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

import topple
from test_cli_equivalence import SURVEY

# The SURVEY of test_cli_equivalence as a dict (the TOML file's structure; test_survey_dict_is_the_file checks it).
SURVEY_DICT = {
    "site": {"name": "test site"},
    "inversion": {"pga_g": [0.05, 1.5, 5], "freq_hz": [1.0, 8.0, 4], "motions_per_cell": 3, "duration_s": 8},
    "object": [
        {"id": "box", "shape": "block", "width": "10cm", "height": "40cm", "mu": 0.5, "outcome": "overturned"},
        {"id": "jar", "shape": "cylinder", "diameter": "10cm", "height": "20cm", "mu": 0.4, "outcome": "not_slid"},
    ],
}


def tomllib():
    return pytest.importorskip("tomllib")  # Python >= 3.11 (the package itself needs 3.9)


def test_survey_dict_is_the_file():
    assert tomllib().loads(SURVEY) == SURVEY_DICT


def without_timing(result):
    result = dict(result)
    result.pop("seconds")  # wall-clock time
    return result


def assert_same_inversion(a, b):
    a, b = without_timing(a), without_timing(b)
    assert a.keys() == b.keys()
    for key in a:
        if isinstance(a[key], np.ndarray):
            assert np.array_equal(a[key], b[key]), key
        elif key == "objects":
            assert len(a[key]) == len(b[key])
            for oa, ob in zip(a[key], b[key]):
                assert np.array_equal(oa.pop("probability_grid"), ob.pop("probability_grid"))
                assert oa == ob
        else:
            assert a[key] == b[key], key


def test_survey_toml_reads_back_as_the_same_dict():
    d = {"site": {"name": 'Kitchen "A"\\B', "lat": 17.4, "notes": "line1\nline2"},
         "inversion": {"pga_g": [0.05, np.float64(1.5), 5], "freq_hz": (1.0, 8.0, 4), "seed": np.int64(3)},
         "object": [{"id": "box", "shape": "block", "width": "10cm", "mu": [0.4, 0.6], "certain": True},
                    {"id": "jar", "shape": "cylinder", "diameter": "10cm"}],
         "event": {"epicentre": [17.0, 73.0]}}
    back = tomllib().loads(topple.survey_toml(d))
    assert back["site"] == d["site"]
    assert back["inversion"] == {"pga_g": [0.05, 1.5, 5], "freq_hz": [1.0, 8.0, 4], "seed": 3}
    assert back["object"] == d["object"] and back["event"] == d["event"]
    with pytest.raises(TypeError, match="site.lat is None"):
        topple.survey_toml({"site": {"lat": None}})


def test_invert_a_dict_equals_the_file(tmp_path):
    path = tmp_path / "survey.toml"
    path.write_text(SURVEY)
    from_file = topple.invert(path, threads=2)  # a path-like, not only str
    from_dict = topple.invert(SURVEY_DICT, threads=2)
    # Same survey, same seed: the same bits (the library reads both; only the text's layout differs).
    assert_same_inversion(from_file, from_dict)


def test_a_bad_dict_survey_names_the_object_and_field():
    bad = copy.deepcopy(SURVEY_DICT)
    bad["object"][1]["height"] = "20"  # no unit
    with pytest.raises(topple.InputError) as err:
        topple.invert(bad)
    assert err.value.field is not None and "height" in err.value.field
    assert "<survey dict>" in str(err.value)


def test_invert_writes_the_report(tmp_path):
    report = tmp_path / "new" / "report"  # made when missing, as `topple invert --report` does
    result = topple.invert(SURVEY_DICT, threads=2, report_dir=report)
    page = (report / "index.html").read_text()
    assert result["site"] == "test site" and "test site" in page
    assert (report / "grid.csv").is_file() and (report / "result.json").is_file()


@pytest.mark.parametrize("call", [
    lambda p: topple.invert(p),
    lambda p: topple.read(p),
    lambda p: topple.sweep(p),
], ids=["invert", "read", "sweep"])
def test_a_missing_file_is_a_file_not_found_error(tmp_path, call):
    path = str(tmp_path / "absent.toml")
    with pytest.raises(FileNotFoundError) as err:
        call(path)
    assert isinstance(err.value, topple.InputError) and isinstance(err.value, topple.MissingFileError)
    assert err.value.filename == path and err.value.errno == 2  # ENOENT
    assert str(err.value).startswith(path)  # still the CLI's message: "PATH: cannot open ..."


def test_a_bad_existing_file_stays_an_input_error_only(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[site\n")
    with pytest.raises(topple.InputError) as err:
        topple.invert(path)
    assert not isinstance(err.value, FileNotFoundError)


def test_import_plot_without_matplotlib_names_the_extra():
    code = "import sys; sys.modules['matplotlib'] = None; import topple.plot"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode != 0
    assert "ImportError" in proc.stderr and 'pip install "topple-quake[plot]"' in proc.stderr


def test_a_fit_at_the_beta_bound_warns_with_its_numbers():
    # Separated counts (none fail at 0.1 and 0.2, all fail at 0.4 and 0.8): the likelihood grows as beta -> 0 and
    # the fit stops at kMinimumBeta = 0.01 (fragility.hpp).
    with pytest.warns(RuntimeWarning, match=r"beta = 0\.01 is at its lower bound 0\.01 \(theta = 0\.28"):
        fit = topple.fragility_fit([0.1, 0.2, 0.4, 0.8], [10, 10, 10, 10], [0, 0, 10, 10])
    assert fit.beta_at_bound
    # theta lies between the last none-fail and the first all-fail level (0.2 and 0.4); the MLE puts it at their
    # geometric mean 0.2828 when beta is at the bound (the printed 4 digits).
    assert fit.theta == pytest.approx(math.sqrt(0.2 * 0.4), rel=1e-3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an ordinary fit says nothing
        ok = topple.fragility_fit([0.1, 0.2, 0.4, 0.8], [10, 10, 10, 10], [1, 3, 6, 9])
    assert not ok.beta_at_bound


# ---- plots ----

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

import topple.plot  # noqa: E402


@pytest.fixture(scope="module")
def motion():
    return topple.synth(pga_g=0.5, freq_hz=2.0, duration_s=10.0, seed=11)


def single_axes_plots(motion):
    spec = topple.slide_spectrum(motion, np.linspace(0.05, 0.5, 8))
    omap = topple.overturning_map(motion, alpha_rad=0.25, heights_m=[0.3, 1.0], pga_g=[0.2, 0.5, 1.0], threads=2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        frag = topple.fragility([motion, motion.inverted()], [0.1, 0.3, 0.9], body=topple.Block(width=0.2, height=0.6),
                                threads=2)
    return [
        lambda ax: topple.plot.sliding_spectrum(spec, ax=ax),
        lambda ax: topple.plot.response_spectrum(topple.response_spectrum(motion), ax=ax),
        lambda ax: topple.plot.fourier_spectrum(topple.fourier_spectrum(motion), ax=ax),
        lambda ax: topple.plot.overturning_map(omap, ax=ax),
        lambda ax: topple.plot.fragility(frag, ax=ax),
        lambda ax: topple.plot.inversion_map(topple.invert(SURVEY_DICT, threads=2), ax=ax),
    ]


def test_every_plot_draws_into_given_axes_and_returns_the_figure(motion):
    for draw in single_axes_plots(motion):
        fig = Figure()
        ax = fig.subplots(1, 2)[1]  # the second of two: the plot must use the axes it is given
        assert draw(ax) is fig
        assert ax.has_data() and not fig.axes[0].has_data()
        assert isinstance(draw(None), Figure)  # and a new figure without


def test_history_plots_draw_into_a_given_figure_or_subfigure(motion):
    fig = Figure()
    left, right = fig.subfigures(1, 2)
    assert topple.plot.sliding(motion, topple.slide(motion, mu=0.2), fig=right) is fig
    assert topple.plot.response(motion, topple.rock(motion, topple.Block(width=0.2, height=0.6)), fig=left) is fig
    assert len(fig.axes) == 6


def test_titles_name_the_analysis_never_a_folder(tmp_path, made_record):
    m = topple.read(made_record)
    assert os.path.isabs(m.name)  # the record's name is the path as given
    folder = os.path.dirname(m.name)
    titles = [topple.plot.sliding(m, topple.slide(m, mu=0.25, slope_deg=3.0)).texts[0].get_text(),
              topple.plot.response_spectrum(m).axes[0].get_title()]
    for t in titles:
        assert folder not in t and "made.csv" in t
    assert "mu = 0.25" in titles[0] and "slope 3 deg" in titles[0]
    assert "5 % damping" in titles[1]
    # A synthetic motion's name is its description, slashes ("m/s2") and all: kept, not cut at the last "/".
    synthetic = topple.plot.fourier_spectrum(topple.synth(pga_g=0.3, freq_hz=3.0, duration_s=5.0, seed=1))
    assert "synthetic clough-penzien motion" in synthetic.axes[0].get_title().replace("\n", " ")


def test_inversion_map_has_the_reports_axes_and_every_object():
    result = topple.invert(SURVEY_DICT, threads=2)
    fig = topple.plot.inversion_map(result)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "PGA (g)" and ax.get_xscale() == "log"
    assert ax.get_ylabel() == "predominant frequency (Hz)" and ax.get_yscale() == "log"
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    for obj in result["objects"]:  # drawn, or the legend says why not
        assert any(t.startswith(f"{obj['id']} ({obj['outcome']})") for t in legend), (obj["id"], legend)
    assert any("68 % credible region" in t for t in legend) and any("95 % credible region" in t for t in legend)
    assert any(t.startswith("median:") for t in legend)
    # 1-2-5 labels on the PGA axis: 0.1, 0.2, 0.5, 1 are among the tick labels of the 0.05-1.5 g grid.
    fig.canvas.draw() if hasattr(fig.canvas, "draw") else None
    labels = {t.get_text() for t in ax.get_xticklabels()}
    assert {"0.1", "0.2", "0.5", "1"} <= labels


def test_credible_levels_hold_their_mass():
    # Four cells with posterior 0.5, 0.3, 0.15, 0.05: the 68 % region is the two largest (0.8 >= 0.68), the 95 %
    # region the three largest (0.95): the levels are the smallest kept values, exactly.
    levels = topple.plot._credible_levels(np.array([[0.15, 0.5], [0.05, 0.3]]), (0.68, 0.95))
    assert levels == [0.3, 0.15]


def test_old_names_warn_and_still_work(motion):
    with pytest.warns(DeprecationWarning, match="topple.slide_spectrum"):
        compute = topple.plot.slide_spectrum
    assert compute is topple.slide_spectrum
    with pytest.warns(DeprecationWarning, match="deprecated"):
        fig = topple.plot.sliding_spectrum(motion, [0.1, 0.2, 0.3])
    assert isinstance(fig, Figure)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the new way says nothing
        topple.plot.sliding_spectrum(topple.slide_spectrum(motion, [0.1, 0.2, 0.3]))
        topple.plot.sliding_spectrum(motion)  # a motion alone: computed with the defaults, as the other spectra
