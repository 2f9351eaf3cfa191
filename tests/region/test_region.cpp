// The regional picture (issue 17): geodesic distances, the survey's regional keys, the joint fit against closed
// forms, and the regional recovery test (sites simulated by the solvers).
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/input_errors.hpp"
#include "support/pinned_region.hpp"
#include "support/regional_scenario.hpp"
#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/output/region_output.hpp"
#include "topple/region/region.hpp"

namespace topple {
namespace {

// ---- Distances ----

// GeographicLib's own worked example (example-Geodesic.cpp, Karney 2013): JFK (40.6, -73.8) to LHR (51.6, -0.5) on
// WGS84 is 5551759.400319 m. Tolerance 1 mm: the printed digits go to the micrometre; the algorithm is accurate to
// 15 nm.
TEST(RegionDistance, KarneyJfkToLhr) {
  EXPECT_NEAR(geodesic_distance_km(40.6, -73.8, 51.6, -0.5), 5551.759400319, 1e-6);
}

// One degree of latitude from the equator on WGS84: the meridian arc 110574.3 m (the standard table value, to 0.1 m).
// A sphere of 6371 km gives 111195 m: the test tells the ellipsoid from the haversine.
TEST(RegionDistance, OneDegreeOfLatitudeAtTheEquator) {
  EXPECT_NEAR(geodesic_distance_km(0.0, 10.0, 1.0, 10.0), 110.5743, 1e-4);
  EXPECT_DOUBLE_EQ(geodesic_distance_km(12.0, 34.0, 12.0, 34.0), 0.0);
}

TEST(RegionDistance, HypocentralIsTheHypotenuse) {
  EXPECT_DOUBLE_EQ(hypocentral_distance_km(30.0, 40.0), 50.0);
  EXPECT_DOUBLE_EQ(hypocentral_distance_km(7.0, 0.0), 7.0);
}

// ---- The survey's regional keys ----

const std::string kObject = "[[sites.object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                            "outcome = \"overturned\"\n";

TEST(RegionSurvey, EpicentreDepthAndStations) {
  const Survey s = io::parse_survey("[event]\nepicentre = [38.0, 23.0]\ndepth_km = 12.5\n"
                                    "[[sites]]\nname = \"a\"\nlat = 38.1\nlon = 23.0\n" + kObject +
                                    "[[sites]]\nname = \"station\"\nlat = 38.2\nlon = 23.1\npga_g = 0.31\n"
                                    "[[sites]]\nname = \"station with objects\"\nlat = 38.0\nlon = 23.2\npga_g = 0.2\n" +
                                    kObject,
                                    "r.toml");
  ASSERT_TRUE(s.epicentre_depth_km);
  EXPECT_EQ(*s.epicentre_depth_km, 12.5);
  ASSERT_EQ(s.sites.size(), 3u);
  EXPECT_FALSE(s.sites[0].is_station());
  EXPECT_TRUE(s.sites[1].objects.empty());
  EXPECT_EQ(*s.sites[1].instrument_pga_g, 0.31);
  EXPECT_EQ(s.sites[2].objects.size(), 1u);
  EXPECT_EQ(*s.sites[2].instrument_pga_g, 0.2);
}

// Old surveys keep their meaning: no depth, no instrument, and a site without objects still refused.
TEST(RegionSurvey, OldSurveysUnchanged) {
  const Survey s = io::read_survey(std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples/survey.toml");
  EXPECT_FALSE(s.epicentre_depth_km);
  ASSERT_EQ(s.sites.size(), 1u);
  EXPECT_FALSE(s.sites[0].is_station());
  EXPECT_EQ(s.sites[0].objects.size(), 8u);
  EXPECT_THROW((void)io::parse_survey("[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nname = \"empty\"\n", "s.toml"),
               InputError);
}

// A station given by its record: the measured PGA is the record's peak |a| (a plain file in g whose peak is -0.42 g:
// the sign does not matter), read at the edge by io::read_survey, in g exactly (the file states its unit).
TEST(RegionSurvey, StationRecordGivesItsPeak) {
  test::TempDir tmp;
  test::write_file(tmp.path() / "station.csv", "time_s,accel_g\n0,0\n0.01,0.2\n0.02,-0.42\n0.03,0.1\n0.04,0\n");
  test::write_file(tmp.path() / "r.toml", "[[sites]]\nname = \"a\"\n" + kObject +
                                              "[[sites]]\nname = \"station\"\nrecord = \"station.csv\"\n");
  const Survey s = io::read_survey(tmp.path() / "r.toml");
  ASSERT_TRUE(s.sites[1].instrument_pga_g);
  EXPECT_NEAR(*s.sites[1].instrument_pga_g, 0.42, 1e-12);  // g -> m/s^2 -> g: a few ulps
  EXPECT_EQ(s.sites[1].instrument_record, (tmp.path() / "station.csv").string());
}

// A spreadsheet's CSV survey carries the regional site keys as `site.KEY` rows, read as the TOML they stand for.
TEST(RegionSurvey, CsvSurveyCarriesTheStationPga) {
  const Survey s = io::parse_survey("site.name,station\nsite.lat,38.1\nsite.lon,23.0\nsite.pga_g,0.25\n"
                                    "event.epicentre,\"[38.0, 23.0]\"\nevent.depth_km,8\n"
                                    "id,width_cm,height_cm,mu,outcome\nb,10,40,0.5,overturned\n",
                                    "s.csv");
  ASSERT_TRUE(s.sites[0].instrument_pga_g);
  EXPECT_EQ(*s.sites[0].instrument_pga_g, 0.25);
  EXPECT_EQ(*s.epicentre_depth_km, 8.0);
}

TEST(RegionSurvey, BadRegionalKeysNameTheirField) {
  const auto fails = [](const std::string& text, const std::string& field) {
    try {
      (void)io::parse_survey(text, "s.toml");
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, field) << e.what();
      return;
    }
    ADD_FAILURE() << "no InputError for field " << field;
  };
  fails("[event]\nepicentre = [38.0, 23.0]\ndepth_km = -1\n[[sites]]\n" + kObject, "event.depth_km");
  fails("[event]\ndepth_km = 10\n[[sites]]\n" + kObject, "event.depth_km");
  fails("[event]\nepicentre = [98.0, 23.0]\n[[sites]]\n" + kObject, "event.epicentre");
  fails("[[sites]]\npga_g = -0.1\n" + kObject, "sites[1].pga_g");
  fails("[[sites]]\npga_g = 0.1\nrecord = \"x.AT2\"\n" + kObject, "sites[1].record");
  fails("[[sites]]\nrecord = \"no-such-file.AT2\"\n" + kObject, "sites[1].record");
  fails("[[sites]]\npga_g = 0.1\n[[sites]]\npga_g = 0.2\n", "sites[1].object");  // nothing to invert
}

// ---- The joint fit against closed forms ----

SiteEvidence station(const std::string& name, double r_km, double pga_g) {
  return site_evidence(name, r_km, nullptr, pga_g);
}

// With the parameters pinned (a prior box a millionth wide), a station's pooled PGA is the product of two normal
// densities in ln a (docs/method.md eq. R4): mean (mu sigma^2 + y tau^2) / (tau^2 + sigma^2), sd tau sigma /
// sqrt(tau^2 + sigma^2). Tolerance 0.3 % of the value: the pooled CDF is tabulated at steps of 0.01 in ln a and
// interpolated linearly (error well under a step), the pinned box spans 1e-6.
TEST(RegionFit, PinnedParametersGiveTheClosedFormPooledStation) {
  const double c0 = 2.0, c1 = 1.1, tau = 0.4;
  std::vector<SiteEvidence> sites{station("a", 10, 0.3), station("b", 30, 0.12), station("c", 60, 0.02)};
  const RegionalSettings st = test::pinned_relation(sites, c0, c1, tau);
  const RegionalResult fit = fit_region(sites, st);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    const double mu = c0 - c1 * std::log(std::hypot(sites[s].distance_km, st.c2_km));
    const double y = std::log(*sites[s].instrument_pga_g);
    const double sig = st.instrument_sigma_ln;
    const double m = (mu * sig * sig + y * tau * tau) / (tau * tau + sig * sig);
    const double sd = tau * sig / std::hypot(tau, sig);
    EXPECT_NEAR(fit.sites[s].pga_g.median, std::exp(m), 3e-3 * std::exp(m)) << s;
    EXPECT_NEAR(fit.sites[s].pga_g.ci95_low, std::exp(m - 1.959964 * sd), 3e-3 * std::exp(m)) << s;
    EXPECT_NEAR(fit.sites[s].pga_g.ci95_high, std::exp(m + 1.959964 * sd), 3e-3 * std::exp(m)) << s;
    EXPECT_NEAR(fit.sites[s].relation_pga_g.median, std::exp(mu), 1e-5 * std::exp(mu)) << s;
  }
  EXPECT_NEAR(fit.c0.median, c0, 1e-5);
}

// A site whose likelihood is flat (objects that say nothing) borrows everything: its pooled median is the relation's
// at its distance. Stations exactly on a relation recover it: c1 within 0.05 of the truth (the stations' 5 % noise
// over a lever arm of ln(80/8) = 2.3 gives a c1 sd of about 0.02) and tau's 95 % upper end below 0.15.
TEST(RegionFit, StationsOnTheRelationRecoverItAndAFlatSiteBorrowsIt) {
  const double c0 = 2.4, c1 = 1.3;
  std::vector<SiteEvidence> sites;
  for (double r : {8.0, 12.0, 20.0, 30.0, 45.0, 60.0, 80.0}) {
    sites.push_back(station(fmt::format("s{}", r), r, relation_pga_g(c0, c1, 6.0, r)));
  }
  SiteEvidence flat;
  flat.name = "flat";
  flat.distance_km = 25.0;
  flat.ln_edges = {-std::numeric_limits<double>::infinity(), std::log(0.1), std::numeric_limits<double>::infinity()};
  flat.likelihood = {1.0, 1.0};
  sites.push_back(flat);
  const RegionalResult fit = fit_region(sites);
  EXPECT_NEAR(fit.c1.median, c1, 0.05);
  EXPECT_TRUE(fit.c1.holds95(c1));
  EXPECT_TRUE(fit.c0.holds95(c0));
  EXPECT_LT(fit.tau.ci95_high, 0.15);
  // The flat site: median within 3 % of the relation (1000 draws of theta; tau ~ 0.05 here).
  const double rel = relation_pga_g(c0, c1, 6.0, 25.0);
  EXPECT_NEAR(fit.sites.back().pga_g.median, rel, 0.03 * rel);
}

TEST(RegionFit, NeedsThreeSites) {
  EXPECT_THROW((void)fit_region({station("a", 10, 0.3), station("b", 20, 0.2)}), InputError);
}

// ---- The frequency relation (F1-F3) ----

// A site with a measured PGA (for the PGA relation) and a frequency known to within a narrow cell of width h around
// f_hz (likelihood 1 there, 0 elsewhere): its frequency evidence is h times the normal density at ln f (eq. F2).
SiteEvidence station_with_frequency(const std::string& name, double r_km, double pga_g, double f_hz, double h) {
  SiteEvidence e = station(name, r_km, pga_g);
  const double y = std::log(f_hz);
  e.ln_freq_edges = {-std::numeric_limits<double>::infinity(), y - 0.5 * h, y + 0.5 * h,
                     std::numeric_limits<double>::infinity()};
  e.freq_likelihood = {0.0, 1.0, 0.0};
  return e;
}

// The marginal likelihoods against closed forms (eq. F3) with tau_f pinned (a box 1e-6 wide) and the frequencies
// known to cells h = 0.01 wide: Z0 = h^n (2 pi tau^2)^(-n/2) exp(-S0 / 2 tau^2) sqrt(2 pi tau^2 / n) / V_x with S0 the
// sum of squares about the mean; the relation's ln B = (S0 - RSS) / 2 tau^2 + 1/2 ln(2 pi tau^2 / sum dx^2) - ln V_d1
// (a linear regression's Gaussian integral over (x, d1), dx centred). Tolerance 2e-3 in ln Z: the cell's mass is
// h phi to a relative (h / tau)^2 / 24 = 5e-5 per site, the trapezoid rule on a Gaussian at > 2 points per sd errs
// far less, and the pinned tau moves ln Z by n x 1e-6 / tau.
TEST(RegionFrequency, MarginalLikelihoodsAreTheClosedForms) {
  const double tau = 0.3, h = 0.01;
  RegionalSettings st;
  st.tau_f_min = tau;
  st.tau_f_max = tau + 1e-6;
  const std::vector<double> r{8.0, 15.0, 25.0, 40.0, 60.0, 90.0};
  const std::vector<double> wobble{0.1, -0.2, 0.15, 0.05, -0.1, 0.0};
  std::vector<SiteEvidence> sites;
  std::vector<double> dx, y;
  double mean_ln_rho = 0.0;
  for (double d : r) mean_ln_rho += std::log(std::hypot(d, st.c2_km)) / 6.0;
  for (std::size_t s = 0; s < r.size(); ++s) {
    dx.push_back(std::log(std::hypot(r[s], st.c2_km)) - mean_ln_rho);
    y.push_back(std::log(5.0) - 0.5 * dx.back() + wobble[s]);
    sites.push_back(station_with_frequency(fmt::format("s{}", s), r[s], relation_pga_g(2.0, 1.2, 6.0, r[s]),
                                           std::exp(y.back()), h));
  }
  const RegionalResult fit = fit_region(sites, st);
  ASSERT_TRUE(fit.frequency);
  const double n = 6.0;
  double ybar = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t s = 0; s < 6; ++s) ybar += y[s] / n;
  double s0 = 0.0;
  for (std::size_t s = 0; s < 6; ++s) {
    s0 += (y[s] - ybar) * (y[s] - ybar);
    sxx += dx[s] * dx[s];
    sxy += dx[s] * (y[s] - ybar);
  }
  const double rss = s0 - sxy * sxy / sxx;
  const double two_pi_t2 = 2.0 * std::numbers::pi * tau * tau;
  const double ln_z0 = n * std::log(h) - 0.5 * n * std::log(two_pi_t2) - s0 / (2.0 * tau * tau) +
                       0.5 * std::log(two_pi_t2 / n) - std::log(st.ln_f_ref_max - st.ln_f_ref_min);
  EXPECT_NEAR(fit.frequency->log_evidence_constant, ln_z0, 2e-3);
  const double ln_b = (s0 - rss) / (2.0 * tau * tau) + 0.5 * std::log(two_pi_t2 / sxx) - std::log(st.d1_max - st.d1_min);
  EXPECT_NEAR(fit.frequency->ln_bayes_factor, ln_b, 2e-3);
  // The slope's posterior is the regression's: mean sxy / sxx, sd tau / sqrt(sxx) (the median within 1 % of the sd:
  // the marginal is tabulated on 41 points).
  EXPECT_NEAR(fit.frequency->d1.median, sxy / sxx, 0.01 * tau / std::sqrt(sxx));
  EXPECT_NEAR(fit.frequency->d1.ci95_high - fit.frequency->d1.median, 1.959964 * tau / std::sqrt(sxx),
              0.01 * tau / std::sqrt(sxx) + 0.02 * 1.959964 * tau / std::sqrt(sxx));
}

// A clear trend (d1 = -0.6, scatter 0.05 over a lever arm of 2.4 in ln rho) is supported and every site's frequency
// is pooled through it, a site without frequency evidence (a bare station) at the relation's value; the same sites at
// one frequency are not: B < 3 (the constant model explains them with one parameter fewer).
TEST(RegionFrequency, ATrendIsSupportedAndAConstantIsNot) {
  const std::vector<double> r{6.0, 10.0, 16.0, 25.0, 40.0, 60.0, 90.0};
  const std::vector<double> wobble{0.05, -0.04, 0.02, -0.05, 0.04, -0.02, 0.0};
  const double c2 = RegionalSettings{}.c2_km;
  double mean_ln_rho = 0.0;
  for (double d : r) mean_ln_rho += std::log(std::hypot(d, c2)) / static_cast<double>(r.size() + 1);
  mean_ln_rho += std::log(std::hypot(30.0, c2)) / static_cast<double>(r.size() + 1);  // the bare station below
  const auto sites_for = [&](double d1) {
    std::vector<SiteEvidence> sites;
    for (std::size_t s = 0; s < r.size(); ++s) {
      const double f = std::exp(std::log(4.0) + d1 * (std::log(std::hypot(r[s], c2)) - mean_ln_rho) + wobble[s]);
      sites.push_back(station_with_frequency(fmt::format("s{}", s), r[s], relation_pga_g(2.0, 1.2, c2, r[s]), f, 0.02));
    }
    sites.push_back(station("bare", 30.0, relation_pga_g(2.0, 1.2, c2, 30.0)));
    return sites;
  };
  const RegionalResult trend = fit_region(sites_for(-0.6));
  ASSERT_TRUE(trend.frequency);
  EXPECT_TRUE(trend.frequency->supported);
  EXPECT_GT(trend.frequency->ln_bayes_factor, std::log(100.0));  // a slope 0.6 / 0.05 x 2.4 lever: decisive
  EXPECT_TRUE(trend.frequency->d1.holds95(-0.6));
  EXPECT_EQ(trend.frequency->sites_with_frequency, 7u);
  for (const PooledSite& p : trend.sites) ASSERT_TRUE(p.freq_hz) << p.name;
  // The bare station: its pooled frequency is the relation's prediction at 30 km, 4 Hz x (rho / rho_ref)^-0.6, with
  // the relation's and tau_f's spread (the 95 % interval within +-4 tau_f of the median, and the median within 5 %).
  const double f_bare = 4.0 * std::exp(-0.6 * (std::log(std::hypot(30.0, c2)) - mean_ln_rho));
  EXPECT_NEAR(trend.sites.back().freq_hz->median, f_bare, 0.05 * f_bare);
  EXPECT_NEAR(trend.sites.back().relation_freq_hz->median, f_bare, 0.05 * f_bare);
  // A site known to 0.02 in ln f keeps its own frequency (within 2 %).
  const double f0 = std::exp(std::log(4.0) - 0.6 * (std::log(std::hypot(6.0, c2)) - mean_ln_rho) + 0.05);
  EXPECT_NEAR(trend.sites[0].freq_hz->median, f0, 0.02 * f0);

  const RegionalResult flat = fit_region(sites_for(0.0));
  ASSERT_TRUE(flat.frequency);
  EXPECT_FALSE(flat.frequency->supported);
  EXPECT_LT(flat.frequency->ln_bayes_factor, std::log(3.0));
  EXPECT_NEAR(flat.frequency->constant_f_hz.median, 4.0, 0.05 * 4.0);
  for (const PooledSite& p : flat.sites) EXPECT_FALSE(p.freq_hz) << p.name;
}

// The frequency evidence of a site: its inversion's likelihood summed over the PGA rows (eq. F2), scaled to a maximum
// of 1, on cells with edges at the geometric midpoints of the grid's frequencies (the ends open). Exact to rounding.
TEST(RegionFrequency, SiteEvidenceMarginalisesThePga) {
  InversionResult r;
  r.pga_g = {0.1, 0.2};
  r.freq_hz = {1.0, 4.0, 16.0};
  r.log_likelihood = {std::log(0.1), std::log(0.4), std::log(0.2), std::log(0.3), std::log(0.4), std::log(0.0)};
  const SiteEvidence e = site_evidence("a", 10.0, &r, std::nullopt);
  ASSERT_EQ(e.freq_likelihood.size(), 3u);
  EXPECT_NEAR(e.freq_likelihood[0], 0.4 / 0.8, 1e-12);
  EXPECT_NEAR(e.freq_likelihood[1], 1.0, 1e-12);
  EXPECT_NEAR(e.freq_likelihood[2], 0.2 / 0.8, 1e-12);
  ASSERT_EQ(e.ln_freq_edges.size(), 4u);
  EXPECT_NEAR(e.ln_freq_edges[1], std::log(2.0), 1e-12);
  EXPECT_NEAR(e.ln_freq_edges[2], std::log(8.0), 1e-12);
  EXPECT_TRUE(std::isinf(e.ln_freq_edges[0]) && e.ln_freq_edges[0] < 0);
  EXPECT_TRUE(std::isinf(e.ln_freq_edges[3]) && e.ln_freq_edges[3] > 0);
}

// Fewer than 3 sites with frequency evidence: no frequency relation, a note saying so.
TEST(RegionFrequency, NoneWithoutFrequencyEvidence) {
  const RegionalResult fit = fit_region({station("a", 10, 0.3), station("b", 20, 0.2), station("c", 40, 0.1)});
  EXPECT_FALSE(fit.frequency);
  ASSERT_FALSE(fit.notes.empty());
  EXPECT_NE(fit.notes.back().find("no frequency relation"), std::string::npos);
}

// ---- The pooled field and its contours ----

// A radially symmetric field (the relation alone, no site): the contour at level L is the circle where the relation
// gives L. Every vertex must lie within one grid step (the linear interpolation along a cell edge errs by far less)
// of that radius, measured by the geodesic; the line must close.
TEST(RegionContours, RelationAloneGivesCirclesOfTheRightRadius) {
  PooledField f;
  f.range_km = 8.5;
  const double c0 = 2.0, c1 = 1.2, c2 = 6.0;
  for (int i = 0; i < 101; ++i) {
    f.lat_deg.push_back(37.5 + 0.01 * i);
    f.lon_deg.push_back(22.5 + 0.0127 * i);  // about 1.1 km a step on both axes at 38 N
  }
  for (double la : f.lat_deg) {
    for (double lo : f.lon_deg) f.pga_g.push_back(relation_pga_g(c0, c1, c2, geodesic_distance_km(38.0, 23.14, la, lo)));
  }
  for (double level : {0.2, 0.4}) {
    // Radius where exp(c0 - c1 ln sqrt(R^2 + c2^2)) = level.
    const double rho = std::exp((c0 - std::log(level)) / c1);
    const double radius = std::sqrt(rho * rho - c2 * c2);
    const auto contours = contour_field(f, {level});
    ASSERT_EQ(contours.size(), 1u);
    ASSERT_EQ(contours[0].lines.size(), 1u) << level;
    const auto& line = contours[0].lines[0];
    EXPECT_GT(line.size(), 20u);
    EXPECT_EQ(line.front(), line.back());  // closed
    for (const auto& p : line) EXPECT_NEAR(geodesic_distance_km(38.0, 23.14, p[1], p[0]), radius, 1.1) << level;
  }
}

// Simple kriging with the site's own variance as nugget: near a site with a tiny pooled interval (nugget
// (0.002/3.92)^2, negligible against tau^2 = 0.09) the field keeps the site's residual; 200 km from every site it is
// the relation (the correlation exp(-3 * 200 / 8.5) is 2e-31).
TEST(RegionContours, KrigedFieldHonoursSitesAndFallsBackToTheRelation) {
  Survey survey;
  survey.epicentre_lat_deg = 38.0;
  survey.epicentre_lon_deg = 23.0;
  RegionalResult fit;
  fit.c1 = {1.2, 1.2, 1.2, 1.2, 1.2};
  fit.tau = {0.3, 0.3, 0.3, 0.3, 0.3};
  fit.c2_km = 6.0;
  fit.reference_distance_km = 20.0;
  const double c0 = 2.4;
  fit.ln_a_ref.median = c0 - 1.2 * std::log(20.0);
  for (int s = 0; s < 3; ++s) {
    Site site;
    site.lat_deg = 38.0 + 0.1 * (s + 1);
    site.lon_deg = 23.0;
    survey.sites.push_back(site);
    PooledSite p;
    p.site_index = static_cast<std::size_t>(s);
    p.distance_km = geodesic_distance_km(38.0, 23.0, *site.lat_deg, 23.0);
    const double value = relation_pga_g(c0, 1.2, 6.0, p.distance_km) * (s == 1 ? 1.5 : 0.8);
    p.pga_g = {value, value, value, value * 0.999, value * 1.001};
    fit.sites.push_back(p);
  }
  // At the site: the grid node nearest to it.
  const PooledField g = pooled_field(fit, survey, 8.5, 41);
  const auto nearest = [&](double la, double lo) {
    std::size_t bi = 0, bj = 0;
    for (std::size_t i = 0; i < g.lat_deg.size(); ++i) if (std::abs(g.lat_deg[i] - la) < std::abs(g.lat_deg[bi] - la)) bi = i;
    for (std::size_t j = 0; j < g.lon_deg.size(); ++j) if (std::abs(g.lon_deg[j] - lo) < std::abs(g.lon_deg[bj] - lo)) bj = j;
    return std::pair{bi, bj};
  };
  const auto [i, j] = nearest(*survey.sites[1].lat_deg, 23.0);
  const double d = geodesic_distance_km(g.lat_deg[i], g.lon_deg[j], *survey.sites[1].lat_deg, 23.0);
  ASSERT_LT(d, 0.6);  // the grid passes within 0.6 km of the site
  // Within 0.6 km the correlation is exp(-3 * 0.6 / 8.5) = 0.81: the residual ln 1.5 is kept to within ~20 %.
  const double rel = relation_pga_g(c0, 1.2, 6.0, geodesic_distance_km(38.0, 23.0, g.lat_deg[i], g.lon_deg[j]));
  EXPECT_GT(std::log(g.pga_g[i * g.lon_deg.size() + j] / rel), 0.75 * std::log(1.5));
  // Far away: a site 200 km from all: the relation exactly (to 1e-12 relative).
  Survey far = survey;
  far.epicentre_lat_deg = 36.0;
  const PooledField h = pooled_field(fit, far, 8.5, 3);
  const double r0 = geodesic_distance_km(36.0, 23.0, h.lat_deg[0], h.lon_deg[0]);
  EXPECT_GT(geodesic_distance_km(h.lat_deg[0], h.lon_deg[0], 38.1, 23.0), 200.0);
  EXPECT_NEAR(h.pga_g[0], relation_pga_g(c0, 1.2, 6.0, r0), 1e-12 * h.pga_g[0]);
}

// ---- The command on the example (the README's command) ----

// examples/regional_survey.toml end to end: the JSON gains `region` with the relation, every site pooled beside its
// own estimate, the station's calibration and the contour levels; --map writes the region CSV. The example's truth
// (its header comment) is c1 = 1.2, c0 = 2.36: both must lie in their 95 % intervals, and the station's pooled PGA
// within 10 % of its measured 0.573 g (sigma_i = 5 %, so the 95 % interval spans about +-10 %).
TEST(RegionCli, ExampleRunsEndToEnd) {
  test::TempDir tmp;
  const auto map = tmp.path() / "sites.geojson";
  const auto r = test::run_cli("invert '" + (std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples/regional_survey.toml").string() +
                               "' --json --quiet --map '" + map.string() + "' --report '" + (tmp.path() / "rep").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("region"));
  const auto& region = j.at("region");
  const auto holds = [](const nlohmann::json& v, double x) {
    return v.at("ci95")[0].get<double>() <= x && x <= v.at("ci95")[1].get<double>();
  };
  EXPECT_TRUE(holds(region.at("relation").at("c1"), 1.2));
  EXPECT_TRUE(holds(region.at("relation").at("c0_ln_g"), 2.36));
  EXPECT_EQ(region.at("relation").at("c2_km").get<double>(), 6.0);
  ASSERT_EQ(region.at("sites").size(), 12u);
  const auto& station = region.at("sites")[0];
  EXPECT_EQ(station.at("instrument_pga_g").get<double>(), 0.573);
  EXPECT_NEAR(station.at("pooled_pga_g").at("median").get<double>(), 0.573, 0.1 * 0.573);
  EXPECT_TRUE(station.at("calibration").at("objects_agree").is_boolean());
  EXPECT_TRUE(region.at("sites")[5].at("independent_pga_g").at("median").is_number());
  EXPECT_EQ(region.at("contour_levels_g").size(), 4u);
  // The frequency relation: the example's truth is one frequency (3 Hz) everywhere, so a trend must not be supported
  // (B < 3) and no site gets a pooled frequency; each site's own frequency estimate is given beside.
  const auto& freq = region.at("frequency_relation");
  EXPECT_FALSE(freq.at("supported").get<bool>());
  EXPECT_LT(freq.at("ln_bayes_factor").get<double>(), std::log(3.0));
  EXPECT_EQ(freq.at("sites_with_frequency").get<int>(), 12);
  EXPECT_TRUE(region.at("sites")[5].at("pooled_freq_hz").is_null());
  EXPECT_TRUE(region.at("sites")[5].at("independent_freq_hz").at("median").is_number());
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "sites.region.csv"));
  const auto contours = nlohmann::json::parse(test::slurp(tmp.path() / "sites.contours.geojson"));
  ASSERT_EQ(contours.at("features").size(), 4u);
  EXPECT_EQ(contours["features"][1]["properties"]["pga_g"].get<double>(), 0.1);
  EXPECT_EQ(contours["features"][1]["geometry"]["type"], "MultiLineString");
  EXPECT_GE(contours["features"][1]["geometry"]["coordinates"].size(), 1u);  // the sites span 0.05-0.6 g
  // The regional page: at the report's top, linking every site's page, with both figures inline.
  const std::string page = test::slurp(tmp.path() / "rep" / "index.html");
  for (int i = 1; i <= 12; ++i) {
    EXPECT_NE(page.find(fmt::format("href=\"site{}/index.html\"", i)), std::string::npos) << i;
    EXPECT_TRUE(std::filesystem::exists(tmp.path() / "rep" / fmt::format("site{}", i) / "index.html")) << i;
  }
  EXPECT_NE(page.find("<figure id=\"attenuation\"><svg"), std::string::npos);
  EXPECT_NE(page.find("<figure id=\"map\"><svg"), std::string::npos);
  EXPECT_NE(page.find("calibration: the objects"), std::string::npos);
  EXPECT_NE(page.find("<p id=\"frequency\">Frequency: ln f = d0"), std::string::npos);
  EXPECT_NE(page.find("not supported (&lt; 3)"), std::string::npos);  // the example's truth: one frequency
}

// ---- The regional recovery test ----

// Sites simulated by the solvers (tests/support/regional_scenario.hpp: a true relation with tau = 0.3 and residuals
// correlated as Jayaram & Baker 2009), each site inverted alone (invert_sites), then jointly (fit_survey_region).
// Over the trials: the relation's 95 % intervals (c0, c1, tau) hold the truth in >= 85 %, the pooled sites' in >= 85 %,
// and the pooled intervals are narrower on average than the independent ones (an unconstrained independent end is
// taken at the grid's edge, which flatters the independent interval). TOPPLE_REGION_TRIALS sets the number of trials
// (default 3 here, the ctest variant; scripts/region-recovery.sh runs more).
TEST(RegionRecovery, IntervalsCoverTheTruthAndPoolingNarrowsThem) {
  const char* env = std::getenv("TOPPLE_REGION_TRIALS");
  const int trials = env != nullptr ? std::atoi(env) : 3;
  const InversionSettings st = testing::small_grid(0.01, 20, 2.0, 4.5, 2, 8);
  int rel_hits = 0, rel_checks = 0, site_hits = 0, site_checks = 0;
  double ln_width_pooled = 0.0, ln_width_own = 0.0;
  for (int t = 0; t < trials; ++t) {
    const testing::RegionalTruth truth;
    const testing::RegionalScenario sc = testing::make_regional_scenario(static_cast<std::uint64_t>(100 + t), truth, st);
    const std::vector<InversionResult> own = invert_sites(sc.survey.sites, st);
    std::vector<const InversionResult*> per_site;
    for (const auto& r : own) per_site.push_back(&r);
    std::vector<std::string> notes;
    const auto fit = fit_survey_region(sc.survey, per_site, notes);
    ASSERT_TRUE(fit) << (notes.empty() ? "" : notes.front());
    rel_hits += fit->c0.holds95(truth.c0) + fit->c1.holds95(truth.c1) + fit->tau.holds95(truth.tau);
    rel_checks += 3;
    for (std::size_t s = 0; s < fit->sites.size(); ++s) {
      const std::size_t i = fit->sites[s].site_index;
      const double truth_g = sc.true_pga_g[i];
      if (sc.survey.sites[i].instrument_pga_g) continue;  // a station's pooled PGA is its measurement
      site_hits += fit->sites[s].pga_g.holds95(truth_g);
      ++site_checks;
      ln_width_pooled += std::log(fit->sites[s].pga_g.ci95_high / fit->sites[s].pga_g.ci95_low);
      const Estimate& e = own[i].pga_estimate_g;
      ln_width_own += std::log(e.ci95_high.value_or(st.pga_max_g) / e.ci95_low.value_or(st.pga_min_g));
    }
    fmt::print("trial {}: c0 {:.2f} [{:.2f}, {:.2f}], c1 {:.2f} [{:.2f}, {:.2f}], tau {:.2f} [{:.2f}, {:.2f}]\n", t,
               fit->c0.median, fit->c0.ci95_low, fit->c0.ci95_high, fit->c1.median, fit->c1.ci95_low,
               fit->c1.ci95_high, fit->tau.median, fit->tau.ci95_low, fit->tau.ci95_high);
  }
  fmt::print("relation coverage {}/{}, pooled site coverage {}/{}, mean 95 % width (ln) pooled {:.3f} vs own {:.3f} "
             "(ratio {:.2f})\n",
             rel_hits, rel_checks, site_hits, site_checks, ln_width_pooled / site_checks, ln_width_own / site_checks,
             ln_width_pooled / ln_width_own);
  EXPECT_GE(rel_hits, 0.85 * rel_checks);
  EXPECT_GE(site_hits, 0.85 * site_checks);
  EXPECT_LT(ln_width_pooled, ln_width_own);
}

// Where a survey's sites write their outputs (survey_inversion.hpp): the rule every front end shares.
TEST(SurveyInversion, SiteFoldersAndPathsFollowTheSurveyIndex) {
  Survey one;
  one.sites.resize(1);
  EXPECT_EQ(site_report_folder(one, 0), std::filesystem::path());
  EXPECT_EQ(site_output_path("out/grid.csv", one, 0), std::filesystem::path("out/grid.csv"));
  Survey three;
  three.sites.resize(3);
  EXPECT_EQ(site_report_folder(three, 2), std::filesystem::path("site3"));
  EXPECT_EQ(site_output_path("out/grid.csv", three, 0), std::filesystem::path("out/grid.site1.csv"));
  SurveyInversion inv;
  inv.results.resize(2);
  inv.survey_index = {0, 2};  // site 2 (index 1): a station without objects
  three.sites[2].name = "third";
  const std::vector<const InversionResult*> per_site = inv.per_site(3);
  EXPECT_EQ(per_site[1], nullptr);
  EXPECT_EQ(per_site[2], &inv.results[1]);
  const std::vector<Site> sites = inv.sites_with_objects(three);
  ASSERT_EQ(sites.size(), 2u);
  EXPECT_EQ(sites[1].name, "third");
}

// ---- Issue 31: regional surveys refused at the file, line, field and site ----

/// `text` parsed as survey `name` throws InputError at `line` and `field`, its message holding `says`.
void expect_survey_error(const std::string& text, std::size_t line, const std::string& field, const std::string& says) {
  try {
    (void)io::parse_survey(text, "r.toml");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "r.toml") << e.what();
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(line)) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

// A measured PGA above the records' limit (100 g, GroundMotionLimits) is refused, naming the site; 100 g is kept.
class StationPgaLimit : public ::testing::TestWithParam<const char*> {};

TEST_P(StationPgaLimit, AboveOneHundredGIsRefused) {
  expect_survey_error("[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nname = \"st\"\npga_g = " + GetParam() + "\n",
                      11, "sites[2].pga_g", "at most 100 g (the limit records have), got");
  expect_survey_error("[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nname = \"st\"\npga_g = " + GetParam() + "\n",
                      11, "sites[2].pga_g", "at site 'st'");
}

INSTANTIATE_TEST_SUITE_P(Issue31, StationPgaLimit, ::testing::Values("100.5", "150", "1e6", "1e300"));

TEST(RegionSurvey, StationPgaOfOneHundredGIsKept) {
  const Survey s = io::parse_survey("[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nname = \"st\"\npga_g = 100\n",
                                    "r.toml");
  EXPECT_EQ(s.sites[1].instrument_pga_g, 100.0);
}

// components = 3 estimates RotD50; one record file is one component, whose peak is not RotD50: refused (the station
// gives its RotD50 as pga_g, which is kept).
TEST(RegionSurvey, ThreeComponentSurveyRefusesAOneComponentStationRecord) {
  const std::string head = "[inversion]\ncomponents = 3\n[[sites]]\nname = \"a\"\n" + kObject;
  expect_survey_error(head + "[[sites]]\nname = \"st\"\nrecord = \"station.AT2\"\n", 13, "sites[2].record",
                      "site 'st': a station record is one component");
  const Survey s = io::parse_survey(head + "[[sites]]\nname = \"st\"\npga_g = 0.3\n", "r.toml");
  EXPECT_EQ(s.sites[1].instrument_pga_g, 0.3);
}

// Amplification: (0, 10] (docs/survey.md, "Support amplification"); 1e6 used to fail deep in the inversion with
// "scale: scale factor 1e+06 ..." and no location.
TEST(RegionSurvey, AmplificationAboveTenIsRefusedAtItsLine) {
  const std::string obj = "[[object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\noutcome = \"overturned\"\n";
  expect_survey_error(obj + "amplification = 1e6\n", 7, "object[1](b).amplification", "must lie in (0, 10]");
  expect_survey_error(obj + "amplification = [1, 10.5]\n", 7, "object[1](b).amplification", "got 10.5");
  EXPECT_EQ(io::parse_survey(obj + "amplification = [1, 10]\n", "r.toml").sites[0].objects[0].amplification.high, 10.0);
}

// A zero inertia on a walked (slide-rock) object is named at its line (held on main already; kept as a check).
TEST(RegionSurvey, ZeroInertiaOfAWalkedObjectIsLocated) {
  expect_survey_error("[[object]]\nid = \"b\"\nshape = \"general\"\nb1 = \"5cm\"\nb2 = \"5cm\"\nh = \"20cm\"\n"
                      "inertia = \"0m2\"\nmu = 0.5\noutcome = \"walked\"\n",
                      7, "object[1](b).inertia", "must be > 0");
}

// A station record that cannot be read is named where the survey names it: survey file, line, field, site, then the
// record reader's own message. Non-regular files (a FIFO, a directory, /dev/zero) are refused without reading them.
struct BadRecord {
  const char* name;
  std::string file;  ///< in the temporary folder, or absolute
  std::string says;  ///< from the record reader
};

void PrintTo(const BadRecord& c, std::ostream* os) { *os << c.name; }

class StationRecordErrors : public ::testing::TestWithParam<BadRecord> {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    const auto d = dir_->path();
    test::write_file(d / "trunc.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 090\n"
                                      "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=      8, DT=   .0100 SEC,\n"
                                      "  0.1  -0.2  0.1  0\n 0.1 x\n");
    test::write_file(d / "empty.AT2", "");
    test::write_file(d / "plain.csv", "a,b\n1,2\n3,4\n");
    ::mkfifo((d / "fifo").c_str(), 0600);
    std::filesystem::create_directory(d / "a-directory");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static test::TempDir* dir_;
};
test::TempDir* StationRecordErrors::dir_ = nullptr;

TEST_P(StationRecordErrors, NameSurveyLineFieldAndSite) {
  const BadRecord& c = GetParam();
  const auto survey = dir_->path() / "r.toml";
  test::write_file(survey, "[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nname = \"st\"\n# the station\nrecord = \"" +
                               c.file + "\"\n");
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)io::read_survey(survey);
    ADD_FAILURE() << "accepted " << c.file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, survey.string()) << e.what();
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(12)) << e.what();
    EXPECT_EQ(e.where().field, "sites[2].record") << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find("site 'st'"), std::string::npos) << what;
    EXPECT_NE(what.find(c.says), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

INSTANTIATE_TEST_SUITE_P(
    Issue31, StationRecordErrors,
    ::testing::Values(BadRecord{"truncated", "trunc.AT2", "trunc.AT2:6: acceleration: not a number"},
                      BadRecord{"empty", "empty.AT2", "empty.AT2: the file is empty"},
                      BadRecord{"fifo", "fifo", "is a FIFO"}, BadRecord{"directory", "a-directory", "is a directory"},
                      BadRecord{"dev_zero", "/dev/zero", "is a character device"},
                      // the reader's advice names the survey key, not the CLI option
                      BadRecord{"plain_csv", "plain.csv", "plain.csv:1: a: the first of two columns must be the time"}),
    [](const ::testing::TestParamInfo<BadRecord>& p) { return std::string(p.param.name); });

TEST(RegionSurvey, PlainCsvStationRecordAdviceNamesTheSurveyKey) {
  test::TempDir tmp;
  test::write_file(tmp.path() / "plain.csv", "a,b\n1,2\n3,4\n");
  test::write_file(tmp.path() / "r.toml", "[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nrecord = \"plain.csv\"\n");
  test::expect_input_error([&] { return io::read_survey(tmp.path() / "r.toml"); }, "sites[2].record",
                           "[inversion] record_columns");
}

// inversion.records in a one-site survey (TOML and CSV): the survey's line of the list, the field, the record's error.
TEST(RegionSurvey, InversionRecordErrorsNameTheSurveyLine) {
  test::TempDir tmp;
  test::write_file(tmp.path() / "empty.AT2", "");
  test::write_file(tmp.path() / "s.toml", "[inversion]\nfamily = \"records\"\n\nrecords = [\"empty.AT2\"]\n[[object]]\n"
                                          "id = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\noutcome = \"overturned\"\n");
  try {
    (void)io::read_survey(tmp.path() / "s.toml");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, (tmp.path() / "s.toml").string()) << e.what();
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(4)) << e.what();
    EXPECT_EQ(e.where().field, "inversion.records") << e.what();
    EXPECT_NE(std::string(e.what()).find("empty.AT2: the file is empty"), std::string::npos) << e.what();
  }
  test::write_file(tmp.path() / "s.csv", "# records\ninversion.family,records\ninversion.records,empty.AT2\n"
                                         "id,width,height,mu,outcome\nb,10cm,40cm,0.5,overturned\n");
  try {
    (void)io::read_survey(tmp.path() / "s.csv");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(3)) << e.what();
    EXPECT_EQ(e.where().field, "inversion.records") << e.what();
    EXPECT_NE(std::string(e.what()).find("empty.AT2: the file is empty"), std::string::npos) << e.what();
  }
}

// Through the CLI, as a user meets them: exit 2, "file:line: field:" first, promptly (a FIFO must not block; every
// command runs under a kill timeout so that a hang fails instead of stalling the suite).
TEST(RegionSurvey, CliRefusesIssue31SurveysWithExitTwoAtTheirLine) {
  test::TempDir tmp;
  const auto d = tmp.path();
  ::mkfifo((d / "fifo").c_str(), 0600);
  const std::string two = "[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nname = \"st\"\n";
  test::write_file(d / "fifo.toml", two + "record = \"fifo\"\n");
  test::write_file(d / "huge.toml", two + "pga_g = 1e300\n");
  test::write_file(d / "nul.csv", std::string("id,width,height,mu,outcome\nb\0,10cm,40cm,0.5,overturned\n", 55));
  const std::pair<const char*, std::string> cases[] = {
      {"fifo.toml", "fifo.toml:11: sites[2].record: site 'st': the record"},
      {"huge.toml", "huge.toml:11: sites[2].pga_g: a measured PGA is at most 100 g"},
      {"nul.csv", "nul.csv:2: column A: a NUL byte (\\0)"}};
  for (const auto& [file, says] : cases) {
    const auto start = std::chrono::steady_clock::now();
    const test::CommandResult r = test::run_cli("invert '" + (d / file).string() + "' --quiet", 20);
    EXPECT_EQ(r.exit_code, 2) << file << ": " << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0) << file;
  }
}

// ---- Issue 31: maps near the poles and across the antimeridian ----

/// A regional fit of stations alone (pga_g), around an epicentre, as test_region_map builds one.
struct StationField {
  Survey survey;
  RegionalResult fit;
};

StationField stations_around(double lat0, double lon0, const std::vector<std::array<double, 2>>& where) {
  StationField s;
  s.survey.epicentre_lat_deg = lat0;
  s.survey.epicentre_lon_deg = lon0;
  s.survey.epicentre_depth_km = 10.0;
  double pga = 0.3;
  for (const auto& w : where) {
    Site site;
    site.name = fmt::format("station at {} {}", w[0], w[1]);
    site.lat_deg = w[0];
    site.lon_deg = w[1];
    site.instrument_pga_g = pga;
    pga *= 0.8;
    s.survey.sites.push_back(site);
  }
  std::vector<const InversionResult*> none(s.survey.sites.size(), nullptr);
  std::vector<std::string> notes;
  s.fit = fit_survey_region(s.survey, none, notes).value();
  return s;
}

/// The contours GeoJSON of a fit: every coordinate a finite [lon, lat] with lon in [-180, 180], lat in [-90, 90], and
/// no segment longer than 180 degrees of longitude (a line crossing the antimeridian is cut, RFC 7946 3.1.9). Returns
/// the number of points.
std::size_t check_contours_file(const StationField& s, const std::filesystem::path& file) {
  const PooledField field = pooled_field(s.fit, s.survey);
  for (double v : field.pga_g) EXPECT_TRUE(std::isfinite(v));
  for (double lat : field.lat_deg) EXPECT_LE(std::abs(lat), 90.0);
  // Levels from the field's own range, so that every level has lines.
  double lo = *std::min_element(field.pga_g.begin(), field.pga_g.end());
  double hi = *std::max_element(field.pga_g.begin(), field.pga_g.end());
  std::vector<double> levels;
  for (int k = 1; k <= 3; ++k) levels.push_back(lo * std::pow(hi / lo, k / 4.0));
  io::write_contours_geojson(file, contour_field(field, levels), field);
  const nlohmann::json j = nlohmann::json::parse(test::slurp(file));
  std::size_t points = 0;
  for (const auto& f : j.at("features")) {
    for (const auto& line : f.at("geometry").at("coordinates")) {
      EXPECT_GE(line.size(), 2u);
      for (std::size_t k = 0; k < line.size(); ++k) {
        EXPECT_TRUE(line[k][0].is_number() && line[k][1].is_number()) << line[k];
        if (!line[k][0].is_number() || !line[k][1].is_number()) return points;
        const double lon = line[k][0].get<double>(), lat = line[k][1].get<double>();
        EXPECT_TRUE(std::isfinite(lon) && std::isfinite(lat));
        EXPECT_LE(std::abs(lon), 180.0);
        EXPECT_LE(std::abs(lat), 90.0);
        if (k > 0) {
          EXPECT_LE(std::abs(lon - line[k - 1][0].get<double>()), 180.0) << line;
        }
        ++points;
      }
    }
  }
  return points;
}

// Six stations at latitude 89.9 around an epicentre at the north pole; at -89.95 around the south pole; one station
// at the pole itself. The grid stops at +-90 and spans every longitude (a polar cap): no null reaches the file.
TEST(RegionField, PolarSurveysGiveFiniteContours) {
  test::TempDir tmp;
  const std::vector<double> lons{0, 60, 120, 180, -120, -60};
  for (const double lat : {89.9, -89.95}) {
    std::vector<std::array<double, 2>> where;
    for (double lon : lons) where.push_back({lat, lon});
    SCOPED_TRACE(lat);
    EXPECT_GT(check_contours_file(stations_around(lat > 0 ? 90.0 : -90.0, 0.0, where), tmp.path() / "c.geojson"), 0u);
  }
  std::vector<std::array<double, 2>> with_pole{{90.0, 0.0}};
  for (std::size_t k = 1; k < lons.size(); ++k) with_pole.push_back({89.9, lons[k]});
  SCOPED_TRACE("a station at the pole");
  EXPECT_GT(check_contours_file(stations_around(89.8, 10.0, with_pole), tmp.path() / "c.geojson"), 0u);
}

// Stations on both sides of the antimeridian: the grid is the small box around them (not the whole globe), and the
// file's longitudes stay in [-180, 180] with the lines cut where they cross it.
TEST(RegionField, AntimeridianSurveyIsCutAndNormalised) {
  test::TempDir tmp;
  const StationField s = stations_around(0.0, 180.0, {{0.1, 179.95}, {-0.1, 179.9}, {0.05, -179.95}, {-0.05, -179.9},
                                                       {0.2, 179.8}, {-0.2, -179.8}});
  const PooledField field = pooled_field(s.fit, s.survey);
  EXPECT_LT(field.lon_deg.back() - field.lon_deg.front(), 2.0);  // 0.4 degrees of sites, padded by 10 km a side
  EXPECT_GT(check_contours_file(s, tmp.path() / "c.geojson"), 0u);
  const nlohmann::json j = nlohmann::json::parse(test::slurp(tmp.path() / "c.geojson"));
  bool east = false, west = false;
  for (const auto& f : j.at("features")) {
    for (const auto& line : f.at("geometry").at("coordinates")) {
      for (const auto& p : line) {
        east = east || p[0].get<double>() > 179.0;
        west = west || p[0].get<double>() < -179.0;
      }
    }
  }
  EXPECT_TRUE(east && west);
}

// The cut itself, against hand-computed points: from (179, 0) to (181, 2) crosses 180 at latitude 1; a line that
// crosses twice (there and back) gives three pieces; one that does not cross comes back whole, wrapped.
TEST(RegionField, SplitAtTheAntimeridianInterpolatesTheCrossing) {
  using L = std::vector<std::array<double, 2>>;
  const auto one = split_at_antimeridian(L{{179.0, 0.0}, {181.0, 2.0}});
  ASSERT_EQ(one.size(), 2u);
  EXPECT_EQ(one[0], (L{{179.0, 0.0}, {180.0, 1.0}}));
  EXPECT_EQ(one[1], (L{{-180.0, 1.0}, {-179.0, 2.0}}));
  const auto back = split_at_antimeridian(L{{178.0, 0.0}, {182.0, 4.0}, {178.0, 8.0}});
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[1], (L{{-180.0, 2.0}, {-178.0, 4.0}, {-180.0, 6.0}}));
  EXPECT_EQ(back[2], (L{{180.0, 6.0}, {178.0, 8.0}}));
  const auto west = split_at_antimeridian(L{{-179.5, 0.0}, {-180.5, 1.0}});
  ASSERT_EQ(west.size(), 2u);
  EXPECT_EQ(west[0], (L{{-179.5, 0.0}, {-180.0, 0.5}}));
  EXPECT_EQ(west[1], (L{{180.0, 0.5}, {179.5, 1.0}}));
  EXPECT_EQ(split_at_antimeridian(L{{190.0, 0.0}, {200.0, 1.0}}), (std::vector<L>{L{{-170.0, 0.0}, {-160.0, 1.0}}}));
}

// ---- Issue 31: provenance once per output ----

// A regional survey's JSON holds the survey text once, at the top level; each site keeps the small fields (equal to
// the top level's) and a JSON pointer to the text, never a copy of it.
TEST(RegionJson, ProvenanceOnceAtTheTopLevel) {
  test::TempDir tmp;
  std::string text = "[event]\nepicentre = [38, 23]\ndepth_km = 10\n[inversion]\npga_g = [0.05, 2, 3]\n"
                     "freq_hz = [1, 5, 2]\nmotions_per_cell = 1\n";
  for (int k = 0; k < 3; ++k) {
    text += fmt::format("[[sites]]\nname = \"s{}\"\nlat = {}\nlon = {}\n", k, 38.05 + 0.05 * k, 23.0 + 0.04 * k) + kObject;
  }
  test::write_file(tmp.path() / "r.toml", text);
  const nlohmann::json j = test::run_json("invert '" + (tmp.path() / "r.toml").string() + "' --json --quiet --no-next-objects");
  ASSERT_TRUE(j.contains("provenance")) << j.dump().substr(0, 400);
  const auto& top = j.at("provenance");
  EXPECT_EQ(top.at("survey_text").get<std::string>(), text);
  const std::string dumped = j.dump();
  EXPECT_EQ(dumped.find("epicentre = [38, 23]"), dumped.rfind("epicentre = [38, 23]"));  // the text once
  ASSERT_EQ(j.at("sites").size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& p = j.at("sites")[k].at("provenance");
    EXPECT_FALSE(p.contains("survey_text"));
    EXPECT_EQ(p.at("survey_text_at"), "#/provenance/survey_text");
    EXPECT_EQ(p.at("site"), fmt::format("s{}", k));
    for (const char* key : {"topple_version", "git_commit", "date_utc", "command_line", "survey_file", "survey_xxh3_64"}) {
      EXPECT_EQ(p.at(key), top.at(key)) << key;
    }
  }
}

}  // namespace
}  // namespace topple