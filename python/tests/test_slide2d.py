"""topple.slide_2d (bidirectional sliding): the CLI's JSON bit for bit, the 1-D solver on collinear input, the
histories, and bad input raising topple.InputError that names the parameter."""
import math

import numpy as np
import pytest

import topple
from test_cli_equivalence import assert_attributes_match

N = 1500
DT = 0.01


def write_csv(path, accel_g):
    with open(path, "w") as f:
        f.write("time_s,accel_g\n")
        for i, a in enumerate(accel_g):
            f.write(f"{i * DT:.2f},{float(a)!r}\n")
    return str(path)


@pytest.fixture(scope="module")
def station(tmp_path_factory):
    """Three components made here (always available): two horizontals of different frequency content and a
    vertical, CSV time_s,accel_g at 0.01 s. The horizontals peak near 0.5 g and 0.4 g so the block slips for
    mu = 0.2 in several directions."""
    t = np.arange(N) * DT
    env = np.exp(-((t - 5.0) / 3.0) ** 2)
    h1 = 0.5 * np.sin(2 * np.pi * 1.7 * t) * env + 0.1 * np.sin(2 * np.pi * 5.3 * t)
    h2 = 0.4 * np.cos(2 * np.pi * 1.1 * t + 0.4) * env + 0.08 * np.sin(2 * np.pi * 3.7 * t)
    v = 0.2 * np.sin(2 * np.pi * 4.1 * t) * env
    d = tmp_path_factory.mktemp("station")
    return (write_csv(d / "h1.csv", h1), write_csv(d / "h2.csv", h2), write_csv(d / "v.csv", v))


CASES = [
    ({"mu": 0.2}, ["--azimuths", "90,0", "--mu", "0.2"]),
    ({"mu": 0.2, "mu_kinetic": 0.15, "azimuths_deg": (30.0, 120.0)},
     ["--azimuths", "30,120", "--mu", "0.2", "--mu-kinetic", "0.15"]),
    ({"mu": 0.25, "slope_deg": 8.0, "slope_azimuth_deg": 200.0, "azimuths_deg": (0.0, 270.0)},
     ["--azimuths", "0,270", "--mu", "0.25", "--slope-deg", "8", "--slope-azimuth-deg", "200"]),
    ({"mu": 0.05, "g": 9.81}, ["--azimuths", "90,0", "--mu", "0.05", "--g", "9.81"]),
]


@pytest.mark.parametrize("kwargs,args", CASES)
@pytest.mark.parametrize("with_vertical", [False, True])
@pytest.mark.parametrize("history", [False, True])
def test_slide_2d_equals_cli(cli, station, kwargs, args, with_vertical, history):
    h1, h2, v = station
    extra = ["--vertical", v] if with_vertical else []
    expected = cli.json("slide", h1, "--h2", h2, *args, *extra)
    g = kwargs.get("g", 9.80665)
    vertical = topple.read(v, g=g) if with_vertical else None
    result = topple.slide_2d(topple.read(h1, g=g), topple.read(h2, g=g), vertical=vertical, history=history, **kwargs)
    # Exact equality: nlohmann prints the shortest round-trip form and Python parses to the nearest double.
    assert result.json() == expected
    assert_attributes_match(result, expected)
    assert expected["slip_episodes"] > 0  # the case exercises the slip integration, not only the stick test
    # The "input" object says what was run (both front ends build it with io::sliding_2d_input_json).
    inp = result.json()["input"]
    assert inp["motion"] == h1 and inp["h2"] == h2 and inp["scale_factor"] == 1.0
    assert inp["azimuths_deg"] == list(kwargs.get("azimuths_deg", (90.0, 0.0)))
    assert inp["vertical"] is (True if with_vertical else None)
    assert inp.get("slope_azimuth_deg") == kwargs.get("slope_azimuth_deg")
    # pga_g: the components' peaks in the run's g (the CSVs are in g; 17 digits printed, so to round-off).
    assert inp["pga_g"] == pytest.approx([topple.read(h1, g=g).pga_g, topple.read(h2, g=g).pga_g], rel=1e-15)


def test_history_is_consistent_with_summary(station):
    h1, h2, _ = station
    r = topple.slide_2d(topple.read(h1), topple.read(h2), mu=0.2, history=True)
    s = topple.slide_2d(topple.read(h1), topple.read(h2), mu=0.2)
    assert s.time_s.size == 0 and s.slipping.size == 0  # summary only by default
    assert r.json() == s.json()  # the history does not change the summary
    n = r.time_s.size
    assert n >= N and all(a.size == n for a in (r.east_m, r.north_m, r.east_m_s, r.north_m_s, r.slipping))
    assert r.slipping.dtype == np.uint8 and set(np.unique(r.slipping)) == {0, 1}
    assert np.all(np.diff(r.time_s) >= 0.0)
    assert not r.east_m.flags.writeable
    # The block ends at rest at its residual displacement (the same numbers, stored once per state).
    assert r.east_m[-1] == pytest.approx(r.residual_east_m, rel=1e-12, abs=1e-15)
    assert r.north_m[-1] == pytest.approx(r.residual_north_m, rel=1e-12, abs=1e-15)
    # max |u| over the history's rows cannot exceed the solver's max |u| (which also sees between rows), and the
    # rows include every stop, where |u| is locally largest along straight runs: agree to the integration tolerance.
    u = np.hypot(r.east_m, r.north_m)
    assert u.max() <= r.max_abs_displacement_m * (1 + 1e-12)
    assert u.max() == pytest.approx(r.max_abs_displacement_m, rel=1e-3)


@pytest.mark.parametrize("azimuth_deg", [0.0, 30.0, 145.0, 270.0])
def test_collinear_equals_1d_solver(station, azimuth_deg):
    # The ground shakes along one azimuth phi: east = a sin(phi), north = a cos(phi). The 2-D block must move on that
    # line as the 1-D two-way block: sliding.hpp's d (positive where a positive a pushes the block, i.e. toward
    # phi + 180) is -u . e_phi. 1e-9 relative: the bound (the slip integration is exact for the collinear
    # quadratic velocity; what remains is round-off and the stop's root finding).
    a = topple.read(station[0])
    phi = math.radians(azimuth_deg)
    east = topple.GroundMotion(np.asarray(a.accel_m_s2) * math.sin(phi), a.dt_s, units="m/s2")
    north = topple.GroundMotion(np.asarray(a.accel_m_s2) * math.cos(phi), a.dt_s, units="m/s2")
    one = topple.slide(a, mu=0.2, mu_kinetic=0.15, history=False)
    two = topple.slide_2d(east, north, mu=0.2, mu_kinetic=0.15)
    assert one.slip_episodes > 1 and two.slip_episodes == one.slip_episodes
    tol = dict(rel=1e-9, abs=1e-12)  # abs: components that are zero up to round-off
    assert two.residual_displacement_m == pytest.approx(abs(one.residual_displacement_m), **tol)
    along = two.residual_east_m * math.sin(phi) + two.residual_north_m * math.cos(phi)
    assert -along == pytest.approx(one.residual_displacement_m, **tol)
    across = two.residual_east_m * math.cos(phi) - two.residual_north_m * math.sin(phi)
    assert abs(across) <= 1e-9 * abs(one.residual_displacement_m) + 1e-12
    expected_azimuth = (azimuth_deg + (180.0 if one.residual_displacement_m > 0 else 0.0)) % 360.0
    assert math.isclose(two.residual_azimuth_deg, expected_azimuth, abs_tol=1e-6) or \
        math.isclose(abs(two.residual_azimuth_deg - expected_azimuth), 360.0, abs_tol=1e-6)
    assert two.max_abs_displacement_m == pytest.approx(one.max_abs_displacement_m, **tol)
    assert two.max_abs_velocity_m_s == pytest.approx(one.max_abs_velocity_m_s, **tol)
    assert two.total_slip_duration_s == pytest.approx(one.total_slip_duration_s, **tol)
    assert two.first_slip_time_s == pytest.approx(one.first_slip_time_s, **tol)


def test_never_slipping_block_has_no_azimuth(station):
    r = topple.slide_2d(topple.read(station[0]), topple.read(station[1]), mu=2.0)
    assert r.slip_episodes == 0 and r.residual_displacement_m == 0.0 and r.residual_azimuth_deg is None
    assert r.json()["residual_azimuth_deg"] is None


BAD = [
    ({"azimuths_deg": (90.0, 10.0)}, "azimuths_deg", "perpendicular"),
    ({"azimuths_deg": (90.0,)}, "azimuths_deg", "two"),
    ({"azimuths_deg": (math.nan, 0.0)}, "azimuths_deg", "finite"),
    ({"slope_deg": 10.0}, "slope_azimuth_deg", "required"),
    ({"slope_azimuth_deg": 45.0}, "slope_azimuth_deg", "slope_deg"),
    ({"slope_deg": 10.0, "slope_azimuth_deg": math.inf}, "slope_azimuth_deg", "finite"),
    ({"slope_deg": 95.0, "slope_azimuth_deg": 0.0}, "slope_deg", "slope"),
    ({"mu": -0.1}, "mu", "friction"),
    ({"mu_kinetic": 0.5}, "mu_kinetic", "kinetic"),
    ({"g": 0.0}, "g", "g must be positive"),
]


@pytest.mark.parametrize("kwargs,field,words", BAD, ids=[f"{b[1]}-{i}" for i, b in enumerate(BAD)])
def test_bad_input_names_the_parameter(station, kwargs, field, words):
    args = {"mu": 0.2, **kwargs}
    with pytest.raises(topple.InputError, match=words) as info:
        topple.slide_2d(topple.read(station[0]), topple.read(station[1]), **args)
    assert info.value.field == field
    assert isinstance(info.value, ValueError)
