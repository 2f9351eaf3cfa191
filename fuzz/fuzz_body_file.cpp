// libFuzzer target for the body file (io::parse_body_file: the JSON `topple body --json` writes, read by `rock --body`
// and `fragility --body`). Contract (docs/fuzzing.md): an InputError, or a body whose rocking body can be built with
// every number finite and positive; any other exception, a crash or a sanitizer report ends the run.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "topple/core/error.hpp"
#include "topple/io/body_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const topple::io::BodyFile body = topple::io::parse_body_file(text, "fuzz-body.json");
    const topple::RockingBody rb = body.rocking_body();
    for (const int side : {-1, 1}) {
      if (!(rb.pivot_b_m(side) > 0.0) || !std::isfinite(rb.pivot_b_m(side)) || !(rb.pivot_D_m2(side) > 0.0) ||
          !std::isfinite(rb.pivot_D_m2(side))) {
        std::abort();  // accepted, but not a body
      }
    }
    if (!(rb.h_m > 0.0) || !std::isfinite(rb.h_m)) std::abort();
  } catch (const topple::InputError&) {
    // refusing bad input is the expected outcome
  }
  return 0;
}
