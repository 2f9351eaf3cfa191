#pragma once
// Figures: what an engineer expects to see of each analysis, drawn by gnuplot (Debian gnuplot-nox) through a pipe.
//
// The library describes a figure as data (panels of series on a shared x axis, or a map); render() writes a gnuplot
// script with the data inline and runs `gnuplot` on it, producing SVG or PNG by the file's extension. Plotting never
// computes physics: the builders below take solver results as they are.
#include <filesystem>
#include <string>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/fragility/fragility.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/motion/spectra.hpp"

namespace topple::io {
class OutputFile;
}

namespace topple::plot {

struct Series {
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  std::string style = "lines";  ///< gnuplot style: "lines", "points", "linespoints", "steps", "impulses"
  std::string color;            ///< "#rrggbb"; empty: gnuplot's cycle
  double width = 1.5;           ///< line width, a multiple of gnuplot's default line width (dimensionless)
};

/// Horizontal reference line (e.g. a yield acceleration), drawn dashed with its label.
struct Level {
  double y = 0.0;
  std::string label;
};

struct Panel {
  std::string ylabel;  ///< with units, e.g. "ground acceleration (g)"
  std::vector<Series> series;
  std::vector<Level> levels;
  std::vector<double> marks_x;  ///< instants marked by thin vertical lines (slip starts, impacts)
  bool log_x = false;
  bool log_y = false;
};

/// Panels stacked with a shared x axis (time histories), or a single panel (spectra, fragility curves).
struct Figure {
  std::string title;
  std::string xlabel;  ///< with units
  std::vector<Panel> panels;
  int width_px = 1000;
  int panel_height_px = 260;
  /// By panel index: a non-empty label (with units) gives that panel its own x axis and the range of its own data
  /// instead of the shared one (e.g. a spectrum below time histories). Missing or empty: the shared axis.
  std::vector<std::string> own_xlabels;
};

/// A gridded field (e.g. a likelihood over PGA x frequency) with optional contour lines of other fields.
struct MapFigure {
  std::string title;
  std::string xlabel;
  std::string ylabel;
  std::string zlabel;
  std::vector<double> x;       ///< column coordinates (ascending)
  std::vector<double> y;       ///< row coordinates (ascending)
  std::vector<double> z;       ///< row-major, y.size() x x.size()
  bool log_x = false;
  bool log_y = false;
  std::vector<Series> overlay;  ///< lines or points drawn over the map (bounds, best estimate)
  int width_px = 900;
  int height_px = 700;
  bool tics_125 = false;   ///< log axes ticked and labelled at 1, 2, 5 x 10^k (0.2, 0.5 g readable)
  std::string palette;     ///< gnuplot "set palette defined (...)" body; empty: white to dark blue
  std::string key;         ///< gnuplot "set key ..." arguments; empty: below the plot, horizontal
  std::string colorbox;    ///< gnuplot "set colorbox ..." arguments; empty: gnuplot's default, right of the plot
};

/// A file as a figure title names it: its file name, without the directories (a title travels with the figure, to
/// other machines and reports; an absolute path there is noise and private). Text that is not a file path is kept.
[[nodiscard]] std::string file_label(const std::string& path_or_name);

/// Writes the figure to `path` (.svg or .png) through a temporary file renamed once gnuplot succeeded. Throws
/// InputError for another extension, OutputError (naming the path) for an unwritable one, and
/// std::runtime_error when gnuplot is missing or fails (its message is included).
void render(const Figure& figure, const std::filesystem::path& path);
void render(const MapFigure& figure, const std::filesystem::path& path);

/// Runs `program` (a command word for /bin/sh, e.g. "gnuplot" or "bash") on `script`, written beside `image`'s
/// temporary file with `script_suffix` and removed afterwards, followed by `arguments` (each quoted for the shell).
/// The program must write the figure to image.temporary_path(); the figure appears under its final name only when
/// the program exits 0 (OutputFile's rename), and SIGINT/SIGTERM remove both temporaries. Throws std::runtime_error
/// naming the program, the final path, `hint` and the program's output when it fails. render() and the regional map
/// (region_map.hpp, GMT) both run through it.
void run_figure_program(const std::string& program, const std::string& script, const std::string& script_suffix,
                        const std::vector<std::string>& arguments, io::OutputFile& image, const std::string& hint);

/// The gnuplot script render() runs (for tests and for users who want to restyle).
[[nodiscard]] std::string gnuplot_script(const Figure& figure, const std::filesystem::path& path);
[[nodiscard]] std::string gnuplot_script(const MapFigure& figure, const std::filesystem::path& path);

/// Record with the yield levels +-yield (in g), relative velocity and displacement, slip episodes marked.
[[nodiscard]] Figure sliding_figure(const GroundMotion& horizontal, const SlidingResult& result,
                                    const SlidingBlock& block, const std::string& title);

/// Record with the uplift levels +-g a/h (in g; the vertical component too when given), theta / alpha with the
/// overturning limits +-1 (the CM over the pivot), theta'; uplifts, impacts and the fall marked.
[[nodiscard]] Figure rocking_figure(const GroundMotion& horizontal, const RockingResult& result,
                                    const RockingBody& body, const std::string& title,
                                    const GroundMotion* vertical = nullptr);

/// The coupled slide-rock model's run (slide_rock.hpp; needs options.record_history): the record with the uplift
/// levels g b1/h, -g b2/h and the slip onset ±mu_s g (in g; the vertical too when given), theta over the alpha of its
/// side with the overturning limits ±1, the pivot's slide u with the slip starts marked, and the mode as a step line;
/// the fall marked. `g` is the gravity the run used (m/s^2). On a base inclined at slope_rad (SlideRockOptions) the
/// levels are the tilted ones: tan(alpha- - beta), -tan(alpha+ + beta), tan(phi - beta), -tan(phi + beta).
[[nodiscard]] Figure slide_rock_figure(const GroundMotion& horizontal, const SlideRockResult& result,
                                       const SlideRockBody& body, const std::string& title,
                                       const GroundMotion* vertical, double g_m_s2, double slope_rad = 0.0);

/// A frequency or period marked on a spectrum by a vertical line with its label.
struct Mark {
  double x = 0.0;
  std::string label;
  std::string color;  ///< "#rrggbb"
};

/// Acceleration (g) over time, and below it the Fourier amplitude spectrum (m/s) on log axes: the raw FAS and its
/// smoothed version at `smooth_hz`, with frequencies marked (e.g. requested and measured predominant frequency).
[[nodiscard]] Figure motion_spectrum_figure(const GroundMotion& motion, const FourierSpectrum& fas,
                                            const std::vector<double>& smooth_hz,
                                            const std::vector<double>& smooth_amplitude_m_s,
                                            const std::vector<Mark>& frequency_marks, double g_m_s2,
                                            const std::string& title);

/// Ground acceleration (g), velocity (m/s) and displacement (m) stacked over time, and below them the
/// pseudo-acceleration response spectrum (g) over period on log axes, with periods marked (e.g. Tp).
[[nodiscard]] Figure record_figure(const GroundMotion& motion, const GroundVelocityDisplacement& ground,
                                   const ResponseSpectrum& spectrum, const std::vector<Mark>& period_marks,
                                   double g_m_s2, const std::string& title);

/// One component of a station for record_set_figure: its name in the legend (e.g. "H1 (90 deg)", "V"), the motion
/// on the set's grid, its ground velocity and displacement and its response spectrum (the caller computes them).
struct ComponentRecord {
  std::string label;
  const GroundMotion* motion = nullptr;
  GroundVelocityDisplacement ground;
  ResponseSpectrum spectrum;
};

/// record_figure for the components of one station (`topple info H1 H2 [V] --plot`): acceleration (g), velocity
/// (m/s) and displacement (m) of every component in one panel each, and below them every component's PSA (g) with
/// the pair's RotD50 and RotD100 PSA (`rotd`, its periods; none drawn when null).
[[nodiscard]] Figure record_set_figure(const std::vector<ComponentRecord>& components, const RotDMeasures* rotd,
                                       double g_m_s2, const std::string& title);

/// Bidirectional sliding (`topple slide H1 --h2 H2 [--vertical V] --plot`): both horizontal components (and the
/// vertical) in g with the level-ground onset levels +-mu_s g, the relative velocity and displacement of the block,
/// east and north (m/s, m), slip starts marked. `first`, `second`, `vertical` with their azimuths as given to
/// slide_2d.
[[nodiscard]] Figure sliding_2d_figure(const GroundMotion& first, const GroundMotion& second,
                                       const ComponentAzimuths& azimuths, const GroundMotion* vertical,
                                       const Sliding2dResult& result, const SlidingBlock& block,
                                       const std::string& title);

// ---- Object spectra and fragility (src/output/plot_object_spectra.cpp) ----

/// Sliding displacement spectrum: max |d| and residual d (m) against mu, or against k_y g / PGA.
[[nodiscard]] Figure sliding_spectrum_figure(const SlidingSpectrum& spectrum, bool against_yield_ratio,
                                             const std::string& title);

/// Overturning map as boxes over block height (m, log axis over a wide range) x PGA (g), 1 = overturned, with the
/// first-overturn PGA of each size and the uplift level g tan(alpha) drawn over it.
[[nodiscard]] MapFigure overturning_map_figure(const OverturningMap& map, const std::string& title);

/// Fragility curves over the IM (log axis, in the IM's display unit): the fraction failing at each level (points),
/// the fitted lognormal curve and its delta-method band at `band_level` (dashed).
[[nodiscard]] Figure fragility_figure(const FragilityResult& result, double g_m_s2, double band_level,
                                      const std::string& title);

}  // namespace topple::plot
