// The survey's report (region_report.hpp: write_survey_report) and its regional page (write_region_report): the
// relation, every site pooled beside its own estimate with a link to its page, the calibration sites, the attenuation
// figure, the pooled PGA field and the map drawn by GMT (region_map.hpp).
#include "topple/output/region_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "topple/core/output_file.hpp"
#include "topple/output/plot.hpp"
#include "topple/output/region_map.hpp"
#include "topple/output/region_output.hpp"
#include "topple/output/report.hpp"
#include "topple/region/field.hpp"

namespace topple {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

plot::Series points(const std::string& label, const std::string& color) {
  plot::Series s;
  s.label = label;
  s.style = "points";
  s.color = color;
  return s;
}

/// PGA against hypocentral distance: each site's pooled 95 % interval (a vertical bar) and median, its own 95 %
/// interval (an open end drawn to its grid's edge) and median beside it, the instruments, and the relation's median
/// with its 95 % band.
plot::Figure attenuation_figure(const RegionalResult& fit, const std::vector<const InversionResult*>& per_site) {
  plot::Panel p;
  p.ylabel = "PGA (g)";
  p.log_x = true;
  p.log_y = true;
  plot::Series median{"relation, posterior median", {}, {}, "lines", "#2171b5", 2.0};
  plot::Series lo{"relation, 95 % interval", {}, {}, "lines", "#6baed6", 1.0};
  plot::Series hi{"", {}, {}, "lines", "#6baed6", 1.0};
  for (std::size_t q = 0; q < fit.curve_distance_km.size(); ++q) {
    median.x.push_back(fit.curve_distance_km[q]);
    median.y.push_back(fit.curve_pga_g[q].median);
    lo.x.push_back(fit.curve_distance_km[q]);
    lo.y.push_back(fit.curve_pga_g[q].ci95_low);
    hi.x.push_back(fit.curve_distance_km[q]);
    hi.y.push_back(fit.curve_pga_g[q].ci95_high);
  }
  plot::Series bars{"site, pooled 95 % interval", {}, {}, "lines", "#222222", 1.5};
  plot::Series pooled = points("site, pooled median", "#222222");
  plot::Series own = points("site, own median (objects alone)", "#E69F00");
  plot::Series own_bars{"site, own 95 % interval (objects alone)", {}, {}, "lines", "#E69F00", 1.0};
  plot::Series inst = points("instrument", "#D55E00");
  // Intensity sites (issue 30): the intensity's PGA through WGRW12 and its 95 % interval, beside the pooled one.
  plot::Series inten = points("intensity through WGRW12", "#56B4E9");
  plot::Series inten_bars{"intensity site, 95 % interval", {}, {}, "lines", "#56B4E9", 1.0};
  for (const PooledSite& s : fit.sites) {
    if (s.intensity) {
      const double x = s.distance_km * 0.97;
      inten.x.push_back(x);
      inten.y.push_back(s.intensity->pga_g);
      inten_bars.x.insert(inten_bars.x.end(), {x, x, kNaN});
      inten_bars.y.insert(inten_bars.y.end(), {s.intensity->ci95_low_g(), s.intensity->ci95_high_g(), kNaN});
    }
    bars.x.insert(bars.x.end(), {s.distance_km, s.distance_km, kNaN});
    bars.y.insert(bars.y.end(), {s.pga_g.ci95_low, s.pga_g.ci95_high, kNaN});
    pooled.x.push_back(s.distance_km);
    pooled.y.push_back(s.pga_g.median);
    if (const InversionResult* r = per_site.at(s.site_index)) {
      const double x = s.distance_km * 1.03;  // beside the pooled one, not on it
      const Estimate& e = r->pga_estimate_g;
      own.x.push_back(x);
      own.y.push_back(e.median);
      own_bars.x.insert(own_bars.x.end(), {x, x, kNaN});
      own_bars.y.insert(own_bars.y.end(), {e.ci95_low.value_or(r->pga_g.front()), e.ci95_high.value_or(r->pga_g.back()), kNaN});
    }
    if (s.instrument_pga_g) {
      inst.x.push_back(s.distance_km);
      inst.y.push_back(*s.instrument_pga_g);
    }
  }
  p.series = {median, lo, hi, bars, pooled};
  if (!own.x.empty()) p.series.insert(p.series.end(), {own_bars, own});
  if (!inst.x.empty()) p.series.push_back(inst);
  if (!inten.x.empty()) p.series.insert(p.series.end(), {inten_bars, inten});
  plot::Figure f;
  f.title = "PGA against hypocentral distance";
  f.xlabel = "hypocentral distance (km)";
  f.panels = {p};
  f.panel_height_px = 520;
  return f;
}

/// The pooled PGA field as a map (lon x lat), its contours, the sites, the instruments and the epicentre, drawn by
/// gnuplot: the field itself, which the GMT map (region_map.hpp, coastlines and borders) leaves out.
plot::MapFigure field_figure(const PooledField& field, const std::vector<Contour>& contours, const RegionalResult& fit,
                             const Survey& survey) {
  plot::MapFigure m;
  m.title = "Pooled PGA (g): the relation plus kriged site residuals";
  m.xlabel = "longitude (deg)";
  m.ylabel = "latitude (deg)";
  m.zlabel = "PGA (g)";
  m.x = field.lon_deg;
  m.y = field.lat_deg;
  m.z = field.pga_g;
  const char* colors[] = {"#009E73", "#0072B2", "#CC79A7", "#D55E00"};
  for (std::size_t c = 0; c < contours.size(); ++c) {
    plot::Series s{fmt::format("{:g} g", contours[c].level_g), {}, {}, "lines", colors[c % 4], 2.0};
    for (const auto& line : contours[c].lines) {
      for (const auto& pt : line) {
        s.x.push_back(pt[0]);
        s.y.push_back(pt[1]);
      }
      s.x.push_back(kNaN);
      s.y.push_back(kNaN);
    }
    if (!s.x.empty()) m.overlay.push_back(s);
  }
  plot::Series sites = points("sites", "#222222");
  plot::Series stations = points("instrument stations", "#D55E00");
  plot::Series intensities = points("intensity sites", "#56B4E9");
  for (const PooledSite& p : fit.sites) {
    const Site& site = survey.sites.at(p.site_index);
    // A station is drawn as a station; an intensity site without objects or instrument as an intensity site.
    plot::Series& s = p.instrument_pga_g ? stations : (site.objects.empty() && p.intensity ? intensities : sites);
    s.x.push_back(*site.lon_deg);
    s.y.push_back(*site.lat_deg);
  }
  if (!sites.x.empty()) m.overlay.push_back(sites);
  if (!stations.x.empty()) m.overlay.push_back(stations);
  if (!intensities.x.empty()) m.overlay.push_back(intensities);
  plot::Series epi = points("epicentre", "#b71c1c");
  epi.x.push_back(*survey.epicentre_lon_deg);
  epi.y.push_back(*survey.epicentre_lat_deg);
  m.overlay.push_back(epi);
  return m;
}

std::string interval(const Interval95& v, const char* fmt_spec = "{:.3g}") {
  return fmt::format(fmt::runtime(std::string(fmt_spec) + " (68 %: " + fmt_spec + "&ndash;" + fmt_spec + ", 95 %: " +
                                  fmt_spec + "&ndash;" + fmt_spec + ")"),
                     v.median, v.ci68_low, v.ci68_high, v.ci95_low, v.ci95_high);
}

}  // namespace

std::vector<std::string> write_region_report(const std::filesystem::path& dir, const Survey& survey, const RegionalResult& fit,
                         const std::vector<const InversionResult*>& per_site,
                         const std::vector<std::string>& site_pages, const RegionalSettings& settings) {
  std::filesystem::create_directories(dir);
  const PooledField field = pooled_field(fit, survey);
  const std::vector<Contour> contours = contour_field(field, io::contour_levels_g());
  plot::render(attenuation_figure(fit, per_site), dir / "attenuation.svg");
  plot::render(field_figure(field, contours, fit, survey), dir / "pga_map.svg");
  const MapOutcome map = write_region_map(dir, region_map(fit, survey, contours, per_site), gmt_program_from_environment());
  std::vector<std::string> warnings;
  if (!map.drawn) warnings.push_back(map.note);
  io::write_contours_geojson(dir / "contours.geojson", contours, field);
  io::write_region_csv(dir / "region.csv", fit, per_site);
  io::write_file_atomically(dir / "region.json", io::region_json(fit, survey, per_site, settings).dump(2) + "\n");
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>topple: regional picture</title>\n"
       "<style>body{font-family:Helvetica,Arial,sans-serif;max-width:1150px;margin:2em auto;color:#222;line-height:1.45}"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:4px 8px;text-align:left}"
       "th{background:#f2f2f2}.note{background:#fff7e6;border-left:4px solid #e6a100;padding:6px 10px;margin:6px 0}"
       "figure svg{max-width:100%;height:auto}.flag{color:#b71c1c;font-weight:bold}</style></head><body>\n";
  h << "<h1>The regional picture: " << fit.sites.size() << " sites, one earthquake</h1>\n";
  h << "<p>Attenuation relation fitted to every site at once (docs/method.md, &ldquo;Regional joint inversion&rdquo;): "
       "ln PGA = c0 &minus; c1 ln &radic;(R&sup2; + c2&sup2;) + &delta;, &delta; ~ N(0, &tau;&sup2;), PGA in g, R the "
       "hypocentral distance in km. Each site's PGA is <i>pooled</i> through it: a weakly observed site borrows "
       "strength from the relation and its neighbours.</p>\n";
  h << "<table><tr><th>parameter</th><th>median (68 %, 95 % intervals)</th></tr>\n";
  h << "<tr><td>c0 (ln g)</td><td>" << interval(fit.c0) << "</td></tr>\n";
  h << "<tr><td>c1</td><td>" << interval(fit.c1) << "</td></tr>\n";
  h << "<tr><td>c2 (km)</td><td>" << fmt::format("{:g}", fit.c2_km) << " (fixed: a dozen sites cannot resolve it)</td></tr>\n";
  h << "<tr><td>&tau; (ln units)</td><td>" << interval(fit.tau) << "</td></tr>\n";
  h << fmt::format("<tr><td>PGA at {:.3g} km (g)</td><td>", fit.reference_distance_km)
    << interval(Interval95{std::exp(fit.ln_a_ref.median), std::exp(fit.ln_a_ref.ci68_low), std::exp(fit.ln_a_ref.ci68_high),
                           std::exp(fit.ln_a_ref.ci95_low), std::exp(fit.ln_a_ref.ci95_high)})
    << "</td></tr></table>\n";
  for (const std::string& n : fit.notes) h << "<p class=\"note\">" << html_escape(n) << "</p>\n";
  if (fit.frequency) {  // the frequency relation (region.hpp, "Frequency"; docs/method.md eqs. F1-F3)
    const FrequencyRelation& f = *fit.frequency;
    h << "<p id=\"frequency\">Frequency: ln f = d0 + d1 ln &radic;(R&sup2; + c2&sup2;) + &epsilon;, d1 = " << interval(f.d1)
      << fmt::format(", against one frequency for all sites: Bayes factor {:.3g}: ", std::exp(f.ln_bayes_factor))
      << (f.supported ? "supported (&ge; 3); the sites' frequencies are pooled through it (region.json)"
                      : "not supported (&lt; 3); each site's frequency stays its own estimate")
      << ".</p>\n";
  }
  h << "<figure id=\"attenuation\">" << inline_svg(dir / "attenuation.svg")
    << "<figcaption>Each site's pooled 95 % interval (bar) and median (black), its own 95 % interval and median from "
       "its objects alone (orange, shifted right by 3 % to stay visible; an open end drawn to the edge of its grid), "
       "the instruments (red), and the relation's posterior median with its 95 % band (blue).</figcaption></figure>\n";
  h << "<h2>Map</h2>\n";
  if (map.drawn) {
    h << "<figure id=\"geomap\"><img style=\"max-width:100%;height:auto\" alt=\"map of the sites' pooled PGA\" src=\""
      << inline_png(dir / kRegionMapPng) << "\">"
      << "<figcaption>The sites at their places, coloured by their pooled PGA (posterior median, logarithmic scale "
         "in g) and numbered in survey order (siteN below); triangles: instrument stations; star: the epicentre; "
         "black lines: the iso-acceleration lines of the pooled field, labelled in g. Coastlines and lakes from "
         "GSHHG (Wessel &amp; Smith 1996), national borders from WDBII, drawn by GMT (Wessel et al. 2019): "
         "<a href=\"region_map.png\">region_map.png</a>, redrawn by <code>bash region_map.gmt.sh</code>."
         "</figcaption></figure>\n";
  } else {
    h << "<p class=\"note\" id=\"geomap-missing\">No map: " << html_escape(map.note)
      << ". The pooled field below shows the sites, the stations, the epicentre and the contours without "
         "coastlines.</p>\n";
  }
  // The intensity column only when some site has an intensity (issue 30): other surveys' pages are unchanged.
  const bool any_intensity =
      std::any_of(fit.sites.begin(), fit.sites.end(), [](const PooledSite& p) { return p.intensity.has_value(); });
  h << "<h2>Sites</h2>\n<table><tr><th>site</th><th>R (km)</th><th>objects</th><th>instrument (g)</th>"
    << (any_intensity ? "<th>intensity [reports]: PGA median [95 %] (g)</th>" : "")
    << "<th>own median [95 %] (g)</th><th>pooled median [95 %] (g)</th><th>relation median (g)</th></tr>\n";
  for (const PooledSite& p : fit.sites) {
    const InversionResult* r = per_site.at(p.site_index);
    const std::string& page = site_pages.at(p.site_index);
    const std::string name = page.empty() ? html_escape(p.name)
                                          : fmt::format("<a href=\"{}\">{}</a>", html_escape(page), html_escape(p.name));
    std::string own = "&ndash; (no objects)";
    if (r != nullptr) {
      const Estimate& e = r->pga_estimate_g;
      const auto end = [](const std::optional<double>& v) { return v ? fmt::format("{:.3g}", *v) : std::string("open"); };
      own = fmt::format("{:.3g} [{}, {}]", e.median, end(e.ci95_low), end(e.ci95_high));
      if (p.instrument_pga_g) {
        own += objects_agree_with_instrument(e, *p.instrument_pga_g)
                   ? " &mdash; calibration: the objects agree with the instrument"
                   : " &mdash; <span class=\"flag\">calibration: the objects disagree with the instrument</span>";
      }
      if (p.intensity) {
        own += objects_agree_with_intensity(e, *p.intensity)
                   ? " &mdash; the objects agree with the intensity"
                   : " &mdash; <span class=\"flag\">the objects disagree with the intensity</span>";
      }
    }
    std::string inten;
    if (any_intensity) {
      inten = "<td>&ndash;</td>";
      if (const auto& i = p.intensity) {
        inten = fmt::format("<td>{} {:g} [{}]: {:.3g} [{:.3g}, {:.3g}]{}</td>", intensity_scale_name(i->intensity.scale),
                            i->intensity.value, i->intensity.reports ? fmt::format("{}", *i->intensity.reports) : "?",
                            i->pga_g, i->ci95_low_g(), i->ci95_high_g(), i->extrapolated ? " (extrapolated above X)" : "");
      }
    }
    h << fmt::format("<tr><td>{}</td><td>{:.1f}</td><td>{}</td><td>{}</td>{}<td>{}</td><td>{:.3g} [{:.3g}, {:.3g}]</td>"
                     "<td>{:.3g}</td></tr>\n",
                     name, p.distance_km, survey.sites.at(p.site_index).objects.size(),
                     p.instrument_pga_g ? fmt::format("{:.3g}", *p.instrument_pga_g) : std::string("&ndash;"), inten, own,
                     p.pga_g.median, p.pga_g.ci95_low, p.pga_g.ci95_high, p.relation_pga_g.median);
  }
  h << "</table>\n";
  h << "<figure id=\"map\">" << inline_svg(dir / "pga_map.svg")
    << fmt::format("<figcaption>The pooled PGA field: the relation at the posterior medians plus the sites' residuals "
                   "kriged with the exponential correlation exp(&minus;3h/{:g} km) (Jayaram &amp; Baker 2009), and the "
                   "iso-acceleration lines at 0.05, 0.1, 0.2 and 0.4 g (also in contours.geojson).</figcaption>"
                   "</figure>\n",
                   field.range_km);
  h << "<p>Files beside this page: <a href=\"region.json\">region.json</a>, <a href=\"region.csv\">region.csv</a>, "
       "<a href=\"contours.geojson\">contours.geojson</a>.</p>\n</body></html>\n";
  io::write_file_atomically(dir / "index.html", h.str());
  return warnings;
}

SurveyReport write_survey_report(const std::filesystem::path& dir, const Survey& survey, const SurveyInversion& inversion,
                                 const std::optional<io::Provenance>& provenance, const RegionalSettings& settings) {
  SurveyReport out;
  const std::vector<Site> sites = inversion.sites_with_objects(survey);
  // The regional page links each site's page (a station without objects has none), relative to DIR.
  std::vector<std::string> pages(survey.sites.size());
  for (std::size_t k = 0; k < inversion.results.size(); ++k) {
    const std::filesystem::path folder = site_report_folder(survey, inversion.survey_index[k]);
    const std::filesystem::path site_dir = folder.empty() ? dir : dir / folder;
    write_report(site_dir, survey, sites[k], inversion.results[k], provenance);
    out.site_pages.push_back(site_dir / "index.html");
    if (!folder.empty()) pages[inversion.survey_index[k]] = (folder / "index.html").string();
  }
  if (inversion.region) {
    out.warnings = write_region_report(dir, survey, *inversion.region, inversion.per_site(survey.sites.size()), pages,
                                       settings);
    out.region_page = dir / "index.html";
  }
  return out;
}

}  // namespace topple
