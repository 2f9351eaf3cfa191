"""Bad input raises the documented exceptions, never crashes (python/topple/__init__.py states the rule)."""
import threading

import numpy as np
import pytest

import topple


@pytest.mark.parametrize("dtype", [np.int64, np.int32, np.float32, np.complex128, np.bool_])
def test_wrong_dtype_is_a_type_error_naming_float64(dtype):
    with pytest.raises(TypeError, match="float64"):
        topple.GroundMotion(np.ones(10, dtype=dtype), 0.01)


def test_wrong_dtype_for_time_too():
    with pytest.raises(TypeError, match="time must be a float64 array"):
        topple.GroundMotion(np.ones(3), time=np.arange(3))


def test_two_dimensional_is_a_value_error():
    with pytest.raises(ValueError, match="1-D"):
        topple.GroundMotion(np.ones((4, 2)), 0.01)


def test_not_an_array():
    with pytest.raises(TypeError):
        topple.GroundMotion("0.1 0.2", 0.01)
    with pytest.raises(TypeError):
        topple.GroundMotion([0.1, "x"], 0.01)


def test_non_contiguous_is_copied_with_its_stride():
    base = np.linspace(-1.0, 1.0, 41)
    strided = base[::3]
    assert not strided.flags["C_CONTIGUOUS"]
    m = topple.GroundMotion(strided, 0.02, units="m/s2")
    assert np.array_equal(m.accel_m_s2, np.ascontiguousarray(strided))
    reverse = topple.GroundMotion(base[::-1], 0.02, units="m/s2")
    assert np.array_equal(reverse.accel_m_s2, base[::-1])


def test_list_is_converted():
    m = topple.GroundMotion([0, 1, 0.5], 0.01, units="m/s2")
    assert m.accel_m_s2.tolist() == [0.0, 1.0, 0.5]


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_sample_is_an_input_error(bad):
    a = np.zeros(10)
    a[3] = bad
    with pytest.raises(topple.InputError, match="sample 3 is not finite") as err:
        topple.GroundMotion(a, 0.01)
    assert isinstance(err.value, ValueError)
    assert err.value.field == "accel"


@pytest.mark.parametrize("dt", [-0.01, 0.0, float("nan"), float("inf")])
def test_bad_dt_is_an_input_error(dt):
    with pytest.raises(topple.InputError, match="time step must be positive"):
        topple.GroundMotion(np.zeros(10), dt)


def test_dt_or_time_is_required_and_not_both():
    with pytest.raises(topple.InputError, match="give dt"):
        topple.GroundMotion(np.zeros(3))
    with pytest.raises(topple.InputError, match="not both"):
        topple.GroundMotion(np.zeros(3), 0.01, time=np.arange(3.0))


def test_decreasing_times_are_an_input_error():
    with pytest.raises(topple.InputError):
        topple.GroundMotion(np.zeros(3), time=np.array([0.0, 0.2, 0.1]))


def test_irregular_motion():
    m = topple.GroundMotion(np.array([0.0, 0.3, -0.2, 0.0]), time=np.array([0.0, 0.1, 0.25, 0.4]))
    assert not m.is_uniform
    assert m.time_s.tolist() == [0.0, 0.1, 0.25, 0.4]
    assert m.pga_g == pytest.approx(0.3, rel=1e-15)


def test_unknown_unit_and_parameters():
    with pytest.raises(topple.InputError):
        topple.GroundMotion(np.zeros(3), 0.01, units="furlongs")
    m = topple.GroundMotion(np.zeros(3), 0.01)
    with pytest.raises(topple.InputError, match="mode"):
        topple.slide(m, mu=0.3, mode="sideways")
    with pytest.raises(topple.InputError, match="mu"):
        topple.slide(m, mu=-0.3)
    with pytest.raises(topple.InputError, match="width"):
        topple.Block(width=-0.1, height=0.2)
    with pytest.raises(topple.InputError, match="housner"):
        topple.rock(m, topple.Block(width=0.1, height=0.2), e="elastic")


def test_file_errors_carry_the_cli_message(cli, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("time_s,accel_g\n0.0,0.1\n0.01,abc\n")
    proc = cli("info", bad, check=False)
    assert proc.returncode == 2
    with pytest.raises(topple.InputError) as err:
        topple.read(str(bad))
    assert proc.stderr.strip() == f"topple: error: {err.value}"
    assert err.value.file == str(bad) and err.value.line == 3


def test_records_as_recorded_columns_and_baseline(cli, tmp_path):
    # Issue 28: an eight-column tab-separated table file with spaces in its header names and a +0.02 g offset.
    path = tmp_path / "table.txt"
    rows = ["Time (s)\tTable Acc (g)\tTable Disp (mm)\tV (m/s)\tAcc 2 (g)\tStatus\tLVDT (mm)\tCmd (mm)"]
    for k in range(201):
        a = 0.02 + 0.3 * np.sin(2 * np.pi * k / 20)
        rows.append(f"{k * 0.005:.3f}\t{float(a)!r}\t{k}\t0\t0.1\tOK\t0\t0")
    path.write_text("\n".join(rows) + "\n")
    for columns in ("Time (s),Table Acc (g)", "1,2", ("Time (s)", "Table Acc (g)"), (1, 2)):
        m = topple.read(str(path), columns=columns, baseline="mean")
        assert m.accel_m_s2.size == 201
        # 10 whole periods of 20 samples plus one (sin 0 = 0): the mean is the offset, the sine remains.
        assert m.accel_m_s2[5] == pytest.approx(0.3 * 9.80665, abs=1e-12)
    raw = topple.read(str(path), columns=(1, 2))
    assert raw.accel_m_s2[0] == pytest.approx(0.02 * 9.80665, abs=1e-14)
    with pytest.raises(topple.InputError, match="Table Acc"):
        topple.read(str(path), columns="Time (s),Acc (g)")
    with pytest.raises(topple.InputError, match="0..3"):
        topple.read(str(path), columns="1,2", baseline="poly:5")
    with pytest.raises(topple.InputError):
        topple.read(str(path), columns=(1, 2, 3))
    # The CLI reads it the same way.
    j = cli.json("info", path, "--columns", "1,2", "--baseline", "mean")
    assert j["pga_g"] == pytest.approx(0.3, abs=1e-12)


def test_missing_file():
    with pytest.raises(topple.InputError, match="cannot open"):
        topple.read("/nonexistent/record.AT2")


def test_views_are_read_only_and_keep_their_owner_alive():
    m = topple.GroundMotion(np.array([0.0, 0.2, -0.1, 0.0]), 0.01)
    a = m.accel_m_s2
    assert not a.flags["WRITEABLE"] and not a.flags["OWNDATA"]
    r = topple.slide(m, mu=0.1)
    d = r.displacement_m
    del m, r
    assert a.shape == (4,) and d.shape[0] >= 4  # still valid after the owners' names are gone
    with pytest.raises(ValueError):
        a[0] = 1.0


def test_threads_run_concurrently_and_agree():
    m = topple.synth(pga_g=0.4, freq_hz=2.0, duration_s=20.0, seed=3)
    expected = topple.slide(m, mu=0.1).json()
    results = [None] * 4

    def work(i):
        results[i] = topple.slide(m, mu=0.1).json()

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(r == expected for r in results)


def test_values_in_g_are_in_the_motions_own_g(tmp_path):
    # A motion built with g = 9.81 from values in g gives them back in that g, not in standard gravity: 0.5 g of
    # 9.81 m/s2 is 4.905 m/s2 and reads 0.5 again (1e-15: one rounding of the product and one of the quotient).
    m = topple.GroundMotion([0.0, 0.5, -0.25, 0.0], dt=0.01, units="g", g=9.81)
    assert m.g_m_s2 == 9.81
    assert m.pga_m_s2 == pytest.approx(4.905, rel=1e-15)
    assert m.pga_g == pytest.approx(0.5, rel=1e-15)
    np.testing.assert_allclose(m.accel_g, [0.0, 0.5, -0.25, 0.0], rtol=1e-15)
    # Operations keep the motion's g; scaled_to_pga's default g is the motion's own.
    assert m.scaled(2.0).pga_g == pytest.approx(1.0, rel=1e-15)
    assert m.scaled_to_pga(0.3).pga_m_s2 == pytest.approx(0.3 * 9.81, rel=1e-15)
    # A file read with g = 9.81 likewise.
    path = tmp_path / "m.csv"
    path.write_text("time_s,accel_g\n0,0\n0.01,0.5\n0.02,0\n")
    r = topple.read(str(path), g=9.81)
    assert r.g_m_s2 == 9.81
    assert r.pga_g == pytest.approx(0.5, rel=1e-15)
    # Standard gravity stays the default.
    assert topple.GroundMotion([0.0, 1.0], dt=0.01).g_m_s2 == topple.STANDARD_GRAVITY
