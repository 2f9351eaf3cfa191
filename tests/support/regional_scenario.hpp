#pragma once
// A synthetic regional earthquake for tests and examples/regional_survey.toml (issue 17): sites around an
// epicentre whose true PGAs follow a stated relation with spatially correlated scatter, and objects whose outcomes
// are computed by the solvers (observation_match: the rocking and sliding solvers) under a motion of the synthetic
// family, with seeds the inversion does not use, scaled to each site's true PGA.
#include <cstdint>
#include <string>
#include <vector>

#include "topple/survey/survey.hpp"

namespace topple::testing {

struct RegionalTruth {
  double c0 = 2.36;   ///< ln(g): 0.5 g at R = 11 km (epicentral 5 km, depth 10 km)
  double c1 = 1.2;
  double c2_km = 6.0;
  double tau = 0.3;   ///< between-site scatter, natural-log units
  /// Jayaram & Baker (2009) exponential correlation of the residuals, rho(h) = exp(-3 h / range_km); for PGA without
  /// clustered Vs30 their range is b = 8.5 km (their eq. 17 at T = 0).
  double range_km = 8.5;
  double freq_hz = 3.0;  ///< the motions' predominant frequency
};

struct RegionalScenario {
  Survey survey;                   ///< sites with lat/lon, [event] epicentre and depth, the inversion's settings
  std::vector<double> true_pga_g;  ///< per site, g
  RegionalTruth truth;
};

/// Inversion settings on a small grid: PGA log-spaced over [pga_min_g, 2 g] with pga_count rows, frequency over
/// [freq_min_hz, freq_max_hz] with freq_count columns, motions_per_cell motions (the rest the defaults).
[[nodiscard]] InversionSettings small_grid(double pga_min_g, int pga_count, double freq_min_hz, double freq_max_hz,
                                           int freq_count, int motions_per_cell);

/// A dozen sites (5-80 km), site 0 an instrument station (its true PGA, 3 digits) with two objects, sites 9-11 with
/// one or two objects only, the others five; `sites` > 12 adds sites 5-80 km out with three objects each (the scale
/// benchmark's survey). `seed` draws the residuals and the objects' choice.
[[nodiscard]] RegionalScenario make_regional_scenario(std::uint64_t seed, const RegionalTruth& truth,
                                                      const InversionSettings& settings, std::size_t sites = 12);

/// The scenario as a survey file (TOML), with a comment block saying how it was made.
[[nodiscard]] std::string regional_survey_toml(const RegionalScenario& scenario, const std::string& command);

}  // namespace topple::testing
