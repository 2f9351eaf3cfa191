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
