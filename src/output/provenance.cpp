#include "topple/output/provenance.hpp"

#include <chrono>
#include <ctime>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <xxhash.h>

#include "topple/core/error.hpp"

// Set for this file alone by src/CMakeLists.txt at configure time (so that a new commit recompiles one file).
#ifndef TOPPLE_VERSION
#define TOPPLE_VERSION "unknown"
#endif
#ifndef TOPPLE_GIT_COMMIT
#define TOPPLE_GIT_COMMIT "unknown"
#endif

namespace topple::io {

std::string topple_version() { return TOPPLE_VERSION; }
std::string topple_git_commit() { return TOPPLE_GIT_COMMIT; }

std::string xxh3_64_hex(std::string_view bytes) {
  return fmt::format("{:016x}", static_cast<unsigned long long>(XXH3_64bits(bytes.data(), bytes.size())));
}

Provenance make_provenance_without_file(const std::string& command_line) {
  Provenance p;
  p.topple_version = topple_version();
  p.git_commit = topple_git_commit();
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &utc);
  p.date_utc = date;
  p.command_line = command_line.empty() ? std::string("unknown") : command_line;
  p.survey_file = "unknown";
  p.survey_xxh3_64 = "unknown";
  return p;
}

Provenance make_provenance(const std::filesystem::path& survey_file, const std::string& command_line) {
  std::ifstream in(survey_file, std::ios::binary);
  std::ostringstream text;
  if (!in || !(text << in.rdbuf()) || in.bad()) {
    throw InputError(InputLocation{survey_file.string(), {}, {}}, "cannot be read for its checksum");
  }
  Provenance p = make_provenance_without_file(command_line);
  p.survey_file = survey_file.string();
  p.survey_text = text.str();
  p.survey_xxh3_64 = xxh3_64_hex(p.survey_text);
  return p;
}

}  // namespace topple::io
