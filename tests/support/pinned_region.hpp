#pragma once
// The regional fit with its parameters pinned, for the closed-form tests of the pooled sites (test_region.cpp:
// stations; test_intensity.cpp: intensities).
#include <cmath>
#include <vector>

#include "topple/region/fit.hpp"

namespace topple::test {

/// `st` with its prior box pinned, each parameter a millionth wide, at the relation ln a = c0 - c1 ln rho with scatter
/// tau (docs/method.md eq. R1, rho = hypot(r, c2)): the box is on the reference intercept, c0 - c1 times the sites'
/// mean ln rho, where fit_region centres the relation. With the parameters fixed, each site's pooled PGA is a product
/// of normal densities in ln a (eq. R4), a closed form.
inline RegionalSettings pinned_relation(const std::vector<SiteEvidence>& sites, double c0, double c1, double tau,
                                        RegionalSettings st = {}) {
  double mean_ln_rho = 0.0;
  for (const auto& s : sites) {
    mean_ln_rho += std::log(std::hypot(s.distance_km, st.c2_km)) / static_cast<double>(sites.size());
  }
  const double x = c0 - c1 * mean_ln_rho;
  st.ln_a_ref_min = x;
  st.ln_a_ref_max = x + 1e-6;
  st.c1_min = c1;
  st.c1_max = c1 + 1e-6;
  st.tau_min = tau;
  st.tau_max = tau + 1e-6;
  return st;
}

}  // namespace topple::test
