#pragma once
// GroundMotion: one component of ground acceleration as a function of time.
//
// Model. The acceleration is piecewise linear between its samples (the assumption of the thesis' programs, of
// Nigam & Jennings 1969 and of every exact solver in topple). Samples are either uniform (t_i = t0 + i*dt) or at
// arbitrary non-decreasing times, as hand-digitised records come (the thesis' programs read (T, A) pairs scaled by
// FT and FA). Two samples at the same instant are allowed inside the library and mean a jump (a rectangular pulse
// is exact that way); readers refuse repeated times in files, where they are a digitising error.
//
// Units. Acceleration in m/s^2, time in s. Readers convert at the edge and keep what they read in Metadata.
//
// Limits (GroundMotionLimits below; README "Limits"). A record is refused, with an InputError naming the limit, when
// it lies outside what any earthquake record or shaking-table motion is, by a wide margin. Within them every
// quantity derived from a record (velocity, displacement, Arias intensity, spectra, sliding and rocking responses)
// is far from the range of double precision, so that no inf or NaN can come out of a finite input:
//   records (readers, scaled records, synthesis) |a| <= 100 g; any GroundMotion (idealised pulses too) |a| <= 1e6
//   m/s^2; duration <= 6 h, |t0| <= 1 day, 1 us <= uniform dt <= 10 s, positive irregular steps >= 1 us, at most
//   5e7 samples. Worst cases at 1e6 m/s^2 for 6 h: PGV <= a T = 2.2e10 m/s, PGD <= a T^2 / 2 = 2.3e14 m,
//   integral a^2 dt <= 2.2e16; at 100 g: 2.1e7 m/s, 2.3e11 m, 2.1e10.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "topple/core/units.hpp"

namespace topple {

namespace detail {
struct GroundMotionFactory;  // library-internal construction paths (src/motion/ground_motion_detail.hpp)
}  // namespace detail

/// The physically sensible range of a ground motion (see the header). Every GroundMotion satisfies them: the
/// constructors, scaled(), time_scaled() and resampled() throw InputError naming the limit otherwise.
struct GroundMotionLimits {
  /// |a| <= 100 g (980.665 m/s^2) for a record: what readers return, a record scaled by the user (require_record_
  /// acceleration), a synthetic motion. The largest accelerations ever recorded are about 4 g (Iwate-Miyagi 2008,
  /// IWTH25); threshold searches of small, stiff objects under short pulses legitimately reach tens of g.
  static constexpr double max_record_accel_m_s2 = 100.0 * kStandardGravity;
  /// |a| <= 1e6 m/s^2 for any GroundMotion: an idealised velocity impulse is a rectangular pulse of a few
  /// microseconds carrying metres per second (1e5 m/s^2 for 1 m/s in 10 us; tests/solvers/test_rocking.cpp,
  /// R8VelocityImpulse); a million m/s^2 for 6 h still keeps every derived quantity below 1e17.
  static constexpr double max_abs_accel_m_s2 = 1e6;
  /// Duration <= 6 h. Strong shaking lasts minutes (the longest K-NET records, Tohoku 2011, are 300 s); continuous
  /// recordings cut around an event are at most hours.
  static constexpr double max_duration_s = 6.0 * 3600.0;
  /// |t0| <= 1 day: times of day in seconds are accepted; epoch times (1.7e9 s) would leave dt at the resolution
  /// of the time variable (ulp(1.7e9) = 2.4e-7 s) and are refused.
  static constexpr double max_abs_start_time_s = 86400.0;
  /// Uniform dt >= 1 us and positive irregular steps >= 1 us: accelerographs sample at 50 Hz to a few kHz (a
  /// shaking-table controller at tens of kHz); 1 MHz is three orders beyond. Below it 1/dt and FFT frequencies
  /// lose meaning.
  static constexpr double min_dt_s = 1e-6;
  /// Uniform dt <= 10 s: a coarser grid cannot describe any shaking (Nyquist 0.05 Hz).
  static constexpr double max_dt_s = 10.0;
  /// At most 5e7 samples (400 MB of doubles per array): 6 h at 2 kHz; the same cap as synthesis.
  static constexpr std::size_t max_samples = 50'000'000;
};

/// Where a record came from; all fields optional and informative only (no computation depends on them).
struct RecordMetadata {
  std::string format;        ///< reader that produced it: "peer-at2", "cosmos-v2", "knet", "plain", "pulse", ...
  std::string source_file;   ///< path as given
  std::string event;         ///< earthquake name / date
  std::string station;       ///< station name or code
  std::string component;     ///< e.g. "180", "N-S", "HNE", "UP"
  std::string units_as_read; ///< acceleration unit in the file ("g", "cm/s2", "counts*3920/6182761 gal", ...)
  /// The sensor's azimuth as the file states it, degrees clockwise from north in [0, 360), positive acceleration
  /// toward it (readers of COSMOS V2, CSMIP V2, K-NET/KiK-net, ESM and USGS SMC: io::orientation_from_component).
  /// None when the file does not state it (PEER AT2, plain) or for a vertical channel.
  std::optional<double> azimuth_deg;
  /// True when the file states that this is the vertical channel, positive up.
  bool vertical = false;
  /// The g (m/s^2) that values in g were converted with and that this motion's values in g are expressed in (the
  /// Python package's accel_g and pga_g): the caller's g where one built or read the motion with its own g.
  double g_m_s2 = kStandardGravity;
};

class GroundMotion {
 public:
  /// Uniformly sampled record. Throws InputError for an empty record, a non-finite value, or anything outside
  /// GroundMotionLimits.
  static GroundMotion uniform(std::vector<double> accel_m_s2, double dt_s, double start_time_s = 0.0,
                              RecordMetadata metadata = {});

  /// Record at arbitrary non-decreasing times (equal consecutive times mean a jump). Throws InputError for
  /// mismatched lengths, fewer than 2 samples, decreasing or non-finite times, non-finite accelerations, or anything
  /// outside GroundMotionLimits.
  static GroundMotion irregular(std::vector<double> time_s, std::vector<double> accel_m_s2,
                                RecordMetadata metadata = {});

  [[nodiscard]] std::size_t size() const noexcept { return accel_.size(); }
  [[nodiscard]] bool is_uniform() const noexcept { return time_.empty(); }
  /// Sample interval of a uniform record; for an irregular one, the mean interval (duration / (n-1)).
  [[nodiscard]] double dt_s() const noexcept { return dt_; }
  [[nodiscard]] double start_time_s() const noexcept { return t0_; }
  [[nodiscard]] double end_time_s() const noexcept { return time_s(size() - 1); }
  [[nodiscard]] double duration_s() const noexcept { return end_time_s() - t0_; }
  [[nodiscard]] double time_s(std::size_t i) const noexcept {
    return time_.empty() ? t0_ + static_cast<double>(i) * dt_ : time_[i];
  }
  [[nodiscard]] std::span<const double> accel_m_s2() const noexcept { return accel_; }
  /// All sample times (materialised for a uniform record).
  [[nodiscard]] std::vector<double> times_s() const;
  [[nodiscard]] const RecordMetadata& metadata() const noexcept { return meta_; }
  void set_metadata(RecordMetadata metadata) { meta_ = std::move(metadata); }

  /// Acceleration at time t by linear interpolation; 0 outside the record (the ground is still before and after).
  /// At a jump, the value after it.
  [[nodiscard]] double accel_at(double t_s) const noexcept;

  /// Peak |a| in m/s^2 and the time of its first occurrence.
  [[nodiscard]] double pga_m_s2() const noexcept;
  [[nodiscard]] double pga_time_s() const noexcept;

  // ---- Operations: each returns a new record; metadata is kept. ----
  /// a -> factor * a. factor must be finite and the result within GroundMotionLimits::max_abs_accel_m_s2.
  [[nodiscard]] GroundMotion scaled(double factor) const;
  /// Scaled so that max |a| = pga_m_s2 (> 0). Throws when the record is identically zero.
  [[nodiscard]] GroundMotion scaled_to_pga(double pga_m_s2) const;
  /// Polarity flip a -> -a.
  [[nodiscard]] GroundMotion inverted() const { return scaled(-1.0); }
  /// Time axis stretched by factor (> 1 slower, < 1 compressed): t -> t0 + factor (t - t0). Acceleration values
  /// are unchanged, so the predominant frequency is divided by factor.
  [[nodiscard]] GroundMotion time_scaled(double factor) const;
  /// The part between t_begin and t_end (interpolated end points), times kept.
  [[nodiscard]] GroundMotion trimmed(double t_begin_s, double t_end_s) const;
  /// Linear resampling on a uniform grid of step dt_s from start to end (the last point falls at or before end).
  [[nodiscard]] GroundMotion resampled(double dt_s) const;
  /// Baseline correction by least-squares removal of a polynomial in t of the given order (0 = mean, 1 = linear,
  /// 2 = quadratic ...; at most 6), as the thesis did for its table motion (Table 4.1, note).
  [[nodiscard]] GroundMotion baseline_corrected(int order) const;
  /// Uniform version of the record: itself if already uniform, else resampled at the smallest interval.
  [[nodiscard]] GroundMotion to_uniform() const;

 private:
  friend struct detail::GroundMotionFactory;
  GroundMotion() = default;
  std::vector<double> accel_;
  std::vector<double> time_;  // empty for uniform records
  double dt_ = 0.0;
  double t0_ = 0.0;
  RecordMetadata meta_;
};

/// The amplitude factor that turned `original` into `transformed` (|PGA ratio|; 1 for an identically zero original).
/// It is the factor a vertical component gets when its horizontal is scaled: scaling scales the whole shaking,
/// while a polarity flip is the horizontal's own.
[[nodiscard]] double amplitude_factor(const GroundMotion& original, const GroundMotion& transformed) noexcept;
/// Throws InputError naming `field` (e.g. "--scale") when `pga_m_s2`, the PGA a record would have (say |factor| x
/// its PGA, before scaling it), exceeds GroundMotionLimits::max_record_accel_m_s2 (100 g), or is not finite: for
/// records scaled at a user's request.
void require_record_acceleration(double pga_m_s2, const std::string& field);

}  // namespace topple
