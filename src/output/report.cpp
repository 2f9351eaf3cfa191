// The inversion's figures and HTML report.
#include "topple/output/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <tuple>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"
#include "topple/output/inversion_output.hpp"
#include "topple/output/provenance.hpp"
#include "topple/inversion/evidence.hpp"
#include "topple/inversion/inversion_3c.hpp"
#include "topple/inversion/matching.hpp"
#include "topple/region/intensity.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Object colours: the Okabe-Ito palette (distinguishable with the common colour-vision deficiencies) less its yellow,
// which vanishes on white; with the dash patterns below, 6 x 5 = 30 objects get distinct lines.
const char* kPalette[] = {"#E69F00", "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#56B4E9"};
const int kDashes[] = {1, 2, 4, 5, 3};  // gnuplot dash types: solid, dashed, dash-dot, dash-dot-dot, dotted

std::string object_color(std::size_t o) { return kPalette[o % std::size(kPalette)]; }
/// Colour and dash of object o's line: the colour cycles first, then the dash.
std::string object_style(std::size_t o) {
  return fmt::format("lines dt {}", kDashes[(o / std::size(kPalette)) % std::size(kDashes)]);
}

}  // namespace

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

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

/// Base64 (RFC 4648, with '=' padding) of the file's bytes behind the data: URI's prefix.
std::string inline_png(const std::filesystem::path& p) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::string bytes = slurp(p);
  std::string out = "data:image/png;base64,";
  out.reserve(out.size() + 4 * (bytes.size() / 3 + 1));
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 0x3F] : '=';
  }
  return out;
}

/// The SVG without its XML prologue/doctype, for inline embedding.
std::string inline_svg(const std::filesystem::path& p) {
  std::string svg = slurp(p);
  const auto at = svg.find("<svg");
  return at == std::string::npos ? svg : svg.substr(at);
}

namespace {

std::string dims(const ObservedObject& o) {
  const auto cm = [](double m) { return fmt::format("{:.3g} cm", 100.0 * m); };
  switch (o.body.shape) {
    case RockingBody::Shape::block: return fmt::format("block {} x {}", cm(*o.width_m), cm(*o.height_m));
    case RockingBody::Shape::cylinder: return fmt::format("cylinder &#8960; {} x {}", cm(*o.diameter_m), cm(*o.height_m));
    case RockingBody::Shape::general:
      if (!o.body.symmetric()) {  // asymmetric: both pivots; from a scan, the mesh and its plane
        const std::string from_mesh =
            o.mesh_file.empty() ? std::string()
                                : fmt::format(" (mesh {}, azimuth {:g}&#176;{}{})", html_escape(o.mesh_file),
                                              o.mesh_azimuth_deg.value_or(0.0), o.mesh_pose.empty() ? "" : "; ",
                                              html_escape(o.mesh_pose));
        return fmt::format("b1 = {}, b2 = {}, h = {}{}", cm(o.body.pivot_b_m(-1)), cm(o.body.pivot_b_m(1)),
                           cm(o.body.h_m), from_mesh);
      }
      return fmt::format("a = {}, h = {}, D = {:.3g} m&#178;", cm(o.body.a_m), cm(o.body.h_m), o.body.D_m2);
  }
  return "";
}

std::string interval_text(const Interval& iv) {
  return iv.is_value() ? fmt::format("{:.3g}", iv.low) : fmt::format("{:.3g}&ndash;{:.3g}", iv.low, iv.high);
}

/// The observation as scored: a measured distance with the sigma the likelihood uses (sliding_sigma_m), and the given
/// one when the floor raised it.
std::string observed_text(const ObservedObject& o, const ObjectReport& rep, bool three_component) {
  std::string s(outcome_name(o.outcome));
  if (o.slid_m) {
    const double used = sliding_sigma_m(o);
    s += fmt::format(" {:.3g} cm &plusmn; {:.3g} cm", 100.0 * *o.slid_m, 100.0 * used);
    if (used != o.slid_uncertainty_m) {
      s += fmt::format(" (&sigma; used = max(given {:.3g} cm, 25 % of slid, 2 mm))", 100.0 * o.slid_uncertainty_m);
    }
  }
  if (o.slid_at_least_m) s += fmt::format(" &ge; {:.3g} cm", 100.0 * *o.slid_at_least_m);
  if (rep.model == ObjectModel::coupled) {
    s += " (coupled slide-rock model)";
  } else if (three_component) {  // the model its runs used (inversion_3c.cpp): said for every object
    s += rep.model == ObjectModel::slide     ? " (2-D sliding block model)"
         : rep.model == ObjectModel::three_d ? " (3-D rocking model)"
                                             : " (oriented rocking model)";
  }
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

namespace {

/// An object's field P(observation | cell) in the map's layout (row-major over frequency x PGA).
std::vector<double> object_field(const InversionResult& r, std::size_t o) {
  const std::size_t np = r.pga_g.size(), nf = r.freq_hz.size();
  std::vector<double> z(np * nf);
  for (std::size_t j = 0; j < nf; ++j) {
    for (std::size_t i = 0; i < np; ++i) z[j * np + i] = r.objects[o].probability[i * nf + j];
  }
  return z;
}

/// Which side of its P = 0.5 line fits object o's observation: the centroid (in log PGA, log frequency, each scaled
/// by its axis' log span) of the cells where P >= 0.5 against that of the others, along the axis where they differ
/// most. Empty when every cell lies on one side.
std::string fitting_side(const InversionResult& r, std::size_t o) {
  const std::size_t np = r.pga_g.size(), nf = r.freq_hz.size();
  const double sx = std::log(r.pga_g.back() / r.pga_g.front());
  const double sy = std::log(r.freq_hz.back() / r.freq_hz.front());
  double fx = 0, fy = 0, ux = 0, uy = 0;
  std::size_t nfit = 0, nun = 0;
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) {
      const double x = std::log(r.pga_g[i]) / sx, y = std::log(r.freq_hz[j]) / sy;
      if (r.objects[o].probability[i * nf + j] >= 0.5) {
        fx += x, fy += y, ++nfit;
      } else {
        ux += x, uy += y, ++nun;
      }
    }
  }
  if (nfit == 0 || nun == 0) return "";
  const double a = static_cast<double>(nfit), b = static_cast<double>(nun);
  const double dx = fx / a - ux / b, dy = fy / a - uy / b;
  if (std::abs(dx) >= std::abs(dy)) return dx > 0 ? "fits at higher PGA" : "fits at lower PGA";
  return dy > 0 ? "fits at higher frequency" : "fits at lower frequency";
}

/// Object o's line on the map (its P = 0.5 contour, coloured and dashed as the object, labelled with the side that
/// fits), or, when it has none, the reason in words.
struct ObjectLine {
  std::optional<plot::Series> line;
  std::string reason;  ///< why no line, when line is empty
};

ObjectLine object_line(const InversionResult& r, std::size_t o) {
  const ObjectReport& rep = r.objects[o];
  const auto [lo, hi] = std::minmax_element(rep.probability.begin(), rep.probability.end());
  ObjectLine out;
  if (*hi < 0.5) {
    out.reason = fmt::format("P(observation) < 0.5 in every cell (at most {:.2f}): no P = 0.5 line", *hi);
    return out;
  }
  if (*lo >= 0.5) {
    out.reason = fmt::format("P(observation) >= 0.5 in every cell (at least {:.2f}): it fits everywhere, no line", *lo);
    return out;
  }
  plot::Series c = contour_series(r.pga_g, r.freq_hz, object_field(r, o), 0.5,
                                  fmt::format("{} ({}): {}", rep.id, outcome_name(rep.outcome), fitting_side(r, o)));
  c.color = object_color(o);
  c.style = object_style(o);
  c.width = 2.0;
  if (c.x.empty()) {
    out.reason = "its P = 0.5 line has no segment on the grid";
    return out;
  }
  out.line = std::move(c);
  return out;
}

/// The posterior/max level whose highest-posterior-density region holds `mass` (between the last cell in and the
/// first cell out, so the contour separates them).
double hpd_level(const InversionResult& r, double mass) {
  std::vector<double> p = r.posterior;
  std::sort(p.begin(), p.end(), std::greater<>());
  const double peak = p.front();
  double sum = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    sum += p[k];
    if (sum >= mass) return (k + 1 < p.size() ? 0.5 * (p[k] + p[k + 1]) : 0.5 * p[k]) / peak;
  }
  return 0.0;
}

}  // namespace

plot::MapFigure likelihood_map_figure(const InversionResult& r, const Site& site) {
  plot::MapFigure m;
  m.title = fmt::format("{}: posterior over PGA x predominant frequency", site.name);
  m.xlabel = "PGA (g)";
  m.ylabel = "predominant frequency (Hz)";
  m.zlabel = "posterior / its maximum";
  m.log_x = m.log_y = true;
  m.tics_125 = true;
  // Grey field under coloured lines: no object colour is lost on it.
  m.palette = "(0 '#ffffff', 0.5 '#bdbdbd', 1 '#525252')";
  // The legend beside the plot (never over the x label), the colour bar below the legend.
  m.key = "outside right top vertical Left reverse font ',10' samplen 4 spacing 1.15";
  m.colorbox = "user vertical origin screen 0.745, screen 0.10 size screen 0.018, screen 0.36";
  m.x = r.pga_g;
  m.y = r.freq_hz;
  // Map is stored row-major over y (frequency) x x (PGA); the result is indexed [i_pga * nf + j_freq].
  const std::size_t np = r.pga_g.size(), nf = r.freq_hz.size();
  const double peak = *std::max_element(r.posterior.begin(), r.posterior.end());
  m.z.resize(np * nf);
  for (std::size_t j = 0; j < nf; ++j) {
    for (std::size_t i = 0; i < np; ++i) m.z[j * np + i] = r.posterior[i * nf + j] / peak;
  }
  // Credible regions: highest posterior density (the smallest set of cells holding the mass), as in_credible_region.
  // The field is padded with a ring of zeros at the grid's outer edges, so that a region reaching an edge is closed
  // along it instead of left open.
  const auto padded_axis = [](const std::vector<double>& v) {
    std::vector<double> out{v.front() * std::sqrt(v.front() / v[1])};
    out.insert(out.end(), v.begin(), v.end());
    out.push_back(v.back() * std::sqrt(v.back() / v[v.size() - 2]));
    return out;
  };
  const std::vector<double> px = padded_axis(r.pga_g), py = padded_axis(r.freq_hz);
  std::vector<double> pz(px.size() * py.size(), 0.0);
  for (std::size_t j = 0; j < nf; ++j) {
    for (std::size_t i = 0; i < np; ++i) pz[(j + 1) * px.size() + i + 1] = m.z[j * np + i];
  }
  for (const auto& [mass, dash, label] : {std::tuple{0.68, 1, "68 % credible region"}, std::tuple{0.95, 2, "95 % credible region"}}) {
    plot::Series region = contour_series(px, py, pz, hpd_level(r, mass), label);
    region.color = "#000000";
    region.style = fmt::format("lines dt {}", dash);
    region.width = 3.0;
    if (!region.x.empty()) m.overlay.push_back(std::move(region));
  }
  const double fy0 = r.freq_hz.front(), fy1 = r.freq_hz.back();
  const auto threshold_label = [&r](const char* side, double v) {
    bool hard = false;
    for (const auto& b : std::string(side) == "lower" ? r.bounds.lower : r.bounds.upper) hard = hard || (b.hard && b.pga_g == v);
    return fmt::format("static {} threshold {:.3g} g ({})", side, v, hard ? "hard" : "soft");
  };
  if (r.bounds.lower_g) m.overlay.push_back({threshold_label("lower", *r.bounds.lower_g), {*r.bounds.lower_g, *r.bounds.lower_g}, {fy0, fy1}, "lines dt 3", "#c0392b", 2.5});
  if (r.bounds.upper_g) m.overlay.push_back({threshold_label("upper", *r.bounds.upper_g), {*r.bounds.upper_g, *r.bounds.upper_g}, {fy0, fy1}, "lines dt 3", "#8e44ad", 2.5});
  for (std::size_t o = 0; o < r.objects.size(); ++o) {
    ObjectLine line = object_line(r, o);
    if (line.line) m.overlay.push_back(std::move(*line.line));
  }
  // The ridge (evidence.hpp, item 2): the PGA the objects need at each frequency, median and 68 % band, where the
  // column's likelihood is not negligible; a gap where an end is off the grid.
  {
    // Magenta: a colour no object line, threshold or region uses (the objects' palette is Okabe-Ito's).
    plot::Series mid{"PGA the objects need at each frequency (likelihood median)", {}, {}, "lines", "#e7298a", 3.5};
    plot::Series lo{"its 68 % band", {}, {}, "lines dt 4", "#e7298a", 2.0};
    plot::Series hi{"", {}, {}, "lines dt 4", "#e7298a", 2.0};
    for (const PgaGivenFreq& g : r.pga_given_freq) {
      const bool on = g.pga_g.has_value();
      mid.x.push_back(on ? g.pga_g->median : kNaN);
      mid.y.push_back(g.freq_hz);
      lo.x.push_back(on && g.pga_g->ci68_low ? *g.pga_g->ci68_low : kNaN);
      lo.y.push_back(g.freq_hz);
      hi.x.push_back(on && g.pga_g->ci68_high ? *g.pga_g->ci68_high : kNaN);
      hi.y.push_back(g.freq_hz);
    }
    const auto drawn = [](const plot::Series& se) {
      return std::any_of(se.x.begin(), se.x.end(), [](double v) { return std::isfinite(v); });
    };
    if (drawn(mid)) m.overlay.push_back(std::move(mid));
    if (drawn(lo)) m.overlay.push_back(std::move(lo));
    if (drawn(hi)) m.overlay.push_back(std::move(hi));
  }
  m.overlay.push_back({"median (PGA, frequency)", {r.pga_estimate_g.median}, {r.freq_estimate_hz.median}, "points pt 3 ps 2.2", "#000000", 2.0});
  m.overlay.push_back({"maximum-likelihood cell", {r.pga_estimate_g.best}, {r.freq_estimate_hz.best}, "points pt 6 ps 1.6", "#000000", 1.5});
  m.width_px = 1150;
  m.height_px = 760;
  return m;
}

plot::Figure marginal_figure(const InversionResult& r, bool pga) {
  const auto& x = pga ? r.pga_g : r.freq_hz;
  const auto& p = pga ? r.marginal_pga : r.marginal_freq;
  const Estimate& e = pga ? r.pga_estimate_g : r.freq_estimate_hz;
  const char* unit = pga ? "g" : "Hz";
  plot::Figure f;
  f.title = pga ? "PGA: prior, the objects' likelihood and the posterior"
                : "Predominant frequency: prior, the objects' likelihood and the posterior";
  f.xlabel = pga ? "PGA (g)" : "predominant frequency (Hz)";
  plot::Panel panel;
  panel.ylabel = "probability per grid cell";
  panel.log_x = true;
  // Prior and likelihood marginals beside the posterior's (evidence.hpp, item 1): what the prior adds is the
  // difference between the two last curves.
  const std::size_t np = r.pga_g.size(), nf = r.freq_hz.size();
  const std::vector<double> prior = prior_cells(r);
  const std::vector<double> prior_marginal = pga ? marginal_over_pga(prior, np, nf) : marginal_over_freq(prior, np, nf);
  panel.series.push_back({fmt::format("prior ({})", r.prior), x, prior_marginal, "lines dt 2", "#7f7f7f", 2.0});
  const auto& lik = pga ? r.marginal_pga_likelihood : r.marginal_freq_likelihood;
  if (lik.size() == x.size()) {
    // Wide and light under the posterior: under the log-uniform prior the two are one curve, and this one shows as
    // its halo.
    panel.series.push_back({"likelihood (the objects alone)", x, lik, "lines", "#fdae6b", 6.0});
  }
  panel.series.push_back({"posterior", x, p, "linespoints pt 7 ps 0.6", "#2171b5", 2.0});
  double top = *std::max_element(p.begin(), p.end());
  for (const auto& se : panel.series) top = std::max(top, *std::max_element(se.y.begin(), se.y.end()));
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

/// Three components: the posterior of the direction of strongest shaking over [0, 180) deg, its mode and arcs, and the
/// directions the objects give (bearings and sliding directions, mod 180).
plot::Figure direction_figure(const InversionResult& r, const Site& site) {
  const DirectionEstimate& d = r.three_component->direction;
  plot::Figure f;
  f.title = fmt::format("Direction of strongest shaking (azimuth of the major axis of horizontal motion, mod 180 deg): "
                        "{}",
                        d.constrained ? fmt::format("mode {:.0f} deg", d.mode_deg)
                                      : fmt::format("unconstrained (95 % arc {:.0f} deg wide, more than {:.0f})",
                                                    d.ci95.width_deg, kUnconstrainedArcDeg));
  f.xlabel = "azimuth (deg clockwise from north, mod 180)";
  plot::Panel panel;
  panel.ylabel = "posterior probability per bin";
  plot::Series post{"posterior", d.azimuth_deg, d.posterior, "linespoints pt 7 ps 0.6", "#2171b5", 2.0};
  post.x.push_back(180.0);  // the axis at 180 deg is the one at 0
  post.y.push_back(d.posterior.front());
  panel.series.push_back(std::move(post));
  const double top = *std::max_element(d.posterior.begin(), d.posterior.end());
  panel.series.push_back({fmt::format("mode {:.0f} deg", d.mode_deg), {d.mode_deg, d.mode_deg}, {0.0, top}, "lines",
                          "#000000", 2.0});
  // An arc may pass 180 deg: drawn in two pieces, the second unlabelled.
  const auto arc = [&](const DirectionArc& a, const char* label, double y, const char* color) {
    const double end = std::min(a.high_deg(), 180.0);
    panel.series.push_back({label, {a.low_deg, end}, {y, y}, "linespoints pt 2", color, 3.0});
    if (a.high_deg() > 180.0) panel.series.push_back({"", {0.0, a.high_deg() - 180.0}, {y, y}, "linespoints pt 2", color, 3.0});
  };
  arc(d.ci68, "68 % arc", 0.5 * top, "#e6550d");
  arc(d.ci95, "95 % arc", 0.25 * top, "#31a354");
  plot::Series bearings{"objects' bearings", {}, {}, "points pt 13 ps 1.4", "#7f3b08", 1.0};
  plot::Series slid{"sliding directions", {}, {}, "points pt 9 ps 1.4", "#542788", 1.0};
  for (const ObservedObject& o : site.objects) {
    if (o.azimuth_deg) bearings.x.push_back(std::fmod(*o.azimuth_deg, 180.0));
    if (o.slid_azimuth_deg) slid.x.push_back(std::fmod(*o.slid_azimuth_deg, 180.0));
  }
  bearings.y.assign(bearings.x.size(), 0.0);
  slid.y.assign(slid.x.size(), 0.0);
  if (!bearings.x.empty()) panel.series.push_back(std::move(bearings));
  if (!slid.x.empty()) panel.series.push_back(std::move(slid));
  // Populations (issue 30): their fallen azimuths, a sample of fall directions (mod 180: an axis).
  plot::Series fallen{"populations' fall directions", {}, {}, "points pt 5 ps 1.0", "#d95f02", 1.0};
  for (const Population& p : site.populations) {
    for (const double az : p.fallen_azimuths_deg) fallen.x.push_back(std::fmod(az, 180.0));
  }
  fallen.y.assign(fallen.x.size(), 0.0);
  if (!fallen.x.empty()) panel.series.push_back(std::move(fallen));
  f.panels.push_back(panel);
  f.panel_height_px = 380;
  return f;
}

namespace {

/// The tilt (the angle of the body's z axis from the vertical) of a unit quaternion (w, x, y, z): the z component of
/// R e_z is 1 - 2 (x^2 + y^2).
double tilt_of(const Quaternion& q) {
  const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  return std::acos(std::clamp(1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]) / n2, -1.0, 1.0));
}

/// A model = "3d" object's replay (docs/survey.md, "The report"): the three-dimensional engine as its runs use it
/// (inversion_3c.cpp, observation_match_3c: the realisation's minor component as the engine's x, the major as its y,
/// the vertical; amplified, the horizontals through a flexible support; a box or a mesh turned to its bearing from
/// the major axis, 0 when unknown; a cylinder, the rim engine, as it is; friction_3d: mu_s = the nominal mu), drawn
/// as the tilt from Rigid3DHistory over the body's smallest static limit (over every direction: a box's narrower
/// side, a cylinder's atan(R / h)), so that 1 is the first direction in which the centre of mass passes the base.
void replay_3d(const ObservedObject& obj, const DrawnParameters& nominal, const Realisation3c& real, double scale,
               double g, const std::string& color, plot::Panel& rocking) {
  const double amp = nominal.amplification * scale;
  const GroundMotion major = object_motion(obj, nominal, real.major->scaled(amp));
  const GroundMotion minor = object_motion(obj, nominal, real.minor->scaled(amp));
  const GroundMotion vertical = real.vertical->scaled(amp);
  Rigid3DOptions options = rigid3d_options(inversion_rocking_options(obj, nominal, g));
  if (obj.friction_3d) options.mu_s = nominal.mu;
  options.record_history = true;
  Rigid3DResult res;
  double limit = INFINITY;
  if (obj.body_3d) {
    const double angle = obj.azimuth_deg.value_or(0.0);
    const RigidBody3D turned = obj.body_3d->rotated_about_vertical(deg_to_rad(90.0 - angle));
    res = rock3d(minor, &major, &vertical, turned, options);
    for (int a = 0; a < 360; ++a) limit = std::min(limit, turned.static_tilt_limit_rad(a));
  } else {  // a cylinder (survey.cpp: model = "3d" is a box, a mesh or a cylinder)
    const CylinderBody3D cylinder = CylinderBody3D::solid(2.0 * obj.body.a_m, 2.0 * obj.body.h_m);
    res = rock3d_cylinder(minor, &major, &vertical, cylinder, options);
    limit = cylinder.static_tilt_limit_rad();
  }
  std::vector<double> ratio(res.history.time_s.size());
  for (std::size_t i = 0; i < ratio.size(); ++i) ratio[i] = tilt_of(res.history.orientation[i]) / limit;
  const bool observed_fallen = obj.outcome == Outcome::overturned;
  std::string label = obj.id + " (3-D: tilt / smallest static limit)";
  if (res.summary.overturned) {
    label += fmt::format(" (falls toward {:.0f} deg from the major axis{})", res.summary.overturn_azimuth_deg,
                         observed_fallen ? ", as observed" : " in this one motion; observed standing");
  }
  if (!res.summary.overturned && observed_fallen) label += " (stands in this one motion; observed overturned)";
  rocking.series.push_back({label, res.history.time_s, ratio, "lines", color, 1.6});
}

}  // namespace

plot::Figure best_cell_figure(const InversionResult& r, const Site& site, const InversionSettings& settings) {
  const double pga = r.pga_g[r.best_cell / r.freq_hz.size()];
  const double freq = r.freq_hz[r.best_cell % r.freq_hz.size()];
  InversionSettings one = settings;
  one.motions_per_cell = 1;
  // Three components: the major-axis component of the family's first realisation, each object as if across it (an
  // illustration; the runs use the projection on each object's bearing and the vertical, inversion_3c.hpp); a
  // model = "3d" object under the whole realisation (replay_3d).
  const bool three = settings.components == 3;
  const GroundMotion motion = three ? family_realisation_3c(one, freq, 0).major->scaled(pga * settings.g_m_s2)
                                    : family_motions(one, freq).front().scaled(pga * settings.g_m_s2);
  plot::Figure f;
  f.title = fmt::format("Maximum-likelihood cell (PGA {:.3g} g{}, {:.3g} Hz): {}, each object's response", pga,
                        three ? " RotD50" : "", freq,
                        three ? std::any_of(site.objects.begin(), site.objects.end(),
                                            [](const ObservedObject& o) {
                                              return object_model(o) == ObjectModel::three_d;
                                            })
                                    ? "the major-axis component of one motion of the family, each planar object "
                                      "across it, 3-D objects under all three components"
                                    : "the major-axis component of one motion of the family, each object across it"
                              : "one motion of the family");
  f.xlabel = "time (s)";
  plot::Panel ground{"ground acceleration (g)", {}, {}, {}, false, false};
  plot::Series gs{"ground", {}, {}, "lines", "#555555", 1.0};
  for (std::size_t i = 0; i < motion.size(); ++i) {
    gs.x.push_back(motion.time_s(i));
    gs.y.push_back(motion.accel_m_s2()[i] / settings.g_m_s2);
  }
  ground.series.push_back(gs);
  plot::Panel rocking{"rotation theta / alpha", {}, {{1.0, "CM over pivot"}, {-1.0, ""}}, {}, false, false};
  // model = "3d" objects (three components): the whole realisation, as their runs take it (inversion_3c.cpp).
  std::optional<Realisation3c> real;
  if (three) real = family_realisation_3c(one, freq, 0);
  plot::Panel sliding{"sliding displacement (m)", {}, {}, {}, false, false};
  for (std::size_t o = 0; o < site.objects.size(); ++o) {
    const ObservedObject& obj = site.objects[o];
    const std::string color = object_color(o);
    // The inversion's own matching (matching.hpp) at the middle of every range: the model, the motion the object
    // feels (flexible support, amplification, orientation) and the solver options its runs use.
    const DrawnParameters nominal = nominal_parameters(obj);
    const GroundMotion seen = object_motion(obj, nominal, motion);  // through a flexible support, if any
    const double factor = rocking_plane_factor(obj, nominal);
    const ObjectModel model = object_model(obj);
    if (model == ObjectModel::three_d && real) {
      replay_3d(obj, nominal, *real, pga * settings.g_m_s2, settings.g_m_s2, color, rocking);
    } else if (model == ObjectModel::coupled) {
      // The coupled body (survey.hpp, object_model): its tilt over its side's alpha and its base's slide.
      SlideRockOptions opt = inversion_slide_rock_options(obj, nominal, settings.g_m_s2);
      opt.record_history = true;
      const auto res = slide_rock(seen.scaled(factor), SlideRockBody::from_rocking(obj.body, nominal.mu), opt);
      std::vector<double> ratio(res.history.theta_rad.size());
      for (std::size_t i = 0; i < ratio.size(); ++i) {
        const double theta = res.history.theta_rad[i];
        ratio[i] = theta / (theta < 0.0 ? res.summary.alpha_negative_rad : res.summary.alpha_positive_rad);
      }
      const std::string fell = res.summary.overturned ? " (falls in this one motion)" : "";
      rocking.series.push_back({obj.id + " (coupled)" + fell, res.history.time_s, ratio, "lines", color, 1.6});
      sliding.series.push_back({fmt::format("{} (coupled, mu {:.2g})", obj.id, nominal.mu), res.history.time_s,
                                res.history.slide_m, "lines", color, 1.6});
    } else if (model == ObjectModel::slide) {
      const auto res = slide(seen.scaled(nominal.amplification),
                             SlidingBlock::make(nominal.mu, nominal.mu, 0.0, SlidingMode::two_way, settings.g_m_s2));
      sliding.series.push_back({fmt::format("{} (mu {:.2g})", obj.id, nominal.mu), res.history.time_s,
                                res.history.displacement_m, "lines", color, 1.6});
    } else {
      const RockingOptions opt = inversion_rocking_options(obj, nominal, settings.g_m_s2);
      const auto res = rock(seen.scaled(factor), obj.body, opt);
      std::vector<double> ratio(res.history.theta_rad.size());
      // theta over its side's alpha (an asymmetric body: alpha- = atan(b1/h) for theta < 0).
      const double alpha_minus = obj.body.side_body(-1).alpha_rad();
      for (std::size_t i = 0; i < ratio.size(); ++i) {
        const double theta = res.history.theta_rad[i];
        ratio[i] = theta / (theta < 0.0 ? alpha_minus : obj.body.alpha_rad());
      }
      // One motion with nominal parameters is not the likelihood (N motions, drawn parameters): an object observed
      // standing may fall in it, or one observed fallen stand. The label says so rather than contradict the survey.
      const bool observed_fallen = obj.outcome == Outcome::overturned;
      std::string label = obj.id;
      // Which side an asymmetric body falls to: toward +x (about O+, b2) or -x (O-, b1).
      const std::string side = obj.body.symmetric() ? std::string()
                               : res.summary.overturned_side > 0 ? std::string(" toward +x (about b2)")
                                                                 : std::string(" toward -x (about b1)");
      if (res.summary.overturned) {
        label += observed_fallen ? " (falls" + side + ", as observed)"
                                 : " (falls" + side + " in this one motion; observed standing)";
      }
      if (!res.summary.overturned && observed_fallen) label += " (stands in this one motion; observed overturned)";
      rocking.series.push_back({label, res.history.time_s, ratio, "lines", color, 1.6});
    }
  }
  f.panels.push_back(ground);
  if (!rocking.series.empty()) f.panels.push_back(rocking);
  if (!sliding.series.empty()) f.panels.push_back(sliding);
  return f;
}

namespace {

/// A median for the page: the number, or "below/above the grid" when it lies in an edge cell (no estimate).
std::string median_html(const Estimate& e, const std::vector<double>& axis, const char* unit) {
  if (e.median_edge < 0) return fmt::format("below the grid (&le; {:.3g} {})", axis.front(), unit);
  if (e.median_edge > 0) return fmt::format("above the grid (&ge; {:.3g} {})", axis.back(), unit);
  return fmt::format("{:.3g} {}", e.median, unit);
}

std::string interval_html(const std::optional<double>& lo, const std::optional<double>& hi, const char* unit) {
  const std::string a = lo ? fmt::format("{:.3g} {}", *lo, unit) : std::string("below the grid");
  const std::string b = hi ? fmt::format("{:.3g} {}", *hi, unit) : std::string("above the grid");
  return a + " &ndash; " + b;
}

std::string best_html(const Estimate& e, const char* unit) {
  return fmt::format("{:.3g} {}{}", e.best, unit, e.best_edge != 0 ? " (a grid-edge cell: no estimate)" : "");
}

}  // namespace

namespace {

/// The provenance the report shows: the caller's, or, for a library caller without one, the survey file's (when there
/// is one) and an unknown command line.
io::Provenance report_provenance(const Survey& survey, const std::optional<io::Provenance>& given_provenance) {
  std::error_code ec;
  io::Provenance provenance;
  if (given_provenance) {
    provenance = *given_provenance;
  } else if (!survey.source_file.empty() && std::filesystem::is_regular_file(survey.source_file, ec)) {
    provenance = io::make_provenance(survey.source_file, "unknown (the report was written by a library call)");
  } else {
    provenance = io::make_provenance_without_file("unknown (the report was written by a library call)");
  }
  return provenance;
}

/// The page's head, title, summary and location.
void head_html(std::ostringstream& h, const Site& site, const InversionResult& r) {
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>topple: " << html_escape(site.name)
    << "</title>\n<style>\nbody{font-family:Helvetica,Arial,sans-serif;max-width:1150px;margin:2em auto;color:#222;line-height:1.45}\n"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:4px 8px;text-align:left}th{background:#f2f2f2}\n"
       ".num{font-size:1.15em}.note{background:#fff7e6;border-left:4px solid #e6a100;padding:6px 10px;margin:6px 0}\n"
       ".summary{font-size:1.2em;background:#eef5fb;border-left:5px solid #2171b5;padding:10px 14px}\n"
       "tr.misfit td{background:#fde0dc}.flag{color:#b71c1c;font-weight:bold}.def{color:#444;font-size:.92em}\n"
       "#observations{font-size:.85em}.wide{overflow-x:auto}\n"
       "pre{background:#f7f7f7;border:1px solid #ddd;padding:8px;overflow-x:auto;font-size:.85em}\n"
       "figure{margin:1.5em 0}figure svg{max-width:100%;height:auto}figcaption{color:#444;font-size:.92em}\n</style></head><body>\n";
  h << "<h1>Shaking estimated from objects: " << html_escape(site.name) << "</h1>\n";
  h << "<p id=\"summary\" class=\"summary\">" << html_escape(inversion_summary(r)) << "</p>\n";
  if (site.lat_deg && site.lon_deg) h << fmt::format("<p>Location {:.4f}&deg;, {:.4f}&deg;.</p>\n", *site.lat_deg, *site.lon_deg);
  if (!site.notes.empty()) h << "<p>" << html_escape(site.notes) << "</p>\n";

}

/// The estimate, every number defined beside it.
void estimate_html(std::ostringstream& h, const InversionResult& r) {
  const Estimate& pga = r.pga_estimate_g;
  const Estimate& freq = r.freq_estimate_hz;
  h << "<h2 id=\"estimate\">Estimate</h2>\n<table id=\"numbers\"><tr><th></th><th>median</th><th>68 % interval</th>"
       "<th>95 % interval</th><th>maximum-likelihood cell</th></tr>\n";
  h << fmt::format("<tr><td>PGA</td><td class=\"num\">{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                   median_html(pga, r.pga_g, "g"), interval_html(pga.ci68_low, pga.ci68_high, "g"),
                   interval_html(pga.ci95_low, pga.ci95_high, "g"), best_html(pga, "g"));
  h << fmt::format("<tr><td>predominant frequency</td><td class=\"num\">{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                   median_html(freq, r.freq_hz, "Hz"), interval_html(freq.ci68_low, freq.ci68_high, "Hz"),
                   interval_html(freq.ci95_low, freq.ci95_high, "Hz"), best_html(freq, "Hz"));
  if (!r.marginal_pga_likelihood.empty()) {
    // The objects alone (evidence.hpp, item 1): the likelihood normalised over the grid, no prior; the same numbers
    // as the rows above under the log-uniform prior.
    const Estimate& lp = r.pga_likelihood_g;
    const Estimate& lf = r.freq_likelihood_hz;
    h << fmt::format("<tr id=\"likelihood-pga\"><td>PGA, the objects alone (likelihood, no prior)</td><td class=\"num\">"
                     "{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                     median_html(lp, r.pga_g, "g"), interval_html(lp.ci68_low, lp.ci68_high, "g"),
                     interval_html(lp.ci95_low, lp.ci95_high, "g"), best_html(lp, "g"));
    h << fmt::format("<tr id=\"likelihood-freq\"><td>predominant frequency, the objects alone</td><td class=\"num\">"
                     "{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                     median_html(lf, r.freq_hz, "Hz"), interval_html(lf.ci68_low, lf.ci68_high, "Hz"),
                     interval_html(lf.ci95_low, lf.ci95_high, "Hz"), best_html(lf, "Hz"));
  }
  if (r.three_component) {  // components = 3 (inversion_3c.hpp): the direction of strongest shaking, an axis
    const DirectionEstimate& d = r.three_component->direction;
    const auto arc = [](const DirectionArc& a) {
      return fmt::format("{:.0f}&ndash;{:.0f}&deg;", a.low_deg, a.high_deg());
    };
    h << fmt::format("<tr id=\"direction\"><td>direction of strongest shaking (azimuth of the major axis, mod 180&deg;)"
                     "</td><td class=\"num\">{}</td><td>{}</td><td>{}</td><td>bin {:.0f}&deg;</td></tr>\n",
                     d.constrained ? fmt::format("{:.0f}&deg;", d.mode_deg) : std::string("unconstrained"),
                     arc(d.ci68), arc(d.ci95), d.mode_deg);
  }
  h << "</table>\n<p class=\"def\" id=\"definitions\"><b>Median</b>: half of the posterior probability lies below it. "
       "<b>68 % / 95 % interval</b>: equal-tailed credible intervals of the marginal posterior (16&ndash;84 % and "
       "2.5&ndash;97.5 % of its probability); an end written &ldquo;below/above the grid&rdquo; falls in the grid's "
       "first or last cell, where the observations do not bound it. <b>Maximum-likelihood cell</b>: the grid cell "
       "whose likelihood is largest; among cells of nearly equal likelihood it moves with the seed, so it is a "
       "diagnostic, not the estimate. <b>Predominant frequency</b>: the peak of the motion's Konno&ndash;Ohmachi-"
       "smoothed Fourier amplitude spectrum. PGA in g = 9.80665 m/s&#178;.</p>\n";
}

/// A site's macroseismic intensity (issue 30; region/intensity.hpp, eqs. I1-I3): its value, scale and reports, the
/// PGA it implies through WGRW12 with its 95 % interval, and whether the objects' own estimate agrees with it (the
/// test the regional page and the JSON apply, objects_agree_with_intensity). Nothing for a site without one.
void intensity_html(std::ostringstream& h, const Site& site, const InversionResult& r) {
  if (!site.intensity) return;
  const IntensityPga i = intensity_pga(*site.intensity);
  const bool agree = objects_agree_with_intensity(r.pga_estimate_g, i);
  h << "<h2 id=\"intensity\">Macroseismic intensity</h2>\n";
  h << fmt::format("<p id=\"intensity-value\">{} {:g} from {}; through the conversion PGA {:.3g} g, 95 % interval "
                   "[{:.3g}, {:.3g}] g (&sigma; = {:.3g} in ln PGA, of which {:.3g} intensity units from the number "
                   "of reports){}.</p>\n",
                   intensity_scale_name(i.intensity.scale), i.intensity.value,
                   i.intensity.reports ? fmt::format("{} report{}", *i.intensity.reports,
                                                     *i.intensity.reports == 1 ? "" : "s")
                                       : std::string("an unstated number of reports (counted as one)"),
                   i.pga_g, i.ci95_low_g(), i.ci95_high_g(), i.sigma_ln, i.sigma_intensity,
                   i.extrapolated ? " (extrapolated: above MMI 10 the conversion has no data)" : "");
  h << fmt::format("<p id=\"intensity-check\">{}: {}.</p>\n",
                   agree ? "The objects agree with the intensity"
                         : "<span class=\"flag\">The objects disagree with the intensity</span>",
                   html_escape(std::string(kIntensityAgreementTest)));
  h << "<p class=\"def\">Conversion: " << html_escape(std::string(kIntensityConversion))
    << " (docs/method.md, &ldquo;Macroseismic intensity as PGA evidence&rdquo;). The estimate above is the "
       "objects' alone; the intensity enters the regional fit of a survey with several sites.</p>\n";
}

/// Static thresholds, hard and soft, beside the estimate; then the notes.
void thresholds_html(std::ostringstream& h, const InversionResult& r) {
  const Estimate& pga = r.pga_estimate_g;
  h << "<h2 id=\"thresholds\">Static thresholds</h2>\n<table id=\"static\"><tr><th>object</th><th>threshold on PGA</th>"
       "<th>kind</th><th>from</th></tr>\n";
  const auto threshold_row = [&h](const StaticBound& b, const char* relation, const char* axis) {
    h << fmt::format("<tr><td>{}</td><td>{}PGA {} {:.3g} g</td><td>{}</td><td>{}</td></tr>\n", html_escape(b.object_id),
                     axis, relation, b.pga_g, b.hard ? "hard" : "soft", html_escape(b.reason));
  };
  // Three components (inversion_3c.hpp, item 6): the thresholds on RotD100, where they hold, each followed by its
  // consequence on RotD50, the axis of the estimate and of Figure 1 (the lists are in the same order).
  const StaticBounds* r100 = r.rotd100_bounds ? &*r.rotd100_bounds : nullptr;
  for (std::size_t i = 0; i < r.bounds.lower.size(); ++i) {
    if (r100 != nullptr) threshold_row(r100->lower.at(i), "&gt;", "RotD100 ");
    threshold_row(r.bounds.lower[i], "&gt;", r100 != nullptr ? "RotD50 " : "");
  }
  for (std::size_t i = 0; i < r.bounds.upper.size(); ++i) {
    if (r100 != nullptr) threshold_row(r100->upper.at(i), "&le;", "RotD100 ");
    threshold_row(r.bounds.upper[i], "&le;", r100 != nullptr ? "RotD50 " : "");
  }
  if (r.bounds.lower.empty() && r.bounds.upper.empty()) h << "<tr><td colspan=\"4\">none: no object slid, rocked, overturned or was seen not to slide</td></tr>\n";
  h << "</table>\n<p class=\"def\" id=\"hard-soft\">A <b>hard</b> threshold comes from an object that slid, rocked or "
       "overturned: the physics forbids that below it (no slip while the support's acceleration stays under "
       "&mu;g, no uplift while it stays under g&middot;b/h, b/h the half-width over the height of the centre of mass); "
       "only a wrong observation crosses it. A <b>soft</b> threshold comes from an object that did <i>not</i> slide "
       "visibly: the ground may pass &mu;g for an instant and slip it less than the visible 2 mm, so it is no bound, "
       "and the dynamic estimate, which simulates how far each object would slide, may lie above it.";
  if (r100 != nullptr) {
    h << " <b>Three components</b>: uplift and slip answer to the horizontal acceleration <i>vector</i> and the "
         "vertical, and every bearing's projection peaks at most at RotD100 PGA (the peak over all directions), so "
         "the thresholds hold on RotD100, with the family's vertical lowering an object's uplift and slip levels; "
         "RotD50, the axis of the estimate and of Figure 1, is at least 0.704 RotD100 for any pair, which carries "
         "each threshold over, weaker (docs/method.md, &ldquo;Static thresholds in three components&rdquo;).";
  }
  for (const auto& b : r.bounds.upper) {
    if (!b.hard && pga.median_edge == 0 && pga.median > b.pga_g) {
      h << fmt::format(" Here the median {:.3g} g lies above the soft threshold {:.3g} g of {}: the runs find that "
                       "shaking of that strength slips it less than 2 mm often enough.",
                       pga.median, b.pga_g, html_escape(b.object_id));
    }
  }
  h << "</p>\n";
  for (const auto& note : r.notes) h << "<p class=\"note\">" << html_escape(note) << "</p>\n";
}

/// The representative members the populations ran (each one run per motion, as an object): for the runs per cell.
std::size_t population_members_simulated(const InversionResult& r) {
  std::size_t n = 0;
  for (const PopulationReport& p : r.populations) n += p.members;
  return n;
}

/// Populations (issue 30; docs/method.md, "Populations of objects"): each population's observed overturned fraction
/// (dashed, constant) against the model's, over PGA in the median frequency's column (top) and over frequency in the
/// median PGA's row (bottom): the slices of io::populations_json.
plot::Figure population_figure(const InversionResult& r) {
  const io::PopulationSlices at = io::population_slices_at_estimate(r);
  const std::size_t nf = r.freq_hz.size();
  plot::Figure f;
  f.title = "Populations: the observed overturned fraction against the model's";
  f.xlabel = fmt::format("PGA (g), at {:.3g} Hz (the median frequency's column)", r.freq_hz[at.freq_column]);
  plot::Panel over_pga{"overturned fraction", {}, {}, {}, true, false};
  plot::Panel over_freq{"overturned fraction", {}, {}, {}, true, false};
  for (std::size_t p = 0; p < r.populations.size(); ++p) {
    const PopulationReport& rep = r.populations[p];
    std::vector<double> by_pga, by_freq;
    for (std::size_t i = 0; i < r.pga_g.size(); ++i) by_pga.push_back(rep.model_fraction[i * nf + at.freq_column]);
    for (std::size_t j = 0; j < nf; ++j) by_freq.push_back(rep.model_fraction[at.pga_row * nf + j]);
    const std::string color = object_color(p);
    over_pga.series.push_back({fmt::format("{}: model", rep.id), r.pga_g, by_pga, "linespoints pt 7 ps 0.6", color, 2.0});
    over_pga.series.push_back({fmt::format("{}: observed {} of {}", rep.id, rep.overturned, rep.count),
                               {r.pga_g.front(), r.pga_g.back()}, {rep.observed_fraction, rep.observed_fraction},
                               "lines dt 2", color, 2.0});
    over_freq.series.push_back({fmt::format("{}: model", rep.id), r.freq_hz, by_freq, "linespoints pt 7 ps 0.6", color, 2.0});
    over_freq.series.push_back({fmt::format("{}: observed", rep.id), {r.freq_hz.front(), r.freq_hz.back()},
                                {rep.observed_fraction, rep.observed_fraction}, "lines dt 2", color, 2.0});
  }
  f.panels = {over_pga, over_freq};
  f.own_xlabels = {"", fmt::format("predominant frequency (Hz), at {:.3g} g (the median PGA's row)", r.pga_g[at.pga_row])};
  f.panel_height_px = 300;
  return f;
}

/// The populations' table and Figure 5 (only for a survey with populations).
void populations_html(std::ostringstream& h, const std::filesystem::path& dir, const InversionResult& r) {
  if (r.populations.empty()) return;
  h << "<h2 id=\"populations\">Populations</h2>\n<table id=\"populations-table\">\n<tr><th>population</th><th>count</th>"
       "<th>overturned</th><th>observed fraction</th><th>model at the estimate</th><th>posterior-predictive</th>"
       "<th>members simulated</th></tr>\n";
  for (const PopulationReport& p : r.populations) {
    h << fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{:.3f}</td><td>{}</td></tr>\n",
                     html_escape(p.id), p.count, p.overturned, p.observed_fraction, p.model_fraction_at_estimate,
                     p.posterior_predictive_fraction, html_escape(p.member_rule));
  }
  h << "</table>\n<figure id=\"population-figure\">" << inline_svg(dir / "population.svg")
    << "<figcaption>Figure 5. Each population's observed overturned fraction (dashed) against the model's (the mean, "
       "over the cell's motions, of the share of its representative members that overturned): over PGA in the median "
       "frequency's column (top) and over frequency in the median PGA's row (bottom). The likelihood of the counts is "
       "the multinomial under each motion, averaged over the motions (docs/method.md, \"Populations of "
       "objects\").</figcaption></figure>\n";
}

/// Figures 1 to 3b, each with its caption (the SVGs already written in `dir`).
void figures_html(std::ostringstream& h, const std::filesystem::path& dir, const InversionResult& r) {
  std::string undrawn;
  for (std::size_t o = 0; o < r.objects.size(); ++o) {
    const ObjectLine line = object_line(r, o);
    if (!line.line) undrawn += fmt::format(" {} ({}): {}.", html_escape(r.objects[o].id), outcome_name(r.objects[o].outcome), line.reason);
  }
  h << "<figure id=\"map\">" << inline_svg(dir / "likelihood.svg")
    << "<figcaption>Figure 1. Posterior probability over PGA and predominant frequency (log axes; grey shade: the "
       "posterior divided by its maximum). Black lines: the 68 % (solid) and 95 % (dashed) credible regions, the "
       "smallest sets of cells holding that probability. Dotted vertical lines: the static lower and upper "
       "thresholds (hard or soft, see above). Coloured lines: for each object the line where its observation has "
       "probability 0.5; the legend says on which side it fits. Magenta: the ridge, the PGA the objects need at each "
       "frequency (the median of that frequency's likelihood over PGA, no prior; dashed: its 68 % band; absent where "
       "that frequency's likelihood is negligible): if the frequency is known from elsewhere, read the PGA off it "
       "(JSON: pga_given_freq). Cross: the medians; circle: the maximum-likelihood cell.";
  if (!undrawn.empty()) h << " Not drawn:" << undrawn;
  h << "</figcaption></figure>\n";
  h << "<figure id=\"marginal-pga\">" << inline_svg(dir / "marginal_pga.svg")
    << "<figcaption>Figure 2. PGA: the marginal posterior (blue; the probability of each grid cell, the posterior "
       "summed over frequency) beside the prior's marginal (grey, dashed) and the objects' own evidence (wide light orange: "
       "the likelihood normalised over the grid, i.e. the posterior under the log-uniform prior, under which the two "
       "curves coincide), with the posterior's "
       "median and its 68 % and 95 % intervals (drawn where both ends are on the grid). Where orange and blue differ, "
       "the prior, not the objects, made the difference.</figcaption></figure>\n";
  h << "<figure id=\"marginal-freq\">" << inline_svg(dir / "marginal_freq.svg")
    << "<figcaption>Figure 3. Predominant frequency: the marginal posterior (the posterior summed over PGA), the "
       "prior's and the likelihood's, as in Figure 2, with the posterior's median and the 68 % and 95 % "
       "intervals.</figcaption></figure>\n";
  if (r.three_component) {
    h << "<figure id=\"direction-figure\">" << inline_svg(dir / "direction.svg")
      << "<figcaption>Figure 3b. Posterior of the direction of strongest shaking, the azimuth of the major axis of "
         "horizontal motion (an axis: 10&deg; and 190&deg; are one direction), per bin, with its mode and its 68 % and "
         "95 % arcs (the shortest arcs holding those shares of the highest bins; an arc passing 180&deg; goes on "
         "from 0&deg;). Diamonds on the axis: the objects' bearings (across their narrow side, mod 180&deg;); "
         "triangles: observed sliding directions; filled squares: the populations' fall directions. The direction is unconstrained when the 95 % arc spans more "
         "than 120&deg;.</figcaption></figure>\n";
  }
}

/// What to look for next (evidence.hpp, item 3): the catalogue ranked by expected information gain.
void next_objects_html(std::ostringstream& h, const InversionResult& r) {
  if (r.next_objects.empty()) return;
  h << "<h2 id=\"next\">What to look for next</h2>\n<p>Before leaving the site: the expected information (bits) that "
       "seeing what happened to one more object of each kind would add to the PGA and to the frequency, for the "
       "answer above (Lindley 1956: the entropy of the marginal now, less its expected entropy after the "
       "observation; 1 bit halves the uncertainty). Each object's outcome was simulated under the inversion's own motions "
       "(the first ten of each cell, pooled over neighbouring cells) in the cells that hold 99.9 % of the posterior, "
       "on a rigid support (amplification 1).</p>\n"
       "<table id=\"next-objects\"><tr><th>object</th><th>size and base</th><th>look for</th><th>bits on PGA</th>"
       "<th>bits on frequency</th></tr>\n";
  for (const NextObject& n : r.next_objects) {
    h << fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{:.2f}</td><td class=\"num\">{:.2f}"
                     "</td></tr>\n",
                     html_escape(n.object), html_escape(n.description), html_escape(n.look_for), n.bits_pga,
                     n.bits_freq);
  }
  h << "</table>\n";
}

/// The observations and how well the answer explains each, and Figure 4.
void observations_html(std::ostringstream& h, const std::filesystem::path& dir, const Site& site,
                       const InversionResult& r) {
  h << "<h2 id=\"objects\">Observations</h2>\n<div class=\"wide\"><table id=\"observations\"><tr><th>id</th><th>description</th>"
       "<th>geometry</th><th>&mu;</th><th>e</th><th>support (amplification)</th><th>observed</th><th>evidence</th>"
       "<th>static threshold</th><th>P(observation), posterior-predictive</th><th>P at the maximum-likelihood cell</th>"
       "<th>information (bits)</th></tr>\n";
  for (std::size_t o = 0; o < site.objects.size(); ++o) {
    const ObservedObject& obj = site.objects[o];
    const ObjectReport& rep = r.objects[o];
    std::string bound = "&ndash;";
    for (const auto& b : r.bounds.lower) if (b.object_id == obj.id) bound = html_escape(b.reason) + (b.hard ? " (hard)" : " (soft)");
    for (const auto& b : r.bounds.upper) if (b.object_id == obj.id) bound = html_escape(b.reason) + (b.hard ? " (hard)" : " (soft)");
    const bool sliding = object_model(obj) == ObjectModel::slide;
    const std::string e = sliding ? std::string("&ndash; (not used: sliding)")
                          : obj.e_housner ? fmt::format("Housner {:.3f}", housner_restitution(obj.body))
                                          : interval_text(obj.e);
    h << fmt::format("<tr{}><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{} ({})</td><td>{}</td><td>{}</td>"
                     "<td>{}</td><td>{:.3f}{}</td><td>{:.2f}</td><td>{:.2f}</td></tr>\n",
                     rep.misfit ? " class=\"misfit\"" : "", html_escape(obj.id), html_escape(obj.description), dims(obj),
                     interval_text(obj.mu), e, html_escape(obj.support), interval_text(obj.amplification),
                     observed_text(obj, rep, r.three_component.has_value()), evidence_name(obj.evidence), bound, rep.posterior_predictive,
                     rep.misfit ? " <span class=\"flag\">MISFIT</span>" : "", rep.probability_at_best,
                     rep.constraint_bits);
  }
  h << "</table></div>\n<p class=\"def\"><b>P(observation), posterior-predictive</b>: the probability of the object's "
       "observation averaged over the posterior (each cell's share of runs that reproduce it, weighted by the cell's "
       "posterior probability); below "
    << kMisfitProbability
    << " the object is flagged <span class=\"flag\">MISFIT</span>: the answer does not explain it (check the "
       "observation, its friction and its support). For a measured sliding distance a run scores exp(&minus;z&#178;/2), "
       "z the residual over &sigma;, so P stays well below 1 even where it fits (the runs scatter around the observed distance). <b>P at the maximum-likelihood "
       "cell</b>: the same at that one cell. <b>Information</b>: how much the object's observation changes the answer, "
       "the Kullback&ndash;Leibler divergence (bits) of the posterior from the posterior computed without that object; "
       "the summary names the largest (each &ge; 0.1 bit, at most three).</p>\n";
  h << "<figure id=\"best-cell\">" << inline_svg(dir / "best_cell.svg")
    << "<figcaption>Figure 4. One motion of the family at the maximum-likelihood cell and each object's response with "
       "nominal parameters (rocking objects as &theta;/&alpha;, where &plusmn;1 is the centre of mass over the pivot; "
       "sliding ones as displacement). One motion is one sample: an object observed standing may fall in it (its label "
       "then says so) while most motions of the cell leave it standing; the likelihood counts every motion with drawn "
       "parameters.</figcaption></figure>\n";
}

/// The method in short, with the grid and the family of this run.
void method_html(std::ostringstream& h, const InversionSettings& st, const Site& site, const InversionResult& r) {
  h << "<h2>Method in short</h2>\n<ol>\n"
       "<li>Static thresholds (Mittal 1971, section 1.1): an object that slid needs PGA &gt; &mu;g, one that rocked or "
       "overturned PGA &gt; g&middot;b/h (divided by the support's amplification): hard; one that did not slide "
       "visibly gives PGA &le; &mu;g: soft.</li>\n"
    << fmt::format("<li>Dynamic inversion: on a grid of {} PGA values ({:.3g}&ndash;{:.3g} g) &times; {} predominant "
                   "frequencies ({:.3g}&ndash;{:.3g} Hz), log-spaced, every object is simulated under {} {} motions per "
                   "cell (sliding: exact Coulomb block; rocking: Housner's equation with impacts and overturning), with "
                   "uncertain &mu;, e and amplification drawn per motion. The frequency axis is the motions' measured "
                   "predominant frequency (peak of the Konno&ndash;Ohmachi-smoothed Fourier amplitude spectrum).</li>\n",
                   st.pga_count, st.pga_min_g, st.pga_max_g, st.freq_count, st.freq_min_hz, st.freq_max_hz,
                   r.runs / std::max<std::size_t>(1, (site.objects.size() + population_members_simulated(r)) *
                                                         r.pga_g.size() * r.freq_hz.size()),
                   st.family == MotionFamily::synthetic      ? "synthetic (Clough&ndash;Penzien filtered noise)"
                   : st.family == MotionFamily::rezaeian2010 ? "synthetic record-like (Rezaeian &amp; Der Kiureghian 2010)"
                   : st.family == MotionFamily::boore2003
                       ? "stochastic point-source (Boore 2003: Brune source, magnitude and distance drawn for the frequency)"
                   : st.family == MotionFamily::mixture
                       ? "model-averaged (half synthetic Clough&ndash;Penzien, half stochastic point-source Boore 2003, "
                         "prior weights 1/2 each)"
                       : "recorded")
    << "<li>All objects saw the same motion: a cell's likelihood is the average over its motions of the product over "
       "objects of 0.98 (certain), 0.90 (likely) or 0.75 (reported) when the run reproduces the observation and 0.02, "
       "0.10 or 0.25 when it does not (the chance that the observation itself is wrong); the runs of neighbouring "
       "cells are pooled. Prior uniform in log PGA and log frequency. Intervals are equal-tailed from the marginal "
       "posteriors; an end that lies in the grid's first or last cell is reported as below/above the grid.</li>\n</ol>\n";

}

/// Provenance: enough to trace and rerun the result.
void provenance_html(std::ostringstream& h, const io::Provenance& provenance, const InversionSettings& st,
                     const InversionResult& r) {
  h << "<h2 id=\"provenance\">Provenance</h2>\n<table id=\"provenance-table\">\n";
  const auto row = [&h](const char* key, const std::string& value) {
    h << "<tr><th>" << key << "</th><td><code>" << html_escape(value) << "</code></td></tr>\n";
  };
  for (const io::ProvenanceField& field : io::kProvenanceFields) {
    if (field.label != nullptr) row(field.label, provenance.*field.member);
  }
  h << "</table>\n";
  h << fmt::format("<p>Family {}, seed {}, g = {} m/s&#178;, {} runs in {:.1f} s.</p>\n",
                   motion_family_name(st.family), st.seed, st.g_m_s2, r.runs, r.seconds);
  if (!r.family_weights.empty()) {  // family = "mixture": what the objects made of its members
    h << "<p>Posterior weights of the mixture's families (prior weights in brackets):";
    for (const FamilyWeight& w : r.family_weights) {
      h << fmt::format(" {} {:.2f} ({:.2f});", w.family, w.posterior_weight, w.prior_weight);
    }
    h << "</p>\n";
  }
  if (st.family == MotionFamily::records) {
    h << "<ul>";
    for (const auto& rec : st.records) h << "<li><code>" << html_escape(rec) << "</code></li>";
    h << "</ul>\n";
  }
  h << "<p>The survey, verbatim:</p>\n<pre id=\"survey-text\">" << html_escape(provenance.survey_text) << "</pre>\n";
  h << "<p>Files beside this page: <a href=\"grid.csv\">grid.csv</a> (the likelihood grid), <a href=\"result.json\">result.json</a>.</p>\n";
}

}  // namespace

void write_report(const std::filesystem::path& dir, const Survey& survey, const Site& site, const InversionResult& r,
                  const std::optional<io::Provenance>& given_provenance) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError(fmt::format("cannot create the report directory '{}': {}", dir.string(), ec.message()));
  const io::Provenance provenance = report_provenance(survey, given_provenance);
  plot::render(likelihood_map_figure(r, site), dir / "likelihood.svg");
  plot::render(marginal_figure(r, true), dir / "marginal_pga.svg");
  plot::render(marginal_figure(r, false), dir / "marginal_freq.svg");
  plot::render(best_cell_figure(r, site, survey.inversion), dir / "best_cell.svg");
  if (r.three_component) plot::render(direction_figure(r, site), dir / "direction.svg");
  if (!r.populations.empty()) plot::render(population_figure(r), dir / "population.svg");
  io::write_inversion_grid_csv(dir / "grid.csv", r);
  io::write_file_atomically(dir / "result.json", io::inversion_json(r, site, provenance).dump(2) + "\n");
  std::ostringstream h;
  head_html(h, site, r);
  estimate_html(h, r);
  intensity_html(h, site, r);
  thresholds_html(h, r);
  figures_html(h, dir, r);
  next_objects_html(h, r);
  observations_html(h, dir, site, r);
  populations_html(h, dir, r);
  method_html(h, survey.inversion, site, r);
  provenance_html(h, provenance, survey.inversion, r);
  h << "</body></html>\n";
  io::write_file_atomically(dir / "index.html", h.str());
}

}  // namespace topple
