"""topple.rock_oriented: an oriented object under two components, as `topple rock --h2 --json` (oriented.hpp)."""
import pytest

import topple


def station():
    """Two different synthetic components (portable: the same bits everywhere) and a vertical."""
    h1 = topple.synth(pga_g=0.3, freq_hz=2.5, duration_s=20.0, seed=4)
    h2 = topple.synth(pga_g=0.25, freq_hz=3.5, duration_s=20.0, seed=5)
    v = topple.synth(pga_g=0.1, freq_hz=6.0, duration_s=20.0, seed=6)
    return h1, h2, v


def test_bearing_on_a_component_is_that_component_alone():
    # The projection on a component's own azimuth is that component bit for bit (eq. M1): equal numbers.
    h1, h2, v = station()
    block = topple.Block(0.2, 0.8)
    for bearing, alone in ((90.0, h1), (0.0, h2)):
        o = topple.rock_oriented(h1, h2, block, azimuths_deg=(90.0, 0.0), bearing_deg=bearing, vertical=v)
        single = topple.rock(alone, block, vertical=v, history=False).json()
        assert single["uplifts"] > 0
        for key in ("max_abs_rotation_rad", "max_rotation_over_alpha", "impacts", "energy_lost_j_per_kg"):
            assert o[key] == single[key], key
        assert o["orientation"]["governing_azimuth_deg"] == bearing


def test_box_and_cylinder():
    h1, h2, _ = station()
    box = topple.rock_oriented(h1, h2, topple.Block(0.2, 0.8), bearing_deg=30.0, depth_m=0.4)
    assert [d["axis"] for d in box["orientation"]["directions"]] == ["bearing", "across"]
    assert [d["azimuth_deg"] for d in box["orientation"]["directions"]] == [30.0, 120.0]
    cyl = topple.rock_oriented(h1, h2, topple.Cylinder(0.2, 0.8))
    ratios = [d["max_rotation_over_alpha"] for d in cyl["orientation"]["directions"]]
    assert len(ratios) == 12
    assert not any(d["overturned"] for d in cyl["orientation"]["directions"])
    assert cyl["max_rotation_over_alpha"] == max(ratios)


def test_refusals_name_the_parameter():
    h1, h2, _ = station()
    block = topple.Block(0.2, 0.8)
    cylinder = topple.Cylinder(0.2, 0.8)
    for kwargs, name in (
        (dict(shape=block), "bearing_deg"),
        (dict(shape=cylinder, bearing_deg=10.0), "bearing_deg"),
        (dict(shape=cylinder, depth_m=0.3), "depth_m"),
        (dict(shape=cylinder, direction_step_deg=7.0), "direction_step_deg"),
        (dict(shape=block, bearing_deg=0.0, azimuths_deg=(90.0, 45.0)), "azimuths"),
        (dict(shape=block, bearing_deg=0.0, azimuths_deg=(90.0,)), "azimuths_deg"),
    ):
        with pytest.raises(topple.InputError, match=name):
            topple.rock_oriented(h1, h2, **kwargs)
