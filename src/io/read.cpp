// Placeholder: the readers are being written (issue 2, section 2).
#include "topple/io/read.hpp"

#include <fstream>
#include <sstream>

#include "topple/error.hpp"

namespace topple::io {

std::string_view format_name(Format format) {
  switch (format) {
    case Format::automatic: return "auto";
    case Format::peer_at2: return "peer-at2";
    case Format::cosmos_v2: return "cosmos-v2";
    case Format::csmip_v2: return "csmip-v2";
    case Format::knet: return "knet";
    case Format::usgs_smc: return "usgs-smc";
    case Format::esm: return "esm";
    case Format::plain: return "plain";
  }
  return "unknown";
}

Format parse_format_name(std::string_view name, const std::string& field) {
  for (Format f : {Format::automatic, Format::peer_at2, Format::cosmos_v2, Format::csmip_v2, Format::knet,
                   Format::usgs_smc, Format::esm, Format::plain}) {
    if (name == format_name(f)) return f;
  }
  throw parameter_error(field, "unknown format '" + std::string(name) + "'");
}

Format detect_format(std::string_view) { return Format::plain; }

GroundMotion parse_motion(std::string_view, const std::string& name, const ReadOptions&) {
  throw InputError(InputLocation{.file = name, .line = {}, .field = {}}, "readers not implemented yet");
}

GroundMotion read_motion(const std::filesystem::path& path, const ReadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputLocation{.file = path.string(), .line = {}, .field = {}}, "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_motion(text.str(), path.string(), options);
}

}  // namespace topple::io
