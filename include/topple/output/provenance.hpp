#pragma once
// Where a result came from: the program (topple version and git commit, fixed when the build was configured), when
// (UTC), how (the exact command line) and from what (the survey file, its XXH3-64 checksum and its text verbatim).
// The inversion's JSON and report carry it so that a result handed on can be traced and rerun.
#include <filesystem>
#include <string>

namespace topple::io {

struct Provenance {
  std::string topple_version;  ///< e.g. "0.1.0" (CMake's PROJECT_VERSION)
  std::string git_commit;      ///< 12 hex digits, "-dirty" when tracked files differed; "unknown" outside a checkout
  std::string date_utc;        ///< ISO 8601, seconds, "2026-11-24T01:02:03Z"
  std::string command_line;    ///< the exact command, each argument shell-quoted where needed; "unknown" if unknown
  std::string survey_file;     ///< the path as given
  std::string survey_xxh3_64;  ///< XXH3 64-bit of the file's bytes, 16 hex digits
  std::string survey_text;     ///< the file's bytes, verbatim
};

/// The version and commit this library was built from (fixed at configure time).
[[nodiscard]] std::string topple_version();
[[nodiscard]] std::string topple_git_commit();

/// XXH3 64-bit of `bytes` as 16 lower-case hex digits (the checksum the sweep store uses too).
[[nodiscard]] std::string xxh3_64_hex(std::string_view bytes);

/// Reads the survey file (InputError naming it when it cannot be read) and fills every field; `command_line` as the
/// caller knows it (the CLI: its own argv).
[[nodiscard]] Provenance make_provenance(const std::filesystem::path& survey_file, const std::string& command_line);

/// The same without a survey file (a survey built in memory): survey_file, checksum and text say "unknown" / "".
[[nodiscard]] Provenance make_provenance_without_file(const std::string& command_line);

}  // namespace topple::io
