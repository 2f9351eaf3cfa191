"""topple.slide_spectrum_2d (the bidirectional sliding spectrum of a pair): the CLI's JSON bit for bit, the 1-D
spectrum on collinear input, and bad input raising exceptions that name the parameter."""
import math

import numpy as np
import pytest

import topple
from test_slide2d import DT, N, station, write_csv  # noqa: F401 (station is a fixture)

MU = [0.05, 0.12, 0.2, 0.35]


def spectrum_args(h1, h2, azimuths, mu, vertical=None):
    args = ["spectrum", "slide", h1, "--h2", h2, "--azimuths", azimuths, "--mu", ",".join(map(str, mu))]
    return args + (["--vertical", vertical] if vertical else [])


@pytest.mark.parametrize("azimuths", [(90.0, 0.0), (30.0, 120.0)])
@pytest.mark.parametrize("with_vertical", [False, True])
def test_equals_cli(cli, station, azimuths, with_vertical):
    h1, h2, v = station
    expected = cli.json(*spectrum_args(h1, h2, f"{azimuths[0]:g},{azimuths[1]:g}", MU, v if with_vertical else None))
    vertical = topple.read(v) if with_vertical else None
    got = topple.slide_spectrum_2d(topple.read(h1), topple.read(h2), MU, azimuths_deg=azimuths, vertical=vertical)
    # Exact equality: nlohmann prints the shortest round-trip form and Python parses to the nearest double; the
    # names are the paths as given to both.
    for key, value in expected.items():
        assert got[key] == value, key
    # The columns are the points' numbers.
    points = expected["points"]
    assert got["mu"].tolist() == [p["mu"] for p in points]
    assert got["ky_over_rotd50_pga"].tolist() == [p["ky_over_rotd50_pga"] for p in points]
    assert got["max_abs_displacement_m"].tolist() == [p["max_abs_displacement_m"] for p in points]
    assert got["residual_displacement_m"].tolist() == [p["residual_displacement_m"] for p in points]
    assert got["h1_max_abs_displacement_m"].tolist() == [p["h1_alone"]["max_abs_displacement_m"] for p in points]
    assert got["h2_max_abs_displacement_m"].tolist() == [p["h2_alone"]["max_abs_displacement_m"] for p in points]
    # The case is not trivial: the blocks slip, and the pair moves the block more than its first component alone
    # at the lowest mu (the second component adds to it).
    assert points[0]["slip_episodes"] > 0
    assert points[0]["max_abs_displacement_m"] > points[0]["h1_alone"]["max_abs_displacement_m"]
    assert expected["vertical"] is with_vertical


def test_each_point_is_slide_2d(station):
    # object_spectra.hpp: each point is slide_2d with that mu, bit for bit.
    h1, h2, _ = station
    first, second = topple.read(h1), topple.read(h2)
    got = topple.slide_spectrum_2d(first, second, MU, azimuths_deg=(30.0, 120.0))
    for p in got["points"]:
        run = topple.slide_2d(first, second, mu=p["mu"], azimuths_deg=(30.0, 120.0)).json()
        for key, value in run.items():
            if key != "input":
                assert p[key] == value, key


@pytest.fixture(scope="module")
def accel_m_s2():
    """One horizontal acceleration (m/s^2) that makes the block slip at every mu of MU."""
    t = np.arange(N) * DT
    env = np.exp(-((t - 5.0) / 3.0) ** 2)
    a_g = 0.5 * np.sin(2 * np.pi * 1.7 * t) * env + 0.1 * np.sin(2 * np.pi * 5.3 * t)
    return a_g * topple.STANDARD_GRAVITY


def collinear_pair(accel_m_s2, direction_deg, on_second):
    """The record along azimuth direction_deg as one component of a perpendicular pair, the other zero."""
    record = topple.GroundMotion(accel_m_s2, DT, units="m/s2")
    zero = topple.GroundMotion(np.zeros(N), DT, units="m/s2")
    if on_second:
        return zero, record, ((direction_deg + 90.0) % 360.0, direction_deg)
    return record, zero, (direction_deg, (direction_deg + 270.0) % 360.0)


def assert_equals_1d(two, one, direction_deg, rel):
    """The 2-D spectrum of shaking along direction_deg against the 1-D spectrum of the record, `rel` of each point's
    max |d| (the scale the C++ collinear test, tests/solvers/test_sliding2d.cpp, uses)."""
    scale = one["max_abs_displacement_m"]
    assert np.all(scale > 1e-4)  # every point slides
    assert np.all(np.abs(two["max_abs_displacement_m"] - scale) <= rel * scale)
    assert np.all(np.abs(two["residual_displacement_m"] - np.abs(one["residual_displacement_m"])) <= rel * scale)
    for p, d, n, s in zip(two["points"], one["residual_displacement_m"], one["slip_episodes"], scale):
        assert p["slip_episodes"] == n
        # The 1-D d is positive where a positive ground acceleration pushes the block, i.e. away from the axis (the
        # block lags the ground): the 2-D residual points to the axis + 180 deg for d > 0 and along it for d < 0.
        # Its direction is known to rel x max|d| / |d| rad.
        toward = (direction_deg + 180.0) % 360.0 if d > 0 else direction_deg
        delta = (p["residual_azimuth_deg"] - toward + 180.0) % 360.0 - 180.0
        assert abs(math.radians(delta)) <= 2.0 * rel * s / abs(d)


@pytest.mark.parametrize("direction_deg", [0.0, 30.0, 137.5, 270.0])
@pytest.mark.parametrize("on_second", [False, True])
def test_collinear_pair_is_the_1d_spectrum(accel_m_s2, direction_deg, on_second):
    # The record along one azimuth (on either component, the other zero): the block slides on that line only, as
    # the exact 1-D solver's two-way block, to 1e-9 of max |d| (the collinear test; the C++ one,
    # tests/solvers/test_sliding2d.cpp, at the same scale: DP5 integrates the collinear slip exactly, the stops come from
    # TOMS 748 to 4 ulp).
    first, second, azimuths = collinear_pair(accel_m_s2, direction_deg, on_second)
    one = topple.slide_spectrum(topple.GroundMotion(accel_m_s2, DT, units="m/s2"), MU)
    two = topple.slide_spectrum_2d(first, second, MU, azimuths_deg=azimuths)
    assert_equals_1d(two, one, direction_deg, 1e-9)
    # RotD50 of a linearly polarised pair: PGA x the median of |cos| over the RotD angles 0, 1, ..., 179 deg
    # (Boore 2010), between cos 46 deg and cos 44 deg.
    pga_g = one["pga_g"]
    assert math.cos(math.radians(46.0)) * pga_g <= two["rotd50_pga_g"] <= math.cos(math.radians(44.0)) * pga_g


@pytest.mark.parametrize("direction_deg", [30.0, 237.0])
def test_collinear_shaking_between_the_axes(accel_m_s2, direction_deg):
    # The same line of shaking split over both components (east = a sin psi, north = a cos psi): collinear input at
    # an azimuth between the axes, to the 1e-9 of max |d| as in the C++ collinear test (tests/solvers/test_sliding2d.cpp
    # runs the split too). The direction is fixed only to rounding here; measured worst 8.0e-10 (residual, mu = 0.35).
    psi = math.radians(direction_deg)
    east = topple.GroundMotion(accel_m_s2 * math.sin(psi), DT, units="m/s2")
    north = topple.GroundMotion(accel_m_s2 * math.cos(psi), DT, units="m/s2")
    one = topple.slide_spectrum(topple.GroundMotion(accel_m_s2, DT, units="m/s2"), MU)
    two = topple.slide_spectrum_2d(east, north, MU, azimuths_deg=(90.0, 0.0))
    assert_equals_1d(two, one, direction_deg, 1e-9)


def test_a_zero_second_component_alone_is_the_1d_run(accel_m_s2):
    # Second component zero: the first alone (h1_alone, the 1-D solver) is the 1-D spectrum exactly, the second alone
    # never slips.
    first = topple.GroundMotion(accel_m_s2, DT, units="m/s2")
    zero = topple.GroundMotion(np.zeros(N), DT, units="m/s2")
    one = topple.slide_spectrum(first, MU)
    two = topple.slide_spectrum_2d(first, zero, MU, azimuths_deg=(10.0, 100.0))
    assert [p["h1_alone"]["max_abs_displacement_m"] for p in two["points"]] == one["max_abs_displacement_m"].tolist()
    assert [p["h1_alone"]["residual_displacement_m"] for p in two["points"]] == one["residual_displacement_m"].tolist()
    assert all(p["h2_alone"]["slip_episodes"] == 0 for p in two["points"])
    assert two["h2_pga_g"] == 0.0


def test_bad_input_names_the_parameter(station):
    h1, h2, _ = station
    first, second = topple.read(h1), topple.read(h2)
    with pytest.raises(topple.InputError) as err:
        topple.slide_spectrum_2d(first, second, MU, azimuths_deg=(90.0,))
    assert err.value.field == "azimuths_deg"
    with pytest.raises(topple.InputError) as err:
        topple.slide_spectrum_2d(first, second, MU, azimuths_deg=(30.0, 100.0))  # not perpendicular
    assert err.value.field == "azimuths_deg"
    with pytest.raises(topple.InputError) as err:
        topple.slide_spectrum_2d(first, second, [0.1, -0.2])
    assert err.value.field == "mu" and "-0.2" in str(err.value)
    with pytest.raises(topple.InputError) as err:
        topple.slide_spectrum_2d(first, second, [])
    assert err.value.field == "mu"
    with pytest.raises(topple.InputError) as err:
        topple.slide_spectrum_2d(first, second, [float("nan")])
    assert err.value.field == "mu"
    with pytest.raises(topple.InputError) as err:
        topple.slide_spectrum_2d(first, second, MU, g=0.0)
    assert err.value.field == "g"
    with pytest.raises(TypeError, match="float64"):
        topple.slide_spectrum_2d(first, second, np.array([1, 2]))
    with pytest.raises(TypeError):
        topple.slide_spectrum_2d(first, None, MU)
