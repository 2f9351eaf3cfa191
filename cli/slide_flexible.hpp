#pragma once
// `topple slide` on a flexible support (shelf, floor, or SLAMMER's flexible sliding mass): options and printing.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "topple/solvers/flexible.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/sliding.hpp"

namespace topple::cli {

struct FlexibleOptions {
  std::string support_freq;      ///< "4Hz", "0.25s" ... (a shelf or floor)
  std::string support_damping;   ///< "5%" or 0.05
  std::optional<double> mass_ratio;  ///< with --coupled only
  std::string height;            ///< SLAMMER sliding mass: "50m"
  std::optional<double> vs_slope_m_s;
  std::optional<double> vs_base_m_s;
  std::string damping;           ///< SLAMMER material damping, "5%" or 0.05
  std::string reference_strain;  ///< SLAMMER equivalent linear: "0.05%" or 0.0005
  bool coupled = false;

  [[nodiscard]] bool active() const { return !support_freq.empty() || !height.empty(); }
};

void add_flexible_options(CLI::App& cmd, FlexibleOptions& options);

/// Before any work: an option that describes a support nobody gave is refused, naming it ("--ref-strain needs
/// --height", "--mass-ratio needs --coupled", "--coupled needs --support-freq or --height"), as are the two supports
/// together. Throws a parameter error (exit 2).
void check_flexible_options(const FlexibleOptions& options);

/// The shelf or floor of `--support-freq F [--support-damping Z]` (damping default 5 %, as `topple slide` documents).
[[nodiscard]] SupportOscillator support_from_options(const std::string& support_freq, const std::string& support_damping,
                                                     double mass_ratio = 0.0);

/// Runs and prints (text or JSON) the flexible-support analysis; `mu` is the friction coefficient (shelf) or the
/// yield coefficient k_y (sliding mass); `vertical` as in the rigid run (both analyses).
/// `out` / `plot` (empty: none) receive the history CSV and the figure, as the rigid run's --out / --plot.
/// `pulse_kind` names the --pulse the motion came from (empty: a record file, `motion_name`), for the refusal of an
/// irregularly sampled motion.
void run_flexible_slide(const GroundMotion& horizontal, const SlidingBlock& block, const FlexibleOptions& o, bool json,
                        const std::string& motion_name, const GroundMotion* vertical = nullptr,
                        const std::string& out = {}, const std::string& plot = {},
                        const std::string& pulse_kind = {});

}  // namespace topple::cli
