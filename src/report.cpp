// The inversion's figures and HTML report.
#include "topple/report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "topple/error.hpp"
#include "topple/io/output_file.hpp"
#include "topple/io/inversion_output.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"

namespace topple {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* kPalette[] = {"#e6550d", "#31a354", "#756bb1", "#636363", "#d6616b", "#3182bd", "#8c6d31", "#bcbddc",
                          "#e7ba52", "#ad494a"};

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The SVG without its XML prologue/doctype, for inline embedding.
std::string inline_svg(const std::filesystem::path& p) {
  std::string svg = slurp(p);
  const auto at = svg.find("<svg");
  return at == std::string::npos ? svg : svg.substr(at);
}

std::string opt_text(const std::optional<double>& v, const char* unit) {
  return v ? fmt::format("{:.3g} {}", *v, unit) : std::string("unconstrained");
}

std::string dims(const ObservedObject& o) {
  const auto cm = [](double m) { return fmt::format("{:.3g} cm", 100.0 * m); };
  switch (o.body.shape) {
    case RockingBody::Shape::block: return fmt::format("block {} x {}", cm(*o.width_m), cm(*o.height_m));
    case RockingBody::Shape::cylinder: return fmt::format("cylinder &#8960; {} x {}", cm(*o.diameter_m), cm(*o.height_m));
    case RockingBody::Shape::general:
      return fmt::format("a = {}, h = {}, D = {:.3g} m&#178;", cm(o.body.a_m), cm(o.body.h_m), o.body.D_m2);
  }
  return "";
}

std::string interval_text(const Interval& iv) {
  return iv.is_value() ? fmt::format("{:.3g}", iv.low) : fmt::format("{:.3g}&ndash;{:.3g}", iv.low, iv.high);
}

std::string observed_text(const ObservedObject& o) {
  std::string s(outcome_name(o.outcome));
  if (o.slid_m) s += fmt::format(" {:.3g} cm &plusmn; {:.3g} cm", 100.0 * *o.slid_m, 100.0 * o.slid_uncertainty_m);
  if (o.slid_at_least_m) s += fmt::format(" &ge; {:.3g} cm", 100.0 * *o.slid_at_least_m);
  return s;
}

}  // namespace

plot::Series contour_series(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
                            double level, const std::string& label) {
  plot::Series s;
  s.label = label;
  s.style = "lines";
  const std::size_t nx = x.size();
  // Interpolate in log coordinates (the axes are log-spaced), then map back.
  const auto lerp = [&](double x0, double x1, double z0, double z1) {
    const double f = (level - z0) / (z1 - z0);
    return std::exp(std::log(x0) + f * (std::log(x1) - std::log(x0)));
  };
  for (std::size_t r = 0; r + 1 < y.size(); ++r) {
    for (std::size_t c = 0; c + 1 < nx; ++c) {
      const double z00 = z[r * nx + c], z01 = z[r * nx + c + 1], z10 = z[(r + 1) * nx + c], z11 = z[(r + 1) * nx + c + 1];
      std::vector<std::pair<double, double>> pts;
      if ((z00 < level) != (z01 < level)) pts.emplace_back(lerp(x[c], x[c + 1], z00, z01), y[r]);
      if ((z10 < level) != (z11 < level)) pts.emplace_back(lerp(x[c], x[c + 1], z10, z11), y[r + 1]);
      if ((z00 < level) != (z10 < level)) pts.emplace_back(x[c], lerp(y[r], y[r + 1], z00, z10));
      if ((z01 < level) != (z11 < level)) pts.emplace_back(x[c + 1], lerp(y[r], y[r + 1], z01, z11));
      for (std::size_t k = 0; k + 1 < pts.size(); k += 2) {
        s.x.insert(s.x.end(), {pts[k].first, pts[k + 1].first, kNaN});
        s.y.insert(s.y.end(), {pts[k].second, pts[k + 1].second, kNaN});
      }
    }
  }
  return s;
}

plot::MapFigure likelihood_map_figure(const InversionResult& r, const Site& site) {
  plot::MapFigure m;
  m.title = fmt::format("{}: posterior over PGA x predominant frequency", site.name);
  m.xlabel = "PGA (g)";
  m.ylabel = "predominant frequency (Hz)";
  m.zlabel = "posterior / max";
  m.log_x = m.log_y = true;
  m.x = r.pga_g;
  m.y = r.freq_hz;
  // Map is stored row-major over y (frequency) x x (PGA); the result is indexed [i_pga * nf + j_freq].
  const std::size_t np = r.pga_g.size(), nf = r.freq_hz.size();
  const double peak = *std::max_element(r.posterior.begin(), r.posterior.end());
  m.z.resize(np * nf);
  for (std::size_t j = 0; j < nf; ++j) {
    for (std::size_t i = 0; i < np; ++i) m.z[j * np + i] = r.posterior[i * nf + j] / peak;
  }
  const double fy0 = r.freq_hz.front(), fy1 = r.freq_hz.back();
  if (r.bounds.lower_g) m.overlay.push_back({fmt::format("static lower bound {:.3g} g", *r.bounds.lower_g), {*r.bounds.lower_g, *r.bounds.lower_g}, {fy0, fy1}, "lines", "#c0392b", 2.5});
  if (r.bounds.upper_g) m.overlay.push_back({fmt::format("static upper bound {:.3g} g", *r.bounds.upper_g), {*r.bounds.upper_g, *r.bounds.upper_g}, {fy0, fy1}, "lines", "#8e44ad", 2.5});
  for (std::size_t o = 0; o < r.objects.size(); ++o) {
    std::vector<double> z(np * nf);
    for (std::size_t j = 0; j < nf; ++j) {
      for (std::size_t i = 0; i < np; ++i) z[j * np + i] = r.objects[o].probability[i * nf + j];
    }
    plot::Series c = contour_series(r.pga_g, r.freq_hz, z, 0.5, fmt::format("{} ({}) P=0.5", r.objects[o].id, outcome_name(r.objects[o].outcome)));
    c.color = kPalette[o % std::size(kPalette)];
    c.width = 1.5;
    if (!c.x.empty()) m.overlay.push_back(std::move(c));
  }
  m.overlay.push_back(
      {"best", {r.pga_estimate_g.best}, {r.freq_estimate_hz.best}, "points pt 7 ps 1.8", "#000000", 1.0});
  m.height_px = 760;
  return m;
}

plot::Figure marginal_figure(const InversionResult& r, bool pga) {
  const auto& x = pga ? r.pga_g : r.freq_hz;
  const auto& p = pga ? r.marginal_pga : r.marginal_freq;
  const Estimate& e = pga ? r.pga_estimate_g : r.freq_estimate_hz;
  const char* unit = pga ? "g" : "Hz";
  plot::Figure f;
  f.title = pga ? "Marginal posterior of PGA" : "Marginal posterior of the predominant frequency";
  f.xlabel = pga ? "PGA (g)" : "predominant frequency (Hz)";
  plot::Panel panel;
  panel.ylabel = "posterior probability per grid cell";
  panel.log_x = true;
  panel.series.push_back({"posterior", x, p, "linespoints pt 7 ps 0.6", "#2171b5", 2.0});
  const double top = *std::max_element(p.begin(), p.end());
  panel.series.push_back({fmt::format("median {:.3g} {}", e.median, unit), {e.median, e.median}, {0.0, top}, "lines", "#000000", 2.0});
  if (e.ci68_low && e.ci68_high) {
    panel.series.push_back({"68 % interval", {*e.ci68_low, *e.ci68_high}, {0.5 * top, 0.5 * top}, "linespoints pt 2", "#e6550d", 3.0});
  }
  if (e.ci95_low && e.ci95_high) {
    panel.series.push_back({"95 % interval", {*e.ci95_low, *e.ci95_high}, {0.25 * top, 0.25 * top}, "linespoints pt 2", "#31a354", 3.0});
  }
  f.panels.push_back(panel);
  f.panel_height_px = 380;
  return f;
}

plot::Figure best_cell_figure(const InversionResult& r, const Site& site, const InversionSettings& settings) {
  const double pga = r.pga_g[r.best_cell / r.freq_hz.size()];
  const double freq = r.freq_hz[r.best_cell % r.freq_hz.size()];
  InversionSettings one = settings;
  one.motions_per_cell = 1;
  const GroundMotion motion = family_motions(one, freq).front().scaled(pga * settings.g_m_s2);
  plot::Figure f;
  f.title = fmt::format("Best cell: PGA {:.3g} g, {:.3g} Hz: one motion of the family and each object's response", pga, freq);
  f.xlabel = "time (s)";
  plot::Panel ground{"ground acceleration (g)", {}, {}, {}, false, false};
  plot::Series gs{"ground", {}, {}, "lines", "#555555", 1.0};
  for (std::size_t i = 0; i < motion.size(); ++i) {
    gs.x.push_back(motion.time_s(i));
    gs.y.push_back(motion.accel_m_s2()[i] / settings.g_m_s2);
  }
  ground.series.push_back(gs);
  plot::Panel rocking{"rotation theta / alpha", {}, {{1.0, "CM over pivot"}, {-1.0, ""}}, {}, false, false};
  plot::Panel sliding{"sliding displacement (m)", {}, {}, {}, false, false};
  for (std::size_t o = 0; o < site.objects.size(); ++o) {
    const ObservedObject& obj = site.objects[o];
    const std::string color = kPalette[o % std::size(kPalette)];
    const double amp = obj.amplification.mid();
    const GroundMotion seen = nominal_object_motion(obj, motion);  // through a flexible support, if any
    if (obj.outcome == Outcome::slid || obj.outcome == Outcome::not_slid) {
      const auto res = slide(seen.scaled(amp), SlidingBlock::make(obj.mu.mid(), obj.mu.mid(), 0.0, SlidingMode::two_way, settings.g_m_s2));
      sliding.series.push_back({fmt::format("{} (mu {:.2g})", obj.id, obj.mu.mid()), res.history.time_s, res.history.displacement_m, "lines", color, 1.6});
    } else {
      RockingOptions opt;
      opt.g_m_s2 = settings.g_m_s2;
      if (!obj.e_housner) {
        opt.restitution = RestitutionMode::given;
        opt.e = obj.e.mid();
      }
      double factor = amp;
      if (obj.orientation_deg) factor *= std::cos(*obj.orientation_deg * kPi / 180.0);
      const auto res = rock(seen.scaled(factor), obj.body, opt);
      std::vector<double> ratio(res.history.theta_rad.size());
      for (std::size_t i = 0; i < ratio.size(); ++i) ratio[i] = res.history.theta_rad[i] / obj.body.alpha_rad();
      rocking.series.push_back({fmt::format("{}{}", obj.id, res.summary.overturned ? " (falls)" : ""), res.history.time_s, ratio, "lines", color, 1.6});
    }
  }
  f.panels.push_back(ground);
  if (!rocking.series.empty()) f.panels.push_back(rocking);
  if (!sliding.series.empty()) f.panels.push_back(sliding);
  return f;
}

void write_report(const std::filesystem::path& dir, const Survey& survey, const Site& site, const InversionResult& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError(fmt::format("cannot create the report directory '{}': {}", dir.string(), ec.message()));
  plot::render(likelihood_map_figure(r, site), dir / "likelihood.svg");
  plot::render(marginal_figure(r, true), dir / "marginal_pga.svg");
  plot::render(marginal_figure(r, false), dir / "marginal_freq.svg");
  plot::render(best_cell_figure(r, site, survey.inversion), dir / "best_cell.svg");
  io::write_inversion_grid_csv(dir / "grid.csv", r);
  io::write_file_atomically(dir / "result.json", io::inversion_json(r, site).dump(2) + "\n");
  const InversionSettings& st = survey.inversion;
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>topple: " << html_escape(site.name)
    << "</title>\n<style>\nbody{font-family:Helvetica,Arial,sans-serif;max-width:1100px;margin:2em auto;color:#222;line-height:1.45}\n"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:4px 8px;text-align:left}th{background:#f2f2f2}\n"
       ".num{font-size:1.25em}.note{background:#fff7e6;border-left:4px solid #e6a100;padding:6px 10px;margin:6px 0}\n"
       "figure{margin:1.5em 0}figure svg{max-width:100%;height:auto}figcaption{color:#555;font-size:.9em}\n</style></head><body>\n";
  h << "<h1>Shaking estimated from objects: " << html_escape(site.name) << "</h1>\n";
  if (site.lat_deg && site.lon_deg) h << fmt::format("<p>Location {:.4f}&deg;, {:.4f}&deg;.</p>\n", *site.lat_deg, *site.lon_deg);
  if (!site.notes.empty()) h << "<p>" << html_escape(site.notes) << "</p>\n";
  h << "<h2 id=\"estimate\">Estimate</h2>\n<table id=\"numbers\"><tr><th></th><th>best</th><th>median</th><th>68 % interval</th><th>95 % interval</th></tr>\n";
  h << fmt::format("<tr><td>PGA</td><td class=\"num\">{:.3g} g</td><td class=\"num\">{:.3g} g</td><td>{} &ndash; {}</td><td>{} &ndash; {}</td></tr>\n",
                   r.pga_estimate_g.best, r.pga_estimate_g.median, opt_text(r.pga_estimate_g.ci68_low, "g"),
                   opt_text(r.pga_estimate_g.ci68_high, "g"), opt_text(r.pga_estimate_g.ci95_low, "g"),
                   opt_text(r.pga_estimate_g.ci95_high, "g"));
  h << fmt::format("<tr><td>predominant frequency</td><td class=\"num\">{:.3g} Hz</td><td class=\"num\">{:.3g} Hz</td><td>{} &ndash; {}</td><td>{} &ndash; {}</td></tr>\n",
                   r.freq_estimate_hz.best, r.freq_estimate_hz.median, opt_text(r.freq_estimate_hz.ci68_low, "Hz"),
                   opt_text(r.freq_estimate_hz.ci68_high, "Hz"), opt_text(r.freq_estimate_hz.ci95_low, "Hz"),
                   opt_text(r.freq_estimate_hz.ci95_high, "Hz"));
  h << fmt::format("<tr><td>static bounds on PGA</td><td colspan=\"4\">{} &ndash; {}</td></tr>\n</table>\n",
                   opt_text(r.bounds.lower_g, "g"), opt_text(r.bounds.upper_g, "g"));
  for (const auto& note : r.notes) h << "<p class=\"note\">" << html_escape(note) << "</p>\n";
  h << "<figure id=\"map\">" << inline_svg(dir / "likelihood.svg")
    << "<figcaption>Posterior over PGA and predominant frequency (log axes, normalised to its maximum), the static "
       "bounds, and for each object the line where its observation has probability 0.5.</figcaption></figure>\n";
  h << "<figure>" << inline_svg(dir / "marginal_pga.svg") << "</figure>\n";
  h << "<figure>" << inline_svg(dir / "marginal_freq.svg") << "</figure>\n";
  h << "<h2>Observations</h2>\n<table id=\"observations\"><tr><th>id</th><th>description</th><th>geometry</th><th>&mu;</th>"
       "<th>e</th><th>support (amplification)</th><th>observed</th><th>evidence</th><th>static bound</th>"
       "<th>P(observation) at best</th></tr>\n";
  for (std::size_t o = 0; o < site.objects.size(); ++o) {
    const ObservedObject& obj = site.objects[o];
    std::string bound = "&ndash;";
    for (const auto& b : r.bounds.lower) if (b.object_id == obj.id) bound = html_escape(b.reason);
    for (const auto& b : r.bounds.upper) if (b.object_id == obj.id) bound = html_escape(b.reason);
    h << fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{} ({})</td><td>{}</td><td>{}</td><td>{}</td><td>{:.2f}</td></tr>\n",
                     html_escape(obj.id), html_escape(obj.description), dims(obj), interval_text(obj.mu),
                     obj.e_housner ? fmt::format("Housner {:.3f}", housner_restitution(obj.body)) : interval_text(obj.e),
                     html_escape(obj.support), interval_text(obj.amplification), observed_text(obj),
                     evidence_name(obj.evidence), bound, r.objects[o].probability_at_best);
  }
  h << "</table>\n";
  h << "<figure>" << inline_svg(dir / "best_cell.svg")
    << "<figcaption>One motion of the family at the best cell and each object's response with nominal parameters "
       "(rocking objects as &theta;/&alpha;, sliding ones as displacement).</figcaption></figure>\n";
  h << "<h2>Method in short</h2>\n<ol>\n"
       "<li>Static bounds (Mittal 1971, section 1.1): an object that slid needs PGA &gt; &mu;g, one that rocked or "
       "overturned PGA &gt; g&middot;a/h (divided by the support's amplification); one that did not slide gives "
       "PGA &le; &mu;g.</li>\n"
    << fmt::format("<li>Dynamic inversion: on a grid of {} PGA values ({:.3g}&ndash;{:.3g} g) &times; {} predominant "
                   "frequencies ({:.3g}&ndash;{:.3g} Hz), log-spaced, every object is simulated under {} {} motions per "
                   "cell (sliding: exact Coulomb block; rocking: Housner's equation with impacts and overturning), with "
                   "uncertain &mu;, e and amplification drawn per motion. The frequency axis is the motions' measured "
                   "predominant frequency (peak of the Konno&ndash;Ohmachi-smoothed Fourier amplitude spectrum).</li>\n",
                   st.pga_count, st.pga_min_g, st.pga_max_g, st.freq_count, st.freq_min_hz, st.freq_max_hz,
                   r.runs / std::max<std::size_t>(1, site.objects.size() * r.pga_g.size() * r.freq_hz.size()),
                   st.family == MotionFamily::synthetic ? "synthetic (Clough&ndash;Penzien filtered noise)" : "recorded")
    << "<li>All objects saw the same motion: a cell's likelihood is the average over its motions of the product over "
       "objects of 0.98 (certain), 0.90 (likely) or 0.75 (reported) when the run reproduces the observation and 0.02, "
       "0.10 or 0.25 when it does not (the chance that the observation itself is wrong); the runs of neighbouring "
       "cells are pooled. Prior uniform in log PGA and log frequency. Intervals are equal-tailed from the marginal "
       "posteriors; an end that lies in the grid's first or last cell is reported as unconstrained.</li>\n</ol>\n";
  h << "<h2>Inputs</h2>\n<p>" << fmt::format("Survey file <code>{}</code>; family {}, seed {}, g = {} m/s&#178;, {} runs in {:.1f} s.",
                                           html_escape(survey.source_file),
                                           st.family == MotionFamily::synthetic ? "synthetic" : "records", st.seed,
                                           st.g_m_s2, r.runs, r.seconds)
    << "</p>\n";
  if (st.family == MotionFamily::records) {
    h << "<ul>";
    for (const auto& rec : st.records) h << "<li><code>" << html_escape(rec) << "</code></li>";
    h << "</ul>\n";
  }
  h << "<p>Files beside this page: <a href=\"grid.csv\">grid.csv</a> (the likelihood grid), <a href=\"result.json\">result.json</a>.</p>\n";
  h << "<p style=\"color:#888\">Made by topple 0.1.0.</p>\n</body></html>\n";
  io::write_file_atomically(dir / "index.html", h.str());
}

}  // namespace topple
