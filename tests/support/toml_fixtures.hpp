#pragma once
// Test fixtures: the pieces of sweep TOML files that the CLI tests write again and again, built in one place.
#include <string>
#include <string_view>

namespace topple::test {

/// The `[[motions.set]]` table of the synthetic station (SyntheticStation, shared_data.hpp: m.h1.csv north, m.h2.csv
/// east, azimuths 0 and 90), with its vertical m.v.csv when `vertical`.
inline std::string station_set_toml(bool vertical) {
  return std::string("[[motions.set]]\nh1 = \"m.h1.csv\"\nh2 = \"m.h2.csv\"\n") +
         (vertical ? "vertical = \"m.v.csv\"\n" : "") + "azimuths_deg = [0, 90]\n";
}

/// A sweep's `[[object]]` rocking block (model "rock", shape "block") of the given width and height (lengths with
/// their units, e.g. "20cm"), followed by the `extra` lines as written (each ending in a newline).
inline std::string rock_block_toml(std::string_view width, std::string_view height, std::string_view extra = "") {
  return std::string("[[object]]\nmodel = \"rock\"\nshape = \"block\"\nwidth = \"") + std::string(width) +
         "\"\nheight = \"" + std::string(height) + "\"\n" + std::string(extra);
}

}  // namespace topple::test
