// Writes examples/regional_survey.toml (issue 17): build the target make_regional_example and run
//   build/release/tests/make_regional_example > examples/regional_survey.toml
#include <cstdio>

#include "regional_scenario.hpp"

int main() {
  topple::InversionSettings st;
  st.pga_min_g = 0.01;
  st.pga_max_g = 2.0;
  st.pga_count = 24;
  st.freq_min_hz = 1.5;
  st.freq_max_hz = 6.0;
  st.freq_count = 4;
  st.motions_per_cell = 12;
  const auto sc = topple::testing::make_regional_scenario(7, topple::testing::RegionalTruth{}, st);
  std::fputs(topple::testing::regional_survey_toml(
                 sc, "build/release/tests/make_regional_example > examples/regional_survey.toml").c_str(),
             stdout);
  return 0;
}
