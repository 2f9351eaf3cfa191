// libFuzzer target for the TOML inputs: the survey reader (io::parse_survey, TOPPLE_FUZZ_SURVEY; TOML or CSV,
// told apart by content since the name has no extension) or the sweep-file reader (io::parse_sweep_file,
// TOPPLE_FUZZ_SWEEP), or the campaign-file reader (io::parse_campaign_file, TOPPLE_FUZZ_CAMPAIGN; records and meshes
// are not read there, and their existence is not checked). Contract (docs/fuzzing.md): an InputError, or a value; any other
// exception, a crash or a sanitizer report ends the run. Record paths in the input resolve against a directory that
// does not exist, so that the fuzzer does not wander the file system (absolute paths are still read, through the
// same bounded io::read_input_file).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "topple/core/error.hpp"
#include "topple/io/campaign_file.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/io/sweep_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
#ifdef TOPPLE_FUZZ_SURVEY
    (void)topple::io::parse_survey(text, "fuzz-survey", "/nonexistent-topple-fuzz");
#elif defined(TOPPLE_FUZZ_CAMPAIGN)
    (void)topple::io::parse_campaign_file(text, "/nonexistent-topple-fuzz/campaign.toml", false);
#else
    (void)topple::io::parse_sweep_file(text, "/nonexistent-topple-fuzz/sweep.toml");
#endif
  } catch (const topple::InputError&) {
    // refusing bad input is the expected outcome
  }
  return 0;
}
