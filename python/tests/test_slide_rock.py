"""The coupled slide-rock model from Python (topple.slide_rock): the binding translates the library's body, options
and summary (the physics is tested in tests/solvers/test_slide_rock.cpp); here its results against the CLI and against the
two limits the model must reach (no slip: Housner rocking; no uplift: the sliding solver)."""
import math

import numpy as np
import pytest

import topple

from conftest import write_record


@pytest.fixture(scope="module")
def pulse_record(tmp_path_factory):
    """One full sine cycle of 0.5 g and period 0.5 s, then 3 s of still ground (time_s,accel_g at 1 ms)."""
    t = np.arange(3501) * 0.001
    a = np.where(t <= 0.5, 0.5 * np.sin(2 * np.pi * t / 0.5), 0.0)
    return write_record(tmp_path_factory.mktemp("records") / "sine_pulse.csv", t, a, time_decimals=3)


@pytest.fixture(scope="module")
def pulse(pulse_record):
    return topple.read(pulse_record)


def test_result_equals_cli_coupled_json(cli, pulse_record, pulse):
    expected = cli.json("rock", pulse_record, "--shape", "block", "--width", "0.2m", "--height", "0.6m", "--model", "coupled",
                        "--mu", "0.6", "--mu-k", "0.5")
    r = topple.slide_rock(pulse, topple.Block(width=0.2, height=0.6), 0.6, 0.5)
    # The pulse (0.5 g > g b/h = 0.333 g) moves the block: the comparison is not of two bodies at rest.
    assert r.onset_mode != "rest" and r.max_rotation_over_alpha > 0.0
    # The same library call on the same samples: equal to the last bit, field by field, "input" included.
    assert r.json() == expected
    for key, value in expected.items():
        if key in ("input", "modes", "body", "sign_convention"):
            continue
        assert getattr(r, key) == value, key
    assert r.modes == expected["modes"]
    assert r.warnings == expected["warnings"]
    summary_only = topple.slide_rock(pulse, topple.Block(width=0.2, height=0.6), 0.6, 0.5, history=False)
    assert summary_only.json() == expected
    assert len(summary_only.time_s) == 0 and len(r.time_s) > 0 and len(r.transitions) > 0


@pytest.mark.parametrize("body", [topple.Block(width=0.2, height=0.6),
                                  topple.GeneralAsymmetric(b1=0.08, b2=0.12, h=0.3, inertia=0.04)],
                         ids=["block", "asymmetric"])
@pytest.mark.parametrize("amp", [0.8, 1.0], ids=["survives", "falls"])
def test_high_friction_is_housner_rocking(pulse, body, amp):
    motion = pulse.scaled(amp)  # 0.4 g: rocks (55-61 impacts) and survives; 0.5 g: falls (measured, both bodies)
    coupled = topple.slide_rock(motion, body, 5.0, history=False)
    housner = topple.rock(motion, body, history=False)
    # mu = 5 is far above b/h and above the impulse ratio of a Housner impact: the pivot sticks while the body
    # rocks, so the coupled model is Housner's (verdict and impact count are discrete: exact).
    assert coupled.overturned == housner.overturned == (amp == 1.0)
    assert coupled.impacts == housner.impacts
    assert coupled.onset_mode == "rock"
    if not coupled.overturned:
        # (A falling body slips at the end, where its normal force goes to 0: physics, not a difference.)
        assert coupled.slip_episodes == 0 and housner.impacts > 10
        # Both integrate Housner's equation with Dormand-Prince at rel_tol 1e-8 per step: 1e-6 leaves room for the
        # two engines' different step sequences over ~60 impacts (they agree to 1e-14 here).
        assert coupled.max_rotation_over_alpha == pytest.approx(housner.max_rotation_over_alpha, rel=1e-6)


def test_wide_body_slides_as_the_sliding_solver(pulse):
    body = topple.Block(width=0.5, height=0.2)  # b/h = 2.5 > mu: slides before it can lift
    r = topple.slide_rock(pulse, body, 0.3, 0.25, history=False)
    s = topple.slide(pulse, mu=0.3, mu_kinetic=0.25, history=False)
    assert r.impacts == 0 and r.uplifts == 0 and r.max_rotation_over_alpha == 0.0
    assert abs(s.residual_displacement_m) > 1e-3  # the 0.5 g pulse beats the 0.3 g yield: a real slide
    # sliding.hpp's d is positive toward -x (the way a positive a_h pushes the block): d = -u. 1e-9 relative: the
    # coupled model runs the exact sliding solver for such a body, so only round-off can separate them.
    assert r.residual_slide_m == pytest.approx(-s.residual_displacement_m, rel=1e-9)


@pytest.mark.parametrize("mu, mu_k, field", [(-0.1, None, "mu"), (math.nan, None, "mu"), (0.3, 0.5, "mu_k")])
def test_bad_friction_raises_value_error_naming_it(pulse, mu, mu_k, field):
    with pytest.raises(ValueError, match=field) as info:
        topple.slide_rock(pulse, topple.Block(width=0.2, height=0.6), mu, mu_k)
    assert isinstance(info.value, topple.InputError)
    assert info.value.field == field
