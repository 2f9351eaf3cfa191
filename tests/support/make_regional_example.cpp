// Writes examples/regional_survey.toml (issue 17): build the target make_regional_example and run
//   build/release/tests/make_regional_example > examples/regional_survey.toml
// With an argument N, a survey of N sites (the dozen and N - 12 more with three objects each): the MPI scale
// benchmark's survey (scripts/region-mpi-speedup.sh).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "regional_scenario.hpp"

int main(int argc, char** argv) {
  const topple::InversionSettings st = topple::testing::small_grid(0.01, 24, 1.5, 6.0, 4, 12);
  const std::size_t sites = argc > 1 ? static_cast<std::size_t>(std::strtoul(argv[1], nullptr, 10)) : 12;
  if (sites < 12) {
    std::fputs("make_regional_example: N must be at least 12\n", stderr);
    return 2;
  }
  const auto sc = topple::testing::make_regional_scenario(7, topple::testing::RegionalTruth{}, st, sites);
  const std::string command = sites == 12 ? "build/release/tests/make_regional_example > examples/regional_survey.toml"
                                          : "build/release/tests/make_regional_example " + std::to_string(sites);
  std::fputs(topple::testing::regional_survey_toml(sc, command).c_str(), stdout);
  return 0;
}
