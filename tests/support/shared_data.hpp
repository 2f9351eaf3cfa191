#pragma once
// Test fixtures: where ../shared lives, and running the built CLI.
#include <sys/types.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace topple::test {

/// The shared/ folder beside the clone (records, verification, seed). Tests that need it skip when it is absent.
[[nodiscard]] std::filesystem::path shared_dir();
[[nodiscard]] std::filesystem::path shared_record(const std::string& name);
[[nodiscard]] bool have_shared();

struct CommandResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs the built `topple` CLI with the given argument string (shell-quoted by the caller). With `timeout_s` > 0 the
/// command is killed (SIGKILL) after that many seconds and the exit code is 137, so that a regression that hangs or
/// eats memory fails the test instead of stalling it.
[[nodiscard]] CommandResult run_cli(const std::string& args, int timeout_s = 0);

/// Runs a script of examples/ (`script`, e.g. "upper_floor.sh") with its arguments (shell-quoted by the caller) and
/// TOPPLE set to the built CLI; stdout and stderr together in `out`.
[[nodiscard]] CommandResult run_example(const std::string& script, const std::string& args);

/// Runs the CLI, expects exit status 0 (a test failure naming the arguments and stderr otherwise) and parses stdout
/// as JSON.
[[nodiscard]] nlohmann::json run_json(const std::string& args);

/// The whole content of a file (binary); empty when it cannot be read.
[[nodiscard]] std::string slurp(const std::filesystem::path& path);

/// Starts the built CLI in the background (argv as given, stdout to /dev/null, stderr to `err`); its pid, or -1.
[[nodiscard]] pid_t spawn_cli(const std::vector<std::string>& args, const std::filesystem::path& err);

/// Whether a test may run topple under mpirun: the test target defines TOPPLE_TEST_MPI=1 when topple is built with
/// MPI (tests/CMakeLists.txt), mpirun is on the PATH, and the build is not a sanitizer build (Open MPI's own
/// allocations trip LeakSanitizer). Inline: it reads the including target's definitions.
inline bool mpi_tests_enabled() {
#if defined(__SANITIZE_ADDRESS__)
  return false;
#elif defined(TOPPLE_TEST_MPI) && TOPPLE_TEST_MPI
  return std::system("command -v mpirun >/dev/null 2>&1") == 0;
#else
  return false;
#endif
}

/// How many times `what` occurs in `text` (overlapping occurrences counted).
[[nodiscard]] std::size_t count(const std::string& text, const std::string& what);

/// A fresh temporary directory, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// A synthetic station in `dir`, written by `topple synth --components 3 --pga 0.3g --freq 2.5Hz --duration 20
/// --seed 4 --azimuths 0,90`: H1 north, H2 east, V up; portable, so every machine gets the same samples. The paths
/// are single-quoted for a command line.
struct SyntheticStation {
  explicit SyntheticStation(const std::filesystem::path& dir);
  std::string h1, h2, v;
};

/// Writes text to a file (binary, exactly as given).
void write_file(const std::filesystem::path& path, const std::string& text);

/// A record of zeros in SLAMMER's two-column format (time in s, acceleration in g), `samples` samples at `dt_s` from
/// t = 0 (times printed to 1e-6 s): the second component of a collinear pair, on the grid of a shared SLAMMER record.
void write_zero_record(const std::filesystem::path& path, int samples, double dt_s);

/// The shared SLAMMER record Kocaeli 1999 ATS-090 and a record of zeros on its grid (26780 samples at 0.005 s),
/// written as dir/zero.csv; both single-quoted for a command line. With --azimuths 90,0 they are a collinear pair,
/// whose two-component runs are the record's one-component runs.
struct CollinearPair {
  std::string record;
  std::string zero;
};
[[nodiscard]] CollinearPair kocaeli_with_zero_partner(const std::filesystem::path& dir);

}  // namespace topple::test
