#pragma once
// The inversion's report: figures (likelihood map with static bounds and one contour per object, marginal
// posteriors, an example motion at the best cell with every object's response) and a self-contained HTML page that
// a field engineer can hand on (figures embedded, observations table, method in short, the numbers, the inputs).
#include <filesystem>
#include <optional>

#include "topple/inversion/inversion.hpp"
#include "topple/output/provenance.hpp"
#include "topple/output/plot.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// The likelihood map (posterior over PGA x frequency, log axes ticked at 1-2-5), the 68 % and 95 % credible regions,
/// the static thresholds as vertical lines, each object's P(observation) = 0.5 contour in its own colour and dash,
/// labelled with the side that fits, the medians and the maximum-likelihood cell. An object without a line is named
/// with the reason in the report's caption.
[[nodiscard]] plot::MapFigure likelihood_map_figure(const InversionResult& result, const Site& site);

/// Marginal posterior of PGA (or frequency) with the median and the 68 % / 95 % intervals.
[[nodiscard]] plot::Figure marginal_figure(const InversionResult& result, bool pga);

/// One motion of the family at the best cell and each object's response to it (nominal parameters).
[[nodiscard]] plot::Figure best_cell_figure(const InversionResult& result, const Site& site,
                                            const InversionSettings& settings);

/// Segments of the level-`level` contour of a field on a grid (marching squares), as one polyline with NaN
/// separators between segments; x and y in data coordinates.
[[nodiscard]] plot::Series contour_series(const std::vector<double>& x, const std::vector<double>& y,
                                          const std::vector<double>& z, double level, const std::string& label);

/// Text for HTML: & < > " escaped (the report pages; region_report.cpp too).
[[nodiscard]] std::string html_escape(const std::string& text);
/// An SVG file's text without its XML prologue or doctype, for inline embedding in a page.
[[nodiscard]] std::string inline_svg(const std::filesystem::path& svg);
/// A PNG file as a data: URI (base64), for an <img src> that keeps the page self-contained.
[[nodiscard]] std::string inline_png(const std::filesystem::path& png);

/// Writes DIR/index.html and the figures (DIR/likelihood.svg, DIR/marginal_pga.svg, DIR/marginal_freq.svg,
/// DIR/best_cell.svg, DIR/grid.csv, DIR/result.json). The page embeds the SVGs inline: it is self-contained. It opens
/// with inversion_summary, defines every number where it is shown, sets the hard and soft static thresholds beside
/// the estimate, flags misfits, and ends with the provenance and the survey verbatim. Without `provenance` (a library
/// caller), it is made from survey.source_file with an unknown command line.
void write_report(const std::filesystem::path& dir, const Survey& survey, const Site& site,
                  const InversionResult& result, const std::optional<io::Provenance>& provenance = std::nullopt);

}  // namespace topple
