// --quiet on every command, and the progress bar of the long commands (invert, fragility, spectrum rock, sweep): drawn
// on a terminal only, never into a pipe or a file, never with --quiet (issue 13).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"

namespace topple {
namespace {

const std::string kFragility =
    "fragility --synth 20 --im-range 0.05:2:12 --mu 0.3 --threshold 5cm --threads 2 --json";  // 240 runs
const std::string kSpectrumRock =
    "spectrum rock --pulse sine --amp-g 1 --duration 0.5 --slenderness 0.25 --height-range 10cm:1m:8 "
    "--pga-range 0.1g:1g:10 --threads 2 --json";  // 80 runs

/// A survey small enough to invert in a fraction of a second (3 x 2 cells, 2 motions, 2 objects), as CSV.
std::filesystem::path small_survey(const test::TempDir& tmp) {
  const auto path = tmp.path() / "small.csv";
  test::write_file(path, "inversion.pga_g,\"[0.1, 1.0, 3]\"\ninversion.freq_hz,\"[1.0, 4.0, 2]\"\n"
                         "inversion.motions_per_cell,2\n"
                         "id,width_cm,height_cm,mu,outcome\nvase,8,40,0.5,toppled\nbox,30,40,0.5,not_overturned\n");
  return path;
}

/// stdout and stderr of the CLI run under a pseudo-terminal (util-linux `script`), as a user at a terminal sees them.
std::string run_on_terminal(const std::string& args, const test::TempDir& tmp) {
  const auto log = tmp.path() / "terminal.txt";
  const std::string inner = std::string("'") + TOPPLE_CLI_PATH + "' " + args + " >/dev/null";
  const std::string cmd = "script -qec \"" + inner + "\" /dev/null >'" + log.string() + "' 2>&1 </dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return test::slurp(log);
}

bool have_script() { return std::system("command -v script >/dev/null 2>&1") == 0; }

// Every command takes --quiet (scripts can pass it to any of them).
TEST(CliQuiet, EveryCommandAcceptsQuiet) {
  for (const char* cmd : {"info", "slide", "rock", "synth", "sweep", "spectrum slide", "spectrum rock", "fragility",
                          "invert", "campaign"}) {
    const auto r = test::run_cli(std::string(cmd) + " --help");
    EXPECT_EQ(r.exit_code, 0) << cmd;
    EXPECT_NE(r.out.find("--quiet"), std::string::npos) << cmd << " --help lacks --quiet:\n" << r.out;
  }
  const auto r = test::run_cli("rock --pulse sine --amp-g 0.5 --duration 0.5 --shape block --width 10cm --height 40cm --quiet --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Into a file (the tests' stderr is one), the long commands write nothing on stderr: no bar, no carriage return.
TEST(CliProgress, NothingOnStderrWhenItIsNotATerminal) {
  test::TempDir tmp;
  for (const std::string& args : {kFragility, kSpectrumRock, "invert " + small_survey(tmp).string() + " --json --quiet"}) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    EXPECT_EQ(r.err.find('\r'), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(r.err.find("runs/s"), std::string::npos) << args << "\n" << r.err;
  }
  // invert without --quiet still says what it does (one line per site), but draws no bar into a file.
  const auto r = test::run_cli("invert " + small_survey(tmp).string() + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("topple: inverting site 1 (2 objects)"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("runs/s"), std::string::npos) << r.err;
}

// On a terminal, each long command draws the bar up to its total number of runs (the library's callback reaching
// the CLI); --quiet draws nothing.
TEST(CliProgress, BarOnATerminalAndNotWithQuiet) {
  if (!have_script()) GTEST_SKIP() << "util-linux `script` (a pseudo-terminal) is not installed";
  test::TempDir tmp;
  const std::string survey = small_survey(tmp).string();
  const struct {
    std::string args;
    std::string total;  // runs: levels x motions x objects, cells x motions x objects, PGAs x sizes
  } cases[] = {{kFragility, "240/240 runs 100%"},
               {kSpectrumRock, "80/80 runs 100%"},
               {"invert " + survey + " --json", "24/24 runs 100%"}};
  for (const auto& c : cases) {
    const std::string shown = run_on_terminal(c.args, tmp);
    EXPECT_NE(shown.find(c.total), std::string::npos) << c.args << "\n" << shown;
    const std::string quiet = run_on_terminal(c.args + " --quiet", tmp);
    EXPECT_EQ(quiet.find("runs/s"), std::string::npos) << c.args << " --quiet\n" << quiet;
  }
}

}  // namespace
}  // namespace topple
