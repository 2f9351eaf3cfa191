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
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "topple/units.hpp"

namespace topple {

/// Where a record came from; all fields optional and informative only (no computation depends on them).
struct RecordMetadata {
  std::string format;        ///< reader that produced it: "peer-at2", "cosmos-v2", "knet", "plain", "pulse", ...
  std::string source_file;   ///< path as given
  std::string event;         ///< earthquake name / date
  std::string station;       ///< station name or code
  std::string component;     ///< e.g. "180", "N-S", "HNE", "UP"
  std::string units_as_read; ///< acceleration unit in the file ("g", "cm/s2", "counts*3920/6182761 gal", ...)
  /// The g (m/s^2) that values in g were converted with and that this motion's values in g are expressed in (the
  /// Python package's accel_g and pga_g): the caller's g where one built or read the motion with its own g.
  double g_m_s2 = kStandardGravity;
};

class GroundMotion {
 public:
  /// Uniformly sampled record. Throws InputError for an empty record, dt_s <= 0 or a non-finite value.
  static GroundMotion uniform(std::vector<double> accel_m_s2, double dt_s, double start_time_s = 0.0,
                              RecordMetadata metadata = {});

  /// Record at arbitrary non-decreasing times (equal consecutive times mean a jump). Throws InputError for
  /// mismatched lengths, fewer than 2 samples, decreasing or non-finite times, non-finite accelerations.
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
  /// a -> factor * a. factor must be finite.
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

}  // namespace topple
