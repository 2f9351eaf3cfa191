// Writes examples/regional_survey.toml (issue 17): build the target make_regional_example and run
//   build/release/tests/make_regional_example > examples/regional_survey.toml
#include <cstdio>

#include "regional_scenario.hpp"

int main() {
  const topple::InversionSettings st = topple::testing::small_grid(0.01, 24, 1.5, 6.0, 4, 12);
  const auto sc = topple::testing::make_regional_scenario(7, topple::testing::RegionalTruth{}, st);
  std::fputs(topple::testing::regional_survey_toml(
                 sc, "build/release/tests/make_regional_example > examples/regional_survey.toml").c_str(),
             stdout);
  return 0;
}
