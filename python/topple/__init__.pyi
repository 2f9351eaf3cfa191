"""Type stubs and documentation of the topple package (implemented by the C++ extension topple._core).

Units are SI; every name carries its unit. Lengths are plain floats in metres. Accelerations given "in g" use
g = 9.80665 m/s^2 unless a ``g`` argument says otherwise.
"""
import os
from typing import Any, Literal, Optional, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str
STANDARD_GRAVITY: float  # 9.80665 m/s^2

ArrayIn = Union[npt.NDArray[np.float64], Sequence[float]]

class InputError(ValueError):
    """Bad caller input (file, parameter, array value). str() is the message the CLI prints after 'topple: error: '."""
    file: Optional[str]   # path as given, when the problem is in a file
    line: Optional[int]   # 1-based line in that file
    field: Optional[str]  # parameter, key or column name ("mu", "dt_s", "NPTS", "width")
    problem: str          # the message without its location

class GroundMotion:
    """One component of ground acceleration, piecewise linear between samples.

    GroundMotion(accel, dt, units="g", *, time=None, start_time_s=0.0, g=9.80665)

    accel: 1-D numpy float64 array (TypeError for another dtype: convert explicitly; a strided array is copied) or a
    list of numbers, in `units` ("g", "m/s2", "cm/s2", "gal", "mm/s2"). dt: sample interval, s, for uniform samples;
    or time: the sample times, s (non-decreasing) for irregular ones. NaN/Inf values, dt <= 0, decreasing times:
    InputError.
    """
    def __init__(self, accel: ArrayIn, dt: Optional[float] = None, units: str = "g", *,
                 time: Optional[ArrayIn] = None, start_time_s: float = 0.0, g: float = 9.80665) -> None: ...
    def __len__(self) -> int: ...
    @property
    def npts(self) -> int: ...
    @property
    def is_uniform(self) -> bool: ...
    @property
    def dt_s(self) -> float:
        """Sample interval, s (mean interval of an irregular record)."""
    @property
    def start_time_s(self) -> float: ...
    @property
    def end_time_s(self) -> float: ...
    @property
    def duration_s(self) -> float: ...
    @property
    def accel_m_s2(self) -> npt.NDArray[np.float64]:
        """Acceleration, m/s^2: a read-only view on the C++ data (no copy), valid as long as it is referenced."""
    @property
    def accel_g(self) -> npt.NDArray[np.float64]:
        """Acceleration in the motion's own g (g_m_s2: the g it was built or read with), a new array."""
    @property
    def time_s(self) -> npt.NDArray[np.float64]:
        """Sample times, s (a new array; materialised for uniform records)."""
    @property
    def pga_m_s2(self) -> float: ...
    @property
    def pga_g(self) -> float:
        """Peak |a| in the motion's own g (g_m_s2)."""
    @property
    def g_m_s2(self) -> float:
        """The g (m/s^2) the motion was built or read with (GroundMotion(..., g=), read(..., g=)); accel_g and pga_g
        are in it. Operations (scaled, inverted, ...) keep it."""
    @property
    def pga_time_s(self) -> float: ...
    @property
    def metadata(self) -> dict[str, str]:
        """format, source_file, event, station, component, units_as_read."""
    @property
    def name(self) -> str:
        """The source file as given, else the event description (synthetic and pulse motions)."""
    def accel_at(self, t_s: float) -> float: ...
    def scaled(self, factor: float) -> GroundMotion: ...
    def scaled_to_pga(self, pga_g: float, g: float | None = None) -> GroundMotion:
        """Scaled so that the PGA is pga_g, in g (default: the motion's own g_m_s2)."""
    def inverted(self) -> GroundMotion: ...
    def time_scaled(self, factor: float) -> GroundMotion: ...
    def trimmed(self, t_begin_s: float, t_end_s: float) -> GroundMotion: ...
    def resampled(self, dt_s: float) -> GroundMotion: ...
    def baseline_corrected(self, order: int) -> GroundMotion: ...

def read(path: str, format: Optional[str] = None, units: Optional[str] = None, dt: Optional[float] = None,
         channel: Optional[int] = None, g: float = 9.80665) -> GroundMotion:
    """Read a record (PEER .AT2, COSMOS V2, CSMIP V2, USGS SMC, K-NET, ESM, plain text; detected from content).
    format: "auto" or one of "peer-at2", "cosmos-v2", "csmip-v2", "knet", "usgs-smc", "esm", "plain"; units: unit of a
    plain file's values; dt: time step of a one-column plain file, s; channel: 1-based, multi-channel files."""

class SlidingResult:
    """Sliding response. Summary attributes have the names and units of `topple slide --json`; json() is that
    object (with its "input"). Histories (time_s, displacement_m, velocity_m_s: read-only views; state: -1 slipping
    up-slope/negative, 0 stuck, 1 slipping down-slope/positive) are empty when run with history=False."""
    max_abs_displacement_m: float
    max_displacement_time_s: float
    residual_displacement_m: float
    max_abs_velocity_m_s: float
    slip_episodes: int
    first_slip_time_s: Optional[float]
    total_slip_duration_s: float
    end_time_s: float
    at_rest_at_end: bool
    contact_lost_time_s: Optional[float]
    yield_down_g: float
    yield_up_g: Optional[float]  # None in one-way mode
    mu_static: float
    mu_kinetic: float
    slope_deg: float
    mode: str
    g_m_s2: float
    time_s: npt.NDArray[np.float64]
    displacement_m: npt.NDArray[np.float64]
    velocity_m_s: npt.NDArray[np.float64]
    state: npt.NDArray[np.int8]
    def json(self) -> dict[str, Any]: ...

def slide(motion: GroundMotion, *, mu: float, mu_kinetic: Optional[float] = None,
          mode: Literal["two-way", "one-way"] = "two-way", slope_deg: float = 0.0,
          vertical: Optional[GroundMotion] = None, g: float = 9.80665, history: bool = True) -> SlidingResult:
    """Exact sliding of a rigid block with Coulomb friction (mu static, mu_kinetic <= mu, default = mu) on a plane
    inclined at slope_deg; one-way: down-slope slip only (SLAMMER rigid block). vertical: vertical acceleration,
    positive up. history=False takes the summary-only fast path."""

def slide_flexible(motion: GroundMotion, *, mu: float, mode: Literal["two-way", "one-way"] = "two-way",
                   support_freq_hz: Optional[float] = None, support_damping: float = 0.05, mass_ratio: float = 0.0,
                   height_m: Optional[float] = None, vs_slope_m_s: Optional[float] = None,
                   vs_base_m_s: Optional[float] = None, damping: Optional[float] = None,
                   reference_strain: Optional[float] = None, coupled: bool = False,
                   vertical: Optional[GroundMotion] = None, g: float = 9.80665) -> dict[str, Any]:
    """Sliding on a flexible support (topple/flexible.hpp), decoupled or coupled. Either an object (friction mu) on a
    shelf or floor: support_freq_hz (Hz, the support alone), support_damping (ratio), mass_ratio (object / support
    mass); or SLAMMER's flexible sliding mass (mu is k_y): height_m, vs_slope_m_s, vs_base_m_s (m/s), damping
    (material damping ratio; the mode adds the base impedance damping), reference_strain (decimal: equivalent
    linear when given). vertical: both analyses (coupled: normal force m (g + a_v)). Returns the dict of `topple slide --support-freq|--height --json`:
    the sliding summary fields and "support" (mode_freq_hz, mode_damping_ratio, kmax, vs_final_m_s ...)."""

def slide_spectrum(motion: GroundMotion, mu: ArrayIn, *, slope_deg: float = 0.0,
                   mode: Literal["two-way", "one-way"] = "two-way", g: float = 9.80665) -> dict[str, Any]:
    """Sliding displacement spectrum (topple/object_spectra.hpp) of blocks with mu static = kinetic on a plane at
    slope_deg. Arrays, one value per mu in the given order: mu, max_abs_displacement_m (m),
    residual_displacement_m (m, signed), yield_accel_g (downslope yield k_y = tan(atan(mu) - slope), g),
    yield_over_pga (k_y g / PGA), slip_episodes (int64), total_slip_duration_s (s), at_rest_at_end (bool); scalars
    pga_g, slope_deg, mode, g_m_s2. mu < 0, NaN, or atan(mu) + slope >= 90 deg: InputError."""

class RockingBody:
    """A rigid body that rocks (made by Block, Cylinder or General). a_m: CM to pivot edge, m; h_m: CM height, m;
    D_m2: pivot moment of inertia per unit mass, m^2."""
    shape: str
    a_m: float
    h_m: float
    D_m2: float
    alpha_rad: float
    R_m: float
    housner_e: float
    def p_rad_s(self, g: float = 9.80665) -> float: ...

def Block(width: float, height: float) -> RockingBody:
    """Rectangular block of full width and height, m."""
def Cylinder(diameter: float, height: float) -> RockingBody:
    """Solid cylinder standing on its end, diameter and height in m."""
def General(a: float, h: float, D: float) -> RockingBody:
    """Any body: a, h in m, D = I_O/m in m^2 (D >= a^2 + h^2)."""

class RockingResult:
    """Rocking response. Summary attributes have the names and units of `topple rock --json`; json() is that object.
    Histories (time_s, theta_rad, theta_dot_rad_s: read-only views; state: -1 rocking-, 0 rest, 1 rocking+, 2 fallen)
    and events are empty when run with history=False."""
    max_abs_rotation_rad: float
    max_rotation_over_alpha: float
    max_rotation_time_s: float
    max_abs_theta_dot_rad_s: float
    impacts: int
    uplifts: int
    uplift_time_s: Optional[float]
    exceeded_alpha_time_s: Optional[float]
    overturned: bool
    overturn_time_s: Optional[float]
    end_state: str
    end_time_s: float
    still_rocking_at_end: bool
    energy_lost_j_per_kg: float
    alpha_rad: float
    alpha_deg: float
    R_m: float
    p_rad_s: float
    e: float
    e_mode: str
    onset_mode: str
    onset_accel_ratio: Optional[float]
    critical_mu: Optional[float]
    mu: Optional[float]
    g_m_s2: float
    warnings: list[str]
    body: RockingBody
    time_s: npt.NDArray[np.float64]
    theta_rad: npt.NDArray[np.float64]
    theta_dot_rad_s: npt.NDArray[np.float64]
    state: npt.NDArray[np.int8]
    events: list[dict[str, Any]]
    def json(self) -> dict[str, Any]: ...

def rock(motion: GroundMotion, shape: RockingBody, *, e: Union[Literal["housner"], float] = "housner",
         mu: Optional[float] = None, g: float = 9.80665, method: Literal["adaptive", "rk4"] = "adaptive",
         rel_tol: float = 1e-8, rk4_substeps: int = 10, max_run_out_s: float = 60.0,
         vertical: Optional[GroundMotion] = None, history: bool = True) -> RockingResult:
    """Housner rocking and overturning on a level base that does not slide. e: restitution in [0, 1] or "housner";
    mu: check Shenton's slide/rock onset criterion."""

def synth(*, pga_g: float, freq_hz: float, duration_s: float, seed: int = 0, dt_s: float = 0.01,
          model: Literal["clough-penzien", "kanai-tajimi"] = "clough-penzien",
          envelope: Literal["saragoni-hart", "jennings"] = "saragoni-hart", zeta_g: float = 0.3,
          g: float = 9.80665) -> GroundMotion:
    """Synthetic motion (as `topple synth`): the same parameters and seed give the same bits everywhere."""

def intensity(motion: GroundMotion, g: float = 9.80665) -> dict[str, Any]:
    """Intensity measures as `topple info --json` names them: npts, dt_s, duration_s, pga_g, pga_m_s2, pga_time_s,
    pgv_m_s, pgd_m, arias_m_s, d5_95_s, d5_time_s, d95_time_s, cav_m_s, tp_s, tm_s, predominant_frequency_hz, g_m_s2
    (None where undefined)."""

def invert(survey_path: str, *, threads: int = 0) -> dict[str, Any]:
    """`topple invert --json` of a survey file: one site's dict, or {"sites": [...]}. Each site's dict also holds
    posterior_grid and log_likelihood_grid (numpy, rows PGA, columns frequency) for topple.plot.inversion_map."""


# ---- spectra of a motion ----

def response_spectrum(motion: GroundMotion, periods_s: Optional[ArrayIn] = None, damping: float = 0.05, *,
                      g: float = 9.80665) -> dict[str, Any]:
    """Elastic response spectrum of linear oscillators x'' + 2 zeta w x' + w^2 x = -a_g, from rest, by the exact
    Nigam-Jennings recurrence (topple/spectra.hpp; maxima at the samples, over the record only).

    periods_s: oscillator periods, s (> 0; default: the grid of the predominant period Tp, 100 per decade from
    0.02 s to 5 s); damping: ratio zeta in [0, 1). Returns numpy arrays, one value per period: period_s (s), sd_m
    (max |x|, m), psv_m_s (w SD, m/s), psa_m_s2 (w^2 SD, m/s^2), psa_g (PSA / g), sv_m_s (max |x'|, m/s), sa_m_s2
    (max absolute acceleration, m/s^2); scalars damping, g_m_s2, motion (name). The GIL is released."""

def fourier_spectrum(motion: GroundMotion, smoothing_b: Optional[float] = 40.0, *,
                     centre_hz: Optional[ArrayIn] = None, fft_length: Optional[int] = None) -> dict[str, Any]:
    """Fourier amplitude spectrum |A(f)| = dt |DFT| (m/s) and its Konno-Ohmachi smoothing (topple/spectra.hpp).

    fft_length: zero-padded FFT length (>= npts; default: the next power of two >= 2 npts, as for the predominant
    frequency); smoothing_b: Konno-Ohmachi bandwidth b (> 0), None for no smoothing; centre_hz: centre frequencies
    of the smoothing, Hz (default: 200 per decade from 0.1 Hz to min(25 Hz, 0.8 f_Nyquist)). Returns freq_hz (Hz,
    k / (N dt), k = 0 .. N/2), amplitude_m_s (m/s), smoothed_freq_hz and smoothed_amplitude_m_s (None without
    smoothing), dt_s, fft_length, smoothing_b, predominant_frequency_hz (Hz, the library's definition, as
    topple.intensity()["predominant_frequency_hz"]; None when undefined), motion. Irregular records are resampled at
    their smallest interval first. The GIL is released."""

# ---- object spectra and fragility ----

def overturning_map(motion: GroundMotion, *, alpha_rad: float, heights_m: ArrayIn, pga_g: ArrayIn,
                    shape: Literal["block", "cylinder"] = "block", e: Union[Literal["housner"], float] = "housner",
                    mu: Optional[float] = None, g: float = 9.80665, method: Literal["adaptive", "rk4"] = "adaptive",
                    rel_tol: float = 1e-8, rk4_substeps: int = 10, max_run_out_s: float = 60.0,
                    threads: int = 0) -> dict[str, Any]:
    """Overturning map (topple/object_spectra.hpp): bodies of one shape and slenderness alpha_rad = atan(a/h), of
    full heights heights_m (m), under the motion scaled to each PGA of pga_g (g); rocking options as topple.rock.
    Runs on `threads` cores (0: all), GIL released. Returns pga_g (ascending) and pga_m_s2; per size (in the given
    order): height_m, width_m (full width or diameter, m), R_m (m), p_rad_s (rad/s), first_overturn_pga_g (g, NaN
    when no PGA of the grid overturns it), standing_above_first (bool), overturn_count (int64); overturned (bool) and
    max_rotation_over_alpha, 2-D [size, pga]; alpha_rad, uplift_pga_g (= tan(alpha): no uplift below it), shape,
    g_m_s2, motion."""

class FragilityFit:
    """Lognormal fragility P(failure | IM = x) = Phi(ln(x / theta) / beta), maximum-likelihood fit to binomial
    counts (Baker 2015). theta: median, in the unit of the IM levels given; beta: log standard deviation."""
    theta: float
    beta: float
    log_likelihood: float
    se_ln_theta: float        # standard error of ln theta (observed information)
    se_beta: float
    cov_ln_theta_beta: float
    iterations: int
    beta_at_bound: bool       # separated data: beta held at its lower bound 0.01
    @overload
    def probability(self, im: float) -> float: ...
    @overload
    def probability(self, im: ArrayIn) -> npt.NDArray[np.float64]: ...
    def band(self, im: Union[float, ArrayIn], level: float = 0.95) -> tuple[Any, Any]:
        """Delta-method confidence band (lower, upper) of the probability at im, at confidence `level`."""

def fragility_fit(im: ArrayIn, trials: Sequence[int], failures: Sequence[int]) -> FragilityFit:
    """Fit a lognormal fragility to counts: at IM level im[j] (> 0, any unit: theta comes out in it), trials[j]
    runs of which failures[j] failed. No failure, or failures only: InputError."""

def fragility(motions: Sequence[GroundMotion], levels: ArrayIn, *, im: Literal["pga", "pgv", "pgd", "cav"] = "pga",
              mu: Optional[float] = None, threshold_m: Optional[float] = None, mu_kinetic: Optional[float] = None,
              mode: Literal["two-way", "one-way"] = "two-way", slope_deg: float = 0.0,
              body: Optional[RockingBody] = None, e: Union[Literal["housner"], float] = "housner",
              rock_mu: Optional[float] = None, g: float = 9.80665, method: Literal["adaptive", "rk4"] = "adaptive",
              rel_tol: float = 1e-8, rk4_substeps: int = 10, max_run_out_s: float = 60.0,
              threads: int = 0) -> dict[str, Any]:
    """Fragility analysis (topple/fragility.hpp): every motion scaled so that its IM equals each level, run on a
    sliding block (mu, failure when max |d| > threshold_m, m) and/or a rocking body (body, failure = overturning;
    e, rock_mu and solver options as topple.rock). levels are in g for pga, m/s for pgv and cav, m for pgd. Returns
    im, im_unit, runs, g_m_s2 and curves: a list (slide first, then overturn) of dicts name, im (the levels), trials,
    failures (int64), fraction, fit (FragilityFit with theta in im_unit; None when the counts cannot be fitted) and
    fit_note. Runs on `threads` cores (0: all), GIL released."""

# ---- sweeps ----

class SweepTable(dict[str, Any]):
    """The table of a sweep: column name -> float64 numpy array (numbers, booleans as 0/1, NaN where the CSV cell is
    empty) or list of str (text columns, None where empty), in the CSV's column order."""
    @property
    def columns(self) -> list[str]: ...
    @property
    def n_rows(self) -> int: ...
    def to_pandas(self) -> Any:
        """A pandas.DataFrame (needs pandas, not a dependency of topple)."""

def sweep(path: Union[str, "os.PathLike[str]"], threads: int = 0) -> SweepTable:
    """Run a sweep file (docs/sweeps.md) in memory as `topple sweep` does (the same rows as its CSV; [output] is
    ignored) on `threads` cores (0: all), GIL released."""
