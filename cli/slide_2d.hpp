#pragma once
// topple slide FILE --h2 FILE2 --azimuths A1,A2: bidirectional sliding (sliding2d.hpp). Translation only.
#include <string>

#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/sliding2d.hpp"

namespace topple::cli {

/// "A1,A2" in degrees (clockwise from north) -> azimuths; InputError naming --azimuths otherwise.
[[nodiscard]] ComponentAzimuths parse_azimuths(const std::string& text);

/// Runs the bidirectional solver on `first` and `second` (second already scaled with the first) and prints the text
/// summary or, with `json`, the JSON object (kSliding2dFields, then "input"); with `plot_path`, the figure of both
/// components and the block's east and north response (plot::sliding_2d_figure); with `out_path`, the history CSV
/// (io::write_sliding_2d_history_csv).
void run_bidirectional_slide(const GroundMotion& first, const GroundMotion& second, const ComponentAzimuths& azimuths,
                             const SlidingBlock& block, const GroundMotion* vertical, bool json,
                             const std::string& motion_name, const std::string& second_name, double scale_factor,
                             const std::string& plot_path = "", const std::string& out_path = "");

}  // namespace topple::cli
