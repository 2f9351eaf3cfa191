#pragma once
// Baseline (offset) removal of an accelerogram as recorded: a shaking table's acceleration channel, or a field record
// before standard processing, often sits on a constant or slowly drifting offset (a +0.01-0.02 g DC offset of a
// table's accelerometer, issue 28). Integrated twice, such an offset grows into a spurious displacement; the first
// steps of strong-motion processing remove it (Boore & Bommer 2005, "Processing of strong-motion accelerograms:
// needs, options and consequences", Soil Dyn. Earthq. Eng. 25:93-115, sections 2-3: removal of the pre-event mean,
// or of a low-order polynomial fitted to the whole record). docs/method.md, "Baseline removal".
#include <string>
#include <string_view>

#include "topple/motion/ground_motion.hpp"

namespace topple {

enum class BaselineMethod {
  none,       ///< the record as read (the default: bit for bit what it was before baselines existed)
  mean,       ///< the mean of all samples
  pre_event,  ///< the mean of the samples in the first window_s seconds (a pre-event window)
  polynomial, ///< the least-squares polynomial of degree `order` (0..3) in time over the whole record
};

struct Baseline {
  BaselineMethod method = BaselineMethod::none;
  double window_s = 0.0;  ///< pre_event: the window's length, s (> 0, at most the record's duration)
  int order = 0;          ///< polynomial: the degree, 0..3
};

/// The largest polynomial degree accepted: strong-motion processing fits at most a few terms to an acceleration
/// baseline (Boore & Bommer 2005, section 3); higher degrees start to remove the shaking itself.
inline constexpr int kMaxBaselineOrder = 3;

/// "none", "mean", "pre-event:T" (T in s, a bare number, or with a unit such as "2s", "500ms"), "poly:N" (N = 0..3).
/// Throws InputError naming `field` for anything else.
[[nodiscard]] Baseline parse_baseline(std::string_view text, const std::string& field = "baseline");

/// The inverse of parse_baseline: "none", "mean", "pre-event:2", "poly:1".
[[nodiscard]] std::string baseline_name(const Baseline& baseline);

/// The offset `baseline` describes, evaluated at every sample of `motion` (all zeros for none). Throws InputError
/// naming `field` for a pre-event window that is not positive, longer than the record, or holds fewer than two
/// samples, and for a polynomial degree outside 0..3 or with more coefficients than the record has samples.
[[nodiscard]] std::vector<double> baseline_values(const GroundMotion& motion, const Baseline& baseline,
                                                  const std::string& field = "baseline");

/// `motion` with its baseline removed: a(t_i) - baseline(t_i) on the same samples, metadata kept. For none, the
/// motion itself (a copy, bit for bit). Errors as baseline_values.
[[nodiscard]] GroundMotion remove_baseline(const GroundMotion& motion, const Baseline& baseline,
                                           const std::string& field = "baseline");

}  // namespace topple
