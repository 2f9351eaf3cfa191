// --h2 / --azimuths: a single-run command's motion set (motion_set_options.hpp).
#include "motion_set_options.hpp"

#include <cstdio>
#include <vector>

#include <fmt/format.h>

#include "slide_2d.hpp"
#include "topple/core/error.hpp"

namespace topple::cli {

MotionSet load_motion_set(const RunMotion& run, const MotionOptions& motion, const std::string& h2_path,
                          const std::string& azimuths_text) {
  // --invert flips the horizontal shaking as a whole (both components: the pair seen from the opposite bearing);
  // the vertical keeps its sign, as with one component.
  GroundMotion second = io::read_motion(h2_path, read_options(motion)).scaled(run.input.scale_factor);
  if (motion.invert) second = second.inverted();
  std::vector<std::string> warnings;
  const ComponentAzimuths azimuths =
      resolve_azimuths(run.horizontal, second,
                       azimuths_text.empty() ? std::nullopt : std::optional(parse_azimuths(azimuths_text)), warnings);
  for (const std::string& w : warnings) fmt::print(stderr, "warning: {}\n", w);
  // One grid for the three components (exact merge; refuses records that are not one recording).
  return MotionSet::make(run.horizontal, &second, azimuths, run.vertical_ptr());
}

void refuse_without_h2(const std::string& azimuths_text,
                       std::initializer_list<std::pair<const char*, bool>> others) {
  if (!azimuths_text.empty()) throw parameter_error("--azimuths", "needs --h2 (the second horizontal component)");
  for (const auto& [option, given] : others) {
    if (given) {
      throw parameter_error(option, "needs --h2 (the second horizontal component): with one component there is no "
                                    "direction to choose");
    }
  }
}

void add_motion_set_options(CLI::App& cmd, std::string& vertical, std::string& h2, std::string& azimuths,
                            const std::string& h2_does) {
  cmd.add_option("--vertical", vertical, "Vertical acceleration record (positive up), scaled with the horizontal");
  cmd.add_option("--h2", h2, "Second horizontal component (record file): " + h2_does +
                                 "; --azimuths unless the headers state them");
  cmd.add_option("--azimuths", azimuths, "With --h2: the two components' azimuths A1,A2 in degrees clockwise from "
                                         "north (perpendicular), e.g. 90,0; default: the files' headers where they "
                                         "state them (a value given here wins, with a warning)");
}

}  // namespace topple::cli
