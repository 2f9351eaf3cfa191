#pragma once
// topple rock --model coupled --mu MU [--mu-k MU_K]: the coupled slide-rock model (slide_rock.hpp). Translation only.
#include <optional>
#include <string>

#include "common.hpp"
#include "topple/slide_rock.hpp"

namespace topple::cli {

/// What `topple rock` parsed that the coupled model uses, besides the body and the motion.
struct CoupledRequest {
  SlideRockOptions options;
  std::string out;   ///< history CSV (empty: none)
  bool json = false;
};

/// Runs slide_rock on the loaded motion and prints the text summary or, with `json`, the JSON object
/// (kSlideRockFields, modes, warnings, body, then "input").
void run_coupled(const RunMotion& run, const SlideRockBody& body, const CoupledRequest& request);

}  // namespace topple::cli
