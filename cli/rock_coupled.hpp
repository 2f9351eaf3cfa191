#pragma once
// topple rock --model coupled --mu MU [--mu-k MU_K]: the coupled slide-rock model (slide_rock.hpp). Translation only.
#include <optional>
#include <string>

#include "common.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/slide_rock.hpp"

namespace topple::cli {

/// What `topple rock` parsed that the coupled model uses, besides the body and the motion.
struct CoupledRequest {
  SlideRockOptions options;
  std::string out;   ///< history CSV (empty: none)
  std::string plot;  ///< figure, .svg or .png (empty: none)
  bool json = false;
  /// With a second horizontal component: the run is in the vertical plane of this bearing (degrees clockwise from
  /// north, the body's +x side), under the projection of the pair on it (oriented.hpp, eq. M1); reported in the JSON.
  std::optional<double> bearing_deg;
  std::string h2;                             ///< the second component's file, for the JSON's input
  std::optional<ComponentAzimuths> azimuths;  ///< the pair's azimuths
};

/// Runs slide_rock on the loaded motion and prints the text summary or, with `json`, the JSON object
/// (kSlideRockFields, modes, warnings, body, then "input").
void run_coupled(const RunMotion& run, const SlideRockBody& body, const CoupledRequest& request);

}  // namespace topple::cli
