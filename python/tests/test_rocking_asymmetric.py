"""Asymmetric rocking bodies from Python (topple.GeneralAsymmetric): the binding translates the library's body
and per-side results (the physics is tested in tests/solvers/test_rocking_asymmetric.cpp)."""
import math

import pytest

import topple


@pytest.fixture(scope="module")
def motion():
    return topple.synth(pga_g=0.4, freq_hz=2.0, duration_s=10.0, seed=5)


def test_body_properties():
    b = topple.GeneralAsymmetric(b1=0.07, b2=0.13, h=0.45, inertia=0.025)
    assert not b.symmetric
    assert b.b1_m == pytest.approx(0.07, rel=1e-15)
    assert b.b2_m == pytest.approx(0.13, rel=1e-15)
    # D_s = I_cm/m + b_s^2 + h^2 (parallel axes), exact to round-off
    assert b.D1_m2 == pytest.approx(0.025 + 0.07**2 + 0.45**2, rel=1e-14)
    assert b.D2_m2 == pytest.approx(0.025 + 0.13**2 + 0.45**2, rel=1e-14)
    s = topple.Block(width=0.2, height=0.6)
    assert s.symmetric and s.b1_m == s.b2_m == s.a_m and s.D1_m2 == s.D2_m2 == s.D_m2


def test_equal_pivots_equal_the_symmetric_general_body(motion):
    a, h, k2 = 0.1, 0.3, 0.01
    sym = topple.rock(motion, topple.General(a=a, h=h, D=k2 + a * a + h * h), history=False)
    asym = topple.rock(motion, topple.GeneralAsymmetric(b1=a, b2=a, h=h, inertia=k2), history=False)
    assert asym.impacts == sym.impacts and asym.overturned == sym.overturned
    # the engine's own 1e-12 agreement (tests/solvers/test_rocking_asymmetric.cpp, EqualPivotsReproduceTheSymmetricBody)
    assert asym.max_rotation_over_alpha == pytest.approx(sym.max_rotation_over_alpha, rel=1e-12, abs=1e-15)


def test_mirrored_body_under_negated_input_mirrors_the_response(motion):
    body = topple.GeneralAsymmetric(b1=0.06, b2=0.12, h=0.4, inertia=0.02)
    mirror = topple.GeneralAsymmetric(b1=0.12, b2=0.06, h=0.4, inertia=0.02)
    r = topple.rock(motion, body, history=False)
    m = topple.rock(motion.scaled(-1.0), mirror, history=False)
    assert r.uplifts > 0  # the record rocks it, so the sides are exercised
    # exact mirror symmetry (the engine is bit-exact under it: AsymmetricBody.MirrorBodyUnderNegatedInput...)
    assert m.max_rotation_positive_rad == r.max_rotation_negative_rad
    assert m.max_rotation_negative_rad == r.max_rotation_positive_rad
    assert m.overturned_side == -r.overturned_side
    assert m.impacts == r.impacts
    assert math.isfinite(r.max_rotation_over_alpha_positive)
