#include "topple/output/plot.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"

namespace topple::plot {
namespace {

std::string terminal_for(const std::filesystem::path& path, int width, int height) {
  const std::string ext = path.extension().string();
  if (ext == ".svg") return fmt::format("set terminal svg size {},{} dynamic noenhanced font 'Helvetica,12' background '#ffffff'", width, height);
  if (ext == ".png") return fmt::format("set terminal pngcairo size {},{} noenhanced font 'Helvetica,11'", width, height);
  throw InputError(InputLocation{path.string(), {}, "--plot"}, "figures are written as .svg or .png");
}

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

/// Characters as drawn (UTF-8 code points: "θ" is one), for the layout estimates below.
std::size_t display_length(std::string_view s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// Layout estimates in pixels per character: Helvetica's mean advance is about 0.55 em, taken here as 0.75 em so that
// a label of wide letters (digits, capitals, "W") still fits; a little too much room is harmless, a clipped legend
// ("beta =" cut off) is not.
constexpr double kKeyCharPx = 7.5;     // key font ',10'
constexpr double kTitleCharPx = 9.75;  // title font ',13'

/// The title broken into lines that fit `width_px` (at ", " and ": ", never inside a number), as one gnuplot string
/// with "\n" between the lines; `lines` gets their count.
std::string wrapped_title(const std::string& title, int width_px, int& lines) {
  const auto fit = static_cast<std::size_t>(std::max(20.0, (width_px - 40) / kTitleCharPx));
  std::vector<std::string> out{""};
  std::size_t start = 0;
  while (start < title.size()) {
    // The next piece ends after a ", " or ": " separator (kept with the piece), or at the end.
    std::size_t end = title.size();
    for (std::size_t i = start; i + 1 < title.size(); ++i) {
      if ((title[i] == ',' || title[i] == ':') && title[i + 1] == ' ') {
        end = i + 2;
        break;
      }
    }
    const std::string piece = title.substr(start, end - start);
    if (!out.back().empty() && display_length(out.back()) + display_length(piece) > fit) out.emplace_back();
    out.back() += piece;
    start = end;
  }
  lines = static_cast<int>(out.size());
  std::string joined;
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::string line = out[i];
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::string q = quote(line);
    joined += i == 0 ? q.substr(0, q.size() - 1) : "\\n" + q.substr(1, q.size() - 2);
  }
  return joined + "\"";
}

/// Pixels the legend of `panel` needs beside the plot: its longest label, the sample line (samplen 2) and the gap.
double key_width_px(const Panel& panel) {
  std::size_t longest = 0;
  for (const Series& s : panel.series) longest = std::max(longest, display_length(s.label));
  for (const Level& l : panel.levels) longest = std::max(longest, display_length(l.label));
  return longest == 0 ? 0.0 : kKeyCharPx * static_cast<double>(longest) + 70.0;
}

/// Inline data block $name with x y rows; non-finite values become gaps.
void datablock(std::ostringstream& os, const std::string& name, const std::vector<double>& x,
               const std::vector<double>& y) {
  os << '$' << name << " << EOD\n";
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) {
      os << fmt::format("{:.10g} {:.10g}\n", x[i], y[i]);
    } else {
      os << "\n";
    }
  }
  os << "EOD\n";
}

std::string series_clause(const Series& s, const std::string& block) {
  std::string clause = fmt::format("{} using 1:2 with {} lw {}", block, s.style, s.width);
  if (!s.color.empty()) clause += fmt::format(" lc rgb '{}'", s.color);
  clause += s.label.empty() ? " notitle" : " title " + quote(s.label);
  return clause;
}

}  // namespace

void run_figure_program(const std::string& program, const std::string& script, const std::string& script_suffix,
                        const std::vector<std::string>& arguments, io::OutputFile& image, const std::string& hint) {
  const std::filesystem::path script_path = image.temporary_path().string() + script_suffix;
  const int slot = io::register_temporary(script_path);
  struct RemoveScript {
    const std::filesystem::path& path;
    int slot;
    ~RemoveScript() {
      std::error_code ec;
      std::filesystem::remove(path, ec);
      io::unregister_temporary(slot);
    }
  } remove_script{script_path, slot};
  io::write_file_atomically(script_path, script);
  // Every word goes through /bin/sh in single quotes; a quote inside one is closed, escaped and reopened.
  const auto shell_word = [](const std::string& word) {
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
  };
  std::string cmd = program + " " + shell_word(script_path.string());
  for (const std::string& a : arguments) cmd += " " + shell_word(a);
  cmd += " 2>&1";
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot start " + program);
  std::string messages;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0) messages.append(buffer, got);
  const int status = pclose(pipe.release());
  if (status != 0) {
    throw std::runtime_error(fmt::format("{} failed ({}) writing {}: {}", program, hint, image.final_path().string(),
                                         messages));
  }
  image.commit();
}

namespace {

template <class F>
void render_figure(const F& figure, const std::filesystem::path& path) {
  (void)terminal_for(path, 1, 1);  // a bad extension is bad input (exit 2), before any file is touched
  io::OutputFile image(path);
  // gnuplot writes the figure to the temporary file itself (the script's `set output`).
  run_figure_program("gnuplot", gnuplot_script(figure, image.temporary_path()), ".gp", {}, image,
                     "is gnuplot-nox installed?");
}

/// Explicit tics at 1, 2 and 5 x 10^k within [lo, hi] (a log axis), labelled as plain numbers ("0.2", "5"): gnuplot's
/// default labels only the decades. Minor tics at the other integers x 10^k.
std::string tics_125(double lo, double hi) {
  std::string out = "(";
  for (int k = static_cast<int>(std::floor(std::log10(lo))); k <= static_cast<int>(std::ceil(std::log10(hi))); ++k) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, k);
      if (v < lo * (1.0 - 1e-9) || v > hi * (1.0 + 1e-9)) continue;
      const bool major = m == 1 || m == 2 || m == 5;
      out += fmt::format("{}{} {:.10g}{}", out.size() > 1 ? ", " : "", major ? quote(fmt::format("{:g}", v)) : "\"\"",
                         v, major ? "" : " 1");
    }
  }
  return out + ")";
}

}  // namespace

std::string gnuplot_script(const Figure& f, const std::filesystem::path& path) {
  std::ostringstream os;
  const int n = static_cast<int>(f.panels.size());
  // Nothing clipped: the legends get the right margin their longest label needs (the figure widens when the plots
  // would keep less than 55 % of it), and a long title wraps onto more lines, each given its height.
  double key_px = 0.0;
  for (const Panel& panel : f.panels) key_px = std::max(key_px, key_width_px(panel));
  const int width_px = std::max(f.width_px, static_cast<int>(std::ceil(key_px / 0.36)));
  const double rmargin = std::min(0.78, 1.0 - key_px / width_px);
  int title_lines = 1;
  const std::string title = wrapped_title(f.title, width_px, title_lines);
  os << terminal_for(path, width_px, std::max(1, n) * f.panel_height_px + 40 + 20 * title_lines) << "\n";
  os << "set output " << quote(path.string()) << "\n";
  os << "set grid lc rgb '#dddddd'\nset border lc rgb '#444444'\n";
  for (int p = 0; p < n; ++p) {
    for (std::size_t s = 0; s < f.panels[p].series.size(); ++s) {
      datablock(os, fmt::format("p{}s{}", p, s), f.panels[p].series[s].x, f.panels[p].series[s].y);
    }
  }
  // Shared x axis: one range and fixed margins so that the panels line up. A panel with its own x label has its own
  // axis and range. Legends sit in the right margin, beside their panel, never over the data.
  const auto own_xlabel = [&f](int p) -> std::string {
    return p < static_cast<int>(f.own_xlabels.size()) ? f.own_xlabels[static_cast<std::size_t>(p)] : std::string();
  };
  const auto x_range = [](const Panel& panel) {
    std::pair<double, double> r{INFINITY, -INFINITY};
    for (const Series& s : panel.series) {
      for (double x : s.x) {
        if (std::isfinite(x) && (!panel.log_x || x > 0.0)) {
          r.first = std::min(r.first, x);
          r.second = std::max(r.second, x);
        }
      }
    }
    return r;
  };
  double xmin = INFINITY;
  double xmax = -INFINITY;
  for (int p = 0; p < n; ++p) {
    if (!own_xlabel(p).empty()) continue;
    const auto [lo, hi] = x_range(f.panels[p]);
    xmin = std::min(xmin, lo);
    xmax = std::max(xmax, hi);
  }
  os << fmt::format("set lmargin at screen 0.09\nset rmargin at screen {:.4f}\n", rmargin);
  os << "set key at graph 1.02, graph 1 left top vertical Left reverse noopaque nobox font ',10' samplen 2 "
        "spacing 1.1\n";
  os << fmt::format("set multiplot layout {},1 title {} font ',13'\n", std::max(1, n), title);
  for (int p = 0; p < n; ++p) {
    const Panel& panel = f.panels[p];
    os << "unset arrow\nunset logscale\n";
    os << "set ylabel " << quote(panel.ylabel) << "\n";
    const bool own_axis = !own_xlabel(p).empty();
    const bool last_shared = !own_axis && (p == n - 1 || !own_xlabel(p + 1).empty());
    os << "set xlabel " << (own_axis ? quote(own_xlabel(p)) : last_shared ? quote(f.xlabel) : std::string("\"\""))
       << "\n";
    const auto [lo, hi] = own_axis ? x_range(panel) : std::pair{xmin, xmax};
    if (hi > lo) {
      os << fmt::format("set xrange [{:.10g}:{:.10g}]\n", lo, hi);
    } else {
      os << "set xrange [*:*]\n";
    }
    if (panel.log_x) os << "set logscale x\n";
    if (panel.log_y) os << "set logscale y\n";
    int arrow = 1;
    for (double x : panel.marks_x) {
      os << fmt::format("set arrow {} from {:.10g}, graph 0 to {:.10g}, graph 1 nohead lc rgb '#bbbbbb' lw 0.5\n",
                        arrow++, x, x);
    }
    std::vector<std::string> clauses;
    for (std::size_t s = 0; s < panel.series.size(); ++s) {
      clauses.push_back(series_clause(panel.series[s], fmt::format("$p{}s{}", p, s)));
    }
    for (const Level& level : panel.levels) {
      clauses.push_back(fmt::format("{:.10g} with lines dt 2 lc rgb '#c0392b' lw 1 title {}", level.y,
                                    quote(level.label)));
    }
    if (clauses.empty()) clauses.push_back("NaN notitle");
    os << "plot ";
    for (std::size_t c = 0; c < clauses.size(); ++c) os << (c ? ", \\\n     " : "") << clauses[c];
    os << "\n";
  }
  os << "unset multiplot\nset output\n";
  return os.str();
}

std::string gnuplot_script(const MapFigure& f, const std::filesystem::path& path) {
  std::ostringstream os;
  os << terminal_for(path, f.width_px, f.height_px) << "\n";
  os << "set output " << quote(path.string()) << "\n";
  // Each cell drawn as a filled box between the midpoints to its neighbours (geometric midpoints on a log axis), so
  // that the field sits exactly on its axes whatever their scale.
  const auto edges = [](const std::vector<double>& v, bool log) {
    std::vector<double> e(v.size() + 1);
    const auto mid = [log](double a, double b) { return log ? std::sqrt(a * b) : 0.5 * (a + b); };
    for (std::size_t i = 1; i < v.size(); ++i) e[i] = mid(v[i - 1], v[i]);
    if (v.size() > 1) {
      e[0] = log ? v[0] * v[0] / e[1] : 2.0 * v[0] - e[1];
      e[v.size()] = log ? v.back() * v.back() / e[v.size() - 1] : 2.0 * v.back() - e[v.size() - 1];
    } else if (!v.empty()) {
      e[0] = v[0] * 0.9;
      e[1] = v[0] * 1.1;
    }
    return e;
  };
  const auto ex = edges(f.x, f.log_x);
  const auto ey = edges(f.y, f.log_y);
  os << "$map << EOD\n";
  for (std::size_t r = 0; r < f.y.size(); ++r) {
    for (std::size_t c = 0; c < f.x.size(); ++c) {
      const double z = f.z[r * f.x.size() + c];
      os << fmt::format("{:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g}\n", f.x[c], f.y[r], ex[c], ex[c + 1],
                        ey[r], ey[r + 1], std::isfinite(z) ? z : 0.0);
    }
  }
  os << "EOD\n";
  for (std::size_t s = 0; s < f.overlay.size(); ++s) datablock(os, fmt::format("ov{}", s), f.overlay[s].x, f.overlay[s].y);
  int title_lines = 1;  // a long title wraps rather than running off the figure
  os << "set title " << wrapped_title(f.title, f.width_px, title_lines) << "\nset xlabel " << quote(f.xlabel) << "\nset ylabel " << quote(f.ylabel)
     << "\nset cblabel " << quote(f.zlabel) << "\n";
  if (f.log_x) os << "set logscale x\n";
  if (f.log_y) os << "set logscale y\n";
  if (f.tics_125 && f.log_x && !ex.empty()) os << "set xtics " << tics_125(ex.front(), ex.back()) << "\n";
  if (f.tics_125 && f.log_y && !ey.empty()) os << "set ytics " << tics_125(ey.front(), ey.back()) << "\n";
  os << "set palette defined "
     << (f.palette.empty() ? "(0 '#ffffff', 0.25 '#c6dbef', 0.5 '#6baed6', 0.75 '#2171b5', 1 '#08306b')" : f.palette)
     << "\n";
  os << "set key " << (f.key.empty() ? "outside bottom center horizontal font ',10'" : f.key) << "\nset tics out\n";
  if (!f.colorbox.empty()) os << "set colorbox " << f.colorbox << "\n";
  if (!f.x.empty() && !f.y.empty()) {
    os << fmt::format("set xrange [{:.10g}:{:.10g}]\nset yrange [{:.10g}:{:.10g}]\n", ex.front(), ex.back(),
                      ey.front(), ey.back());
  }
  os << "set style fill solid 1.0 noborder\nset cbrange [0:*]\n";
  os << "plot $map using 1:2:3:4:5:6:7 with boxxyerror fc palette notitle";
  for (std::size_t s = 0; s < f.overlay.size(); ++s) os << ", \\\n     " << series_clause(f.overlay[s], fmt::format("$ov{}", s));
  os << "\nset output\n";
  return os.str();
}

std::string file_label(const std::string& path_or_name) {
  const std::filesystem::path p(path_or_name);
  return p.has_filename() && p.has_parent_path() ? p.filename().string() : path_or_name;
}

void render(const Figure& figure, const std::filesystem::path& path) { render_figure(figure, path); }
void render(const MapFigure& figure, const std::filesystem::path& path) { render_figure(figure, path); }

namespace {

Series ground_series(const GroundMotion& m, double g, double t_end) {
  Series s{"ground acceleration", {}, {}, "lines", "#555555", 1.0};
  for (std::size_t i = 0; i < m.size(); ++i) {
    s.x.push_back(m.time_s(i));
    s.y.push_back(m.accel_m_s2()[i] / g);
  }
  if (t_end > m.end_time_s()) {  // still ground during the run-out
    s.x.push_back(m.end_time_s());
    s.y.push_back(0.0);
    s.x.push_back(t_end);
    s.y.push_back(0.0);
  }
  return s;
}

}  // namespace

Figure sliding_figure(const GroundMotion& m, const SlidingResult& r, const SlidingBlock& block,
                      const std::string& title) {
  const double g = block.g_m_s2;
  const double t_end = r.history.time_s.empty() ? m.end_time_s() : r.history.time_s.back();
  Figure f;
  f.title = title;
  f.xlabel = "time (s)";
  Panel accel{"acceleration (g)", {ground_series(m, g, t_end)}, {}, {}, false, false};
  accel.levels.push_back({block.yield_down_m_s2() / g, "yield (+)"});
  if (std::isfinite(block.yield_up_m_s2())) accel.levels.push_back({block.yield_up_m_s2() / g, "yield (-)"});
  Panel vel{"relative velocity (m/s)", {{"block - ground", r.history.time_s, r.history.velocity_m_s, "lines", "#2171b5", 1.5}}, {}, {}, false, false};
  Panel disp{"relative displacement (m)", {{"block - ground", r.history.time_s, r.history.displacement_m, "lines", "#c0392b", 1.8}}, {}, {}, false, false};
  for (std::size_t i = 1; i < r.history.state.size(); ++i) {
    if (r.history.state[i] != SlipState::stuck && r.history.state[i - 1] == SlipState::stuck) {
      accel.marks_x.push_back(r.history.time_s[i]);
    }
  }
  f.panels = {accel, vel, disp};
  return f;
}

namespace {

/// A vertical line at `mark.x` spanning [lo, hi] of the panel's data, with its label in the legend.
Series mark_series(const Mark& mark, double lo, double hi) {
  return {mark.label, {mark.x, mark.x}, {lo, hi}, "lines dt 4", mark.color.empty() ? "#e67e22" : mark.color, 1.5};
}

std::pair<double, double> y_span(const std::vector<double>& y, bool positive_only) {
  std::pair<double, double> r{INFINITY, -INFINITY};
  for (double v : y) {
    if (std::isfinite(v) && (!positive_only || v > 0.0)) {
      r.first = std::min(r.first, v);
      r.second = std::max(r.second, v);
    }
  }
  if (!(r.second >= r.first)) r = {positive_only ? 1.0 : 0.0, positive_only ? 10.0 : 1.0};
  return r;
}

/// The ground acceleration panel of a planar run (in g): the horizontal and, when given, the vertical.
Panel ground_panel(const GroundMotion& m, const GroundMotion* vertical, double g, double t_end) {
  Panel accel{"ground acceleration (g)", {ground_series(m, g, t_end)}, {}, {}, false, false};
  accel.series.front().label = "horizontal";
  if (vertical != nullptr) {
    Series v = ground_series(*vertical, g, t_end);
    v.label = "vertical";
    v.color = "#27ae60";
    accel.series.push_back(std::move(v));
  }
  return accel;
}

/// The fall at `t` as a dashed vertical line on each panel, spanning the panel's data and levels; only `labelled`
/// keeps the legend entry.
void mark_fall(std::initializer_list<Panel*> panels, const Panel* labelled, double t) {
  const Mark fall{t, fmt::format("overturned, t = {:.3f} s", t), "#8e44ad"};
  for (Panel* panel : panels) {
    double lo = INFINITY;
    double hi = -INFINITY;
    for (const Series& s : panel->series) {
      const auto [a, b] = y_span(s.y, false);
      lo = std::min(lo, a);
      hi = std::max(hi, b);
    }
    for (const Level& level : panel->levels) {
      lo = std::min(lo, level.y);
      hi = std::max(hi, level.y);
    }
    panel->series.push_back(mark_series(fall, lo, hi));
    if (panel != labelled) panel->series.back().label.clear();
  }
}

}  // namespace

Figure rocking_figure(const GroundMotion& m, const RockingResult& r, const RockingBody& body, const std::string& title,
                      const GroundMotion* vertical) {
  const double g = r.summary.g_m_s2 > 0.0 ? r.summary.g_m_s2 : kStandardGravity;
  const double alpha = body.alpha_rad();
  const double t_end = r.history.time_s.empty() ? m.end_time_s() : r.history.time_s.back();
  const double threshold = body.a_m / body.h_m;  // = tan(alpha): uplift at |a_h| > (g + a_v) a / h
  Figure f;
  f.title = title;
  f.xlabel = "time (s)";
  Panel accel = ground_panel(m, vertical, g, t_end);
  accel.levels = {{threshold, fmt::format("uplift ±a/h = ±{:.3g} g", threshold)}, {-threshold, ""}};
  // An asymmetric body: a_h > g b1/h lifts it about O- (the -x edge), a_h < -g b2/h about O+; θ over the alpha of its
  // side, so that ±1 are still the limits.
  const double alpha_negative = body.side_body(-1).alpha_rad();
  if (!body.symmetric()) {
    const double up_neg = body.pivot_b_m(-1) / body.h_m;
    accel.levels = {{up_neg, fmt::format("uplift about O- b1/h = {:.3g} g", up_neg)},
                    {-threshold, fmt::format("uplift about O+ -b2/h = {:.3g} g", -threshold)}};
  }
  std::vector<double> ratio(r.history.theta_rad.size());
  for (std::size_t i = 0; i < ratio.size(); ++i) {
    ratio[i] = r.history.theta_rad[i] / (r.history.theta_rad[i] < 0.0 ? alpha_negative : alpha);
  }
  Panel theta{body.symmetric() ? "rotation θ/α (-)" : "rotation θ/α of its side (-)", {{"θ/α", r.history.time_s, ratio, "lines", "#c0392b", 1.8}},
              {{1.0, "overturning limit ±1"}, {-1.0, ""}}, {}, false, false};
  Panel rate{"angular velocity (rad/s)",
             {{"dθ/dt", r.history.time_s, r.history.theta_dot_rad_s, "lines", "#2171b5", 1.5}}, {}, {}, false,
             false};
  Series impacts{"impacts", {}, {}, "points pt 7 ps 0.45", "#333333", 1.0};
  for (const RockingEvent& e : r.events) {
    if (e.kind == RockingEventKind::impact) {
      impacts.x.push_back(e.time_s);
      impacts.y.push_back(0.0);
    }
    if (e.kind == RockingEventKind::uplift) accel.marks_x.push_back(e.time_s);
  }
  if (!impacts.x.empty()) {
    impacts.label = fmt::format("impacts ({})", impacts.x.size());
    theta.series.push_back(std::move(impacts));
  }
  if (r.summary.overturned && r.summary.overturn_time_s) mark_fall({&accel, &theta, &rate}, &theta, *r.summary.overturn_time_s);
  f.panels = {accel, theta, rate};
  return f;
}

Figure motion_spectrum_figure(const GroundMotion& m, const FourierSpectrum& fas, const std::vector<double>& smooth_hz,
                              const std::vector<double>& smooth_amplitude_m_s, const std::vector<Mark>& marks,
                              double g, const std::string& title) {
  Figure f;
  f.title = title;
  f.xlabel = "time (s)";
  Series ground = ground_series(m, g, m.end_time_s());
  ground.color = "#333333";
  ground.label = "";
  Panel accel{"acceleration (g)", {std::move(ground)}, {}, {}, false, false};
  // The raw FAS over the band the smoothed one covers (plus a little), without f = 0 (log axis).
  const double f_lo = smooth_hz.empty() ? 0.0 : smooth_hz.front();
  const double f_hi = smooth_hz.empty() ? INFINITY : smooth_hz.back();
  Series raw{"FAS", {}, {}, "lines", "#bbbbbb", 0.8};
  for (std::size_t k = 0; k < fas.frequency_hz.size(); ++k) {
    const double fk = fas.frequency_hz[k];
    if (fk > 0.0 && fk >= 0.8 * f_lo && fk <= 1.25 * f_hi && fas.amplitude_m_s[k] > 0.0) {
      raw.x.push_back(fk);
      raw.y.push_back(fas.amplitude_m_s[k]);
    }
  }
  Panel spectrum{"Fourier amplitude (m/s)", {std::move(raw)}, {}, {}, true, true};
  spectrum.series.push_back({"smoothed (K-O, b = 40)", smooth_hz, smooth_amplitude_m_s, "lines", "#2171b5", 2.0});
  auto [lo, hi] = y_span(spectrum.series.front().y, true);
  const auto [slo, shi] = y_span(smooth_amplitude_m_s, true);
  lo = std::min(lo, slo);
  hi = std::max(hi, shi);
  for (const Mark& mark : marks) spectrum.series.push_back(mark_series(mark, lo, hi));
  f.panels = {accel, spectrum};
  f.own_xlabels = {"", "frequency (Hz)"};
  return f;
}

Figure record_figure(const GroundMotion& m, const GroundVelocityDisplacement& ground, const ResponseSpectrum& rs,
                     const std::vector<Mark>& marks, double g, const std::string& title) {
  Figure f;
  f.title = title;
  f.xlabel = "time (s)";
  f.panel_height_px = 220;
  std::vector<double> t(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) t[i] = m.time_s(i);
  Series a = ground_series(m, g, m.end_time_s());
  a.color = "#333333";
  a.label = "";
  Panel accel{"acceleration (g)", {std::move(a)}, {}, {}, false, false};
  Panel vel{"velocity (m/s)", {{"", t, ground.velocity_m_s, "lines", "#2171b5", 1.2}}, {}, {}, false, false};
  Panel disp{"displacement (m)", {{"", t, ground.displacement_m, "lines", "#c0392b", 1.2}}, {}, {}, false, false};
  std::vector<double> psa(rs.psa_m_s2.size());
  for (std::size_t i = 0; i < psa.size(); ++i) psa[i] = rs.psa_m_s2[i] / g;
  Panel spectrum{"pseudo-acceleration (g)",
                 {{fmt::format("PSA, {:.3g} % damping", 100.0 * rs.damping), rs.period_s, psa, "lines", "#2171b5",
                   2.0}},
                 {}, {}, true, false};
  const auto [lo, hi] = y_span(psa, false);
  for (const Mark& mark : marks) spectrum.series.push_back(mark_series(mark, std::min(0.0, lo), hi));
  f.panels = {accel, vel, disp, spectrum};
  f.own_xlabels = {"", "", "", "period (s)"};
  return f;
}


namespace {

/// The palette of a station's components: H1, H2, V (distinct in colour and in print).
constexpr const char* kComponentColors[] = {"#2171b5", "#c0392b", "#2e8b57"};

const char* component_color(std::size_t k) { return kComponentColors[k % 3]; }

}  // namespace

Figure record_set_figure(const std::vector<ComponentRecord>& components, const RotDMeasures* rotd, double g,
                         const std::string& title) {
  Figure f;
  f.title = title;
  f.xlabel = "time (s)";
  f.panel_height_px = 220;
  Panel accel{"acceleration (g)", {}, {}, {}, false, false};
  Panel vel{"velocity (m/s)", {}, {}, {}, false, false};
  Panel disp{"displacement (m)", {}, {}, {}, false, false};
  Panel spectrum{"pseudo-acceleration (g)", {}, {}, {}, true, false};
  for (std::size_t k = 0; k < components.size(); ++k) {
    const ComponentRecord& c = components[k];
    const GroundMotion& m = *c.motion;
    Series a = ground_series(m, g, m.end_time_s());
    a.label = c.label;
    a.color = component_color(k);
    accel.series.push_back(std::move(a));
    std::vector<double> t(m.size());
    for (std::size_t i = 0; i < m.size(); ++i) t[i] = m.time_s(i);
    vel.series.push_back({c.label, t, c.ground.velocity_m_s, "lines", component_color(k), 1.2});
    disp.series.push_back({c.label, t, c.ground.displacement_m, "lines", component_color(k), 1.2});
    std::vector<double> psa(c.spectrum.psa_m_s2.size());
    for (std::size_t i = 0; i < psa.size(); ++i) psa[i] = c.spectrum.psa_m_s2[i] / g;
    spectrum.series.push_back({fmt::format("{} PSA, {:.3g} % damping", c.label, 100.0 * c.spectrum.damping),
                               c.spectrum.period_s, std::move(psa), "lines", component_color(k), 1.2});
  }
  if (rotd != nullptr) {
    std::vector<double> d50(rotd->psa_m_s2.size()), d100(rotd->psa_m_s2.size());
    for (std::size_t i = 0; i < d50.size(); ++i) {
      d50[i] = rotd->psa_m_s2[i].rotd50 / g;
      d100[i] = rotd->psa_m_s2[i].rotd100 / g;
    }
    spectrum.series.push_back({"RotD50 (pair)", rotd->period_s, std::move(d50), "lines", "#333333", 2.2});
    spectrum.series.push_back({"RotD100 (pair)", rotd->period_s, std::move(d100), "lines dt 2", "#333333", 1.6});
  }
  f.panels = {accel, vel, disp, spectrum};
  f.own_xlabels = {"", "", "", "period (s)"};
  return f;
}

Figure sliding_2d_figure(const GroundMotion& first, const GroundMotion& second, const ComponentAzimuths& azimuths,
                         const GroundMotion* vertical, const Sliding2dResult& r, const SlidingBlock& block,
                         const std::string& title) {
  const double g = block.g_m_s2;
  const auto& h = r.history;
  const double t_end = h.time_s.empty() ? first.end_time_s() : h.time_s.back();
  Figure f;
  f.title = title;
  f.xlabel = "time (s)";
  Panel accel{"acceleration (g)", {}, {}, {}, false, false};
  const std::pair<const GroundMotion*, std::string> inputs[] = {
      {&first, fmt::format("H1 ({:g} deg)", azimuths.first_deg)},
      {&second, fmt::format("H2 ({:g} deg)", azimuths.second_deg)},
      {vertical, "V (up)"}};
  for (std::size_t k = 0; k < 3; ++k) {
    if (inputs[k].first == nullptr) continue;
    Series s = ground_series(*inputs[k].first, g, t_end);
    s.label = inputs[k].second;
    s.color = component_color(k);
    accel.series.push_back(std::move(s));
  }
  // The onset on level ground without a vertical: |a_h| = mu_s g (sliding2d.hpp); a reference, not the run's own
  // threshold when there is a slope or a vertical.
  accel.levels.push_back({block.mu_static, "onset +mu_s g (level, no vertical)"});
  accel.levels.push_back({-block.mu_static, "onset -mu_s g"});
  Panel vel{"relative velocity (m/s)",
            {{"east", h.time_s, h.east_m_s, "lines", "#2171b5", 1.5}, {"north", h.time_s, h.north_m_s, "lines", "#c0392b", 1.5}},
            {}, {}, false, false};
  Panel disp{"relative displacement (m)",
             {{"east", h.time_s, h.east_m, "lines", "#2171b5", 1.8}, {"north", h.time_s, h.north_m, "lines", "#c0392b", 1.8}},
             {}, {}, false, false};
  for (std::size_t i = 1; i < h.slipping.size(); ++i) {
    if (h.slipping[i] != 0 && h.slipping[i - 1] == 0) accel.marks_x.push_back(h.time_s[i]);
  }
  f.panels = {accel, vel, disp};
  return f;
}

Figure slide_rock_figure(const GroundMotion& m, const SlideRockResult& r, const SlideRockBody& body,
                         const std::string& title, const GroundMotion* vertical, double g, double slope_rad) {
  const auto& h = r.history;
  const double t_end = h.time_s.empty() ? m.end_time_s() : h.time_s.back();
  Figure f;
  f.title = title;
  f.xlabel = "time (s)";
  Panel accel = ground_panel(m, vertical, g, t_end);
  // From rest without a vertical (slide_rock.hpp, "rest"): a_h > g b1/h lifts the body about O-, a_h < -g b2/h about
  // O+, |a_h| > mu_s g starts a slip (Shenton 1996); the vertical moves all three, so they are references.
  accel.levels = {{body.b1_m / body.h_m, fmt::format("uplift about O- b1/h = {:.3g} g", body.b1_m / body.h_m)},
                  {-body.b2_m / body.h_m, fmt::format("uplift about O+ -b2/h = {:.3g} g", -body.b2_m / body.h_m)},
                  {body.mu_static, fmt::format("slip ±mu_s = ±{:.3g} g", body.mu_static)},
                  {-body.mu_static, ""}};
  if (slope_rad != 0.0) {  // an inclined base: the thresholds tilted by beta (slide_rock.hpp, "Inclined base")
    // an angle + beta at or past 90 deg: no horizontal acceleration reaches that threshold (no level drawn)
    const double ap = std::atan2(body.b2_m, body.h_m) + slope_rad;
    const double phi = std::atan(body.mu_static);
    const double up = std::tan(std::atan2(body.b1_m, body.h_m) - slope_rad);
    const double sd = std::tan(phi - slope_rad);
    accel.levels = {{up, fmt::format("uplift about O- tan(alpha- - beta) = {:.3g} g", up)},
                    {sd, fmt::format("slip down-slope tan(phi - beta) = {:.3g} g", sd)}};
    if (ap < kPi / 2.0) {
      accel.levels.push_back({-std::tan(ap), fmt::format("uplift about O+ -tan(alpha+ + beta) = {:.3g} g",
                                                         -std::tan(ap))});
    }
    if (phi + slope_rad < kPi / 2.0) {
      accel.levels.push_back({-std::tan(phi + slope_rad), fmt::format("slip up-slope -tan(phi + beta) = {:.3g} g",
                                                                      -std::tan(phi + slope_rad))});
    }
  }
  const double alpha_positive = std::atan2(body.b2_m, body.h_m);
  const double alpha_negative = std::atan2(body.b1_m, body.h_m);
  std::vector<double> ratio(h.theta_rad.size());
  for (std::size_t i = 0; i < ratio.size(); ++i) {
    ratio[i] = h.theta_rad[i] / (h.theta_rad[i] < 0.0 ? alpha_negative : alpha_positive);
  }
  Panel theta{"rotation θ/α of its side (-)", {{"θ/α", h.time_s, ratio, "lines", "#c0392b", 1.8}},
              {{1.0, "overturning limit ±1"}, {-1.0, ""}}, {}, false, false};
  Panel slide{"slide u of the pivot (m, +x)", {{"u", h.time_s, h.slide_m, "lines", "#2171b5", 1.8}}, {}, {}, false,
              false};
  // The mode as a step line on its index (SlideRockMode), named on the axis.
  std::vector<double> mode(h.mode.size());
  for (std::size_t i = 0; i < mode.size(); ++i) mode[i] = static_cast<double>(h.mode[i]);
  Panel modes{"mode (index)", {{"0 rest, 1 slide, 2 rock, 3 slide-rock, 4 flight, 5 fallen", h.time_s, mode, "steps",
                                "#555555", 1.5}}, {}, {}, false, false};
  for (const SlideRockTransition& t : r.transitions) {
    if (t.mode == SlideRockMode::slide || t.mode == SlideRockMode::slide_rock) slide.marks_x.push_back(t.time_s);
  }
  if (r.summary.overturned && r.summary.overturn_time_s) {
    mark_fall({&accel, &theta, &slide}, &theta, *r.summary.overturn_time_s);
  }
  f.panels = {accel, theta, slide, modes};
  return f;
}

}  // namespace topple::plot
