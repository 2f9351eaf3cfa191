"""Python results equal the CLI's JSON for the same inputs, bit for bit.

nlohmann::json prints doubles in the shortest form that reads back to the same double, and Python's json parses
to the nearest double, so exact == on floats is the right test (no tolerance)."""
import math

import numpy as np
import pytest

import topple
from conftest import shared_record

SLIDE_CASES = [
    ({"mu": 0.3}, ["--mu", "0.3"]),
    ({"mu": 0.2, "mu_kinetic": 0.15}, ["--mu", "0.2", "--mu-kinetic", "0.15"]),
    ({"mu": 0.6, "slope_deg": 10.0, "mode": "one-way"}, ["--mu", "0.6", "--slope-deg", "10", "--one-way"]),
    ({"mu": 0.05, "g": 9.81}, ["--mu", "0.05", "--g", "9.81"]),
]


def records(made_record):
    return [made_record, "Rinaldi228.AT2", "RSN6_IMPVALL.I_I-ELC180.AT2"]


@pytest.fixture(params=["made", "Rinaldi228.AT2", "RSN6_IMPVALL.I_I-ELC180.AT2"])
def record(request, made_record):
    return made_record if request.param == "made" else shared_record(request.param)


def assert_attributes_match(result, j):
    for key, value in j.items():
        if key in ("input", "sign_convention", "body", "solver"):
            continue
        assert getattr(result, key) == value, key


@pytest.mark.parametrize("kwargs,args", SLIDE_CASES)
@pytest.mark.parametrize("history", [True, False])
def test_slide_equals_cli(cli, record, kwargs, args, history):
    expected = cli.json("slide", record, *args)
    motion = topple.read(record, g=kwargs.get("g", 9.80665))
    result = topple.slide(motion, history=history, **kwargs)
    assert result.json() == expected
    assert_attributes_match(result, expected)
    if expected["first_slip_time_s"] is None:
        assert result.first_slip_time_s is None


ROCK_CASES = [
    (topple.Block(width=0.2, height=0.6), {}, ["--shape", "block", "--width", "20cm", "--height", "60cm"]),
    (topple.Block(width=0.1, height=0.6), {"e": 0.85, "mu": 0.4},
     ["--shape", "block", "--width", "10cm", "--height", "60cm", "--e", "0.85", "--mu", "0.4"]),
    (topple.Cylinder(diameter=0.1, height=0.4), {"mu": 0.5},
     ["--shape", "cylinder", "--diameter", "10cm", "--height", "40cm", "--mu", "0.5"]),
    (topple.General(a=0.05, h=0.2, D=0.06), {"method": "rk4"},
     ["--shape", "general", "--a", "5cm", "--h", "20cm", "--D", "0.06m2", "--method", "rk4"]),
]


@pytest.mark.parametrize("body,kwargs,args", ROCK_CASES)
def test_rock_equals_cli(cli, record, body, kwargs, args):
    expected = cli.json("rock", record, *args)
    result = topple.rock(topple.read(record), body, **kwargs)
    assert result.json() == expected
    assert_attributes_match(result, expected)
    summary_only = topple.rock(topple.read(record), body, history=False, **kwargs)
    assert summary_only.json() == expected


def test_slide_history_matches_cli_csv(cli, made_record, tmp_path):
    out = tmp_path / "h.csv"
    cli("slide", made_record, "--mu", "0.2", "--out", out)
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    r = topple.slide(topple.read(made_record), mu=0.2)
    # The CSV prints times with 9 and displacements with 12 significant digits.
    np.testing.assert_allclose(r.time_s, data[:, 0], rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(r.displacement_m, data[:, 2], rtol=1e-11, atol=1e-15)
    assert np.array_equal(r.state, data[:, 4].astype(np.int8))


def test_intensity_equals_cli_info(cli, record):
    expected = cli.json("info", record)
    got = topple.intensity(topple.read(record))
    for key, value in got.items():
        assert expected[key] == value, key


def test_synth_equals_cli(cli, tmp_path):
    out = tmp_path / "s.csv"
    cli("synth", "--pga", "0.3g", "--freq", "3Hz", "--duration", "10s", "--seed", "7", "--out", out)
    data = np.loadtxt(out, delimiter=",", comments="#", skiprows=3)
    m = topple.synth(pga_g=0.3, freq_hz=3.0, duration_s=10.0, seed=7)
    # The CSV holds a / g in shortest round-trip form: exact.
    assert np.array_equal(m.accel_m_s2 / 9.80665, data[:, 1])
    assert m.pga_g == pytest.approx(0.3, rel=1e-15)


SURVEY = """
[site]
name = "test site"
[inversion]
pga_g = [0.05, 1.5, 5]
freq_hz = [1.0, 8.0, 4]
motions_per_cell = 3
duration_s = 8
[[object]]
id = "box"
shape = "block"
width = "10cm"
height = "40cm"
mu = 0.5
outcome = "overturned"
[[object]]
id = "jar"
shape = "cylinder"
diameter = "10cm"
height = "20cm"
mu = 0.4
outcome = "not_slid"
"""


def test_invert_equals_cli(cli, tmp_path):
    survey = tmp_path / "survey.toml"
    survey.write_text(SURVEY)
    expected = cli.json("invert", survey, "--quiet", "--threads", "2")
    got = topple.invert(str(survey), threads=2)
    post = got.pop("posterior_grid")
    got.pop("log_likelihood_grid")
    for obj in got["objects"]:  # beyond the CLI's JSON: each object's P(observation | cell), for the map
        grid = obj.pop("probability_grid")
        assert grid.shape == (5, 4) and 0.0 <= grid.min() and grid.max() <= 1.0
        assert obj["max_probability"] == grid.max()  # the JSON's number is the grid's maximum, bit for bit
    assert post.shape == (5, 4)
    assert math.isclose(float(post.sum()), 1.0, rel_tol=1e-12)  # normalised: round-off of 20 terms
    for j in (expected, got):
        j.pop("seconds")  # wall-clock time
    # The CLI's JSON says how it was made (version, commit, date, its command line, the survey's checksum and text);
    # that describes the CLI run, not the answer: present there, compared no further.
    provenance = expected.pop("provenance")
    assert provenance["survey_text"] == SURVEY and len(provenance["survey_xxh3_64"]) == 16
    assert got == expected
