"""topple.rock3d: a box rocking and pivoting in three dimensions (rigid3d.hpp), equal to `topple rock --model 3d
--json` for the same inputs, bit for bit (the JSON prints the shortest round-trip form of every double)."""
import math

import numpy as np
import pytest

import topple
from conftest import write_record

BOX = ("--shape", "block", "--width", "0.2m", "--depth", "0.3m", "--height", "0.8m", "--model", "3d")


@pytest.fixture(scope="module")
def station(tmp_path_factory):
    """Two horizontal components and a vertical (plain CSV records in g, 0.01 s) that rock the box and pivot it."""
    d = tmp_path_factory.mktemp("station3d")
    t = np.arange(1500) * 0.01
    env = np.exp(-(((t - 5.0) / 2.0) ** 2))
    a1 = 0.45 * np.sin(2 * np.pi * 1.5 * t) * env
    a2 = 0.35 * np.cos(2 * np.pi * 1.1 * t) * env
    av = 0.1 * np.sin(2 * np.pi * 4.0 * t) * env
    return [write_record(d / f"{n}.csv", t, a, time_decimals=2) for n, a in (("h1", a1), ("h2", a2), ("v", av))]


def without_input(j):
    return {k: v for k, v in j.items() if k != "input"}


def test_one_component_equals_the_cli(cli, station):
    h1, _, v = station
    expected = cli.json("rock", h1, "--vertical", v, *BOX)
    assert expected["impacts"] > 0
    got = topple.rock3d(topple.read(h1), width_m=0.2, depth_m=0.3, height_m=0.8, vertical=topple.read(v))
    assert got == without_input(expected)


def test_two_components_equal_the_cli(cli, station):
    h1, h2, v = station
    expected = cli.json("rock", h1, "--h2", h2, "--vertical", v, "--azimuths", "0,90", "--bearing-deg", "30", *BOX,
                        "--e", "0.9")
    assert any(m["mode"] == "pivot" for m in expected["modes"])  # it pivots on a corner: genuinely 3-D
    got = topple.rock3d(topple.read(h1), topple.read(h2), width_m=0.2, depth_m=0.3, height_m=0.8,
                        azimuths_deg=(0.0, 90.0), bearing_deg=30.0, vertical=topple.read(v), e=0.9)
    assert got == without_input(expected)


def test_history_agrees_with_the_summary(station):
    h1, h2, _ = station
    kwargs = dict(width_m=0.2, depth_m=0.3, height_m=0.8, azimuths_deg=(0.0, 90.0), bearing_deg=30.0)
    plain = topple.rock3d(topple.read(h1), topple.read(h2), **kwargs)
    full = topple.rock3d(topple.read(h1), topple.read(h2), history=True, **kwargs)
    h = full.pop("history")
    assert full == plain  # recording the history changes nothing
    n = len(h["time_s"])
    assert n > 100
    for key in ("position_m", "orientation_wxyz", "angular_velocity_rad_s", "energy_j_per_kg", "mode"):
        assert len(h[key]) == n, key
    assert h["time_s"][-1] == plain["end_time_s"]
    assert h["mode"][0] == "rest" and h["mode"][-1] == plain["end_mode"]
    tilts = [math.acos(min(1.0, 1.0 - 2.0 * (q[1] ** 2 + q[2] ** 2))) for q in h["orientation_wxyz"]]
    # the rows hold every sample (0.01 s apart) and event; the located maximum lies between rows
    assert max(tilts) <= plain["max_tilt_rad"] * (1 + 1e-9)
    assert max(tilts) >= 0.95 * plain["max_tilt_rad"]
    for q in h["orientation_wxyz"]:
        assert abs(sum(c * c for c in q) - 1.0) < 1e-9


def test_refusals_name_the_parameter(station):
    h1, h2, _ = station
    r1, r2 = topple.read(h1), topple.read(h2)
    for args, kwargs, name in (
        ((r1, r2), dict(width_m=0.2, depth_m=0.3, height_m=0.8), "bearing_deg"),
        ((r1,), dict(width_m=0.2, depth_m=0.3, height_m=0.8, bearing_deg=10.0), "bearing_deg"),
        ((r1,), dict(width_m=0.2, depth_m=0.0, height_m=0.8), "depth_m"),
        ((r1,), dict(width_m=0.2, depth_m=0.3, height_m=0.8, e=1.5), "e"),
        ((r1, r2), dict(width_m=0.2, depth_m=0.3, height_m=0.8, bearing_deg=0.0, azimuths_deg=(0.0, 45.0)),
         "azimuths"),
    ):
        with pytest.raises(topple.InputError, match=name):
            topple.rock3d(*args, **kwargs)


# A solid cylinder (diameter_m instead of width_m and depth_m): the rim engine (rigid3d_disc.hpp), as
# `topple rock --model 3d --shape cylinder --diameter --height --json`.
CYLINDER = ("--shape", "cylinder", "--diameter", "0.2m", "--height", "0.8m", "--model", "3d")


@pytest.fixture(scope="module")
def cylinder_station(tmp_path_factory):
    """Components (g, 0.01 s) that rock the 0.2 x 0.8 m cylinder hard without overturning it under the first alone
    (its uplift threshold is tan(alpha) = 0.25 g), and roll it on its rim under both."""
    d = tmp_path_factory.mktemp("cylinder3d")
    t = np.arange(1500) * 0.01
    env = np.exp(-(((t - 5.0) / 2.0) ** 2))
    a1 = 0.28 * np.sin(2 * np.pi * 1.5 * t) * env
    a2 = 0.1 * np.cos(2 * np.pi * 1.1 * t) * env
    av = 0.05 * np.sin(2 * np.pi * 4.0 * t) * env
    return [write_record(d / f"{n}.csv", t, a, time_decimals=2) for n, a in (("h1", a1), ("h2", a2), ("v", av))]


def test_cylinder_equals_the_cli(cli, cylinder_station):
    h1, h2, v = cylinder_station
    one = cli.json("rock", h1, *CYLINDER)
    got = topple.rock3d(topple.read(h1), diameter_m=0.2, height_m=0.8)
    assert got == without_input(one)
    assert got["body"] == {"shape": "cylinder", "diameter_m": 0.2, "height_m": 0.8, "bearing_deg": None}
    assert got["solver"]["impact_law"] == "housner_rim_point" and got["solver"]["simultaneous_contact"] is None
    two = cli.json("rock", h1, "--h2", h2, "--vertical", v, "--azimuths", "0,90", *CYLINDER, "--e", "0.8")
    assert two["impacts"] > 0
    got = topple.rock3d(topple.read(h1), topple.read(h2), diameter_m=0.2, height_m=0.8, azimuths_deg=(0.0, 90.0),
                        vertical=topple.read(v), e=0.8)
    assert got == without_input(two)
    # with friction (rigid3d_disc.hpp): the CLI's --mu, --mu-k, the same JSON; mu = 0.2 below R / h = 0.25, the
    # cylinder slides flat and never tilts (Shenton 1996)
    slid = cli.json("rock", h1, "--h2", h2, "--azimuths", "0,90", *CYLINDER, "--mu", "0.2", "--mu-k", "0.15")
    got = topple.rock3d(topple.read(h1), topple.read(h2), diameter_m=0.2, height_m=0.8, azimuths_deg=(0.0, 90.0),
                        mu=0.2, mu_k=0.15)
    assert got == without_input(slid)
    assert got["solver"]["mu_s"] == 0.2 and got["slide_path_length_m"] > 1e-3 and got["max_tilt_rad"] == 0.0


def test_cylinder_under_one_component_is_the_planar_cylinder(cylinder_station):
    """Under one component and no spin the rim engine stays in the vertical plane through the axis: the planar
    cylinder of `rock` (rigid3d_disc.hpp; a = R, D = J_t + R^2 + h^2), the same impacts and verdict, the max tilt over
    its static limit to 1e-6 (both at their default tolerances, as the CLI test Model3dCylinderIsTheRimEngine)."""
    h1 = topple.read(cylinder_station[0])
    solid = topple.rock3d(h1, diameter_m=0.2, height_m=0.8)
    planar = topple.rock(h1, topple.Cylinder(0.2, 0.8))
    assert planar.impacts > 10 and not planar.overturned
    assert 0.5 < planar.max_rotation_over_alpha < 1.0
    assert solid["impacts"] == planar.impacts
    assert solid["uplifts"] == planar.uplifts
    assert solid["overturned"] == planar.overturned
    assert solid["max_tilt_over_limit"] == pytest.approx(planar.max_rotation_over_alpha, abs=1e-6)
    assert solid["max_tilt_rad"] == pytest.approx(planar.max_abs_rotation_rad, abs=1e-6 * planar.alpha_rad)
    # the record acts along +x (azimuth 90): the tilt is toward east or west
    assert min(abs(solid["max_tilt_azimuth_deg"] - 90.0), abs(solid["max_tilt_azimuth_deg"] - 270.0)) < 1e-6


def test_cylinder_refusals_name_the_parameter(cylinder_station):
    h1, h2, _ = cylinder_station
    r1, r2 = topple.read(h1), topple.read(h2)
    for args, kwargs, name in (
        ((r1,), dict(diameter_m=0.2, width_m=0.2, height_m=0.8), "width_m"),
        ((r1,), dict(diameter_m=0.2, depth_m=0.2, height_m=0.8), "depth_m"),
        ((r1,), dict(height_m=0.8), "width_m"),
        ((r1,), dict(width_m=0.2, height_m=0.8), "depth_m"),
        ((r1, r2), dict(diameter_m=0.2, height_m=0.8, bearing_deg=0.0), "bearing_deg"),
        ((r1,), dict(diameter_m=-0.2, height_m=0.8), "diameter_m"),
        ((r1,), dict(diameter_m=0.2, height_m=0.0), "height_m"),
        ((r1,), dict(diameter_m=0.2, height_m=0.8, simultaneous_contact=0.0), "simultaneous_contact"),
    ):
        with pytest.raises(topple.InputError, match=name):
            topple.rock3d(*args, **kwargs)


def test_simultaneous_contact_is_the_impact_laws_limit(cli, tmp_path):
    """simultaneous_contact (a fraction of the body's size): the diagonal pulse of tests/solvers/test_rigid3d.cpp, a
    box 0.2 x 0.12 x 0.8 m under one sine cycle of 0.45 g, 0.3 s, along its base diagonal, lands nearly flat (three
    corners within ~20 us). The Siconos reference's numbers (docs/verification.md, "Simultaneous or successive"): one
    impact (the default 1e-5) 0.077023 rad toward -121.15 deg; successive impacts (0) 0.08309 rad toward -127.66 deg;
    allowed 1e-4 of the tilt and 0.05 deg. Equal to the CLI's --simultaneous-contact bit for bit; refused outside
    [0, 0.01]."""
    phi = math.atan2(0.06, 0.1)
    t = np.arange(301) * 0.001
    a = 0.45 * np.sin(2 * np.pi * t / 0.3)
    east = write_record(tmp_path / "east.csv", t, -a * math.cos(phi), time_decimals=3)
    north = write_record(tmp_path / "north.csv", t, -a * math.sin(phi), time_decimals=3)
    box = dict(width_m=0.2, depth_m=0.12, height_m=0.8, bearing_deg=90.0, max_run_out_s=1.7)
    for value, tilt, azimuth in ((None, 0.077023, -121.15), (0.0, 0.08309, -127.66)):
        got = topple.rock3d(topple.read(east), topple.read(north), simultaneous_contact=value, **box)
        assert got["solver"]["simultaneous_contact"] == (1e-5 if value is None else value)
        assert got["max_tilt_rad"] == pytest.approx(tilt, rel=1e-4)
        assert abs(math.remainder(got["max_tilt_azimuth_deg"] - azimuth, 360.0)) < 0.05
        if value is not None:
            expected = cli.json("rock", east, "--h2", north, "--azimuths", "90,0", "--bearing-deg", "90", "--shape",
                                "block", "--width", "0.2m", "--depth", "0.12m", "--height", "0.8m", "--model", "3d",
                                "--run-out", "1.7", "--simultaneous-contact", "0")
            assert got == without_input(expected)
    for bad in (-1e-6, 0.02, math.nan):
        with pytest.raises(topple.InputError, match="simultaneous_contact"):
            topple.rock3d(topple.read(east), topple.read(north), simultaneous_contact=bad, **box)


def test_friction_equals_the_cli(cli, station):
    """mu and mu_k are the CLI's --mu and --mu-k (Rigid3DOptions::mu_s, mu_k): the same JSON, bit for bit; without
    them the no-slip engine (the summary's sliding keys zero, the solver's mu_s null)."""
    h1, h2, v = station
    expected = cli.json("rock", h1, "--h2", h2, "--azimuths", "0,90", "--bearing-deg", "30", *BOX, "--mu", "0.2",
                        "--mu-k", "0.15")
    got = topple.rock3d(topple.read(h1), topple.read(h2), width_m=0.2, depth_m=0.3, height_m=0.8,
                        azimuths_deg=(0.0, 90.0), bearing_deg=30.0, mu=0.2, mu_k=0.15)
    assert got == without_input(expected)
    assert got["solver"]["mu_s"] == 0.2 and got["solver"]["mu_k"] == 0.15
    # mu_s = 0.2 below the box's b/h = 0.25: it slides before it can lift (Shenton 1996), under a PGA of 0.45 g
    assert got["slide_path_length_m"] > 1e-3
    dry = topple.rock3d(topple.read(h1), topple.read(h2), width_m=0.2, depth_m=0.3, height_m=0.8,
                        azimuths_deg=(0.0, 90.0), bearing_deg=30.0)
    assert dry["solver"]["mu_s"] is None and dry["slide_path_length_m"] == 0.0


def test_friction_refusals_are_the_librarys(station):
    r1 = topple.read(station[0])
    box = dict(width_m=0.2, depth_m=0.3, height_m=0.8)
    for kwargs, name in ((dict(box, mu=-0.1), "mu"), (dict(box, mu=0.3, mu_k=0.4), "mu_k"),
                         (dict(box, mu_k=0.2), "mu"), (dict(diameter_m=0.2, height_m=0.8, mu=0.3, mu_k=0.5), "mu_k")):
        with pytest.raises(topple.InputError, match=name):
            topple.rock3d(r1, **kwargs)


def test_inclined_base_equals_the_cli(cli, station):
    """base_incline_deg / base_incline_azimuth_deg are the CLI's --base-incline-deg / --base-incline-azimuth-deg
    (rigid3d.hpp, "Inclined base"): the same JSON, whose solver block says the incline; a cylinder refuses it."""
    h1, h2, v = station
    expected = cli.json("rock", h1, "--h2", h2, "--vertical", v, "--azimuths", "0,90", "--bearing-deg", "30", *BOX,
                        "--mu", "0.6", "--base-incline-deg", "6", "--base-incline-azimuth-deg", "200")
    assert expected["solver"]["base_incline_deg"] == 6.0 and expected["solver"]["output_frame"] == "base"
    got = topple.rock3d(topple.read(h1), topple.read(h2), width_m=0.2, depth_m=0.3, height_m=0.8,
                        azimuths_deg=(0.0, 90.0), bearing_deg=30.0, vertical=topple.read(v), mu=0.6,
                        base_incline_deg=6.0, base_incline_azimuth_deg=200.0)
    assert got == without_input(expected)
    with pytest.raises(topple.InputError, match="base_incline_deg"):
        topple.rock3d(topple.read(h1), diameter_m=0.2, height_m=0.8, base_incline_deg=5.0)
