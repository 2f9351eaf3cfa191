// Figures of object spectra and fragility curves (plot.hpp): built from the library's results, no physics here.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "topple/output/plot.hpp"

namespace topple::plot {

Figure sliding_spectrum_figure(const SlidingSpectrum& spectrum, bool against_yield_ratio, const std::string& title) {
  Figure f;
  f.title = title;
  f.xlabel = against_yield_ratio ? "yield acceleration / PGA, k_y g / PGA (-)" : "friction coefficient μ (-)";
  f.panel_height_px = 520;
  Panel p;
  p.ylabel = "sliding displacement (m)";
  Series max{"max |displacement|", {}, {}, "linespoints pt 7 ps 0.6", "#1f4e79", 2.0};
  Series res{"residual displacement", {}, {}, "linespoints pt 6 ps 0.6", "#c0392b", 1.5};
  for (const SlidingSpectrumPoint& pt : spectrum.points) {
    const double x = against_yield_ratio ? pt.yield_over_pga : pt.mu;
    max.x.push_back(x);
    max.y.push_back(pt.max_abs_displacement_m);
    res.x.push_back(x);
    res.y.push_back(pt.residual_displacement_m);
  }
  p.series = {max, res};
  p.levels.push_back({0.0, ""});
  f.panels.push_back(std::move(p));
  return f;
}

MapFigure overturning_map_figure(const OverturningMap& map, const std::string& title) {
  MapFigure f;
  f.title = title;
  f.xlabel = map.shape == RockingBody::Shape::cylinder ? "cylinder height 2h (m)" : "block height 2h (m)";
  f.ylabel = "PGA (g)";
  f.zlabel = "overturned (1) or standing (0)";
  std::vector<std::size_t> order(map.sizes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return map.sizes[a].height_m < map.sizes[b].height_m; });
  for (std::size_t s : order) f.x.push_back(map.sizes[s].height_m);
  for (double a : map.pga_m_s2) f.y.push_back(a / map.g_m_s2);
  f.log_x = f.x.size() > 1 && f.x.front() > 0.0 && f.x.back() / f.x.front() > 5.0;
  for (std::size_t k = 0; k < map.pga_m_s2.size(); ++k) {
    for (std::size_t s : order) f.z.push_back(map.at(s, k) ? 1.0 : 0.0);
  }
  Series first{"first-overturn PGA", {}, {}, "linespoints pt 7 ps 0.7", "#e67e22", 2.0};
  for (std::size_t s : order) {
    first.x.push_back(map.sizes[s].height_m);
    const auto& a = map.sizes[s].first_overturn_pga_m_s2;
    first.y.push_back(a ? *a / map.g_m_s2 : NAN);  // a gap where the size never falls on the grid
  }
  Series uplift{"uplift g tan α", {f.x.empty() ? 0.0 : f.x.front(), f.x.empty() ? 0.0 : f.x.back()},
                {std::tan(map.alpha_rad), std::tan(map.alpha_rad)}, "lines dt 2", "#555555", 1.5};
  f.overlay = {first, uplift};
  return f;
}

Figure fragility_figure(const FragilityResult& result, double g_m_s2, double band_level, const std::string& title) {
  Figure f;
  f.title = title;
  const double k = intensity_measure_display_factor(result.im, g_m_s2);
  std::string name(intensity_measure_name(result.im));
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  f.xlabel = fmt::format("{} ({})", name, intensity_measure_unit(result.im));
  f.panel_height_px = 520;
  Panel p;
  p.ylabel = "probability of failure (-)";
  static const char* colors[] = {"#1f4e79", "#c0392b", "#27ae60", "#8e44ad"};
  std::size_t c = 0;
  for (const FragilityCurve& curve : result.curves) {
    const std::string color = colors[c++ % 4];
    const std::string what = curve.name == "overturn" ? "overturn" : "slide > d";
    Series data{what + ": fraction", {}, {}, "points pt 7 ps 1.0", color, 1.0};
    for (std::size_t j = 0; j < curve.data.im.size(); ++j) {
      data.x.push_back(curve.data.im[j] * k);
      data.y.push_back(static_cast<double>(curve.data.failures[j]) / curve.data.trials[j]);
    }
    p.series.push_back(data);
    if (!curve.fit) continue;
    const auto [lo_it, hi_it] = std::minmax_element(curve.data.im.begin(), curve.data.im.end());
    const double lo = *lo_it / 1.5;
    const double hi = *hi_it * 1.5;
    Series fit{fmt::format("{}: θ = {:.3g} {}, β = {:.2f}", what, curve.fit->theta * k,
                           intensity_measure_unit(result.im), curve.fit->beta),
               {}, {}, "lines", color, 2.0};
    Series band_lo{fmt::format("{:.0f} % band", 100.0 * band_level), {}, {}, "lines dt 2", color, 1.0};
    Series band_hi{"", {}, {}, "lines dt 2", color, 1.0};
    constexpr int kPoints = 200;
    for (int i = 0; i <= kPoints; ++i) {
      const double x = lo * std::pow(hi / lo, static_cast<double>(i) / kPoints);
      fit.x.push_back(x * k);
      fit.y.push_back(curve.fit->probability(x));
      const auto [b0, b1] = curve.fit->band(x, band_level);
      band_lo.x.push_back(x * k);
      band_lo.y.push_back(b0);
      band_hi.x.push_back(x * k);
      band_hi.y.push_back(b1);
    }
    p.series.push_back(fit);
    p.series.push_back(band_lo);
    p.series.push_back(band_hi);
  }
  p.log_x = true;
  f.panels.push_back(std::move(p));
  return f;
}

}  // namespace topple::plot
