// libFuzzer target for one reader: the format is fixed at compile time (TOPPLE_FUZZ_FORMAT, a topple::io::Format
// enumerator), so each target explores one parser deeply. Built once per format by fuzz/CMakeLists.txt.
//
// Contract checked: parse_motion either throws topple::InputError or returns a record that is usable: at least one
// sample, a positive finite dt, finite accelerations and times. Any other exception, a crash, a sanitizer report or
// a NaN ends the run with a reproducer.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string_view>

#include "topple/error.hpp"
#include "topple/io/read.hpp"

namespace {

void check(const topple::GroundMotion& m) {
  if (m.size() == 0) std::abort();
  if (!(m.dt_s() > 0.0) || !std::isfinite(m.dt_s())) std::abort();
  for (double a : m.accel_m_s2()) {
    if (!std::isfinite(a)) std::abort();
  }
  if (!std::isfinite(m.start_time_s()) || !std::isfinite(m.end_time_s())) std::abort();
  if (!std::isfinite(m.pga_m_s2()) || !std::isfinite(m.pga_time_s())) std::abort();
}

void parse(std::string_view text, const topple::io::ReadOptions& options) {
  try {
    check(topple::io::parse_motion(text, "fuzz-input", options));
  } catch (const topple::InputError&) {
    // Refusing bad input is the expected outcome; anything else escapes and is reported by libFuzzer.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  topple::io::ReadOptions options;
#ifdef TOPPLE_FUZZ_DETECT
  // Detection alone must not fail, then the automatic path as a user would call it.
  (void)topple::io::detect_format(text);
  options.format = topple::io::Format::automatic;
#else
  options.format = topple::io::Format::TOPPLE_FUZZ_FORMAT;
#endif
  parse(text, options);
  // The options that change what a reader does: a chosen channel (multi-channel formats), and for plain text a
  // unit and a time step (the one-column path).
  options.channel = 2;
  parse(text, options);
  options.channel = std::nullopt;
  options.units = "g";
  options.dt_s = 0.01;
  parse(text, options);
  return 0;
}
