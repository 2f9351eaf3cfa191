// Object spectra: sliding displacement spectrum and overturning map (object_spectra.hpp).
#include "topple/fragility/object_spectra.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/core/units.hpp"

namespace topple {

SlidingSpectrum sliding_spectrum(const GroundMotion& motion, std::span<const double> mu, double slope_rad,
                                 SlidingMode mode, double g_m_s2) {
  if (mu.empty()) throw parameter_error("mu", "the spectrum needs at least one friction coefficient");
  // slide_summaries validates each mu (SlidingBlock::make names "mu", "slope" or "g" with the value).
  const std::vector<SlidingSummary> summaries = slide_summaries(motion, mu, slope_rad, mode, g_m_s2);
  SlidingSpectrum out;
  out.pga_m_s2 = motion.pga_m_s2();
  out.slope_rad = slope_rad;
  out.mode = mode;
  out.g_m_s2 = g_m_s2;
  out.points.reserve(mu.size());
  for (std::size_t i = 0; i < mu.size(); ++i) {
    const SlidingBlock block = SlidingBlock::make(mu[i], mu[i], slope_rad, mode, g_m_s2);
    SlidingSpectrumPoint p;
    p.mu = mu[i];
    p.yield_accel_g = block.yield_down_m_s2() / g_m_s2;  // tan(phi - beta), thesis eq 2.2
    // A zero record has PGA 0: the ratio is then infinite in principle; report 0 rather than a non-finite number
    // (the block does not move either way).
    p.yield_over_pga = out.pga_m_s2 > 0.0 ? block.yield_down_m_s2() / out.pga_m_s2 : 0.0;
    p.max_abs_displacement_m = summaries[i].max_abs_displacement_m;
    p.residual_displacement_m = summaries[i].residual_displacement_m;
    p.slip_episodes = summaries[i].slip_episodes;
    p.total_slip_duration_s = summaries[i].total_slip_duration_s;
    p.at_rest_at_end = summaries[i].at_rest_at_end;
    out.points.push_back(p);
  }
  return out;
}

SlidingSpectrum2d sliding_spectrum_2d(const MotionSet& set, std::span<const double> mu, double g_m_s2) {
  if (mu.empty()) throw parameter_error("mu", "the spectrum needs at least one friction coefficient");
  if (!set.has_second()) throw parameter_error("second", "the bidirectional spectrum needs two horizontal components");
  if (!set.azimuths()) throw parameter_error("azimuths", "the bidirectional spectrum needs the components' azimuths");
  std::vector<SlidingBlock> blocks;  // every mu checked before any run (SlidingBlock::make names "mu" or "g")
  blocks.reserve(mu.size());
  for (const double m : mu) blocks.push_back(SlidingBlock::make(m, std::nullopt, 0.0, SlidingMode::two_way, g_m_s2));
  SlidingSpectrum2d out;
  out.rotd50_pga_m_s2 = rotd_measures(set, {}).pga_m_s2.rotd50;
  out.first_pga_m_s2 = set.first().pga_m_s2();
  out.second_pga_m_s2 = set.second().pga_m_s2();
  out.azimuths = *set.azimuths();
  out.with_vertical = set.has_vertical();
  out.g_m_s2 = g_m_s2;
  out.points.reserve(mu.size());
  for (std::size_t i = 0; i < mu.size(); ++i) {
    SlidingSpectrum2dPoint p;
    p.mu = mu[i];
    p.yield_accel_g = blocks[i].yield_down_m_s2() / g_m_s2;
    // A zero pair has RotD50 PGA 0: the ratio is reported as 0 (as sliding_spectrum does), the block does not move.
    p.yield_over_rotd50_pga = out.rotd50_pga_m_s2 > 0.0 ? blocks[i].yield_down_m_s2() / out.rotd50_pga_m_s2 : 0.0;
    p.bidirectional = slide_2d_summary(set.first(), set.second(), out.azimuths, blocks[i], set.vertical_ptr());
    p.first_alone = slide_summary(set.first(), blocks[i], set.vertical_ptr());
    p.second_alone = slide_summary(set.second(), blocks[i], set.vertical_ptr());
    out.points.push_back(std::move(p));
  }
  return out;
}

double mu_for_yield_ratio(double ratio, double pga_m_s2, double slope_rad, double g_m_s2) {
  if (!std::isfinite(ratio) || ratio < 0.0) {
    throw parameter_error("ky_over_pga", fmt::format("must be finite and >= 0, got {}", ratio));
  }
  // k_y g = g tan(phi - beta)  =>  phi = beta + atan(k_y g / g)   (thesis eq 2.2)
  const double phi = slope_rad + std::atan(ratio * pga_m_s2 / g_m_s2);
  if (!(phi < kPi / 2.0)) {
    throw parameter_error("ky_over_pga", fmt::format("k_y/PGA = {} on a {} deg slope needs a friction angle of 90 deg "
                                                     "or more", ratio, rad_to_deg(slope_rad)));
  }
  return std::tan(phi);
}

// ---- Overturning map ----

RockingBody BodyFamily::body(std::size_t i) const {
  const double h = 0.5 * heights_m.at(i);
  const double a = h * std::tan(alpha_rad);
  switch (shape) {
    case RockingBody::Shape::block: return RockingBody::block(2.0 * a, 2.0 * h);
    case RockingBody::Shape::cylinder: return RockingBody::cylinder(2.0 * a, 2.0 * h);
    case RockingBody::Shape::general: break;
  }
  throw parameter_error("shape", "an overturning map takes a block or a cylinder family");
}

namespace {

void check_family(const BodyFamily& f) {
  if (f.shape == RockingBody::Shape::general) {
    throw parameter_error("shape", "an overturning map takes a block or a cylinder family");
  }
  if (!std::isfinite(f.alpha_rad) || !(f.alpha_rad > 0.0) || !(f.alpha_rad < kPi / 2.0)) {
    throw parameter_error("alpha", fmt::format("slenderness must be in (0, 90) deg, got {} rad", f.alpha_rad));
  }
  if (f.heights_m.empty()) throw parameter_error("height", "the family needs at least one size");
  for (double h : f.heights_m) {
    if (!std::isfinite(h) || !(h > 0.0)) throw parameter_error("height", fmt::format("must be positive, got {} m", h));
  }
}

}  // namespace

OverturningMap overturning_map(const GroundMotion& motion, const BodyFamily& family, std::span<const double> pga_m_s2,
                               const OverturningMapOptions& options) {
  check_family(family);
  if (pga_m_s2.empty()) throw parameter_error("pga", "the map needs at least one PGA");
  for (double a : pga_m_s2) {
    if (!std::isfinite(a) || !(a > 0.0)) throw parameter_error("pga", fmt::format("must be positive, got {} m/s2", a));
  }
  if (!(motion.pga_m_s2() > 0.0)) throw parameter_error("pga", "the motion is identically zero: it cannot be scaled");
  const double g = options.rocking.g_m_s2;

  OverturningMap map;
  map.pga_m_s2.assign(pga_m_s2.begin(), pga_m_s2.end());
  std::sort(map.pga_m_s2.begin(), map.pga_m_s2.end());
  map.alpha_rad = family.alpha_rad;
  map.shape = family.shape;
  map.g_m_s2 = g;
  const std::size_t na = map.pga_m_s2.size();
  const std::size_t ns = family.heights_m.size();

  std::vector<RockingBody> bodies;
  bodies.reserve(ns);
  for (std::size_t s = 0; s < ns; ++s) bodies.push_back(family.body(s));
  // Validate the options once, here, so that a bad option is an InputError of the caller and not of a worker.
  (void)rock_summary(GroundMotion::uniform({0.0, 0.0}, 1.0), bodies.front(), options.rocking);

  // Plan: motions = PGA levels (the base motion shared, scaled by the engine), objects = sizes.
  ensemble::Plan plan;
  plan.motion_columns = {"pga_g"};
  plan.object_columns = {"height_m"};
  plan.result_columns = {"overturned", "max_rotation_over_alpha"};
  plan.identity = "topple overturning map v1";
  const auto base = std::make_shared<const GroundMotion>(motion);
  for (double a : map.pga_m_s2) {
    ensemble::MotionCase mc;
    mc.base = base;
    mc.transform.target_pga_m_s2 = a;
    mc.values = {ensemble::Value(a / g)};
    plan.motions.push_back(std::move(mc));
  }
  for (double h : family.heights_m) plan.objects.push_back({{ensemble::Value(h)}});
  // Small chunks: a rocking run costs 0.1-10 ms, so a few runs per chunk keep both cores busy to the end.
  plan.chunk_runs = std::max<std::size_t>(1, plan.runs() / 64);
  const RockingOptions ro = options.rocking;
  plan.run = [&bodies, ro](const GroundMotion& m, std::size_t /*motion_index*/, std::size_t o0, std::size_t o1,
                           std::span<ensemble::Value> results) {
    for (std::size_t o = o0; o < o1; ++o) {
      const RockingSummary s = rock_summary(m, bodies[o], ro);
      results[2 * (o - o0)] = ensemble::Value(s.overturned);
      results[2 * (o - o0) + 1] = ensemble::Value(s.max_rotation_over_alpha);
    }
  };
  ensemble::ExecuteOptions exec;
  exec.threads = options.threads;
  exec.progress = options.progress;
  const ensemble::ResultTable table = ensemble::run_in_memory(plan, exec);

  // Rows in run order: motion-major, row = k * ns + s.
  const std::size_t c_over = table.columns.size() - 2;
  map.overturned.assign(ns * na, 0);
  map.max_rotation_over_alpha.assign(ns * na, 0.0);
  for (std::size_t k = 0; k < na; ++k) {
    for (std::size_t s = 0; s < ns; ++s) {
      const auto& row = table.rows[k * ns + s];
      map.overturned[s * na + k] = std::get<bool>(row[c_over]) ? 1 : 0;
      map.max_rotation_over_alpha[s * na + k] = std::get<double>(row[c_over + 1]);
    }
  }
  for (std::size_t s = 0; s < ns; ++s) {
    OverturningSize sz;
    const RockingBody& b = bodies[s];
    sz.height_m = 2.0 * b.h_m;
    sz.width_m = 2.0 * b.a_m;
    sz.R_m = b.R_m();
    sz.p_rad_s = b.p_rad_s(g);
    for (std::size_t k = 0; k < na; ++k) {
      if (!map.at(s, k)) {
        if (sz.first_overturn_pga_m_s2) sz.standing_above_first = true;
        continue;
      }
      ++sz.overturn_count;
      if (!sz.first_overturn_pga_m_s2) sz.first_overturn_pga_m_s2 = map.pga_m_s2[k];
    }
    map.sizes.push_back(sz);
  }
  return map;
}

std::vector<double> linear_grid(double lo, double hi, std::size_t n, const char* field) {
  if (n < 1) throw parameter_error(field, "needs at least one point");
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    throw parameter_error(field, fmt::format("needs finite ends with low <= high, got {} and {}", lo, hi));
  }
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = n == 1 ? lo : lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n - 1);
  }
  if (n > 1) v.back() = hi;
  return v;
}

std::vector<double> log_grid(double lo, double hi, std::size_t n, const char* field) {
  if (!(lo > 0.0)) throw parameter_error(field, fmt::format("a logarithmic grid needs positive ends, got {}", lo));
  std::vector<double> v = linear_grid(std::log(lo), std::log(hi), n, field);
  for (double& x : v) x = std::exp(x);
  v.front() = lo;
  if (n > 1) v.back() = hi;
  return v;
}

}  // namespace topple
