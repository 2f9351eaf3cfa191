#pragma once
// Sliding on a flexible support: a body that slides on Coulomb friction while the thing under (or above) the
// sliding surface vibrates in one mode. Two physical pictures share one machinery:
//
//  * SupportOscillator -- an object on a shelf or an upper floor. The support is a single-degree-of-freedom
//    oscillator (mass M_s, frequency f = omega / 2 pi, damping ratio zeta, both of the support alone); the object
//    (mass m_o = r M_s, r the mass ratio) rests on it and slides with friction coefficient mu.
//  * SlidingMassColumn -- SLAMMER's flexible sliding mass (Jibson et al. 2013, USGS TM 12-B1; Rathje & Bray 2000):
//    a uniform soil column of height H and shear-wave velocity V_s on a base of V_b, sliding at its base with yield
//    coefficient k_y. The column deforms in its first shear mode phi(z) = sin(pi z / 2H) (z up from the sliding
//    surface), so that with m the column's mass per unit area,
//       omega = pi V_s / (2H),   L1 = int rho phi dz = 2m / pi,   M1 = int rho phi^2 dz = m / 2   (pySLAMMER Decoupled).
//
// Sign convention (as sliding.hpp and SLAMMER): the ground acceleration a_g > 0 pushes the body in the +s direction;
// s is the sliding displacement of the body relative to what it rests on. One-way mode lets s grow only (downslope).
//
// Decoupled analysis (Makdisi & Seed 1978; SLAMMER "decoupled"). The support's response is computed without the
// body's slip; the body then slides as a rigid block (topple's exact solver, sliding.hpp) on the support's
// acceleration at its sliding surface: for the shelf the support's absolute acceleration a_g + Y'', for the column
// the average acceleration of the sliding mass (SLAMMER's HEA)  HEA = a_g + (L1/m) Y''  with
//    Y'' + 2 zeta omega Y' + omega^2 Y = -(L1/M1) a_g                                         (modal equation)
// (for the shelf L1/M1 = L1/m = 1). The response is exact for piecewise-linear a_g (closed-form step propagator, no
// period error; the demand by that propagator's second-order output recurrence, Cayley-Hamilton); HEA is sampled on the record's grid and read by the sliding solver as piecewise linear: that is the
// decoupled analysis' one approximation, O(dt^2).
//
// Coupled analysis (Chopra & Zhang 1991; Rathje & Bray 2000 as SLAMMER implements it). The slip feeds back:
//   column, stick:   Y'' = -(L1/M1) a_g - 2 zeta omega Y' - omega^2 Y,    demand D = a_g + (L1/m) Y''
//   column, slip s:  (1 - L1^2/(M1 m)) Y'' = -(L1/M1) sigma k_y g - 2 zeta omega Y' - omega^2 Y,
//                    s'' = a_g + (L1/m) Y'' - sigma k_y g                  (sigma = +1 down, -1 up in two-way)
//   shelf,  stick:   Y'' = -a_g - (2 zeta omega Y' + omega^2 Y) / (1 + r),  demand D = a_g + Y''
//   shelf,  slip:    Y'' = -a_g - 2 zeta omega Y' - omega^2 Y - r sigma mu g,   s'' = a_g + Y'' - sigma mu g
// Slip starts when D crosses sigma k_y g and stops when s' returns to 0. Each phase is a linear system driven by a
// piecewise-linear a_g, so the state (Y, Y', s, s', a_g, a_g', 1) is advanced by the exact propagator exp(A h); slip
// start and stop are located inside the step by root finding on the exact state (TOMS 748). Steps are split so that
// omega h <= 0.5 (at most 256 sub-steps per record step), and each sub-step is also tested at its midpoint, so that an excursion of the demand above k_y g
// lasting longer than h/2 is never missed. After the record the ground is still and a sliding body runs out to rest.
//
// Vertical input (coupled; the decoupled analysis passes it to sliding.hpp, where it does the same). The support is
// flexible horizontally only, so a_v(t) (positive up) reaches the body unfiltered and its normal force is
// m (g + a_v): the capacity sigma k_y g (sigma mu g for the shelf) above becomes sigma k_y (g + a_v) in the body's
// equation and, for the shelf, in the friction force r sigma mu (g + a_v) on the support -- the effective gravity
// g_e = g + a_v of the rigid block (sliding.hpp, after Newmark 1965), carried into Chopra & Zhang's equations; this
// extension is topple's (SLAMMER has no vertical input). The column's own vertical dynamics are not modelled. a_v is read at the
// sub-step ends and linear between them (exact when the vertical record's samples lie on that grid); a_v and a_v'
// join the state, which the propagator advances exactly. g + a_v <= 0 (the body lifts off) is reported as
// contact_lost_time_s, as sliding.hpp does; the model is not valid after it.
//
// Equivalent linear (SLAMMER; formulas from pySLAMMER 0.2.3 decoupled_analysis.py and its SoftwareX paper,
// Arnold & Garcia-Rivas 2025): iterate the linear response of the column, with
//   effective strain  gamma = 0.65 * (pi/2) * max|Y| / H,   G/Gmax = 1 / (1 + gamma/gamma_r)  (hyperbolic),
//   damping D = 0.62 (G/Gmax)^0.1 D_Masing + 0.01  (Darendeli 2001 form), D_Masing from the hyperbola,
//   V_s = V_s0 sqrt(G/Gmax), and the base impedance damping zeta_imp = min(0.55016 (V_b/V_s)^-0.9904, 0.2)
// until G and D each change by less than 5 % (at most 100 iterations, else EquivalentLinearError). The total damping of the
// mode is D + zeta_imp (linear elastic: the given damping + zeta_imp).
#include <cstdint>
#include <optional>
#include <vector>

#include "topple/core/error.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/units.hpp"

namespace topple {

/// A shelf or floor carrying the object: one-mode oscillator. Use make() to validate.
struct SupportOscillator {
  double freq_hz = 0.0;        ///< natural frequency of the support alone (Hz, shelves 5-20, floors 2-10)
  double damping_ratio = 0.0;  ///< viscous damping ratio of the support (typical 0.02-0.05), 0 <= zeta < 1
  double mass_ratio = 0.0;     ///< object mass / support mass (0 = the object does not load the support)

  /// The highest natural frequency a support may have, Hz. Shelves are 5-20 Hz, floors 2-10 Hz, and seismic
  /// qualification treats equipment above 33 Hz as rigid (its zero-period acceleration is the floor's); 1e4 Hz is
  /// beyond the Nyquist frequency of any accelerograph (50 Hz to a few kHz sampling), so a support above it moves with
  /// the ground to within (f_ground / f)^2 ~ 1e-6. It also bounds the sub-steps of the coupled analysis (omega h <= 0.5)
  /// and keeps omega^2 far from overflow (from about 2e154 Hz the propagator's scaling and squaring never ended).
  static constexpr double kMaxFreqHz = 1e4;

  /// Throws InputError (quoting the value) for non-finite values, freq <= 0 or > kMaxFreqHz, damping outside [0, 1),
  /// ratio < 0.
  [[nodiscard]] static SupportOscillator make(double freq_hz, double damping_ratio, double mass_ratio = 0.0);
};

/// SLAMMER's flexible sliding mass. Use make() to validate.
struct SlidingMassColumn {
  double height_m = 0.0;          ///< column height H (m, typical 5-100)
  double vs_slope_m_s = 0.0;      ///< shear-wave velocity of the sliding mass V_s (m/s, typical 200-800)
  double vs_base_m_s = 0.0;       ///< shear-wave velocity below the sliding surface V_b (m/s)
  double damping_ratio = 0.0;     ///< material damping ratio (decimal); the mode's total adds the impedance damping
  /// Equivalent-linear analysis when set: the hyperbola's reference shear strain (decimal: 0.0005 is 0.05 %).
  std::optional<double> reference_strain;

  /// Throws InputError for non-finite values, H, V_s, V_b <= 0, a first mode V_s / 4H above
  /// SupportOscillator::kMaxFreqHz, a reference strain <= 0, or a total damping (material + impedance) outside [0, 1). A negative material damping is accepted as long as the total is not:
  /// SLAMMER's published suite enters -5 % to get 15 % in all with its 20 % impedance damping.
  [[nodiscard]] static SlidingMassColumn make(double height_m, double vs_slope_m_s, double vs_base_m_s,
                                              double damping_ratio,
                                              std::optional<double> reference_strain = std::nullopt);

  /// Base impedance damping zeta_imp = min(0.55016 (V_b/V_s)^-0.9904, 0.2) (SLAMMER, via pySLAMMER).
  [[nodiscard]] static double impedance_damping(double vs_base_m_s, double vs_slope_m_s) noexcept;
};

enum class FlexibleAnalysis : std::uint8_t { decoupled, coupled };

/// The equivalent-linear iteration did not settle (G and D within 5 %) in its 100 iterations (exit 3). The coupled
/// solver's limits throw the common kinds of error.hpp: EventLimitError (64 slip events in one sub-step),
/// RootFindingError (an event not located in 200 TOMS 748 iterations), StepLimitError (still sliding 10^7 sub-steps
/// after the record).
class EquivalentLinearError : public SolverError {
 public:
  using SolverError::SolverError;
};

/// The mode the body slides on, after any equivalent-linear iteration.
struct ModalProperties {
  double omega_rad_s = 0.0;       ///< circular frequency of the mode
  double damping_ratio = 0.0;     ///< total damping ratio of the mode
  double participation = 1.0;     ///< L1/M1: the base acceleration's load on the mode (column 4/pi, shelf 1)
  double mass_fraction = 1.0;     ///< L1/m: share of Y'' in the demand (column 2/pi, shelf 1)
  double vs_m_s = 0.0;            ///< final shear-wave velocity (column only; 0 for a shelf)
  int iterations = 0;             ///< equivalent-linear iterations (0 for linear)
};

struct FlexibleSummary {
  SlidingSummary sliding;          ///< displacement of the body relative to the surface it slides on
  ModalProperties mode;            ///< the mode used (final equivalent-linear properties)
  double kmax = 0.0;               ///< peak |support acceleration| / g of the decoupled response (SLAMMER's k_max),
                                   ///< read at points omega h <= 0.1 apart (the record's samples when they are closer)
};

/// The response as a time history (`topple slide --out/--plot` on a flexible support).
struct FlexibleHistory {
  /// The body relative to the surface it slides on. Decoupled: the rigid solver's history on the support's motion
  /// (its sub-stepped grid plus every slip event); coupled: the start, every sub-step end (omega h <= 0.5) and every
  /// slip event, through the run-out.
  SlidingHistory sliding;
  /// Absolute acceleration of the sliding surface at those times (m/s^2): shelf a_g + Y'', column a_g + (L1/m) Y''.
  std::vector<double> support_accel_m_s2;
};

struct FlexibleResult {
  FlexibleSummary summary;   ///< the same numbers slide_flexible gives
  FlexibleHistory history;
};

/// Support (or sliding-mass average) acceleration of the decoupled response on the record's samples (m/s^2):
/// a_g + (L1/m) Y'' with Y exact for piecewise-linear a_g, starting at rest. The record must be uniformly sampled.
[[nodiscard]] std::vector<double> support_acceleration_m_s2(const GroundMotion& ground, const ModalProperties& mode);

/// The motion a shelf or floor passes to what rests on it (decoupled: its absolute acceleration), as a record on the
/// record's step split so that omega h <= 0.1 (the grid the decoupled analysis slides on). Any solver that takes a
/// GroundMotion (rocking, sliding, spectra) can run on it: this is the support filter a survey or sweep applies to
/// an object's motion. The record must be uniformly sampled; metadata is kept.
[[nodiscard]] GroundMotion support_motion(const GroundMotion& ground, const SupportOscillator& support);

/// The largest ratio of a support's peak absolute acceleration to the ground's peak, over every ground motion: the
/// L1 norm of the support's absolute-acceleration impulse response h (a bound reached by a motion of unit amplitude
/// with the sign of h reversed in time). It depends on the damping ratio alone (0 < zeta < 1); in closed form, with
/// omega_d = sqrt(1 - zeta^2), the zeros t_k of h spaced pi / omega_d and int h between zeros the change of the
/// relative velocity: |1 + Y'(t_1)| + |Y'(t_1)| (1 + q) / (1 - q), q = exp(-zeta pi / omega_d) (per unit impulse,
/// omega = 1). zeta = 0.05: 12.80. Infinite for zeta = 0. Used for the static bounds of objects on flexible supports.
[[nodiscard]] double max_peak_amplification(double damping_ratio) noexcept;

/// Modal properties of a shelf (for `mode`-level calls and tests).
[[nodiscard]] ModalProperties modal_properties(const SupportOscillator& support);

/// Modal properties of a column: the linear ones, or the converged equivalent-linear ones for this record
/// (EquivalentLinearError if the iteration has not converged in 100 iterations).
[[nodiscard]] ModalProperties modal_properties(const SlidingMassColumn& column, const GroundMotion& ground);

/// Object on a shelf or floor. `block` gives mu: the decoupled analysis takes any block of sliding.hpp (static and
/// kinetic friction, slope); the coupled one models level ground and one friction level (slope 0, mu_kinetic =
/// mu_static, else InputError). `vertical` (optional, positive up) reaches the body unfiltered (the support is
/// flexible horizontally only) and changes its normal force to m (g + a_v), in both analyses (header: "Vertical").
[[nodiscard]] FlexibleSummary slide_flexible(const GroundMotion& ground, const SupportOscillator& support,
                                             const SlidingBlock& block, FlexibleAnalysis analysis,
                                             const GroundMotion* vertical = nullptr);

/// SLAMMER's flexible sliding mass with yield coefficient k_y (> 0), one-way (SLAMMER) or two-way; `vertical` as
/// above (capacity k_y (g + a_v); SLAMMER has no vertical input).
[[nodiscard]] FlexibleSummary slide_flexible(const GroundMotion& ground, const SlidingMassColumn& column,
                                             double ky_g, FlexibleAnalysis analysis,
                                             SlidingMode mode = SlidingMode::one_way,
                                             double g_m_s2 = kStandardGravity, const GroundMotion* vertical = nullptr);

/// slide_flexible with the time history (same arguments, same summary).
[[nodiscard]] FlexibleResult slide_flexible_history(const GroundMotion& ground, const SupportOscillator& support,
                                                    const SlidingBlock& block, FlexibleAnalysis analysis,
                                                    const GroundMotion* vertical = nullptr);
[[nodiscard]] FlexibleResult slide_flexible_history(const GroundMotion& ground, const SlidingMassColumn& column,
                                                    double ky_g, FlexibleAnalysis analysis,
                                                    SlidingMode mode = SlidingMode::one_way,
                                                    double g_m_s2 = kStandardGravity,
                                                    const GroundMotion* vertical = nullptr);

}  // namespace topple
