"""Type stubs of the topple package (implemented by the C++ extension topple._core and topple/__init__.py).

Units are SI; every name carries its unit. Lengths are plain floats in metres. Accelerations given "in g" use
g = 9.80665 m/s^2 unless a ``g`` argument says otherwise. Each docstring here is the summary line of the runtime
one; the full numpy-style docstrings (parameters with units, returns) are the runtime's: ``help(topple.slide)``.
python/tests/test_docstrings.py keeps the two in step (the same parameters, the same summary).
"""
import os
from typing import Any, Literal, Mapping, Optional, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str
STANDARD_GRAVITY: float  # 9.80665 m/s^2

ArrayIn = Union[npt.NDArray[np.float64], Sequence[float]]

class InputError(ValueError):
    """Bad caller input (file, parameter, array value)."""
    file: Optional[str]   # path as given, when the problem is in a file
    line: Optional[int]   # 1-based line in that file
    field: Optional[str]  # parameter, key or column name ("mu", "dt_s", "NPTS", "width")
    problem: str          # the message without its location

class MissingFileError(InputError, FileNotFoundError):
    """A file that does not exist (or cannot be opened)."""
    filename: str

class GroundMotion:
    """One component of ground acceleration, piecewise linear between samples (SI)."""
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
    def metadata(self) -> dict[str, Any]:
        """format, source_file, event, station, component, azimuth_deg, vertical, units_as_read."""
    @property
    def name(self) -> str:
        """The source file as given, else the event description (synthetic and pulse motions)."""
    def accel_at(self, t_s: float) -> float:
        """Acceleration at a time, by linear interpolation."""
    def scaled(self, factor: float) -> GroundMotion:
        """The motion with every acceleration multiplied by a factor."""
    def scaled_to_pga(self, pga_g: float, g: float | None = None) -> GroundMotion:
        """The motion scaled so that its PGA is `pga_g`."""
    def inverted(self) -> GroundMotion:
        """The motion with its sign reversed (the other polarity)."""
    def time_scaled(self, factor: float) -> GroundMotion:
        """The motion compressed or stretched in time (frequencies multiplied by 1 / factor)."""
    def trimmed(self, t_begin_s: float, t_end_s: float) -> GroundMotion:
        """The part of the motion between two times (interpolated at the ends)."""
    def resampled(self, dt_s: float) -> GroundMotion:
        """The motion resampled at a uniform interval (linear interpolation: exact for this motion)."""
    def baseline_corrected(self, order: int) -> GroundMotion:
        """The motion with a least-squares polynomial baseline removed."""

def read(path: str, format: Optional[str] = None, units: Optional[str] = None, dt: Optional[float] = None,
         channel: Optional[int] = None, g: float = 9.80665,
         columns: Optional[Union[str, Sequence[Union[int, str]]]] = None, separator: str = "auto",
         baseline: str = "none") -> GroundMotion:
    """Read a strong-motion record."""

class _SlidingSummary:
    # Not a runtime class: the fields topple.slide's and topple.slide_2d's results share (the rows their field tables,
    # solvers/summary_fields.hpp, have in common), written once for both.
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
    mu_static: float
    mu_kinetic: float
    g_m_s2: float
    time_s: npt.NDArray[np.float64]

class SlidingResult(_SlidingSummary):
    """Sliding response of a rigid block (the result of topple.slide)."""
    yield_down_g: float
    yield_up_g: Optional[float]  # None in one-way mode
    slope_deg: float
    mode: str
    displacement_m: npt.NDArray[np.float64]
    velocity_m_s: npt.NDArray[np.float64]
    state: npt.NDArray[np.int8]
    def json(self) -> dict[str, Any]:
        """The summary as `topple slide --json` writes it."""

def slide(motion: GroundMotion, *, mu: float, mu_kinetic: Optional[float] = None,
          mode: Literal["two-way", "one-way"] = "two-way", slope_deg: float = 0.0,
          vertical: Optional[GroundMotion] = None, g: float = 9.80665, history: bool = True) -> SlidingResult:
    """Exact sliding of a rigid block with Coulomb friction on a level or inclined plane."""

class Sliding2dResult(_SlidingSummary):
    """Bidirectional sliding response of a rigid block (the result of topple.slide_2d)."""
    residual_azimuth_deg: Optional[float]  # None when the block never moved
    residual_east_m: float
    residual_north_m: float
    path_length_m: float
    input_work_J_kg: float
    friction_work_J_kg: float
    integrator_steps: int
    east_m: npt.NDArray[np.float64]
    north_m: npt.NDArray[np.float64]
    east_m_s: npt.NDArray[np.float64]
    north_m_s: npt.NDArray[np.float64]
    slipping: npt.NDArray[np.uint8]
    def json(self) -> dict[str, Any]:
        """The summary as `topple slide --h2 --json` writes it."""

def slide_2d(first: GroundMotion, second: GroundMotion, *, mu: float, mu_kinetic: Optional[float] = None,
             azimuths_deg: Sequence[float] = (90.0, 0.0), slope_deg: float = 0.0,
             slope_azimuth_deg: Optional[float] = None, vertical: Optional[GroundMotion] = None, g: float = 9.80665,
             history: bool = False) -> Sliding2dResult:
    """Bidirectional sliding of a rigid block with isotropic Coulomb friction on level or inclined ground."""

def slide_flexible(motion: GroundMotion, *, mu: float, mode: Literal["two-way", "one-way"] = "two-way",
                   support_freq_hz: Optional[float] = None, support_damping: float = 0.05, mass_ratio: float = 0.0,
                   height_m: Optional[float] = None, vs_slope_m_s: Optional[float] = None,
                   vs_base_m_s: Optional[float] = None, damping: Optional[float] = None,
                   reference_strain: Optional[float] = None, coupled: bool = False,
                   vertical: Optional[GroundMotion] = None, g: float = 9.80665) -> dict[str, Any]:
    """Sliding on a flexible support (topple/solvers/flexible.hpp), decoupled or coupled."""

def slide_spectrum(motion: GroundMotion, mu: ArrayIn, *, slope_deg: float = 0.0,
                   mode: Literal["two-way", "one-way"] = "two-way", g: float = 9.80665) -> dict[str, Any]:
    """Sliding displacement spectrum: one block per friction coefficient (topple/fragility/object_spectra.hpp)."""

def slide_spectrum_2d(first: GroundMotion, second: GroundMotion, mu: ArrayIn, *,
                      azimuths_deg: Sequence[float] = (90.0, 0.0), vertical: Optional[GroundMotion] = None,
                      g: float = 9.80665) -> dict[str, Any]:
    """Bidirectional sliding spectrum: one 2-D block per friction coefficient under a pair (topple/fragility/object_spectra.hpp)."""

class RockingBody:
    """A rigid body that rocks about its base edges (made by Block, Cylinder or General)."""
    shape: str
    a_m: float
    h_m: float
    D_m2: float
    alpha_rad: float
    R_m: float
    housner_e: float
    symmetric: bool
    b1_m: float
    b2_m: float
    D1_m2: float
    D2_m2: float
    def p_rad_s(self, g: float = 9.80665) -> float:
        """Frequency parameter p = sqrt(g R / D) of the body."""

def Block(width: float, height: float) -> RockingBody:
    """A rectangular block standing on its base."""
def Cylinder(diameter: float, height: float) -> RockingBody:
    """A solid cylinder standing on its end."""
def General(a: float, h: float, D: float) -> RockingBody:
    """Any rigid body, by its geometry about a pivot."""
def GeneralAsymmetric(b1: float, b2: float, h: float, inertia: float) -> RockingBody:
    """An asymmetric rigid body: CM to the pivot O- (b1) and O+ (b2), CM height h (m), inertia = I_cm / m (m^2)."""

class RockingResult:
    """Rocking response of a rigid body (the result of topple.rock)."""
    max_abs_rotation_rad: float
    max_rotation_over_alpha: float
    max_rotation_positive_rad: float
    max_rotation_negative_rad: float
    max_rotation_over_alpha_positive: float
    max_rotation_over_alpha_negative: float
    overturned_side: int
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
    def json(self) -> dict[str, Any]:
        """The summary as `topple rock --json` writes it."""

def rock(motion: GroundMotion, shape: RockingBody, *, e: Union[Literal["housner"], float] = "housner",
         mu: Optional[float] = None, g: float = 9.80665, method: Literal["adaptive", "rk4"] = "adaptive",
         rel_tol: float = 1e-8, rk4_substeps: int = 10, max_run_out_s: float = 60.0,
         vertical: Optional[GroundMotion] = None, history: bool = True) -> RockingResult:
    """Housner rocking and overturning of a rigid body on a level base that does not slide."""

class SlideRockResult:
    """Coupled sliding and rocking of a rigid body with friction (the result of topple.slide_rock)."""
    overturned: bool
    overturned_side: Optional[Literal["positive", "negative"]]
    overturn_time_s: Optional[float]
    max_rotation_over_alpha: float
    max_rotation_positive_rad: float
    max_rotation_negative_rad: float
    max_rotation_over_alpha_positive: float
    max_rotation_over_alpha_negative: float
    exceeded_alpha_time_s: Optional[float]
    residual_slide_m: float
    max_abs_slide_m: float
    slip_episodes: int
    impacts: int
    uplifts: int
    tangential_impacts: int
    painleve_holds: int
    max_tangential_impulse_ratio: float
    onset_mode: str
    end_mode: str
    end_time_s: float
    moving_at_end: bool
    friction_energy_j_per_kg: float
    impact_energy_j_per_kg: float
    alpha_positive_deg: float
    alpha_negative_deg: float
    mu_static: float
    mu_kinetic: float
    e_mode: str
    used_sliding_kernel: bool
    g_m_s2: float
    warnings: list[str]
    modes: dict[str, dict[str, Any]]
    body: RockingBody
    time_s: npt.NDArray[np.float64]
    slide_m: npt.NDArray[np.float64]
    slide_velocity_m_s: npt.NDArray[np.float64]
    theta_rad: npt.NDArray[np.float64]
    theta_dot_rad_s: npt.NDArray[np.float64]
    cm_height_m: npt.NDArray[np.float64]
    mode: npt.NDArray[np.int8]
    transitions: list[dict[str, Any]]
    def json(self) -> dict[str, Any]:
        """The summary as `topple rock --model coupled --json` writes it."""

def slide_rock(motion: GroundMotion, body: RockingBody, mu: float, mu_k: Optional[float] = None, *,
               vertical: Optional[GroundMotion] = None, e: Union[Literal["housner"], float] = "housner",
               g: float = 9.80665, rel_tol: float = 1e-8, max_run_out_s: float = 60.0, slope_deg: float = 0.0,
               history: bool = True) -> SlideRockResult:
    """Coupled sliding and rocking of a rigid body with Coulomb friction on a level or inclined base (slide_rock.hpp)."""

def rock3d(first: GroundMotion, second: Optional[GroundMotion] = None, *, width_m: Optional[float] = None,
           depth_m: Optional[float] = None, height_m: float, diameter_m: Optional[float] = None,
           azimuths_deg: Sequence[float] = (90.0, 0.0), bearing_deg: Optional[float] = None,
           vertical: Optional[GroundMotion] = None, e: Union[Literal["housner"], float] = "housner",
           g: float = 9.80665, rel_tol: float = 1e-8, simultaneous_contact: Optional[float] = None,
           max_run_out_s: float = 60.0, history: bool = False, mu: Optional[float] = None,
           mu_k: Optional[float] = None, base_incline_deg: float = 0.0,
           base_incline_azimuth_deg: float = 0.0) -> dict[str, Any]:
    """A box or a solid cylinder rocking in three dimensions, as `topple rock --model 3d --json`."""

def rock_oriented(first: GroundMotion, second: GroundMotion, shape: RockingBody, *,
                  azimuths_deg: Sequence[float] = (90.0, 0.0), bearing_deg: Optional[float] = None,
                  depth_m: Optional[float] = None, direction_step_deg: Optional[float] = None,
                  vertical: Optional[GroundMotion] = None, e: Union[Literal["housner"], float] = "housner",
                  mu: Optional[float] = None, g: float = 9.80665, method: Literal["adaptive", "rk4"] = "adaptive",
                  rel_tol: float = 1e-8, rk4_substeps: int = 10, max_run_out_s: float = 60.0) -> dict[str, Any]:
    """Rocking of an oriented object under two horizontal components (and the vertical), as `topple rock --h2`."""

def synth(*, pga_g: float, freq_hz: float, duration_s: float, seed: int = 0, dt_s: float = 0.01,
          model: Literal["clough-penzien", "kanai-tajimi"] = "clough-penzien",
          envelope: Literal["saragoni-hart", "jennings"] = "saragoni-hart", zeta_g: float = 0.3,
          g: float = 9.80665, components: Literal[1, 2, 3] = 1, coherence: Optional[float] = None,
          azimuths_deg: Optional[Sequence[float]] = None, vh_ratio: Optional[float] = None,
          vh_freq_ratio: Optional[float] = None) -> Union[GroundMotion, MotionSet]:
    """A synthetic ground motion, as `topple synth`: the same parameters and seed give the same bits everywhere.

    components=1 (default) returns a GroundMotion; components=2 or 3 a MotionSet (pga_g is its RotD50 PGA)."""

class MotionSet:
    """One station's ground motion in up to three components on one time grid (motion_set.hpp)."""
    def __init__(self, first: GroundMotion, second: Optional[GroundMotion] = None, *,
                 vertical: Optional[GroundMotion] = None, azimuths_deg: Optional[Sequence[float]] = None) -> None: ...
    def __len__(self) -> int: ...
    npts: int
    first: GroundMotion
    second: Optional[GroundMotion]
    vertical: Optional[GroundMotion]
    azimuths_deg: Optional[tuple[float, float]]
    def projected(self, azimuth_deg: float) -> GroundMotion:
        """The horizontal acceleration projected on a direction: a1 cos(az - az1) + a2 cos(az - az2)."""
    def rotated(self, azimuth_deg: float) -> tuple[GroundMotion, GroundMotion]:
        """The horizontal pair rotated to azimuth_deg and azimuth_deg + 90 (clockwise)."""
    def rotd(self, periods_s: Optional[ArrayIn] = None, damping: float = 0.05, *,
             g: float = 9.80665) -> dict[str, Any]:
        """RotD50 and RotD100 of the PGA and of the PSA of the horizontal pair (Boore 2010)."""

def rotd(first: GroundMotion, second: GroundMotion, *, azimuths_deg: Optional[Sequence[float]] = None,
         periods_s: Optional[ArrayIn] = None, damping: float = 0.05, g: float = 9.80665) -> dict[str, Any]:
    """RotD50 and RotD100 of the PGA and of the 5 %-damped PSA of two horizontal components (Boore 2010)."""

def intensity(motion: GroundMotion, g: float = 9.80665) -> dict[str, Any]:
    """Intensity measures of a motion, as `topple info --json` names them."""

def invert(survey: Union[str, "os.PathLike[str]", Mapping[str, Any]], *, threads: int = 0,
           report_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
           base_dir: Optional[Union[str, "os.PathLike[str]"]] = None) -> dict[str, Any]:
    """Estimate the PGA (g) and predominant frequency (Hz) of the shaking from a survey, as ``topple invert --json``."""

def invert_region(survey: Union[str, "os.PathLike[str]", Mapping[str, Any]], *, threads: int = 0,
                  base_dir: Optional[Union[str, "os.PathLike[str]"]] = None) -> dict[str, Any]:
    """The regional joint inversion of a multi-site survey: the attenuation relation and every site pooled through it."""

def survey_toml(survey: Mapping[str, Any]) -> str:
    """The TOML text of a survey built in Python (the structure of a survey file, docs/survey.md)."""


# ---- spectra of a motion ----

def response_spectrum(motion: GroundMotion, periods_s: Optional[ArrayIn] = None, damping: float = 0.05, *,
                      g: float = 9.80665) -> dict[str, Any]:
    """Elastic response spectrum of linear oscillators, by the exact Nigam-Jennings recurrence."""

def fourier_spectrum(motion: GroundMotion, smoothing_b: Optional[float] = 40.0, *,
                     centre_hz: Optional[ArrayIn] = None, fft_length: Optional[int] = None) -> dict[str, Any]:
    """Fourier amplitude spectrum |A(f)| = dt |DFT| and its Konno-Ohmachi smoothing."""

# ---- object spectra and fragility ----

def overturning_map(motion: GroundMotion, *, alpha_rad: float, heights_m: ArrayIn, pga_g: ArrayIn,
                    shape: Literal["block", "cylinder"] = "block", e: Union[Literal["housner"], float] = "housner",
                    mu: Optional[float] = None, g: float = 9.80665, method: Literal["adaptive", "rk4"] = "adaptive",
                    rel_tol: float = 1e-8, rk4_substeps: int = 10, max_run_out_s: float = 60.0,
                    threads: int = 0) -> dict[str, Any]:
    """Overturning map: which bodies of one slenderness overturn at which PGA (topple/fragility/object_spectra.hpp)."""

class FragilityFit:
    """Lognormal fragility P(failure | IM = x) = Phi(ln(x / theta) / beta)."""
    theta: float
    beta: float
    log_likelihood: float
    se_ln_theta: float        # standard error of ln theta (observed information)
    se_beta: float
    cov_ln_theta_beta: float
    iterations: int
    beta_at_bound: bool       # separated data: beta held at its lower bound 0.01
    @overload
    def probability(self, im: float) -> float:
        """Probability of failure at an intensity."""
    @overload
    def probability(self, im: ArrayIn) -> npt.NDArray[np.float64]: ...
    def band(self, im: Union[float, ArrayIn], level: float = 0.95) -> tuple[Any, Any]:
        """Delta-method confidence band of the probability."""

def fragility_fit(im: ArrayIn, trials: Sequence[int], failures: Sequence[int]) -> FragilityFit:
    """Fit a lognormal fragility to counts of failures."""

def fragility(motions: Union[Sequence[GroundMotion], Sequence[MotionSet]], levels: ArrayIn, *, im: Literal["pga", "pgv", "pgd", "cav"] = "pga",
              mu: Optional[float] = None, threshold_m: Optional[float] = None, mu_kinetic: Optional[float] = None,
              mode: Literal["two-way", "one-way"] = "two-way", slope_deg: float = 0.0,
              body: Optional[RockingBody] = None, e: Union[Literal["housner"], float] = "housner",
              rock_mu: Optional[float] = None, g: float = 9.80665, method: Literal["adaptive", "rk4"] = "adaptive",
              rel_tol: float = 1e-8, rk4_substeps: int = 10, max_run_out_s: float = 60.0,
              threads: int = 0, bearing_deg: Optional[float] = None,
              bearing_seed: Optional[int] = None) -> dict[str, Any]:
    """Fragility analysis: failure counts over scaled motions and their lognormal fits (topple/fragility/fragility.hpp)."""

# ---- sweeps ----

class SweepTable(dict[str, Any]):
    """The table of a sweep (the result of topple.sweep): column name -> values, in the CSV's column order."""
    @property
    def columns(self) -> list[str]: ...
    @property
    def n_rows(self) -> int: ...
    def to_pandas(self) -> Any:
        """The table as a pandas DataFrame (pandas is not a dependency of topple)."""

def sweep(path: Union[str, "os.PathLike[str]"], threads: int = 0) -> SweepTable:
    """Run a sweep file (TOML, docs/sweeps.md) in memory, as ``topple sweep`` does, and return its table."""
