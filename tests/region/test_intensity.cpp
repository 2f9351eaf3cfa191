// Macroseismic intensity as PGA evidence (issue 30; topple/region/intensity.hpp, docs/method.md "Macroseismic
// intensity").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "support/pinned_region.hpp"
#include "support/regional_scenario.hpp"
#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/region/intensity.hpp"
#include "topple/region/region.hpp"

namespace topple {
namespace {

// WGRW12 against a peer implementation's published values: ShakeMap 4's test of its WGRW12 (usgs/shakemap,
// tests/shakelib/gmice/wgrw12_test.py, getMIfromGM for PGA without distance and magnitude, and getGMfromMI). ShakeMap
// converts g to cm/s^2 with 981, topple with 980.665 (standard gravity): the PGA differs by 0.034 %, the MMI by at
// most 3.70 x log10(981 / 980.665) = 0.0005; tolerances 0.002 MMI and 0.1 % of the PGA.
TEST(IntensityConversion, Wgrw12MatchesShakeMapsPublishedValues) {
  const double pga_g[] = {0.01, 0.03, 0.1, 0.2, 0.3, 0.4, 0.5};
  const double mmi[] = {3.31708696, 4.05662491, 5.76917533, 6.88298631, 7.53452397, 7.9967973, 8.35536434};
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(wgrw12_mmi_from_pga_g(pga_g[i]), mmi[i], 2e-3) << pga_g[i];
  const double mmi_in[] = {2.0, 3.0, 4.0, 5.0, 6.2, 7.3, 8.1};
  const double pga_pct_g[] = {0.14134045, 0.6243495, 2.75796695, 6.19604804, 13.07492182, 25.92605261, 42.65329774};
  for (int i = 0; i < 7; ++i) {
    // In % g on ShakeMap's 981 cm/s^2 per g (its test lists % g).
    const double pct = wgrw12_pga_g_from_mmi(mmi_in[i]) * 100.0 * 980.665 / 981.0;
    EXPECT_NEAR(pct, pga_pct_g[i], 1e-6 * pga_pct_g[i]) << mmi_in[i];
  }
}

// The relation's own shape (eqs. I1-I2): the inverse undoes the forward relation on each segment (exactly, away from
// the knee: t1 = 1.57 log10 cm/s^2 is MMI 4.2135 by the lower segment and 4.209 by the upper, against t2 = 4.22:
// WGRW12's rounded coefficients leave the knees 0.01 MMI apart, which none of these values falls between).
TEST(IntensityConversion, InverseUndoesForwardOnEachSegment) {
  for (const double m : {1.0, 2.5, 4.0, 4.5, 6.0, 8.0, 10.0}) {
    EXPECT_NEAR(wgrw12_mmi_from_pga_g(wgrw12_pga_g_from_mmi(m)), m, 1e-9) << m;
  }
  // Upper segment: MMI 8 is 10^((8 + 1.60) / 3.70) cm/s^2 = 393.5 cm/s^2 = 0.4013 g.
  EXPECT_NEAR(wgrw12_pga_g_from_mmi(8.0), std::pow(10.0, 9.6 / 3.7) / 980.665, 1e-12);
  EXPECT_NEAR(wgrw12_pga_g_from_mmi(8.0), 0.4013, 1e-3);
}

// Eq. I3: ShakeMap's few-reports term, 0.25 exp(-n / 24.02) + 0.29 (0.5298 for one report, 0.29 in the limit), and
// its propagation through the segment's slope: MMI 7 from 12 reports is sigma_I = 0.25 exp(-12 / 24.02) + 0.29 =
// 0.44170, on the upper segment (c4 = 3.70): sigma_ln = ln 10 x sqrt(0.35^2 + (0.44170 / 3.70)^2) = 0.85149.
TEST(IntensityConversion, SigmaWidensForFewReports) {
  EXPECT_NEAR(intensity_sigma_for_reports(1), 0.25 * std::exp(-1.0 / 24.02) + 0.29, 1e-12);
  EXPECT_NEAR(intensity_sigma_for_reports(1), 0.52981, 1e-5);
  EXPECT_NEAR(intensity_sigma_for_reports(100000), 0.29, 1e-9);
  SiteIntensity in{7.0, IntensityScale::mmi, 12};
  const IntensityPga p = intensity_pga(in);
  EXPECT_NEAR(p.sigma_intensity, 0.44170, 1e-5);
  EXPECT_NEAR(p.sigma_ln, 0.85149, 1e-4);
  EXPECT_NEAR(p.pga_g, std::pow(10.0, 8.6 / 3.7) / 980.665, 1e-12);
  // Fewer reports: wider; the lower segment (MMI 4, slope 1 / 1.55): wider still.
  EXPECT_GT(intensity_pga({7.0, IntensityScale::mmi, 1}).sigma_ln, p.sigma_ln);
  EXPECT_GT(intensity_pga({4.0, IntensityScale::mmi, 12}).sigma_ln, p.sigma_ln);
  // No stated number of reports counts as one.
  EXPECT_DOUBLE_EQ(intensity_pga({7.0, IntensityScale::mmi, std::nullopt}).sigma_ln,
                   intensity_pga({7.0, IntensityScale::mmi, 1}).sigma_ln);
  // EMS-98 is taken as MMI (Musson et al. 2010); above X a flag says the value is extrapolated.
  EXPECT_DOUBLE_EQ(intensity_pga({7.0, IntensityScale::ems98, 12}).pga_g, p.pga_g);
  EXPECT_FALSE(p.extrapolated);
  EXPECT_TRUE(intensity_pga({11.0, IntensityScale::mmi, 12}).extrapolated);
}

// Agreement (objects against an intensity): the two 95 % intervals overlap; an open end counts as open.
TEST(IntensityConversion, AgreementIsOverlapOfTheIntervals) {
  const IntensityPga p = intensity_pga({7.0, IntensityScale::mmi, 12});  // 0.215 g, 95 %: 0.041 - 1.14 g
  Estimate e;
  e.ci95_low = 0.3;
  e.ci95_high = 0.6;
  EXPECT_TRUE(objects_agree_with_intensity(e, p));
  e.ci95_low = 1.5;
  e.ci95_high = 2.0;
  EXPECT_FALSE(objects_agree_with_intensity(e, p));
  e.ci95_high.reset();  // above 1.5 g, open above: still apart
  EXPECT_FALSE(objects_agree_with_intensity(e, p));
  e.ci95_low = 0.01;
  e.ci95_high = 0.03;
  EXPECT_FALSE(objects_agree_with_intensity(e, p));
  e.ci95_low.reset();  // below 0.03 g
  EXPECT_FALSE(objects_agree_with_intensity(e, p));
  e.ci95_high.reset();  // nothing constrained: no disagreement
  EXPECT_TRUE(objects_agree_with_intensity(e, p));
  EXPECT_NEAR(p.ci95_low_g(), p.pga_g * std::exp(-1.959963984540054 * p.sigma_ln), 1e-12);
}

// ---- The survey's intensity keys ----

const std::string kObject = "[[sites.object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                            "outcome = \"overturned\"\n";

// An intensity site may have no objects (it enters the regional fit only); one with objects carries both; the scale
// defaults to MMI and the reports to "not stated".
TEST(IntensitySurvey, SitesCarryTheirIntensity) {
  const Survey s = io::parse_survey("[event]\nepicentre = [38.0, 23.0]\n"
                                    "[[sites]]\nname = \"a\"\nlat = 38.1\nlon = 23.0\n" + kObject +
                                    "[[sites]]\nname = \"felt\"\nlat = 38.2\nlon = 23.1\nintensity = 6.5\n"
                                    "intensity_scale = \"EMS-98\"\nintensity_reports = 12\n"
                                    "[[sites]]\nname = \"both\"\nlat = 38.0\nlon = 23.2\nintensity = 7\n" + kObject,
                                    "r.toml");
  ASSERT_EQ(s.sites.size(), 3u);
  EXPECT_FALSE(s.sites[0].intensity);
  ASSERT_TRUE(s.sites[1].intensity);
  EXPECT_TRUE(s.sites[1].objects.empty());
  EXPECT_EQ(s.sites[1].intensity->value, 6.5);
  EXPECT_EQ(s.sites[1].intensity->scale, IntensityScale::ems98);
  EXPECT_EQ(s.sites[1].intensity->reports, 12);
  ASSERT_TRUE(s.sites[2].intensity);
  EXPECT_EQ(s.sites[2].intensity->value, 7.0);
  EXPECT_EQ(s.sites[2].intensity->scale, IntensityScale::mmi);
  EXPECT_FALSE(s.sites[2].intensity->reports);
  EXPECT_EQ(s.sites[2].objects.size(), 1u);
}

// A one-site survey ([site]) and a spreadsheet's CSV survey (site.KEY rows) carry the same keys.
TEST(IntensitySurvey, OneSiteAndCsvSurveys) {
  const Survey t = io::parse_survey("[site]\nname = \"x\"\nintensity = 8\nintensity_scale = \"MMI\"\n"
                                    "intensity_reports = 3\n[[object]]\nid = \"b\"\nwidth = \"10cm\"\n"
                                    "height = \"40cm\"\nmu = 0.5\noutcome = \"overturned\"\n",
                                    "s.toml");
  ASSERT_TRUE(t.sites[0].intensity);
  EXPECT_EQ(t.sites[0].intensity->value, 8.0);
  EXPECT_EQ(t.sites[0].intensity->reports, 3);
  const Survey c = io::parse_survey("site.name,x\nsite.intensity,7.5\nsite.intensity_scale,EMS-98\n"
                                    "site.intensity_reports,12\nid,width_cm,height_cm,mu,outcome\n"
                                    "b,10,40,0.5,overturned\n",
                                    "s.csv");
  ASSERT_TRUE(c.sites[0].intensity);
  EXPECT_EQ(c.sites[0].intensity->value, 7.5);
  EXPECT_EQ(c.sites[0].intensity->scale, IntensityScale::ems98);
  EXPECT_EQ(c.sites[0].intensity->reports, 12);
}

// Bad intensities are refused with the file, the line and the field (TOML and CSV).
TEST(IntensitySurvey, BadIntensitiesNameFileLineAndField) {
  const auto fails = [](const std::string& text, const std::string& name, std::size_t line, const std::string& field) {
    try {
      (void)io::parse_survey(text, name);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, name) << e.what();
      EXPECT_EQ(e.where().line, line) << e.what();
      EXPECT_EQ(e.where().field.substr(0, field.size()), field) << e.what();
      return;
    }
    ADD_FAILURE() << "no InputError for field " << field;
  };
  const std::string head = "[[sites]]\nname = \"a\"\n" + kObject + "[[sites]]\nname = \"felt\"\n";  // line 11 next
  fails(head + "intensity = 0.5\n", "s.toml", 11, "sites[2].intensity");
  fails(head + "intensity = 12.5\n", "s.toml", 11, "sites[2].intensity");
  fails(head + "intensity = 7\nintensity_reports = -3\n", "s.toml", 12, "sites[2].intensity_reports");
  fails(head + "intensity = 7\nintensity_reports = 0\n", "s.toml", 12, "sites[2].intensity_reports");
  fails(head + "intensity = 7\nintensity_reports = 2.5\n", "s.toml", 12, "sites[2].intensity_reports");
  fails(head + "intensity = 7\nintensity_scale = \"Rossi-Forel\"\n", "s.toml", 12, "sites[2].intensity_scale");
  fails(head + "intensity = 7\nintensity_scale = \"JMA\"\n", "s.toml", 12, "sites[2].intensity_scale");
  fails(head + "intensity = \"VII\"\n", "s.toml", 11, "sites[2].intensity");
  fails(head + "intensity_reports = 4\n", "s.toml", 11, "sites[2].intensity_reports");
  fails(head + "intensity_scale = \"MMI\"\n", "s.toml", 11, "sites[2].intensity_scale");
  fails("site.name,x\nsite.intensity,13\nid,width_cm,height_cm,mu,outcome\nb,10,40,0.5,overturned\n", "s.csv", 2,
        "site.intensity");
  fails("site.name,x\nsite.intensity,7\nsite.intensity_reports,-2\nid,width_cm,height_cm,mu,outcome\n"
        "b,10,40,0.5,overturned\n",
        "s.csv", 3, "site.intensity_reports");
  fails("site.name,x\nsite.intensity,7\nsite.intensity_scale,JMA\nid,width_cm,height_cm,mu,outcome\n"
        "b,10,40,0.5,overturned\n",
        "s.csv", 3, "site.intensity_scale");
}

// ---- The joint fit with intensity sites ----

SiteEvidence felt(const std::string& name, double r_km, double mmi, int reports) {
  return site_evidence(name, r_km, nullptr, std::nullopt, SiteIntensity{mmi, IntensityScale::mmi, reports});
}

// With the parameters pinned (a prior box a millionth wide), an intensity site's pooled PGA is the product of the
// relation's normal N(mu, tau^2) and the intensity's N(ln a_I, sigma_I^2) in ln a (docs/method.md eq. R4 with the
// intensity's own sigma, eq. I3); a site with an instrument and an intensity, the product of three. Tolerance as the
// stations' closed-form test (tests/region/test_region.cpp): 0.3 % of the value.
TEST(IntensityFit, PinnedParametersGiveTheClosedFormPooledSite) {
  const double c0 = 2.0, c1 = 1.1, tau = 0.4;
  std::vector<SiteEvidence> sites{felt("a", 10, 8.2, 30), felt("b", 30, 6.1, 2), felt("c", 60, 3.5, 1)};
  sites.push_back(site_evidence("d", 20, nullptr, 0.25, SiteIntensity{7.0, IntensityScale::mmi, 5}));
  const RegionalSettings st = test::pinned_relation(sites, c0, c1, tau);
  const RegionalResult fit = fit_region(sites, st);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    const double mu = c0 - c1 * std::log(std::hypot(sites[s].distance_km, st.c2_km));
    ASSERT_TRUE(sites[s].intensity);
    const double y_i = std::log(wgrw12_pga_g_from_mmi(sites[s].intensity->intensity.value));
    const double sig_i = sites[s].intensity->sigma_ln;
    // Precisions add; the mean is precision-weighted.
    double prec = 1.0 / (tau * tau) + 1.0 / (sig_i * sig_i);
    double wsum = mu / (tau * tau) + y_i / (sig_i * sig_i);
    if (sites[s].instrument_pga_g) {
      const double sig = st.instrument_sigma_ln;
      prec += 1.0 / (sig * sig);
      wsum += std::log(*sites[s].instrument_pga_g) / (sig * sig);
    }
    const double m = wsum / prec, sd = 1.0 / std::sqrt(prec);
    EXPECT_NEAR(fit.sites[s].pga_g.median, std::exp(m), 3e-3 * std::exp(m)) << s;
    EXPECT_NEAR(fit.sites[s].pga_g.ci95_low, std::exp(m - 1.959964 * sd), 3e-3 * std::exp(m)) << s;
    EXPECT_NEAR(fit.sites[s].pga_g.ci95_high, std::exp(m + 1.959964 * sd), 3e-3 * std::exp(m)) << s;
    ASSERT_TRUE(fit.sites[s].intensity);
  }
  // Few reports weigh less: site c (1 report, lower segment) has the widest intensity sigma.
  EXPECT_GT(sites[2].intensity->sigma_ln, sites[0].intensity->sigma_ln);
}

// `topple invert` on a small regional survey with intensity sites, end to end: the regional JSON carries each
// site's intensity, its PGA through WGRW12 and (for the site with objects) whether they agree; the inverted site's own
// JSON carries its intensity; the GMT script draws intensity-only sites as diamonds with a legend entry; the report's
// sites table has the intensity column. A survey without intensities keeps none of these keys (checked on the same
// survey with the intensity sites made stations).
TEST(IntensityCli, RegionalSurveyWithIntensitySitesEndToEnd) {
  test::TempDir tmp;
  const std::string head = "[event]\nepicentre = [38.0, 23.0]\ndepth_km = 10\n"
                           "[inversion]\npga_g = [0.02, 2.0, 10]\nfreq_hz = [2.0, 4.0, 2]\nmotions_per_cell = 4\n"
                           "[[sites]]\nname = \"stones\"\nlat = 38.05\nlon = 23.0\n";
  const std::string object = "[[sites.object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                             "outcome = \"overturned\"\n";
  const std::string others = "[[sites]]\nname = \"station\"\nlat = 38.27\nlon = 23.0\npga_g = 0.1\n";
  const std::string felt = "[[sites]]\nname = \"felt mid\"\nlat = 38.2\nlon = 23.1\nintensity = 6\n"
                           "intensity_reports = 5\n"
                           "[[sites]]\nname = \"felt far\"\nlat = 38.35\nlon = 23.2\nintensity = 4.6\n"
                           "intensity_scale = \"EMS-98\"\nintensity_reports = 40\n";
  test::write_file(tmp.path() / "r.toml", head + "intensity = 8\nintensity_reports = 20\n" + object + others + felt);
  const auto r = test::run_cli("invert '" + (tmp.path() / "r.toml").string() + "' --json --quiet --report '" +
                               (tmp.path() / "rep").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("region")) << r.out;
  const auto& region = j.at("region");
  EXPECT_TRUE(region.at("intensity_conversion").get<std::string>().starts_with("Worden"));
  ASSERT_EQ(region.at("sites").size(), 4u);
  const auto& stones = region.at("sites")[0];
  EXPECT_EQ(stones.at("intensity").at("value").get<double>(), 8.0);
  EXPECT_EQ(stones.at("intensity").at("reports").get<int>(), 20);
  // MMI 8: 10^((8 + 1.60) / 3.70) cm/s^2 = 0.4013 g.
  EXPECT_NEAR(stones.at("intensity").at("pga_g").at("median").get<double>(), 0.4013, 1e-3);
  // A 10 x 40 cm block that overturned needs about 0.25 g or more (its b/h, open above): the intensity's 95 %
  // interval (MMI 8 from 20 reports: 0.077-2.09 g) overlaps it.
  EXPECT_TRUE(stones.at("intensity_check").at("objects_agree").get<bool>());
  EXPECT_TRUE(region.at("sites")[1].at("intensity").is_null());
  EXPECT_TRUE(region.at("sites")[1].at("intensity_check").is_null());
  EXPECT_EQ(region.at("sites")[3].at("intensity").at("scale").get<std::string>(), "EMS-98");
  EXPECT_TRUE(region.at("sites")[3].at("intensity_check").is_null());  // no objects: nothing to compare
  // The inverted site's own JSON: its intensity beside its objects' estimate.
  ASSERT_EQ(j.at("sites").size(), 1u);
  EXPECT_TRUE(j.at("sites")[0].at("intensity").at("objects_agree").get<bool>());
  const std::string script = test::slurp(tmp.path() / "rep" / "region_map.gmt.sh");
  EXPECT_NE(script.find("gmt plot -Sd0.38c"), std::string::npos);
  EXPECT_NE(script.find("intensity site (macroseismic intensity)"), std::string::npos);
  EXPECT_NE(script.find("# 3 felt mid"), std::string::npos);
  const std::string page = test::slurp(tmp.path() / "rep" / "index.html");
  EXPECT_NE(page.find("<th>intensity [reports]: PGA median [95 %] (g)</th>"), std::string::npos);
  EXPECT_NE(page.find("the intensity</"), std::string::npos);  // agree / disagree with the intensity
  // The site's own page (report.cpp, intensity_html): its intensity, the PGA through WGRW12 with its 95 % interval,
  // and the agreement, as the regional JSON says them (MMI 8: 0.401 g; 20 reports: [0.0767, 2.1] g).
  std::string site_page;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(tmp.path() / "rep")) {
    if (entry.path().filename() == "index.html" && entry.path().parent_path() != tmp.path() / "rep") {
      site_page = test::slurp(entry.path());
    }
  }
  ASSERT_NE(site_page.find("<h2 id=\"intensity\">Macroseismic intensity</h2>"), std::string::npos) << site_page;
  const auto& ij = stones.at("intensity");
  EXPECT_NE(site_page.find(fmt::format("MMI 8 from 20 reports; through the conversion PGA {:.3g} g, 95 % interval "
                                       "[{:.3g}, {:.3g}] g",
                                       ij.at("pga_g").at("median").get<double>(), ij.at("pga_g").at("ci95")[0].get<double>(),
                                       ij.at("pga_g").at("ci95")[1].get<double>())),
            std::string::npos)
      << site_page;
  EXPECT_NE(site_page.find("The objects agree with the intensity: the objects' own 95 % PGA interval overlaps"),
            std::string::npos);
  // region.csv: the old twelve columns where they were, the intensity's seven appended (empty where none).
  const std::string csv = test::slurp(tmp.path() / "rep" / "region.csv");
  std::vector<std::vector<std::string>> rows;
  for (std::size_t at = 0; at < csv.size();) {
    const std::size_t end = csv.find('\n', at);
    std::vector<std::string> cells;
    std::string line = csv.substr(at, end - at), c;
    for (std::size_t p = 0;; ++p) {
      if (p == line.size() || line[p] == ',') {
        cells.push_back(c);
        c.clear();
        if (p == line.size()) break;
      } else {
        c += line[p];
      }
    }
    rows.push_back(cells);
    at = end + 1;
  }
  ASSERT_EQ(rows.size(), 5u) << csv;
  const std::vector<std::string> header{"site", "hypocentral_distance_km", "instrument_pga_g", "independent_median_g",
                                        "independent_ci95_low_g", "independent_ci95_high_g", "pooled_median_g",
                                        "pooled_ci68_low_g", "pooled_ci68_high_g", "pooled_ci95_low_g",
                                        "pooled_ci95_high_g", "relation_median_g", "intensity", "intensity_scale",
                                        "intensity_reports", "intensity_pga_median_g", "intensity_pga_ci95_low_g",
                                        "intensity_pga_ci95_high_g", "intensity_objects_agree"};
  EXPECT_EQ(rows[0], header);
  for (const auto& row : rows) ASSERT_EQ(row.size(), header.size()) << csv;
  EXPECT_EQ(rows[1][0], "stones");
  EXPECT_EQ(std::vector<std::string>(rows[1].begin() + 12, rows[1].begin() + 15),
            (std::vector<std::string>{"8", "MMI", "20"}));
  EXPECT_EQ(std::stod(rows[1][15]), ij.at("pga_g").at("median").get<double>());
  EXPECT_EQ(std::stod(rows[1][16]), ij.at("pga_g").at("ci95")[0].get<double>());
  EXPECT_EQ(std::stod(rows[1][17]), ij.at("pga_g").at("ci95")[1].get<double>());
  EXPECT_EQ(rows[1][18], "true");
  EXPECT_EQ(rows[2][0], "station");
  EXPECT_EQ(rows[2][2], "0.1");
  for (std::size_t c = 12; c < header.size(); ++c) EXPECT_EQ(rows[2][c], "") << header[c];
  EXPECT_EQ(rows[4][12], "4.6");
  EXPECT_EQ(rows[4][13], "EMS-98");
  EXPECT_EQ(rows[4][14], "40");
  EXPECT_EQ(rows[4][18], "");  // no objects: nothing to compare

  // A one-site survey: the intensity beside the objects' estimate in the site's JSON.
  test::write_file(tmp.path() / "one.toml", "[inversion]\npga_g = [0.02, 2.0, 10]\nfreq_hz = [2.0, 4.0, 2]\n"
                                            "motions_per_cell = 4\n[site]\nname = \"x\"\nintensity = 8\n"
                                            "intensity_reports = 20\n[[object]]\nid = \"b\"\nwidth = \"10cm\"\n"
                                            "height = \"40cm\"\nmu = 0.5\noutcome = \"overturned\"\n");
  const auto one = test::run_cli("invert '" + (tmp.path() / "one.toml").string() + "' --json --quiet");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto jo = nlohmann::json::parse(one.out);
  EXPECT_NEAR(jo.at("intensity").at("pga_g").at("median").get<double>(), 0.4013, 1e-3);
  EXPECT_TRUE(jo.at("intensity").at("objects_agree").get<bool>());
  EXPECT_TRUE(jo.contains("pga_g"));  // the objects' own answer, unchanged beside it

  // The same survey without intensities (the felt sites become stations): no intensity key anywhere.
  test::write_file(tmp.path() / "s.toml", head + object + others +
                                              "[[sites]]\nname = \"s2\"\nlat = 38.2\nlon = 23.1\npga_g = 0.15\n");
  const auto r2 = test::run_cli("invert '" + (tmp.path() / "s.toml").string() + "' --json --quiet");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_TRUE(nlohmann::json::parse(r2.out).contains("region"));
  EXPECT_EQ(r2.out.find("intensity"), std::string::npos);
}

// ---- The regional recovery test with intensity sites ----

// The regional scenario of tests/region/test_region.cpp (RegionRecovery: twelve sites whose objects are simulated
// by the solvers under a true relation c0 = 2.36, c1 = 1.2, tau = 0.3), plus 24 intensity-only sites 5-80 km out
// (random azimuths) whose true PGA follows the same relation with independent residuals (tau), and whose intensity
// is drawn through the conversion with its scatter (the test draws, seeded): ln a_I = ln a + ln 10 * eps_Y,
// eps_Y ~ N(0, 0.35) (WGRW12's MMI-to-PGA scatter), MMI = eq. I1 at a_I + eps_I, eps_I ~ N(0, sigma_I(n)) (ShakeMap's
// few-reports term), n uniform in 1..30, the MMI rounded to 0.1 as DYFI reports it. Each trial fits the relation from
// the objects alone and from the objects and the intensities. Over the trials: the relation's 95 % intervals hold the
// truth in >= 85 %, the pooled sites' (object and intensity sites) in >= 85 %, and the intensities narrow the
// relation's 95 % intervals of c0 and c1 (mean ratio of widths < 1; the figures are printed). TOPPLE_INTENSITY_TRIALS
// sets the number of trials (default 2 here; scripts/region-recovery.sh runs more).
TEST(IntensityRecovery, IntensitySitesKeepCoverageAndNarrowTheRelation) {
  const char* env = std::getenv("TOPPLE_INTENSITY_TRIALS");
  const int trials = env != nullptr ? std::atoi(env) : 2;
  const InversionSettings st = testing::small_grid(0.01, 20, 2.0, 4.5, 2, 8);
  const testing::RegionalTruth truth;
  int rel_hits = 0, rel_checks = 0, site_hits = 0, site_checks = 0, felt_hits = 0, felt_checks = 0;
  double c0_ratio = 0.0, c1_ratio = 0.0, tau_ratio = 0.0;
  for (int t = 0; t < trials; ++t) {
    const testing::RegionalScenario sc = testing::make_regional_scenario(static_cast<std::uint64_t>(300 + t), truth, st);
    const std::vector<InversionResult> own = invert_sites(sc.survey.sites, st);
    Survey survey = sc.survey;
    std::vector<double> true_pga = sc.true_pga_g;
    std::mt19937_64 rng(static_cast<std::uint64_t>(7000 + t));
    std::normal_distribution<double> z(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> reports(1, 30);
    const double lat0 = *survey.epicentre_lat_deg, lon0 = *survey.epicentre_lon_deg;
    for (int k = 0; k < 24; ++k) {
      const double epi = 5.0 + 75.0 * u(rng), az = 2.0 * std::numbers::pi * u(rng);
      Site site;
      site.name = fmt::format("felt {}", k + 1);
      site.lat_deg = lat0 + epi * std::cos(az) / 111.2;
      site.lon_deg = lon0 + epi * std::sin(az) / (111.2 * std::cos(lat0 * std::numbers::pi / 180.0));
      const double r = hypocentral_distance_km(geodesic_distance_km(lat0, lon0, *site.lat_deg, *site.lon_deg),
                                               *survey.epicentre_depth_km);
      const double ln_a = truth.c0 - truth.c1 * std::log(std::hypot(r, truth.c2_km)) + truth.tau * z(rng);
      const int n = reports(rng);
      const double a_i = std::exp(ln_a + std::numbers::ln10 * Wgrw12Pga::sigma_log10_pga * z(rng));
      const double mmi = wgrw12_mmi_from_pga_g(a_i) + intensity_sigma_for_reports(n) * z(rng);
      site.intensity = SiteIntensity{std::clamp(std::round(mmi * 10.0) / 10.0, 1.0, 12.0), IntensityScale::mmi, n};
      survey.sites.push_back(site);
      true_pga.push_back(std::exp(ln_a));
    }
    std::vector<const InversionResult*> per_site;
    for (const auto& r : own) per_site.push_back(&r);
    std::vector<std::string> notes;
    const auto alone = fit_survey_region(sc.survey, per_site, notes);
    per_site.resize(survey.sites.size(), nullptr);
    const auto fit = fit_survey_region(survey, per_site, notes);
    ASSERT_TRUE(alone && fit);
    rel_hits += fit->c0.holds95(truth.c0) + fit->c1.holds95(truth.c1) + fit->tau.holds95(truth.tau);
    rel_checks += 3;
    for (const PooledSite& p : fit->sites) {
      if (survey.sites[p.site_index].instrument_pga_g) continue;  // a station's pooled PGA is its measurement
      const bool hit = p.pga_g.holds95(true_pga[p.site_index]);
      site_hits += hit;
      ++site_checks;
      if (p.intensity) {
        felt_hits += hit;
        ++felt_checks;
      }
    }
    const auto width = [](const Interval95& v) { return v.ci95_high - v.ci95_low; };
    c0_ratio += width(fit->c0) / width(alone->c0) / trials;
    c1_ratio += width(fit->c1) / width(alone->c1) / trials;
    tau_ratio += width(fit->tau) / width(alone->tau) / trials;
    fmt::print("trial {}: objects alone c0 [{:.2f}, {:.2f}] c1 [{:.2f}, {:.2f}] tau [{:.2f}, {:.2f}]; with intensities "
               "c0 [{:.2f}, {:.2f}] c1 [{:.2f}, {:.2f}] tau [{:.2f}, {:.2f}]\n",
               t, alone->c0.ci95_low, alone->c0.ci95_high, alone->c1.ci95_low, alone->c1.ci95_high,
               alone->tau.ci95_low, alone->tau.ci95_high, fit->c0.ci95_low, fit->c0.ci95_high, fit->c1.ci95_low,
               fit->c1.ci95_high, fit->tau.ci95_low, fit->tau.ci95_high);
  }
  fmt::print("relation coverage {}/{}, pooled site coverage {}/{} (intensity sites {}/{}); 95 % width with / without "
             "intensities: c0 {:.2f}, c1 {:.2f}, tau {:.2f}\n",
             rel_hits, rel_checks, site_hits, site_checks, felt_hits, felt_checks, c0_ratio, c1_ratio, tau_ratio);
  EXPECT_GE(rel_hits, 0.85 * rel_checks);
  EXPECT_GE(site_hits, 0.85 * site_checks);
  EXPECT_LT(c0_ratio, 1.0);
  EXPECT_LT(c1_ratio, 1.0);
}

}  // namespace
}  // namespace topple
