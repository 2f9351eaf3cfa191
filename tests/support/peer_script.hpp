#pragma once
// The peer programs of tests/peer/ (eqsig, pyrotd, OpenQuake's hazardlib: published implementations topple is
// compared with), run at test time with the test virtual environment's python, .venv-test (scripts/test-venv.sh);
// the tests that use them skip where it is absent, as in the test command. Header-only: test_spectra.cpp,
// test_motion_set.cpp and test_prior.cpp use it.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace topple::test {

/// .venv-test's python; absent until scripts/test-venv.sh has made it.
inline std::filesystem::path venv_python() {
  return std::filesystem::path(TOPPLE_SOURCE_DIR) / ".venv-test" / "bin" / "python";
}

/// `values` one a line, each in the shortest text that reads back to the same double: the input the peer scripts
/// read.
inline void write_column(const std::filesystem::path& path, std::span<const double> values) {
  std::ofstream out(path);
  for (const double x : values) out << fmt::format("{}\n", x);
}

/// Runs tests/peer/`script` with venv_python and `args` (each already quoted for the shell) and parses what it prints
/// (stdout and stderr together) as JSON; anything else is a test failure that shows it, and null.
inline nlohmann::json run_peer_script(const std::string& script, const std::string& args) {
  const std::string cmd =
      fmt::format("'{}' '{}/tests/peer/{}' {} 2>&1", venv_python().string(), TOPPLE_SOURCE_DIR, script, args);
  std::string text;
  {
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
    if (!pipe) {
      ADD_FAILURE() << "cannot run " << cmd;
      return nullptr;
    }
    std::array<char, 4096> buf{};
    while (fgets(buf.data(), static_cast<int>(buf.size()), pipe.get()) != nullptr) text += buf.data();
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    ADD_FAILURE() << "peer script " << script << " failed: " << text;
    return nullptr;
  }
}

}  // namespace topple::test
