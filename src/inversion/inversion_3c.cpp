// The inversion in three components: family, runs, likelihood over (cell, direction bin) and the direction of
// strongest shaking. See inversion_3c.hpp and docs/method.md, "Inversion in three components".
#include "topple/inversion/inversion_3c.hpp"
#include "topple/inversion/prior.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"
#include "topple/survey/population.hpp"
#include "inversion/inversion_detail.hpp"

namespace topple {
namespace {

constexpr double kDeg = kPi / 180.0;

/// x mod m in [0, m).
double wrap(double x, double m) {
  const double r = std::fmod(x, m);
  return r < 0.0 ? r + m : r;
}

}  // namespace

bool DirectionArc::contains(double azimuth_deg) const noexcept {
  return wrap(azimuth_deg - low_deg, 180.0) <= width_deg;
}

std::vector<double> direction_bins_deg(const InversionSettings& st) {
  const double w = 180.0 / st.directions;
  std::vector<double> out(static_cast<std::size_t>(st.directions));
  for (std::size_t b = 0; b < out.size(); ++b) out[b] = w * static_cast<double>(b);
  return out;
}

double direction_jitter_deg(const InversionSettings& st, std::size_t k) {
  PortableRandom rng(detail::mix(detail::mix(st.seed, 0x3C0001), k + 1));
  return (rng.uniform() - 0.5) * (180.0 / st.directions);
}

double unknown_bearing_angle_deg(std::uint64_t seed, std::size_t k, std::size_t o) {
  PortableRandom rng(detail::mix(detail::mix(detail::mix(seed, 0x3C0002), k + 1), o + 1));
  return 180.0 * rng.uniform();
}

SynthesisSetSpec detail::family_set_spec(const InversionSettings& st, double freq_hz, int k) {
  SynthesisSetSpec ss;
  ss.horizontal = family_spec(st, freq_hz, k);
  // 20 samples per period of the vertical too (f_v = vertical_frequency_ratio x f_h).
  ss.horizontal.dt_s = std::min(0.01, 1.0 / (20.0 * freq_hz * std::max(1.0, ss.vertical_frequency_ratio)));
  ss.coherence = st.coherence;
  ss.azimuths = ComponentAzimuths{90.0, 0.0};  // first east, second north
  // The vertical's frequency is capped at the synthesis' 20 Hz (a column above 13.3 Hz gets f_v = 20 Hz).
  ss.vertical_frequency_ratio = std::min(ss.vertical_frequency_ratio, 20.0 / freq_hz);
  return ss;
}

Realisation3c family_realisation_3c(const InversionSettings& st, double freq_hz, int k) {
  const SynthesizedSet raw = synthesize_set(detail::family_set_spec(st, freq_hz, k));
  const MotionSet set = MotionSet::make(raw.first, &raw.second, ComponentAzimuths{90.0, 0.0}, &*raw.vertical);
  // Principal axis of the horizontal acceleration (Penzien & Watabe 1975): theta from east, counter-clockwise.
  double see = 0.0, snn = 0.0, sen = 0.0;
  const auto ae = set.first().accel_m_s2();
  const auto an = set.second().accel_m_s2();
  for (std::size_t i = 0; i < ae.size(); ++i) {
    see += ae[i] * ae[i];
    snn += an[i] * an[i];
    sen += ae[i] * an[i];
  }
  const double theta_deg = 0.5 * std::atan2(2.0 * sen, see - snn) / kDeg;
  const double major_azimuth = wrap(90.0 - theta_deg, 180.0);
  const auto [major_raw, minor_raw] = set.rotated(major_azimuth);
  // Time scaling (it leaves the samples, hence the axes and every peak, unchanged) puts the major-axis component's
  // measured predominant frequency on the column's.
  const double c = predominant_frequency_hz(major_raw) / freq_hz;
  const GroundMotion major = major_raw.time_scaled(c);
  const GroundMotion minor = minor_raw.time_scaled(c);
  const RotDValue rotd = rotd_of(rotd_peaks_by_angle(major.accel_m_s2(), minor.accel_m_s2()));
  const double scale = 1.0 / rotd.rotd50;
  Realisation3c r;
  r.major = std::make_shared<const GroundMotion>(major.scaled(scale));
  r.minor = std::make_shared<const GroundMotion>(minor.scaled(scale));
  r.vertical = std::make_shared<const GroundMotion>(set.vertical().time_scaled(c).scaled(scale));
  r.rotd100_angle_deg = rotd.rotd100_angle_deg;
  r.larger_component_ratio = std::max(set.first().pga_m_s2(), set.second().pga_m_s2()) / rotd.rotd50;
  r.rotd100_ratio = rotd.rotd100 / rotd.rotd50;
  r.measured_freq_hz = predominant_frequency_hz(*r.major);
  return r;
}

FamilyGrid3c build_family_3c(const InversionSettings& st, const std::vector<double>& freq_hz,
                             const InversionOptions& options) {
  validate_inversion_options(options);
  FamilyGrid3c family;
  family.freq_hz = freq_hz;
  family.motions.assign(freq_hz.size(), std::vector<Realisation3c>(static_cast<std::size_t>(st.motions_per_cell)));
  family.measured_freq_hz.assign(freq_hz.size(), 0.0);
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, freq_hz.size() * family.motions.front().size(), [&](std::size_t jk) {
      const std::size_t n = family.motions.front().size();
      family.motions[jk / n][jk % n] = family_realisation_3c(st, freq_hz[jk / n], static_cast<int>(jk % n));
    });
  });
  for (std::size_t j = 0; j < freq_hz.size(); ++j) {
    double sum = 0.0;
    for (const Realisation3c& r : family.motions[j]) sum += r.measured_freq_hz;
    family.measured_freq_hz[j] = sum / static_cast<double>(family.motions[j].size());
  }
  return family;
}

namespace {

bool is_sliding(Outcome o) { return o == Outcome::slid || o == Outcome::not_slid; }

/// The von Mises kernel of header item 4, both senses of the axis (x in deg).
double direction_kernel(double x_deg) {
  const auto v = [](double d) { return std::exp(kSlidDirectionKappa * (std::cos(d * kDeg) - 1.0)); };
  return 0.5 * (v(x_deg) + v(x_deg + 180.0));
}

/// The match of any observation of a model = "3d" object from its run (docs/survey.md, "Three-dimensional objects":
/// the one place the engine's results become outcomes). With friction_3d the base slides: the slide is scored as the
/// sliding block's (sliding_match) on the base's largest excursion max_slide_m (sliding2d.hpp's max |u| where the
/// base never lifts) and its residual displacement |(east, north)| at the end, and the coupled outcomes as the planar
/// coupled model's (matching.cpp, coupled_match) with the 3-D run's counterparts: overturned, the largest tilt for the
/// rotation, impacts, and "never slid flat" as no entry into the flat sliding mode.
double match_3d(const ObservedObject& object, const Rigid3DSummary& s) {
  const double residual = std::hypot(s.residual_slide_east_m, s.residual_slide_north_m);
  switch (object.outcome) {
    case Outcome::slid:
    case Outcome::not_slid: return sliding_match(object, s.max_slide_m, residual);
    case Outcome::slid_stood: return s.overturned ? 0.0 : sliding_match(object, s.max_slide_m, residual);
    case Outcome::slid_toppled: return s.overturned && s.max_slide_m >= kVisibleSlipM ? 1.0 : 0.0;
    case Outcome::walked: {
      const bool never_slid_flat = std::none_of(s.modes.begin(), s.modes.end(), [](const Rigid3DModeChange& m) {
        return m.mode == Rigid3DMode::sliding;
      });
      return !s.overturned && s.max_tilt_rad >= kVisibleRockingRad && s.impacts > 0 && residual >= kVisibleSlipM &&
                     never_slid_flat
                 ? 1.0
                 : 0.0;
    }
    default: return rocking_match(object.outcome, s.overturned, s.max_tilt_rad);
  }
}

}  // namespace

void observation_match_3c(const ObservedObject& object, const DrawnParameters& p, const GroundMotion& major_in,
                          const GroundMotion& minor_in, const GroundMotion& vertical_in, double rotd100_angle_deg,
                          std::span<const double> major_azimuth_deg, double unknown_angle_deg, double g,
                          std::span<double> out) {
  // The object's motion: amplified (all three components), then the horizontals through a flexible support.
  const double amp = p.amplification;
  GroundMotion major = amp == 1.0 ? major_in : major_in.scaled(amp);
  GroundMotion minor = amp == 1.0 ? minor_in : minor_in.scaled(amp);
  const GroundMotion vertical = amp == 1.0 ? vertical_in : vertical_in.scaled(amp);
  if (object.support_filter) {
    const SupportOscillator support = SupportOscillator::make(p.support_freq_hz, p.support_damping);
    major = support_motion(major, support);
    minor = support_motion(minor, support);
  }
  const bool three_d = object_model(object) == ObjectModel::three_d;
  if (is_sliding(object.outcome) && !three_d) {
    const Sliding2dOptions so;  // the solver's defaults (looser tolerances hit its low-speed step limit)
    const Sliding2dSummary s =
        slide_2d_summary(major, minor, ComponentAzimuths{0.0, 90.0},
                         SlidingBlock::make(p.mu, p.mu, 0.0, SlidingMode::two_way, g), &vertical, so);
    const double m = sliding_match(object, s.max_abs_displacement_m, s.residual_displacement_m);
    for (std::size_t b = 0; b < out.size(); ++b) {
      double dir = 1.0;
      if (object.slid_azimuth_deg) {
        dir = s.residual_azimuth_deg
                  ? direction_kernel(*s.residual_azimuth_deg + major_azimuth_deg[b] - *object.slid_azimuth_deg)
                  : std::exp(-kSlidDirectionKappa) * std::cyl_bessel_i(0.0, kSlidDirectionKappa);
      }
      out[b] = m * dir;
    }
    return;
  }
  const RockingOptions options = inversion_rocking_options(object, p, g);
  const auto accel_v = vertical.accel_m_s2();
  const bool lifted = g + *std::min_element(accel_v.begin(), accel_v.end()) <= 0.0;
  const MotionSet frame = MotionSet::make(major, &minor, ComponentAzimuths{0.0, 90.0});
  // One run: its match, and the axis it fell along, deg from the major axis (none: it did not fall, or was lifted
  // off, which has no direction).
  struct Run {
    double match = 0.0;
    std::optional<double> fall_from_major_deg;
    std::optional<double> slid_from_major_deg;  ///< model = "3d", outcome slid: the residual slide's azimuth
  };
  // model = "3d" (header, item 3): the three-dimensional engine (rigid3d.hpp) on the pair and the vertical. The frame's
  // major axis (azimuth 0) plays north (the engine's y), the minor (azimuth 90) east (its x); the body is turned so
  // that its +x axis points at angle_deg from the major axis (90 - angle_deg counter-clockwise seen from above, as
  // `topple rock --model 3d --bearing-deg` turns it), and its fall azimuth is then measured from the major axis.
  std::optional<Rigid3DOptions> options_3d;
  if (three_d) options_3d = rigid3d_options(options);  // rigid3d.hpp: the settings the two engines share
  // friction_3d = "mu": Coulomb friction mu_s = mu_k = the drawn mu (survey.hpp); absent, the no-slip engine.
  if (three_d && object.friction_3d) options_3d->mu_s = p.mu;
  // A cylinder (no mesh, no body_3d): the rim engine's solid cylinder of the planar body's a = d / 2, h = H / 2
  // (rigid3d_disc.hpp; rocking_body.hpp), axisymmetric: the pair as it is at every bearing angle.
  std::optional<CylinderBody3D> cylinder_3d;
  if (three_d && !object.body_3d && object.body.shape == RockingBody::Shape::cylinder) {
    cylinder_3d = CylinderBody3D::solid(2.0 * object.body.a_m, 2.0 * object.body.h_m);
  }
  // Item 3: a run whose vertical lifts the body off (g + a_v <= 0 somewhere) scores as overturned, without a
  // direction. For the sliding and coupled outcomes of a model = "3d" object (friction_3d, survey.cpp) that is: it
  // fell and its base moved (slid_toppled), and it did not stand (slid, not_slid, slid_stood, walked: 0). (The contact
  // engine models the flight, but a thrown body's landing is outside what the observation model can score, and its
  // runs meet the engine's event limit there.)
  const auto thrown = [&]() -> Run {
    if (is_sliding(object.outcome) || is_coupled_outcome(object.outcome)) {
      return {object.outcome == Outcome::slid_toppled ? 1.0 : 0.0, std::nullopt, std::nullopt};
    }
    return {rocking_match(object.outcome, true, 0.0), std::nullopt, std::nullopt};
  };
  const auto run = [&](double angle_deg) -> Run {
    if (lifted) return thrown();
    if (three_d) {
      const Rigid3DSummary s =
          cylinder_3d ? rock3d_cylinder(minor, &major, &vertical, *cylinder_3d, *options_3d).summary
                      : rock3d(minor, &major, &vertical,
                               object.body_3d->rotated_about_vertical((90.0 - angle_deg) * kDeg), *options_3d)
                            .summary;
      Run r{match_3d(object, s), s.overturned ? std::optional<double>(s.overturn_azimuth_deg) : std::nullopt,
            std::nullopt};
      // The residual slide's direction in the frame (east: the minor axis, north: the major), clockwise from the
      // major axis as sliding2d.hpp's residual_azimuth_deg; none when the base never moved.
      if (s.residual_slide_east_m != 0.0 || s.residual_slide_north_m != 0.0) {
        r.slid_from_major_deg = wrap(std::atan2(s.residual_slide_east_m, s.residual_slide_north_m) / kDeg, 360.0);
      }
      return r;
    }
    // A box: both axes, the governing one's response (oriented.hpp, "Box"). A cylinder with an observed fall
    // direction: oriented.hpp's grid of directions, the governing one its fall axis (header, item 4).
    const bool cylinder_grid = object.body.shape == RockingBody::Shape::cylinder && object.toppled_azimuth_deg;
    if (object.depth_m || cylinder_grid) {
      const MotionSet with_vertical = MotionSet::make(major, &minor, ComponentAzimuths{0.0, 90.0}, &vertical);
      const OrientedRockingSummary both =
          rock_oriented_summary(with_vertical, OrientedBody::make(object.body, object.depth_m), angle_deg, options);
      const DirectionResponse& d = both.governing_response();  // azimuth_deg: from the major axis (frame azimuth 0)
      return {rocking_match(object.outcome, d.summary.overturned, d.summary.max_abs_rotation_rad),
              d.summary.overturned ? std::optional<double>(d.azimuth_deg) : std::nullopt, std::nullopt};
    }
    const RockingSummary s = rock_summary(frame.projected(angle_deg), object.body, options, &vertical);
    return {rocking_match(object.outcome, s.overturned, s.max_abs_rotation_rad),
            s.overturned ? std::optional<double>(angle_deg) : std::nullopt, std::nullopt};
  };
  // The fall direction's kernel (item 4) in a bin whose major axis points at major_az: 1 without an observed one;
  // the kernel's mean over a uniform direction for a run with no fall direction (as a block that never slid).
  const auto fall = [&](const Run& r, double major_az) {
    if (object.slid_azimuth_deg && r.match != 0.0) {  // model = "3d", outcome slid: the slide's direction, as above
      return r.slid_from_major_deg
                 ? direction_kernel(*r.slid_from_major_deg + major_az - *object.slid_azimuth_deg)
                 : std::exp(-kSlidDirectionKappa) * std::cyl_bessel_i(0.0, kSlidDirectionKappa);
    }
    if (!object.toppled_azimuth_deg || r.match == 0.0) return 1.0;
    return r.fall_from_major_deg
               ? direction_kernel(*r.fall_from_major_deg + major_az - *object.toppled_azimuth_deg)
               : std::exp(-kSlidDirectionKappa) * std::cyl_bessel_i(0.0, kSlidDirectionKappa);
  };
  if (object.body.shape == RockingBody::Shape::cylinder || !object.azimuth_deg) {
    const Run r = run(object.body.shape == RockingBody::Shape::cylinder ? rotd100_angle_deg : unknown_angle_deg);
    for (std::size_t b = 0; b < out.size(); ++b) out[b] = r.match * fall(r, major_azimuth_deg[b]);
    return;
  }
  for (std::size_t b = 0; b < out.size(); ++b) {
    const Run r = run(wrap(*object.azimuth_deg - major_azimuth_deg[b], 360.0));
    out[b] = r.match * fall(r, major_azimuth_deg[b]);
  }
}

namespace {

/// A three-dimensional body's static coefficients (header, item 6): uplift about some edge needs the resultant of
/// gravity and the ground's inertial force to leave the base polygon (rigid3d.hpp, rest -> rocking), i.e.
/// |a| / (g + a_v) > d(u) / h in the direction u of a, where d(u) is the distance from the centre of mass' plan to
/// where the polygon's boundary meets the ray -u. Its smallest value is the distance from c to the nearest edge line
/// (a rocked or overturned body: |a| reached at least that), its largest the distance to the farthest vertex (a body
/// that did not rock: |a| stayed below that in every direction). A box: min(w, d) / 2 and the half-diagonal, over h.
std::pair<double, double> polygon_static_coefficients(const RigidBody3D& body) {
  const auto& v = body.base_xy_m;
  const double cx = body.centre_of_mass_m[0], cy = body.centre_of_mass_m[1], h = body.centre_of_mass_m[2];
  double nearest_edge = std::numeric_limits<double>::infinity(), farthest_vertex = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % v.size()];
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    // Counter-clockwise polygon, c inside: the distance to the edge's line is the cross product over the length.
    nearest_edge = std::min(nearest_edge, (ex * (cy - a[1]) - ey * (cx - a[0])) / std::hypot(ex, ey));
    farthest_vertex = std::max(farthest_vertex, std::hypot(a[0] - cx, a[1] - cy));
  }
  return {nearest_edge / h, farthest_vertex / h};
}

}  // namespace

ThreeComponentBounds static_bounds_3c(const Site& site, double rho) {
  ThreeComponentBounds out;
  constexpr double c = kRotD50FloorOfRotD100;
  const auto g3 = [](double v) { return fmt::format("{:.3g} g", v); };
  for (const ObservedObject& o : site.objects) {
    const std::string_view name = outcome_name(o.outcome);
    // s: the static coefficient (mu or tan alpha); h, v: the horizontal and vertical gains of the support.
    const auto lower = [&](double s, const char* symbol, double h, double v, const std::string& gain) {
      const double a100 = s / (h + v * rho * s);            // (S3a)
      const double a50 = c * s / (h + c * v * rho * s);     // (S3b)
      const std::string why = fmt::format("{} = {:.3g}{}, vertical V/H <= {:.3g}", symbol, s, gain, rho);
      out.rotd100.lower.push_back({a100, o.id, fmt::format("{}: RotD100 PGA > {} ({})", name, g3(a100), why), true});
      out.rotd50.lower.push_back({a50, o.id,
                                  fmt::format("{}: RotD50 PGA > {} (RotD100 > {} and RotD50 >= {:.4f} RotD100; {})",
                                              name, g3(a50), g3(a100), c, why),
                                  true});
    };
    const auto upper = [&](double s, const char* symbol, double amp, const std::string& gain) {
      if (!(amp > rho * s)) return;  // the vertical could lift it off: no threshold
      const double a = s / (amp * (1.0 - rho * s));
      const std::string why = fmt::format("{} = {:.3g}{}, vertical V/H <= {:.3g}", symbol, s, gain, rho);
      out.rotd100.upper.push_back({a, o.id, fmt::format("{}: RotD100 PGA <= {} ({})", name, g3(a), why), false});
      out.rotd50.upper.push_back(
          {a, o.id, fmt::format("{}: RotD50 PGA <= {} (RotD50 <= RotD100 <= {}; {})", name, g3(a), g3(a), why), false});
    };
    const auto amp_text = [](double amp) { return amp == 1.0 ? std::string() : fmt::format(", amplification {:.3g}", amp); };
    const OrientedBody oriented = OrientedBody::make(o.body, o.depth_m);
    // Uplift: the planar body's tan alpha (detail::uplift_tan_alpha: an asymmetric body's weaker one); a box rocks
    // first about its smaller one when it rocked, and is bounded by both when it did not.
    // A model = "3d" body (a box, or a mesh's support polygon): its polygon's coefficients, every direction at once.
    const std::optional<std::pair<double, double>> polygon =
        o.body_3d ? std::optional(polygon_static_coefficients(*o.body_3d)) : std::nullopt;
    const double tan_lower = polygon          ? polygon->first
                             : oriented.across ? std::min(std::tan(o.body.alpha_rad()), std::tan(oriented.across->alpha_rad()))
                                               : detail::uplift_tan_alpha(o.body, true);
    // A model = "3d" base that may slide (friction_3d) leaves rest only when |a_h| / (g + a_z) passes mu (the flat
    // base slips: rigid3d_slide.cpp, the sliding block's onset) or the nearest edge's b/h (it lifts), whichever is
    // less (Shenton 1996): a base that moved bounds PGA by that smaller one (it may slip while it rocks, below mu g),
    // one that toppled or walked by b/h (it lifted).
    const bool slides_3d = polygon && o.friction_3d;
    const double moved = slides_3d ? std::min(o.mu.low, polygon->first) : o.mu.low;
    const char* moved_symbol = slides_3d ? "min(mu, b/h)" : "mu";
    if (o.support_filter) {  // lower thresholds only (inversion.hpp, item 1); the vertical passes unfiltered
      const double peak = max_peak_amplification(o.support_filter->damping.low);
      const double h = o.amplification.high * peak;
      if (!std::isfinite(h)) continue;
      const std::string gain = fmt::format(", support peak gain <= {:.3g}", h);
      if (o.outcome == Outcome::slid || (slides_3d && o.outcome == Outcome::slid_stood)) {
        lower(moved, moved_symbol, h, o.amplification.high, gain);
      }
      if (o.outcome == Outcome::rocked || o.outcome == Outcome::overturned ||
          (slides_3d && (o.outcome == Outcome::slid_toppled || o.outcome == Outcome::walked))) {
        lower(tan_lower, "b/h", h, o.amplification.high, gain);
      }
      continue;
    }
    const double hi = o.amplification.high, lo = o.amplification.low;
    switch (o.outcome) {
      case Outcome::slid: lower(moved, moved_symbol, hi, hi, amp_text(hi)); break;
      case Outcome::not_slid:
        // model = "3d": a base that may lift before it slips (mu >= b_min / h somewhere in its range) can rock, or
        // topple, without sliding at any PGA: the sliding block's bound holds only where it can never lift.
        if (slides_3d && !(o.mu.high < polygon->first)) break;
        upper(o.mu.high, "mu", lo, amp_text(lo));
        break;
      case Outcome::slid_stood:  // model = "3d" only (the coupled model is one-component)
        if (slides_3d) lower(moved, moved_symbol, hi, hi, amp_text(hi));
        break;
      case Outcome::slid_toppled:
      case Outcome::walked:
        if (slides_3d) lower(tan_lower, "b/h", hi, hi, amp_text(hi));
        break;
      case Outcome::rocked:
      case Outcome::overturned: lower(tan_lower, "b/h", hi, hi, amp_text(hi)); break;
      case Outcome::not_rocked:
        // friction_3d: a base that slides before the resultant leaves it need not rock at any PGA (the friction
        // force caps the horizontal one at mu N): the bound holds only where mu >= the farthest vertex's d/h (the
        // resultant leaves the base, in every direction, while it still sticks).
        if (polygon && o.friction_3d && o.mu.low < polygon->second) break;
        if (polygon) {
          upper(polygon->second, "the farthest base vertex's distance / h", lo, amp_text(lo));
        } else if (oriented.across) {
          upper(std::hypot(std::tan(o.body.alpha_rad()), std::tan(oriented.across->alpha_rad())),
                "hypot of the box's two b/h", lo, amp_text(lo));
        } else if (oriented.axisymmetric()) {
          upper(std::tan(o.body.alpha_rad()), "b/h", lo, amp_text(lo));
        }  // a planar body bounds the projection on its bearing only: no threshold (header, item 6)
        break;
      default: break;  // not_overturned: no static threshold, as in one component
    }
  }
  detail::settle_static_bounds(out.rotd100);
  detail::settle_static_bounds(out.rotd50);
  return out;
}

DirectionEstimate direction_estimate(const std::vector<double>& bins_deg, const std::vector<double>& posterior) {
  DirectionEstimate d;
  const std::size_t n = bins_deg.size();
  d.azimuth_deg = bins_deg;
  d.bin_width_deg = 180.0 / static_cast<double>(n);
  d.posterior = posterior;
  const std::size_t mode = static_cast<std::size_t>(std::max_element(posterior.begin(), posterior.end()) -
                                                    posterior.begin());
  d.mode_deg = bins_deg[mode];
  double c = 0.0, s = 0.0;
  for (std::size_t b = 0; b < n; ++b) {
    c += posterior[b] * std::cos(2.0 * bins_deg[b] * kDeg);
    s += posterior[b] * std::sin(2.0 * bins_deg[b] * kDeg);
  }
  d.resultant_length = std::hypot(c, s);
  d.mean_deg = wrap(0.5 * std::atan2(s, c) / kDeg, 180.0);
  // The shortest arc holding the highest-posterior bins up to `level`: the complement of the longest circular run of
  // bins not selected.
  const auto arc = [&](double level) {
    std::vector<std::size_t> order(n);
    for (std::size_t b = 0; b < n; ++b) order[b] = b;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return posterior[a] > posterior[b]; });
    std::vector<bool> in(n, false);
    double mass = 0.0;
    for (std::size_t b : order) {
      in[b] = true;
      mass += posterior[b];
      if (mass >= level) break;
    }
    std::size_t best_gap = 0, best_end = 0;  // longest run of !in, ending just before bin best_end
    for (std::size_t start = 0; start < n; ++start) {
      if (in[start]) continue;
      std::size_t len = 0;
      while (len < n && !in[(start + len) % n]) ++len;
      if (len > best_gap) {
        best_gap = len;
        best_end = (start + len) % n;
      }
    }
    DirectionArc a;
    if (best_gap == 0) {
      a.low_deg = wrap(bins_deg[0] - 0.5 * d.bin_width_deg, 180.0);
      a.width_deg = 180.0;
      return a;
    }
    a.low_deg = wrap(bins_deg[best_end] - 0.5 * d.bin_width_deg, 180.0);
    a.width_deg = static_cast<double>(n - best_gap) * d.bin_width_deg;
    return a;
  };
  d.ci68 = arc(0.68);
  d.ci95 = arc(0.95);
  d.constrained = d.ci95.width_deg <= kUnconstrainedArcDeg;
  return d;
}

namespace {
/// The runs of every object at every direction bin (header, items 2-4): one MatchTable per bin, and the solver runs
/// done. `draw_index[o]` (empty: o) is the index object o draws its parameters and unknown bearing with, so that a
/// population's members never repeat an object's draws and a fall-direction variant repeats its member's.
std::pair<std::vector<MatchTable>, std::size_t> simulate_matches_3c(const Site& site, const InversionSettings& st,
                                                                    const std::vector<double>& pga_g,
                                                                    const FamilyGrid3c& family,
                                                                    const InversionOptions& options,
                                                                    const std::vector<std::size_t>& draw_index = {}) {
  const std::size_t nf = family.motions.size(), n = family.motions.front().size(), no = site.objects.size();
  const std::size_t nb = static_cast<std::size_t>(st.directions);
  const std::vector<double> bins = direction_bins_deg(st);
  // Per motion k: the major axis' azimuth in every bin (Psi_b + delta_k); per (k, o): the drawn parameters and the
  // angle of an object of unknown bearing. The same in every cell.
  std::vector<double> major_azimuth(n * nb);
  for (std::size_t k = 0; k < n; ++k) {
    const double delta = direction_jitter_deg(st, k);
    for (std::size_t b = 0; b < nb; ++b) major_azimuth[k * nb + b] = bins[b] + delta;
  }
  std::vector<DrawnParameters> drawn(n * no);
  std::vector<double> unknown(n * no);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t o = 0; o < no; ++o) {
      const std::size_t d = draw_index.empty() ? o : draw_index[o];
      drawn[k * no + o] = draw_parameters(site.objects[o], st.seed, k, d);
      unknown[k * no + o] = unknown_bearing_angle_deg(st.seed, k, d);
    }
  }
  ensemble::Plan plan;
  plan.motion_columns = {"cell", "motion"};
  plan.object_columns = {"object"};
  for (std::size_t b = 0; b < nb; ++b) plan.result_columns.push_back(fmt::format("match_bin{}", b));
  plan.identity = "topple inversion 3c v1";
  for (std::size_t i = 0; i < pga_g.size(); ++i) {
    for (std::size_t j = 0; j < nf; ++j) {
      for (std::size_t k = 0; k < n; ++k) {
        ensemble::MotionCase mc;
        mc.base = family.motions[j][k].major;
        mc.transform.factor = pga_g[i] * st.g_m_s2;  // RotD50 1 m/s^2 -> the row's RotD50 PGA
        mc.values = {ensemble::Value(static_cast<std::int64_t>(i * nf + j)), ensemble::Value(static_cast<std::int64_t>(k))};
        plan.motions.push_back(std::move(mc));
      }
    }
  }
  for (const ObservedObject& o : site.objects) plan.objects.push_back({{ensemble::Value(o.id)}});
  const double g = st.g_m_s2;
  plan.run = [&](const GroundMotion& major, std::size_t motion_index, std::size_t o0, std::size_t o1,
                 std::span<ensemble::Value> results) {
    const std::size_t k = motion_index % n;
    const std::size_t cell = motion_index / n;
    const Realisation3c& real = family.motions[cell % nf][k];
    const double factor = pga_g[cell / nf] * g;
    const GroundMotion minor = real.minor->scaled(factor);
    const GroundMotion vertical = real.vertical->scaled(factor);
    std::vector<double> out(nb);
    for (std::size_t o = o0; o < o1; ++o) {
      // A solver's limit names the object, the cell and the motion, so that the one run among thousands is found
      // (as `topple campaign` names its test and model).
      const auto who = [&] {
        return fmt::format("object '{}' (model {}), RotD50 PGA {:.4g} g, {:.4g} Hz, motion {}: ", site.objects[o].id,
                           object_model_name(object_model(site.objects[o])), pga_g[cell / nf],
                           family.freq_hz[cell % nf], k);
      };
      try {
        observation_match_3c(site.objects[o], drawn[k * no + o], major, minor, vertical, real.rotd100_angle_deg,
                             std::span<const double>(major_azimuth.data() + k * nb, nb), unknown[k * no + o], g, out);
      } catch (const StepLimitError& e) {
        throw StepLimitError(who() + e.what());
      } catch (const EventLimitError& e) {
        throw EventLimitError(who() + e.what());
      } catch (const RootFindingError& e) {
        throw RootFindingError(who() + e.what());
      }
      for (std::size_t b = 0; b < nb; ++b) results[(o - o0) * nb + b] = ensemble::Value(out[b]);
    }
  };
  ensemble::ExecuteOptions exec;
  exec.threads = options.threads;
  exec.progress = options.progress;
  const ensemble::ResultTable rows = ensemble::run_in_memory(plan, exec);
  // Rows come in run order: row = (cell * N + k) * objects + o, the MatchTable's own indexing, one table per bin.
  const std::size_t first_col = rows.columns.size() - nb;
  std::vector<MatchTable> tables(nb, MatchTable{pga_g.size(), nf, n, no, std::vector<double>(rows.rows.size())});
  for (std::size_t row = 0; row < rows.rows.size(); ++row) {
    for (std::size_t b = 0; b < nb; ++b) tables[b].match[row] = std::get<double>(rows.rows[row][first_col + b]);
  }
  std::size_t runs = 0;
  // Solver runs: one per bin for a rocking object with a bearing, else one.
  for (const ObservedObject& o : site.objects) {
    // A model = "3d" body with a bearing runs in every bin, whatever it was seen to do (its base is not isotropic).
    const bool slide_block = is_sliding(o.outcome) && object_model(o) != ObjectModel::three_d;
    const bool per_bin = !slide_block && o.azimuth_deg && o.body.shape != RockingBody::Shape::cylinder;
    // A box rocks about both axes; a cylinder with a fall direction on oriented.hpp's 12 directions.
    const std::size_t axes = is_sliding(o.outcome)                                                     ? 1
                             : o.depth_m                                                                ? 2
                             : o.body.shape == RockingBody::Shape::cylinder && o.toppled_azimuth_deg ? 12
                                                                                                       : 1;
    runs += plan.motions.size() * (per_bin ? nb : 1) * axes;
  }
  return {std::move(tables), runs};
}

/// Populations in three components (docs/method.md, "Populations of objects", eq. P2): the K members of each run
/// as objects that overturned (their match: 1 when the run overturned), and, for each fallen azimuth, K variants with
/// that fall direction (their match: overturned times the fall direction's kernel, as an object's). Per (bin, cell,
/// motion): the binomial of the count with the members' overturned share f (eq. P1), and for each fall direction
/// eps + (1 - 2 eps) E[kernel | overturned], E[kernel | overturned] = (the variants' mean) / f (the kernel's mean
/// over a uniform direction where no member fell). Fills out.population_run_log, out.populations and adds the runs.
void simulate_populations_3c(const Site& site, const InversionSettings& st, const std::vector<double>& pga_g,
                             const FamilyGrid3c& family, const InversionOptions& options, detail::SiteRuns& out) {
  struct Span {
    std::size_t first = 0, count = 0;
  };
  Site members;
  std::vector<Span> base;                  // per population: its K members
  std::vector<std::vector<Span>> variants;  // per population, per fallen azimuth: its K variants
  // Draw indices: the members' from far above any object's (as the one-component likelihood's kMemberDrawOffset),
  // numbered over all populations; a variant draws as its member, so that E[kernel | overturned] (eq. P2) is taken
  // over the same realisations as the share f it is divided by.
  constexpr std::size_t kMemberDrawOffset = 1000000;
  std::vector<std::size_t> draw_index;
  std::size_t next_member = 0;
  for (const Population& p : site.populations) {
    const std::vector<ObservedObject> m = population_members(p);
    base.push_back({members.objects.size(), m.size()});
    for (std::size_t j = 0; j < m.size(); ++j) {
      members.objects.push_back(m[j]);
      draw_index.push_back(kMemberDrawOffset + next_member + j);
    }
    variants.emplace_back();
    for (std::size_t i = 0; i < p.fallen_azimuths_deg.size(); ++i) {
      variants.back().push_back({members.objects.size(), m.size()});
      for (std::size_t j = 0; j < m.size(); ++j) {
        ObservedObject o = m[j];
        o.id += fmt::format("@{}", i + 1);
        o.toppled_azimuth_deg = p.fallen_azimuths_deg[i];
        members.objects.push_back(std::move(o));
        draw_index.push_back(kMemberDrawOffset + next_member + j);
      }
    }
    next_member += m.size();
  }
  auto [tables, runs] = simulate_matches_3c(members, st, pga_g, family, options, draw_index);
  out.runs += runs;
  const std::size_t nb = tables.size();
  const std::size_t cells = pga_g.size() * family.motions.size();
  const std::size_t n = family.motions.front().size();
  out.population_run_log.assign(nb * cells * n, 0.0);
  const double uniform_kernel = std::exp(-kSlidDirectionKappa) * std::cyl_bessel_i(0.0, kSlidDirectionKappa);
  for (std::size_t q = 0; q < site.populations.size(); ++q) {
    const Population& pop = site.populations[q];
    const double eps = evidence_error_rate(pop.prototype.evidence);
    PopulationReport rep;
    rep.id = pop.id;
    rep.count = pop.count;
    rep.overturned = pop.overturned;
    rep.members = base[q].count;
    rep.member_rule = population_member_rule(pop);
    rep.observed_fraction = static_cast<double>(pop.overturned) / static_cast<double>(pop.count);
    rep.model_fraction.assign(cells, 0.0);
    const auto mean = [&](const MatchTable& t, std::size_t c, std::size_t k, const Span& sp) {
      double sum = 0.0;
      for (std::size_t o = sp.first; o < sp.first + sp.count; ++o) sum += t.at(c, k, o);
      return sum / static_cast<double>(sp.count);
    };
    for (std::size_t b = 0; b < nb; ++b) {
      for (std::size_t c = 0; c < cells; ++c) {
        for (std::size_t k = 0; k < n; ++k) {
          const double f = mean(tables[b], c, k, base[q]);
          rep.model_fraction[c] += f / static_cast<double>(nb * n);
          const double share[kPopulationCategories] = {1.0 - f, 0.0, 0.0, f};
          double ll = population_log_likelihood(pop, share);
          for (const Span& v : variants[q]) {
            const double conditional = f > 0.0 ? std::min(1.0, mean(tables[b], c, k, v) / f) : uniform_kernel;
            ll += std::log(eps + (1.0 - 2.0 * eps) * conditional);
          }
          out.population_run_log[(b * cells + c) * n + k] += ll;
        }
      }
    }
    out.populations.push_back(std::move(rep));
  }
}

}  // namespace

detail::SiteRuns detail::simulate_site_3c(const Site& site, const InversionSettings& st,
                                          const std::vector<double>& pga_g, const FamilyGrid3c& family,
                                          const InversionOptions& options) {
  SiteRuns out;
  // Static thresholds (header, item 6) with the family's largest vertical ratio rho (RotD50 of the stored pair is 1).
  double rho = 0.0;
  for (const auto& column : family.motions) {
    for (const Realisation3c& real : column) rho = std::max(rho, real.vertical->pga_m_s2());
  }
  ThreeComponentBounds thresholds = static_bounds_3c(site, rho);
  out.bounds = std::move(thresholds.rotd50);
  out.rotd100_bounds = std::move(thresholds.rotd100);
  if (site.objects.empty()) {  // populations only: empty tables of the grid's shape, one per direction bin
    const std::size_t nb = direction_bins_deg(st).size();
    out.bins.assign(nb, MatchTable{pga_g.size(), family.motions.size(), family.motions.front().size(), 0, {}});
  } else {
    std::tie(out.bins, out.runs) = simulate_matches_3c(site, st, pga_g, family, options);
  }
  if (!site.populations.empty()) simulate_populations_3c(site, st, pga_g, family, options, out);
  // The solver its runs used (observation_match_3c): the two-dimensional sliding block or the oriented rocking body.
  // The survey reader refuses the coupled model and a model key that contradicts the outcome with components = 3, so
  // this is also object_model (survey.hpp).
  // model = "3d" is the three-dimensional engine's.
  for (const ObservedObject& o : site.objects) {
    out.models.push_back(object_model(o) == ObjectModel::three_d ? ObjectModel::three_d
                         : is_sliding(o.outcome)                 ? ObjectModel::slide
                                                                 : ObjectModel::rock);
  }
  // The family's facts (the direction estimate is the pipeline's, from the posterior).
  ThreeComponentResult tc;
  double larger = 0.0, r100 = 0.0, count = 0.0;
  for (const auto& column : family.motions) {
    for (const Realisation3c& real : column) {
      larger += real.larger_component_ratio;
      r100 += real.rotd100_ratio;
      count += 1.0;
    }
  }
  tc.larger_component_ratio = larger / count;
  tc.rotd100_ratio = r100 / count;
  const SynthesisSetSpec defaults;
  tc.coherence = st.coherence;
  tc.vertical_pga_ratio = defaults.vertical_pga_ratio;
  tc.vertical_frequency_ratio = defaults.vertical_frequency_ratio;
  tc.slid_direction_kappa = kSlidDirectionKappa;
  tc.threshold_vertical_ratio = rho;
  out.three_component = tc;
  out.direction_bins_deg = direction_bins_deg(st);
  out.log_prior = log_prior_for(pga_g, family.freq_hz, site, st);  // the prior (prior.hpp)
  out.prior = std::string(inversion_prior_name(st.prior));
  if (st.prior != InversionPrior::log_uniform) out.notes.push_back("The prior: " + prior_description(site, st) + ".");
  out.notes.push_back(fmt::format(
      "Three components: the static thresholds hold on RotD100 PGA, the peak of the horizontal acceleration vector, "
      "which bounds its projection on every bearing (with the family's vertical, V/H <= {:.3g}); on RotD50, the PGA "
      "axis of the estimates, they hold as the weaker RotD50 >= {:.4f} RotD100 makes them.",
      rho, kRotD50FloorOfRotD100));
  for (const ObservedObject& o : site.objects) {
    if (o.outcome == Outcome::not_rocked && !o.depth_m && o.body.shape != RockingBody::Shape::cylinder) {
      out.notes.push_back(fmt::format("{} did not rock: that bounds the motion along its bearing only, no "
                                      "direction-free measure, so it gives no static threshold here (a box, with "
                                      "depth, does).",
                                      o.id));
    }
  }
  return out;
}

InversionResult invert_site_3c(const Site& site, const InversionSettings& st, const FamilyGrid3c& family,
                               const InversionOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const std::vector<double> pga_g = detail::pga_axis(st);
  InversionResult r = detail::infer_site(site, pga_g, family.freq_hz, family.measured_freq_hz,
                                         detail::simulate_site_3c(site, st, pga_g, family, options));
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

std::string three_component_summary(const InversionResult& r) {
  if (!r.three_component) return {};
  const ThreeComponentResult& tc = *r.three_component;
  std::string s = fmt::format(
      " PGA is RotD50 of the two horizontal components (the median of the peak over all directions; the larger "
      "component's PGA is about {:.2f} times it here, a median of {:.2g} g).",
      tc.larger_component_ratio, tc.larger_component_median_g);
  if (r.rotd100_bounds && (r.rotd100_bounds->lower_g || r.rotd100_bounds->upper_g)) {
    // Item 6: the thresholds are stated on the axis where they hold.
    const StaticBounds& b = *r.rotd100_bounds;
    std::string range;
    if (b.lower_g) range = fmt::format("above {:.3g} g{}", *b.lower_g, b.hard_lower_g == b.lower_g ? " (hard)" : "");
    if (b.upper_g) range += fmt::format("{}at most {:.3g} g (soft)", range.empty() ? "" : ", ", *b.upper_g);
    s += fmt::format(" The static thresholds hold on RotD100 PGA (the peak over all directions): {}.", range);
  }
  const DirectionEstimate& d = tc.direction;
  if (!d.constrained) {
    s += fmt::format(" The direction of strongest shaking is unconstrained (its 95 % arc spans {:.0f} deg).",
                     d.ci95.width_deg);
  } else {
    const auto arc = [](const DirectionArc& a) {
      return fmt::format("{:.0f}\u2013{:.0f} deg", a.low_deg, wrap(a.high_deg(), 180.0) == 0.0 && a.high_deg() > 0.0
                                                                  ? 180.0
                                                                  : wrap(a.high_deg(), 180.0));
    };
    s += fmt::format(" The strongest shaking ran along the azimuth {:.0f} deg (mod 180, clockwise from north; 68 %: "
                     "{}, 95 %: {}).",
                     d.mode_deg, arc(d.ci68), arc(d.ci95));
  }
  return s;
}

}  // namespace topple
