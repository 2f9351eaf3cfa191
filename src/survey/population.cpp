// Populations of similar objects (topple/survey/population.hpp): their checks and representative members.
#include "topple/survey/population.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "topple/core/error.hpp"

namespace topple {
namespace {

bool is_cylinder(const Population& p) { return p.shape == "cylinder"; }

/// The horizontal dimension's name and range: a cylinder's diameter, a block's width.
const char* base_key(const Population& p) { return is_cylinder(p) ? "diameter" : "width"; }
const std::optional<Interval>& base_range(const Population& p) { return is_cylinder(p) ? p.diameter_m : p.width_m; }
std::optional<double> member_base(const Population& p, const PopulationMember& m) {
  return is_cylinder(p) ? m.diameter_m : m.width_m;
}

RockingBody member_body(const Population& p, double base_m, double height_m) {
  return is_cylinder(p) ? RockingBody::cylinder(base_m, height_m) : RockingBody::block(base_m, height_m);
}

ObservedObject member_object(const Population& p, std::size_t i, double base_m, double height_m) {
  ObservedObject o = p.prototype;
  o.id = fmt::format("{}#{}", p.id, i + 1);
  o.body = member_body(p, base_m, height_m);
  o.height_m = height_m;
  if (is_cylinder(p)) {
    o.diameter_m = base_m;
  } else {
    o.width_m = base_m;
  }
  o.outcome = Outcome::overturned;
  return o;
}

/// The stride of the fixed Latin hypercube: nearest 0.618 K coprime to K (1 for K <= 2).
std::size_t lhs_stride(std::size_t k) {
  if (k <= 2) return 1;
  const auto target = static_cast<std::ptrdiff_t>(std::lround(0.6180339887498949 * static_cast<double>(k)));
  for (std::ptrdiff_t d = 0; d < static_cast<std::ptrdiff_t>(k); ++d) {
    for (const std::ptrdiff_t s : {target - d, target + d}) {
      if (s >= 1 && s < static_cast<std::ptrdiff_t>(k) && std::gcd(static_cast<std::size_t>(s), k) == 1) {
        return static_cast<std::size_t>(s);
      }
    }
  }
  return 1;
}

}  // namespace

void check_population(const Population& p) {
  if (p.shape != "block" && p.shape != "cylinder") {
    throw parameter_error("shape", fmt::format("a population is of blocks or cylinders, not '{}'", p.shape));
  }
  if (p.count < 1) throw parameter_error("count", fmt::format("must be at least 1, got {}", p.count));
  if (p.overturned < 0) throw parameter_error("overturned", fmt::format("must be >= 0, got {}", p.overturned));
  if (p.overturned > p.count) {
    throw parameter_error("overturned", fmt::format("{} overturned of {} counted: more than the count", p.overturned,
                                                    p.count));
  }
  if (p.rocked && *p.rocked < 0) throw parameter_error("rocked", fmt::format("must be >= 0, got {}", *p.rocked));
  if (p.slid && *p.slid < 0) throw parameter_error("slid", fmt::format("must be >= 0, got {}", *p.slid));
  const int moved = p.overturned + p.rocked.value_or(0) + p.slid.value_or(0);
  if (moved > p.count) {
    throw parameter_error(p.slid ? "slid" : "rocked",
                          fmt::format("overturned + rocked + slid = {} is more than the count, {}", moved, p.count));
  }
  if (static_cast<int>(p.fallen_azimuths_deg.size()) > p.overturned) {
    throw parameter_error("fallen_azimuths_deg", fmt::format("{} fall directions for {} overturned",
                                                             p.fallen_azimuths_deg.size(), p.overturned));
  }
  for (const double az : p.fallen_azimuths_deg) {
    if (!(az >= 0.0 && az < 360.0)) {
      throw parameter_error("fallen_azimuths_deg", fmt::format("a direction lies in [0, 360) deg, got {}", az));
    }
  }
  if (p.members < 1 || p.members > kMaxPopulationMembers) {
    throw parameter_error("members", fmt::format("must be 1 to {}, got {}", kMaxPopulationMembers, p.members));
  }
  const auto check_range = [](const char* key, const std::optional<Interval>& r) {
    if (r && !(r->low > 0.0)) throw parameter_error(key, fmt::format("sizes must be positive, got {} m", r->low));
  };
  check_range("height", p.height_m);
  check_range(base_key(p), base_range(p));
  const char* other = is_cylinder(p) ? "width" : "diameter";
  if ((is_cylinder(p) ? p.width_m : p.diameter_m).has_value()) {
    throw parameter_error(other, fmt::format("a population of {}s has no {}", p.shape, other));
  }
  if (p.sample.empty()) {
    if (!p.height_m || !base_range(p)) {
      throw parameter_error(!p.height_m ? "height" : base_key(p),
                            fmt::format("a population needs its sizes: a range for height and {} (or a measured "
                                        "sample = [{{...}}, ...])",
                                        base_key(p)));
    }
    return;
  }
  for (std::size_t i = 0; i < p.sample.size(); ++i) {
    const PopulationMember& m = p.sample[i];
    const auto check = [&](const char* key, const std::optional<double>& v, const std::optional<Interval>& range) {
      const std::string field = fmt::format("sample[{}].{}", i + 1, key);
      if (!v) throw parameter_error(field, fmt::format("a measured {} needs its {}", p.shape, key));
      if (!(*v > 0.0)) throw parameter_error(field, fmt::format("must be positive, got {} m", *v));
      if (range && (*v < range->low || *v > range->high)) {
        throw parameter_error(field, fmt::format("{:.4g} m is outside the population's stated range [{:.4g}, {:.4g}] m", *v,
                                                 range->low, range->high));
      }
    };
    check("height", m.height_m, p.height_m);
    check(base_key(p), member_base(p, m), base_range(p));
    if ((is_cylinder(p) ? m.width_m : m.diameter_m).has_value()) {
      throw parameter_error(fmt::format("sample[{}].{}", i + 1, other),
                            fmt::format("a population of {}s has no {}", p.shape, other));
    }
  }
}

std::vector<ObservedObject> population_members(const Population& p) {
  const auto k = static_cast<std::size_t>(p.members);
  std::vector<ObservedObject> out;
  if (!p.sample.empty()) {
    const std::size_t n = p.sample.size();
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    if (n > k) {
      // Sorted by slenderness b/h (ties by position: deterministic), the middle member of each of K strata.
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return *member_base(p, p.sample[a]) / *p.sample[a].height_m < *member_base(p, p.sample[b]) / *p.sample[b].height_m;
      });
      std::vector<std::size_t> chosen;
      for (std::size_t i = 0; i < k; ++i) {
        chosen.push_back(order[static_cast<std::size_t>((static_cast<double>(i) + 0.5) * static_cast<double>(n) /
                                                        static_cast<double>(k))]);
      }
      order = chosen;
    }
    for (std::size_t i = 0; i < order.size(); ++i) {
      const PopulationMember& m = p.sample[order[i]];
      out.push_back(member_object(p, i, *member_base(p, m), *m.height_m));
    }
    return out;
  }
  const Interval& h = *p.height_m;
  const Interval& b = *base_range(p);
  const std::size_t stride = lhs_stride(k);
  const auto at = [k](const Interval& r, std::size_t stratum) {
    return r.low + (r.high - r.low) * (static_cast<double>(stratum) + 0.5) / static_cast<double>(k);
  };
  for (std::size_t i = 0; i < k; ++i) out.push_back(member_object(p, i, at(b, (i * stride) % k), at(h, i)));
  return out;
}

double population_min_slenderness(const Population& p) {
  if (p.sample.empty()) return base_range(p)->low / p.height_m->high;
  double out = std::numeric_limits<double>::infinity();
  for (const PopulationMember& m : p.sample) out = std::min(out, *member_base(p, m) / *m.height_m);
  return out;
}

double population_log_likelihood(const Population& p, std::span<const double> share) {
  // The categories the survey counts: overturned always, rocked and slid when given; the rest (count minus those)
  // takes every other run's category. Observed n_j, model f_j (the members' shares), J categories with the rest.
  std::vector<double> n_obs{static_cast<double>(p.overturned)};
  std::vector<double> f{share[static_cast<std::size_t>(PopulationCategory::overturned)]};
  if (p.rocked) {
    n_obs.push_back(*p.rocked);
    f.push_back(share[static_cast<std::size_t>(PopulationCategory::rocked)]);
  }
  if (p.slid) {
    n_obs.push_back(*p.slid);
    f.push_back(share[static_cast<std::size_t>(PopulationCategory::slid)]);
  }
  double n_rest = p.count;
  double f_rest = 1.0;
  for (std::size_t j = 0; j < n_obs.size(); ++j) {
    n_rest -= n_obs[j];
    f_rest -= f[j];
  }
  n_obs.push_back(n_rest);
  f.push_back(std::max(0.0, f_rest));
  // Each object's observation is wrong with probability eps (evidence_error_rate), into any of the J categories:
  // p_j = eps + (1 - J eps) f_j, which for J = 2 is the objects' eps + (1 - 2 eps) m (inversion.hpp, item 2).
  const double eps = evidence_error_rate(p.prototype.evidence);
  const auto J = static_cast<double>(f.size());
  // log multinomial: ln N! - sum ln n_j! + sum n_j ln p_j (eq. P1, docs/method.md).
  double ll = std::lgamma(static_cast<double>(p.count) + 1.0);
  for (std::size_t j = 0; j < f.size(); ++j) {
    ll += n_obs[j] * std::log(eps + (1.0 - J * eps) * f[j]) - std::lgamma(n_obs[j] + 1.0);
  }
  return ll;
}

std::string population_member_rule(const Population& p) {
  const std::size_t n = p.sample.size();
  const auto k = static_cast<std::size_t>(p.members);
  if (n > 0 && n <= k) return fmt::format("the measured sample, all {} members", n);
  if (n > k) {
    return fmt::format("{} of the {} measured members: the middle of each of {} strata of slenderness b/h", k, n, k);
  }
  return fmt::format("{} stratified quantiles of the stated ranges (a fixed Latin hypercube, stride {})", k,
                     lhs_stride(k));
}

}  // namespace topple
