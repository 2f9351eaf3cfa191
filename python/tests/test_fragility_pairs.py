"""topple.fragility over pairs (a list of topple.MotionSet): `topple fragility --synth N --components 2|3` and
`topple fragility FILES --h2 ...` for the same inputs, the 1-D fragility from pairs whose second component is zero,
and bad input raising exceptions that name the parameter."""
import math

import numpy as np
import pytest

import topple
from test_slide2d import DT, N, write_csv

G = topple.STANDARD_GRAVITY
BLOCK = {"width": 0.2, "height": 0.6}
BLOCK_ARGS = ["--shape", "block", "--width", "20cm", "--height", "60cm"]
SLIDE = {"mu": 0.2, "threshold_m": 0.02}
SLIDE_ARGS = ["--mu", "0.2", "--threshold", "2cm"]


def log_grid(lo, hi, n):
    """The library's log_grid (src/fragility/object_spectra.cpp): exp of an even grid of logs, the ends exact; the same libm,
    so the same doubles as `--im-range LO:HI:N`."""
    a, b = math.log(lo), math.log(hi)
    v = [math.exp(a + (b - a) * i / (n - 1)) for i in range(n)]
    v[0], v[-1] = lo, hi
    return v


def assert_equals_cli(got, expected):
    """The Python result against `topple fragility --json`. Counts and the fit's dimensionless numbers exactly; the
    levels and theta to 4 ulp: the CLI prints SI x (1/g) and Python returns SI / g (fragility.hpp's display factor
    against its inverse), which may round differently."""
    assert got["rotd50"] is True
    assert got["im"] == "pga" and got["im_unit"] == "g" and expected["im_unit"] == "g"
    assert got["bearings_deg"].tolist() == expected["bearings_deg"]
    assert got["runs"] == expected["runs"]
    assert got["motions"] == len(expected["motions"])
    assert len(got["curves"]) == len(expected["curves"]) == 2
    for c, e in zip(got["curves"], expected["curves"]):
        assert c["name"] == e["curve"]
        assert c["trials"].tolist() == [x["trials"] for x in e["levels"]]
        assert c["failures"].tolist() == [x["failures"] for x in e["levels"]]
        np.testing.assert_allclose(c["im"], [x["im_rotd50_pga_g"] for x in e["levels"]], rtol=4e-16, atol=0)
        assert 0 < sum(c["failures"]) < sum(c["trials"])  # the curve is fitted from a real transition
        fit, ef = c["fit"], e["fit"]
        assert math.isclose(fit.theta, ef["theta"], rel_tol=4e-16)
        for key in ("beta", "se_ln_theta", "se_beta", "cov_ln_theta_beta", "log_likelihood", "beta_at_bound"):
            assert getattr(fit, key) == ef[key], key


# RotD50 PGA levels, g. With a vertical (V/H 2/3, synthesis.hpp) the top level stays below the one where the
# vertical would pass -g (the library refuses a body leaving the ground).
SYNTH_LEVELS = {2: (0.05, 2.0, 8), 3: (0.05, 0.9, 8)}


@pytest.mark.parametrize("components", [2, 3])
@pytest.mark.parametrize("bearing", [None, 40.0])
def test_synthetic_pairs_equal_cli(cli, components, bearing):
    lo, hi, n = SYNTH_LEVELS[components]
    args = ["fragility", "--synth", "6", "--components", str(components), "--duration", "8s", "--seed", "3",
            "--im-range", f"{lo}:{hi}:{n}", *SLIDE_ARGS, *BLOCK_ARGS, "--threads", "2"]
    args += ["--bearing-deg", "40"] if bearing is not None else ["--bearing-seed", "7"]
    expected = cli.json(*args)
    # `fragility --synth` makes each pair as topple.synth does (synthesis.hpp; its PGA is rescaled to every level).
    sets = [topple.synth(pga_g=0.1, freq_hz=2.0, duration_s=8.0, seed=3 + i, dt_s=0.01, components=components)
            for i in range(6)]
    kwargs = {"bearing_deg": bearing} if bearing is not None else {"bearing_seed": 7}
    got = topple.fragility(sets, log_grid(lo, hi, n), body=topple.Block(**BLOCK), threads=2, **SLIDE, **kwargs)
    assert_equals_cli(got, expected)
    if bearing is not None:
        assert got["bearings_deg"].tolist() == [40.0] * 6
    else:
        # Uniform draws on [0, 360): six distinct values in range.
        b = got["bearings_deg"]
        assert np.all((b >= 0.0) & (b < 360.0)) and len(set(b.tolist())) == 6


@pytest.fixture(scope="module")
def station_pairs(tmp_path_factory):
    """Three stations made here (always available): two horizontals and a vertical each, CSV time_s,accel_g."""
    t = np.arange(N) * DT
    env = np.exp(-((t - 5.0) / 3.0) ** 2)
    d = tmp_path_factory.mktemp("pairs")
    out = []
    for k, (f1, f2) in enumerate([(1.7, 1.1), (2.3, 0.9), (1.2, 2.8)]):
        h1 = 0.5 * np.sin(2 * np.pi * f1 * t) * env + 0.1 * np.sin(2 * np.pi * 5.3 * t + k)
        h2 = 0.4 * np.cos(2 * np.pi * f2 * t + 0.4 * k) * env + 0.08 * np.sin(2 * np.pi * 3.7 * t)
        v = 0.05 * np.sin(2 * np.pi * (4.1 + k) * t) * env
        out.append(tuple(write_csv(d / f"{name}{k}.csv", a) for name, a in (("h1_", h1), ("h2_", h2), ("v_", v))))
    return out


def test_record_pairs_equal_cli(cli, station_pairs):
    lo, hi, n = 0.1, 2.0, 24
    h1s, h2s, vs = zip(*station_pairs)
    expected = cli.json("fragility", *h1s, "--h2", *h2s, "--vertical", *vs, "--azimuths", "30,120", "--im-range",
                        f"{lo}:{hi}:{n}", *SLIDE_ARGS, *BLOCK_ARGS, "--bearing-seed", "11", "--threads", "2")
    sets = [topple.MotionSet(topple.read(a), topple.read(b), vertical=topple.read(v), azimuths_deg=(30.0, 120.0))
            for a, b, v in station_pairs]
    got = topple.fragility(sets, log_grid(lo, hi, n), body=topple.Block(**BLOCK), bearing_seed=11, threads=2, **SLIDE)
    assert_equals_cli(got, expected)


def test_zero_second_component_at_the_bearing_is_the_1d_fragility():
    # Pairs (m, 0) with m at azimuth 25 deg and the body's bearing 25 deg: the block slides on m's line only (the
    # 2-D solver equals the 1-D one to 1e-9, test_spectrum_2d.py) and the body rocks under m itself (the projection
    # m cos 0 + 0). The IM differs by a constant: the RotD50 PGA of (m, 0) is c x PGA(m), c the median of |cos| over
    # the RotD angles, the same c for every m; so the pairs at levels c x L are the records at levels L.
    motions = [topple.synth(pga_g=0.1, freq_hz=2.0, duration_s=8.0, seed=20 + i) for i in range(8)]
    zero = topple.GroundMotion(np.zeros(len(motions[0])), 0.01, units="m/s2")
    sets = [topple.MotionSet(m, zero, azimuths_deg=(25.0, 115.0)) for m in motions]
    ratios = [s.rotd()["pga_rotd50_m_s2"] / m.pga_m_s2 for s, m in zip(sets, motions)]
    c = ratios[0]
    # 4e-16: the median of two angles' peaks is their mean, rounded once per motion.
    assert all(math.isclose(r, c, rel_tol=4e-16) for r in ratios)
    assert math.cos(math.radians(46.0)) < c < math.cos(math.radians(44.0))
    levels = log_grid(0.05, 2.0, 10)
    one = topple.fragility(motions, levels, body=topple.Block(**BLOCK), **SLIDE)
    two = topple.fragility(sets, [c * x for x in levels], body=topple.Block(**BLOCK), bearing_deg=25.0, **SLIDE)
    assert one["rotd50"] is False and one["bearings_deg"] is None
    assert two["rotd50"] is True and two["bearings_deg"].tolist() == [25.0] * 8
    for a, b in zip(one["curves"], two["curves"]):
        assert a["name"] == b["name"]
        assert a["trials"].tolist() == b["trials"].tolist()
        assert a["failures"].tolist() == b["failures"].tolist()
        assert 0 < sum(a["failures"]) < sum(a["trials"])
        # The same counts at levels scaled by c: the likelihood is the same function of ln theta - ln c, so the
        # maximum moves by exactly ln c. A maximum is located only to ~sqrt(eps) relative (ln L is flat to second
        # order there: a step of 1e-8 changes it by ~1e-16 of itself, below its round-off), so 1e-7 on theta and
        # beta (measured: 3.5e-9 on beta), and 1e-12 on the maximum value itself (second order in the step).
        assert math.isclose(b["fit"].theta / c, a["fit"].theta, rel_tol=1e-7)
        assert math.isclose(b["fit"].beta, a["fit"].beta, rel_tol=1e-7)
        assert math.isclose(b["fit"].log_likelihood, a["fit"].log_likelihood, rel_tol=1e-12)


@pytest.fixture(scope="module")
def pairs():
    return [topple.synth(pga_g=0.1, freq_hz=2.0, duration_s=4.0, seed=i, components=2) for i in range(2)]


def test_bad_input_names_the_parameter(pairs):
    one = [topple.synth(pga_g=0.1, freq_hz=2.0, duration_s=4.0, seed=1)]
    levels = [0.1, 0.5]
    with pytest.raises(TypeError, match="MotionSet"):
        topple.fragility([pairs[0], one[0]], levels, **SLIDE)  # one kind per ensemble
    with pytest.raises(TypeError, match="GroundMotion"):
        topple.fragility([one[0], pairs[0]], levels, **SLIDE)
    with pytest.raises(TypeError, match="list"):
        topple.fragility(pairs[0], levels, **SLIDE)
    for kwargs, field in [({"bearing_deg": 10.0}, "bearing_deg"), ({"bearing_seed": 3}, "bearing_seed")]:
        with pytest.raises(topple.InputError) as err:
            topple.fragility(one, levels, body=topple.Block(**BLOCK), **kwargs)
        assert err.value.field == field and "MotionSet" in str(err.value)
    with pytest.raises(topple.InputError) as err:
        topple.fragility(pairs, levels, im="pgv", **SLIDE)
    assert err.value.field == "im"
    with pytest.raises(topple.InputError) as err:
        topple.fragility(pairs, levels, body=topple.Cylinder(diameter=0.1, height=0.4), bearing_deg=10.0)
    assert err.value.field == "bearing_deg"
    with pytest.raises(topple.InputError) as err:
        topple.fragility(pairs, levels, body=topple.Block(**BLOCK), bearing_deg=float("nan"))
    assert err.value.field == "bearing_deg"
    with pytest.raises(topple.InputError) as err:
        topple.fragility(pairs, levels, mode="one-way", **SLIDE)
    assert err.value.field == "mode"
    with pytest.raises(topple.InputError) as err:
        topple.fragility(pairs, levels, slope_deg=5.0, **SLIDE)
    assert err.value.field == "slope_deg"
    with pytest.raises(topple.InputError) as err:
        topple.fragility([topple.MotionSet(pairs[0].first)], levels, **SLIDE)  # no second component
    assert err.value.field == "motions"
    with pytest.raises(TypeError):
        topple.fragility(pairs, levels, bearing_seed=-1, **SLIDE)
