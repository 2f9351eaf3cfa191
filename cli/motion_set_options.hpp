#pragma once
// The station's other components on a single-run command line (--h2, --vertical, --azimuths): one reading of them
// for every command that takes a motion set (slide, rock, spectrum, fragility). Translation only; the rules (exact
// merge, azimuths from the headers, the user's value winning with a warning) are the library's (motion_set.hpp).
#include <string>

#include <CLI/CLI.hpp>

#include "common.hpp"
#include "topple/motion/motion_set.hpp"

namespace topple::cli {

/// The motion set of `run` (its horizontal as the motion options made it, and its vertical) with the second
/// horizontal component read from `h2_path` with the same reading options and scaled by the same amplitude factor
/// (the shaking is scaled as a whole) and inverted with it (--invert flips both horizontal components, not the
/// vertical), the azimuths from `azimuths_text` ("A1,A2", parse_azimuths) or the headers.
/// Warnings (a header overridden) go to stderr. Throws InputError naming --azimuths or the file.
[[nodiscard]] MotionSet load_motion_set(const RunMotion& run, const MotionOptions& motion, const std::string& h2_path,
                                        const std::string& azimuths_text);

/// Registers --vertical, --h2 and --azimuths on a single-run command (slide, rock) in the same words everywhere but
/// for what the second component does in that command (`h2_does`, e.g. "bidirectional sliding, ...").
void add_motion_set_options(CLI::App& cmd, std::string& vertical, std::string& h2, std::string& azimuths,
                            const std::string& h2_does);

/// Refuses the set options on a command run with one component: InputError naming the first option given
/// (--azimuths, then each of `others` = {option, text}), saying it needs --h2.
void refuse_without_h2(const std::string& azimuths_text,
                       std::initializer_list<std::pair<const char*, bool>> others = {});

}  // namespace topple::cli
