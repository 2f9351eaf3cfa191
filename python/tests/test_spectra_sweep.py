"""Spectra, object spectra, fragility and sweeps through Python: equal to the CLI where it prints the numbers
(topple info --json, topple sweep's CSV), otherwise checked against closed forms with stated tolerances."""
import csv
import math
import pathlib

import numpy as np
import pytest

import topple

ROOT = pathlib.Path(__file__).resolve().parents[2]


def parabola_vertex(ym, y0, yp):
    """spectra.cpp's refinement of a grid maximum (same operations)."""
    curvature = ym - 2.0 * y0 + yp
    if not curvature < 0.0:
        return 0.0
    return min(max(0.5 * (ym - yp) / curvature, -0.5), 0.5)


# ---- response spectrum ----

def harmonic_sdof_max(period_s, zeta, amp, omega_in, t):
    """max |x(t_i)| of x'' + 2 zeta w x' + w^2 x = -amp sin(omega_in t) from rest: particular + free solution."""
    w = 2 * np.pi / period_s
    k = w * w - omega_in * omega_in
    c = 2 * zeta * w * omega_in
    # x_p = P sin + Q cos: k P - c Q = -amp, c P + k Q = 0.
    P, Q = np.linalg.solve([[k, -c], [c, k]], [-amp, 0.0])
    wd = w * math.sqrt(1 - zeta * zeta)
    C1 = -Q
    C2 = (zeta * w * C1 - P * omega_in) / wd
    x = P * np.sin(omega_in * t) + Q * np.cos(omega_in * t) + np.exp(-zeta * w * t) * (
        C1 * np.cos(wd * t) + C2 * np.sin(wd * t))
    return np.max(np.abs(x))


@pytest.mark.parametrize("zeta", [0.02, 0.05, 0.2])
def test_response_spectrum_harmonic_closed_form(zeta):
    # a_g = A sin(2 pi t), sampled at 1 ms for 20 s: the piecewise-linear input differs from the sine by
    # O((Omega dt)^2 / 8) ~ 5e-6 relative, so the exact Nigam-Jennings maxima agree with the closed form to 1e-4.
    dt, amp, omega = 0.001, 2.0, 2 * np.pi
    t = np.arange(20001) * dt
    motion = topple.GroundMotion(amp * np.sin(omega * t), dt, units="m/s2")
    periods = np.array([0.1, 0.5, 0.9, 1.0, 1.3, 3.0])
    spec = topple.response_spectrum(motion, periods, damping=zeta)
    expected = [harmonic_sdof_max(T, zeta, amp, omega, t) for T in periods]
    np.testing.assert_allclose(spec["sd_m"], expected, rtol=1e-4)
    w = 2 * np.pi / periods
    np.testing.assert_allclose(spec["psv_m_s"], w * spec["sd_m"], rtol=1e-15)
    np.testing.assert_allclose(spec["psa_m_s2"], w * w * spec["sd_m"], rtol=1e-15)
    np.testing.assert_allclose(spec["psa_g"], spec["psa_m_s2"] / topple.STANDARD_GRAVITY, rtol=1e-15)
    assert spec["damping"] == zeta and spec["period_s"].dtype == np.float64
    if zeta == 0.2:  # steady state reached: PSA at resonance = A / (2 zeta)
        assert spec["psa_m_s2"][3] == pytest.approx(amp / (2 * zeta), rel=2e-4)


def test_tp_from_the_spectrum_equals_cli(cli, made_record):
    """topple info --json's Tp is the parabola-refined peak of the default 5 % spectrum (same periods)."""
    info = cli.json("info", made_record)
    spec = topple.response_spectrum(topple.read(made_record))
    psa = spec["psa_m_s2"]
    k = int(np.argmax(psa))
    offset = parabola_vertex(psa[k - 1], psa[k], psa[k + 1]) if 0 < k < len(psa) - 1 else 0.0
    tp = 0.02 * 10 ** ((k + offset) / 100.0)
    assert tp == pytest.approx(info["tp_s"], rel=1e-13)
    assert len(spec["period_s"]) == 241 and spec["period_s"][0] == 0.02


def test_response_spectrum_errors(made_record):
    motion = topple.read(made_record)
    with pytest.raises(topple.InputError):
        topple.response_spectrum(motion, [0.5, -1.0])
    with pytest.raises(topple.InputError):
        topple.response_spectrum(motion, [0.5], damping=1.5)
    with pytest.raises(TypeError, match="float64"):
        topple.response_spectrum(motion, np.array([1, 2]))


# ---- Fourier amplitude spectrum ----

def test_fourier_spectrum_closed_form():
    # 3.5 Hz sine of amplitude A, exactly 35 cycles in N = 1000 samples at 0.01 s, unpadded: the DFT is A N / 2 at
    # bin 35 and zero (rounding: 1e-12 A N) elsewhere, so |A(3.5 Hz)| = dt A N / 2 = 0.5 A * 10 s.
    dt, n, amp = 0.01, 1000, 3.0
    t = np.arange(n) * dt
    motion = topple.GroundMotion(amp * np.sin(2 * np.pi * 3.5 * t), dt, units="m/s2")
    fas = topple.fourier_spectrum(motion, None, fft_length=n)
    assert fas["fft_length"] == n and fas["smoothed_amplitude_m_s"] is None
    np.testing.assert_allclose(fas["freq_hz"], np.arange(n // 2 + 1) / (n * dt), rtol=1e-15)
    assert fas["amplitude_m_s"][35] == pytest.approx(dt * amp * n / 2, rel=1e-12)
    others = np.delete(fas["amplitude_m_s"], 35)
    assert np.max(others) < 1e-11
    # Konno-Ohmachi smoothing of a constant spectrum (a unit impulse: |A| = dt everywhere) is that constant (the
    # weights are normalised), at centres whose window holds FFT frequencies (df = 0.39 Hz here).
    centres = np.geomspace(1.0, 20.0, 30)
    flat = topple.fourier_spectrum(topple.GroundMotion(np.r_[1.0, np.zeros(255)], 0.01, units="m/s2"), 40.0,
                                   centre_hz=centres, fft_length=256)
    np.testing.assert_allclose(flat["smoothed_freq_hz"], centres, rtol=0)
    np.testing.assert_allclose(flat["smoothed_amplitude_m_s"], 0.01, rtol=1e-12)


def test_predominant_frequency_equals_cli(cli, made_record):
    info = cli.json("info", made_record)
    motion = topple.read(made_record)
    fas = topple.fourier_spectrum(motion)
    assert fas["predominant_frequency_hz"] == info["predominant_frequency_hz"]
    assert topple.intensity(motion)["predominant_frequency_hz"] == info["predominant_frequency_hz"]
    # ... and it is the parabola-refined peak of the returned smoothed spectrum (200 centres per decade from 0.1 Hz).
    s = fas["smoothed_amplitude_m_s"]
    k = int(np.argmax(s))
    fp = 0.1 * 10 ** ((k + parabola_vertex(s[k - 1], s[k], s[k + 1])) / 200.0)
    assert fp == pytest.approx(info["predominant_frequency_hz"], rel=1e-13)
    assert fas["fft_length"] == 4096  # next power of two >= 2 x 1500 samples


def test_fourier_spectrum_errors(made_record):
    motion = topple.read(made_record)
    with pytest.raises(topple.InputError):
        topple.fourier_spectrum(motion, fft_length=10)
    with pytest.raises(topple.InputError, match="smoothing_b"):
        topple.fourier_spectrum(motion, -1.0)


# ---- sweeps ----

def cell_matches(csv_cell, value):
    if csv_cell == "":
        return value is None or (isinstance(value, float) and math.isnan(value))
    if isinstance(value, str):
        return csv_cell == value
    if csv_cell in ("true", "false"):
        return value == (1.0 if csv_cell == "true" else 0.0)
    return float(csv_cell) == value  # the CSV prints the shortest round-trip form: exact


def assert_table_equals_csv(table, path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    assert table.columns == header
    assert table.n_rows == len(rows)
    for j, name in enumerate(header):
        column = table[name]
        if isinstance(column, np.ndarray):
            assert column.dtype == np.float64
            column = column.tolist()
        bad = [i for i, row in enumerate(rows) if not cell_matches(row[j], column[i])]
        assert not bad, f"column {name}: {len(bad)} rows differ, first {bad[0]}: {rows[bad[0]][j]!r} vs {column[bad[0]]!r}"


def test_sweep_pulses_equals_cli_csv(cli, tmp_path):
    sweep_file = ROOT / "examples" / "sweep" / "pulses.toml"
    out = tmp_path / "pulses.csv"
    cli("sweep", sweep_file, "--out", out, "--quiet", "--threads", "2")
    table = topple.sweep(sweep_file, threads=2)
    assert isinstance(table, topple.SweepTable) and table.n_rows == 8832
    assert isinstance(table["motion"], list) and isinstance(table["motion"][0], str)
    assert_table_equals_csv(table, out)


SMALL_SWEEP = """
[motions]
polarity = ["normal", "inverse"]
[[motions.pulse]]
kind = "sine"
amp_g = [0.3, 0.6]
freq_hz = 2.0
[[object]]
model = "slide"
mu = [0.1, 0.2]
[[object]]
model = "rock"
shape = "block"
width = "10cm"
height = "40cm"
"""


def test_small_sweep_equals_cli_csv_and_pandas(cli, tmp_path):
    sweep_file = tmp_path / "small.toml"
    sweep_file.write_text(SMALL_SWEEP)
    out = tmp_path / "small.csv"
    cli("sweep", sweep_file, "--out", out, "--quiet")
    table = topple.sweep(str(sweep_file), threads=1)
    assert table.n_rows == 12
    assert_table_equals_csv(table, out)
    assert np.isnan(table["max_abs_displacement_m"][2])  # the rocking row of the first motion
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pandas"):
            table.to_pandas()
    else:
        df = table.to_pandas()
        assert list(df.columns) == table.columns and len(df) == 12


def test_sweep_writes_nothing_and_bad_file(tmp_path):
    sweep_file = tmp_path / "small.toml"
    sweep_file.write_text(SMALL_SWEEP)
    topple.sweep(sweep_file)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["small.toml"]
    bad = tmp_path / "bad.toml"
    bad.write_text(SMALL_SWEEP.replace('mu = [0.1, 0.2]', 'mu = [0.1, 0.2]\nfrobnicate = 1'))
    with pytest.raises(topple.InputError) as err:
        topple.sweep(bad)
    assert err.value.file is not None and "bad.toml" in err.value.file


# ---- object spectra ----

@pytest.fixture(scope="module")
def motion():
    return topple.synth(pga_g=0.4, freq_hz=2.0, duration_s=8.0, seed=5)


def test_slide_spectrum_keys(motion):
    spec = topple.slide_spectrum(motion, [0.05, 0.1, 0.3], slope_deg=0.0)
    for i, mu in enumerate([0.05, 0.1, 0.3]):
        r = topple.slide(motion, mu=mu, history=False)
        assert spec["max_abs_displacement_m"][i] == r.max_abs_displacement_m
        assert spec["slip_episodes"][i] == r.slip_episodes
        assert spec["yield_accel_g"][i] == pytest.approx(mu, rel=1e-14)  # level ground: k_y = mu
    assert spec["pga_g"] == pytest.approx(motion.pga_g, rel=1e-14)
    assert spec["at_rest_at_end"].dtype == np.bool_


def test_overturning_map_matches_single_runs(motion):
    alpha = math.atan(0.25)
    heights = [0.4, 1.2]
    pga = [0.1, 0.3, 0.6, 0.9]
    omap = topple.overturning_map(motion, alpha_rad=alpha, heights_m=heights, pga_g=pga, threads=2)
    assert omap["overturned"].shape == (2, 4) and omap["overturned"].dtype == np.bool_
    assert omap["uplift_pga_g"] == pytest.approx(0.25)
    assert not omap["overturned"][:, 0].any()  # 0.1 g < g tan(alpha): no uplift
    for s, h in enumerate(heights):
        body = topple.Block(width=h * math.tan(alpha), height=h)
        assert omap["width_m"][s] == pytest.approx(h * math.tan(alpha), rel=1e-14)
        for k, p in enumerate(pga):
            r = topple.rock(motion.scaled_to_pga(p), body, history=False)
            assert omap["overturned"][s, k] == r.overturned
            assert omap["max_rotation_over_alpha"][s, k] == pytest.approx(r.max_rotation_over_alpha, rel=1e-6)
        fell = np.nonzero(omap["overturned"][s])[0]
        first = omap["first_overturn_pga_g"][s]
        assert (math.isnan(first) and len(fell) == 0) or first == pytest.approx(pga[fell[0]], rel=1e-14)
    with pytest.raises(topple.InputError):
        topple.overturning_map(motion, alpha_rad=alpha, heights_m=[0.4], pga_g=[0.1], shape="general")


# ---- fragility ----

def normal_cdf(u):
    return 0.5 * math.erfc(-u / math.sqrt(2))


def log_likelihood(im, n, z, theta, beta):
    total = 0.0
    for x, nj, zj in zip(im, n, z):
        p = normal_cdf(math.log(x / theta) / beta)
        total += zj * math.log(p) + (nj - zj) * math.log1p(-p)
    return total


def test_fragility_fit_is_the_likelihood_maximum():
    im = [0.1, 0.2, 0.3, 0.4, 0.6, 0.8]
    n = [20] * 6
    z = [0, 2, 7, 11, 16, 19]
    fit = topple.fragility_fit(im, n, np.array(z))
    assert fit.log_likelihood == pytest.approx(log_likelihood(im, n, z, fit.theta, fit.beta), rel=1e-9)
    for dt, db in ((1e-3, 0), (-1e-3, 0), (0, 1e-3), (0, -1e-3)):
        assert log_likelihood(im, n, z, fit.theta * (1 + dt), fit.beta + db) < fit.log_likelihood
    assert fit.probability(fit.theta) == pytest.approx(0.5, abs=1e-12)
    p = fit.probability(np.array(im))
    assert p.dtype == np.float64 and np.all(np.diff(p) > 0)
    lower, upper = fit.band(np.array(im))
    assert np.all(lower < p) and np.all(p < upper)
    with pytest.raises(topple.InputError):
        topple.fragility_fit(im, n, [0] * 6)  # no failure: no finite maximum
    with pytest.raises(TypeError):
        topple.fragility_fit(im, [20.0] * 6, z)


def test_fragility_analysis(motion):
    motions = [motion, topple.synth(pga_g=0.4, freq_hz=3.0, duration_s=8.0, seed=6)]
    levels = [0.1, 0.2, 0.4, 0.8, 1.2]
    result = topple.fragility(motions, levels, mu=0.2, threshold_m=0.01,
                              body=topple.Block(width=0.1, height=0.4), threads=2)
    assert result["im"] == "pga" and result["im_unit"] == "g" and result["runs"] == 20
    names = [c["name"] for c in result["curves"]]
    assert names == ["slide", "overturn"]
    for c in result["curves"]:
        np.testing.assert_allclose(c["im"], levels, rtol=1e-15)
        assert list(c["trials"]) == [2] * 5
        assert np.all((0 <= c["failures"]) & (c["failures"] <= 2))
        assert c["fit"] is not None or c["fit_note"]
    # a block with mu = 0.2 never slides below 0.2 g
    assert result["curves"][0]["failures"][0] == 0
    with pytest.raises(topple.InputError):
        topple.fragility(motions, levels)  # neither failure mode
    with pytest.raises(TypeError, match="list"):
        topple.fragility(motion, levels, body=topple.Block(width=0.1, height=0.4))
