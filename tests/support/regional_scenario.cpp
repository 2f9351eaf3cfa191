#include "regional_scenario.hpp"

#include <cmath>
#include <algorithm>
#include <numbers>
#include <random>

#include <fmt/format.h>

#include "topple/inversion/inversion.hpp"
#include "topple/region/region.hpp"

namespace topple::testing {
namespace {

struct Template {
  const char* id;
  const char* description;
  double width_m, height_m, mu;
  bool sliding;  ///< judged by sliding (slid / not_slid) rather than rocking
};

// Thresholds g b/h (rocking) or mu g (sliding) from 0.05 g to 0.6 g, so that every site's PGA has objects on both
// sides of it.
const Template kTemplates[] = {
    {"candle", "Slender candle", 0.02, 0.40, 0.6, false},    // b/h = 0.05
    {"vase", "Tall thin vase", 0.04, 0.40, 0.6, false},      // 0.10
    {"bottle", "Wine bottle", 0.06, 0.40, 0.6, false},       // 0.15
    {"frame", "Standing frame", 0.05, 0.20, 0.6, false},     // 0.25
    {"books", "Stack of books", 0.12, 0.30, 0.7, false},     // 0.40
    {"box", "Wooden box", 0.18, 0.30, 0.8, false},           // 0.60
    {"pan", "Pan on a tiled floor", 0.30, 0.10, 0.08, true},  // mu 0.08
    {"chair", "Plastic chair on tiles", 0.45, 0.80, 0.18, true},  // mu 0.18 (b/h 0.56: it slides before it rocks)
    {"table", "Light table", 0.60, 0.75, 0.35, true},        // mu 0.35
};

ObservedObject make_object(const Template& t, int site) {
  ObservedObject o;
  o.id = fmt::format("{}-{}", t.id, site + 1);
  o.description = t.description;
  o.width_m = t.width_m;
  o.height_m = t.height_m;
  o.body = RockingBody::block(t.width_m, t.height_m);
  o.mu = Interval{t.mu, t.mu};
  o.outcome = t.sliding ? Outcome::slid : Outcome::overturned;
  return o;
}

/// The observed outcome: the one whose match under the site's true motion is 1 (observation_match runs the solver).
void observe(ObservedObject& o, bool sliding, const GroundMotion& motion, double g) {
  const DrawnParameters p{o.mu.low, 0.0, 1.0, 0.0, 0.0};
  const auto matches = [&](Outcome outcome) {
    o.outcome = outcome;
    return observation_match(o, p, motion, g) > 0.5;
  };
  if (sliding) {
    if (!matches(Outcome::slid)) o.outcome = Outcome::not_slid;
    return;
  }
  if (matches(Outcome::overturned)) return;
  if (matches(Outcome::rocked)) return;
  o.outcome = Outcome::not_rocked;
}

}  // namespace

InversionSettings small_grid(double pga_min_g, int pga_count, double freq_min_hz, double freq_max_hz, int freq_count,
                             int motions_per_cell) {
  InversionSettings st;
  st.pga_min_g = pga_min_g;
  st.pga_max_g = 2.0;
  st.pga_count = pga_count;
  st.freq_min_hz = freq_min_hz;
  st.freq_max_hz = freq_max_hz;
  st.freq_count = freq_count;
  st.motions_per_cell = motions_per_cell;
  return st;
}

RegionalScenario make_regional_scenario(std::uint64_t seed, const RegionalTruth& truth, const InversionSettings& st,
                                        std::size_t sites) {
  RegionalScenario sc;
  sc.truth = truth;
  Survey& s = sc.survey;
  s.inversion = st;
  s.epicentre_lat_deg = 38.00;
  s.epicentre_lon_deg = 23.00;
  s.epicentre_depth_km = 10.0;
  const double epi_km[12] = {8, 5, 12, 18, 25, 33, 42, 52, 65, 15, 38, 80};
  const double az_deg[12] = {20, 200, 110, 300, 45, 160, 250, 340, 80, 275, 10, 190};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const std::size_t n = sites;
  // Beyond the dozen: 5-80 km by the golden ratio's fractional parts, azimuths by the golden angle (deterministic,
  // spread out).
  const auto epi_of = [&](std::size_t i) {
    return i < 12 ? epi_km[i] : 5.0 + 75.0 * std::fmod(static_cast<double>(i) * 0.6180339887498949, 1.0);
  };
  const auto az_of = [&](std::size_t i) { return i < 12 ? az_deg[i] : std::fmod(static_cast<double>(i) * 137.50776, 360.0); };
  // Site positions by a local flat-Earth offset (inputs only: distances are then measured by the geodesic).
  for (std::size_t i = 0; i < n; ++i) {
    Site site;
    site.name = fmt::format("site {:02d}", i + 1);
    const double az = az_of(i) * std::numbers::pi / 180.0;
    site.lat_deg = std::round((*s.epicentre_lat_deg + epi_of(i) * std::cos(az) / 111.2) * 1e4) / 1e4;
    site.lon_deg = std::round((*s.epicentre_lon_deg +
                               epi_of(i) * std::sin(az) / (111.2 * std::cos(*s.epicentre_lat_deg * std::numbers::pi / 180.0))) *
                              1e4) /
                   1e4;
    s.sites.push_back(site);
  }
  // Residuals with the exponential spatial correlation (Cholesky of the correlation matrix).
  std::vector<double> dist(n);
  std::vector<std::vector<double>> c(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    dist[i] = hypocentral_distance_km(geodesic_distance_km(*s.epicentre_lat_deg, *s.epicentre_lon_deg,
                                                           *s.sites[i].lat_deg, *s.sites[i].lon_deg),
                                      *s.epicentre_depth_km);
    for (std::size_t j = 0; j < n; ++j) {
      const double h = geodesic_distance_km(*s.sites[i].lat_deg, *s.sites[i].lon_deg, *s.sites[j].lat_deg,
                                            *s.sites[j].lon_deg);
      c[i][j] = std::exp(-3.0 * h / truth.range_km);
    }
  }
  std::vector<std::vector<double>> l(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      double sum = c[i][j];
      for (std::size_t k = 0; k < j; ++k) sum -= l[i][k] * l[j][k];
      l[i][j] = i == j ? std::sqrt(sum) : sum / l[j][j];
    }
  }
  std::vector<double> z(n);
  for (double& v : z) v = normal(rng);
  InversionSettings truth_settings = st;
  truth_settings.family = MotionFamily::synthetic;
  truth_settings.motions_per_cell = 1;
  for (std::size_t i = 0; i < n; ++i) {
    double delta = 0.0;
    for (std::size_t k = 0; k <= i; ++k) delta += l[i][k] * z[k];
    const double pga = relation_pga_g(truth.c0, truth.c1, truth.c2_km, dist[i]) * std::exp(truth.tau * delta);
    sc.true_pga_g.push_back(pga);
    // The site's motion: the synthetic family at a seed the inversion does not use, scaled to the true PGA.
    truth_settings.seed = 1000003 * (seed + 1) + i;
    const GroundMotion motion = family_motions(truth_settings, truth.freq_hz).front().scaled(pga * st.g_m_s2);
    const std::size_t count = i >= 12 ? 3 : (i == 0 ? 2 : (i >= 9 ? (i == 10 ? 2 : 1) : 5));
    std::vector<std::size_t> order(std::size(kTemplates));
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t k = 0; k < count; ++k) {
      const Template& t = kTemplates[order[k]];
      ObservedObject o = make_object(t, static_cast<int>(i));
      observe(o, t.sliding, motion, st.g_m_s2);
      s.sites[i].objects.push_back(o);
    }
  }
  s.sites[0].instrument_pga_g = std::round(sc.true_pga_g[0] * 1000.0) / 1000.0;
  s.sites[0].name = "site 01 (instrument station)";
  return sc;
}

std::string regional_survey_toml(const RegionalScenario& sc, const std::string& command) {
  const Survey& s = sc.survey;
  const InversionSettings& st = s.inversion;
  std::string t;
  const std::string count = s.sites.size() == 12 ? std::string("twelve") : fmt::format("{}", s.sites.size());
  t += "# A SYNTHETIC regional survey (issue 17): " + count + " sites around one epicentre, made by\n#   " + command + "\n";
  t += fmt::format("# True relation: ln PGA = {} - {} ln sqrt(R^2 + {}^2) + delta, tau = {}, residuals correlated as\n"
                   "# exp(-3 h / {} km) (Jayaram & Baker 2009); each object's outcome computed by the solvers under a\n"
                   "# synthetic motion ({} Hz) scaled to its site's true PGA. True PGAs (g), site by site:\n#  ",
                   sc.truth.c0, sc.truth.c1, sc.truth.c2_km, sc.truth.tau, sc.truth.range_km, sc.truth.freq_hz);
  for (double p : sc.true_pga_g) t += fmt::format(" {:.3f}", p);
  t += "\n# Run:  topple invert examples/regional_survey.toml --report out/region --json > out/region.json\n\n";
  t += fmt::format("[event]\nepicentre = [{}, {}]\ndepth_km = {}\n\n", *s.epicentre_lat_deg, *s.epicentre_lon_deg,
                   *s.epicentre_depth_km);
  t += fmt::format("[inversion]\npga_g = [{}, {}, {}]\nfreq_hz = [{}, {}, {}]\nmotions_per_cell = {}\nseed = {}\n",
                   st.pga_min_g, st.pga_max_g, st.pga_count, st.freq_min_hz, st.freq_max_hz, st.freq_count,
                   st.motions_per_cell, st.seed);
  for (const Site& site : s.sites) {
    t += fmt::format("\n[[sites]]\nname = \"{}\"\nlat = {}\nlon = {}\n", site.name, *site.lat_deg, *site.lon_deg);
    if (site.instrument_pga_g) t += fmt::format("pga_g = {}   # measured by an accelerograph\n", *site.instrument_pga_g);
    for (const ObservedObject& o : site.objects) {
      t += fmt::format("\n[[sites.object]]\nid = \"{}\"\ndescription = \"{}\"\nshape = \"block\"\nwidth = \"{:g}cm\"\n"
                       "height = \"{:g}cm\"\nmu = {}\noutcome = \"{}\"\n",
                       o.id, o.description, *o.width_m * 100.0, *o.height_m * 100.0, o.mu.low, outcome_name(o.outcome));
    }
  }
  return t;
}

}  // namespace topple::testing
