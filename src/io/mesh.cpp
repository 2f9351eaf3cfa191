// OBJ, OFF, STL and PLY meshes read in double precision by CGAL's own I/O (CGAL::IO::read_OBJ, read_OFF, read_STL,
// read_PLY; Debian libcgal-dev, headers only), recentred, welded, triangulated and checked here with the file's own
// vertex and face numbers in every message.
#include "topple/io/mesh.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>
#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple::io {
namespace {

using Point = CGAL::Simple_cartesian<double>::Point_3;

/// Largest |coordinate| in a file, m (after --unit): 1e8 m holds every projected (UTM northing < 1e7 m) and
/// Earth-centred coordinate, and a double there still resolves 1.5e-8 m (its spacing, 2^-26 m).
constexpr double kMaxFileCoordinateM = 1e8;
/// Most vertices of one polygon face (a scan's faces are triangles; an OBJ cap of a cylinder may have dozens).
constexpr std::size_t kMaxPolygonVertices = 1000;

InputError mesh_error(const std::string& file, const std::string& problem) {
  return InputError(InputLocation{.file = file, .line = {}, .field = {}}, problem);
}
InputError line_error(const std::string& file, std::size_t line, const std::string& problem) {
  return InputError(InputLocation{.file = file, .line = line, .field = {}}, problem);
}

/// An error at a line (0: none, a binary file) and a field of the file: "file:12: vertex 5, z: problem".
InputError field_error(const std::string& file, std::size_t line, const std::string& field, const std::string& problem) {
  return InputError(InputLocation{.file = file, .line = line == 0 ? std::optional<std::size_t>{} : line,
                                  .field = field},
                    problem);
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext;
}

const std::string kPointCloud =
    "this is a point cloud: mesh it first (e.g. Poisson or ball-pivoting surface reconstruction in "
    "CloudCompare/MeshLab/Open3D), then read the closed surface";

/// A read-only stream over the file's bytes (no copy), seekable: CGAL's STL reader rewinds to try the other form.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(std::string_view s) {
    char* b = const_cast<char*>(s.data());  // only read: a streambuf's get area is char*, never written through here
    setg(b, b, b + s.size());
  }

 protected:
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override {
    if ((which & std::ios_base::in) == 0) return pos_type(off_type(-1));
    const off_type size = egptr() - eback();
    const off_type base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? gptr() - eback() : size;
    const off_type target = base + off;
    if (target < 0 || target > size) return pos_type(off_type(-1));
    setg(eback(), eback() + target, egptr());
    return pos_type(target);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
    return seekoff(off_type(pos), std::ios_base::beg, which);
  }
};

struct TooManyVertices {};  // thrown through CGAL's readers by BoundedPolygon

/// A polygon's vertex indices as CGAL's readers fill them (resize, then assign), bounded: CGAL's OFF reader resizes
/// to the count the file gives, before reading any index.
struct BoundedPolygon : std::vector<std::size_t> {
  void resize(std::size_t n) {
    if (n > kMaxPolygonVertices) throw TooManyVertices{};
    std::vector<std::size_t>::resize(n);
  }
};

/// What a reader gives: double-precision points and polygons (indices into points, 0-based) in file order, and how
/// the file numbers them.
struct Soup {
  std::vector<Point> points;
  std::vector<BoundedPolygon> polygons;
  /// True where points are the file's numbered vertices (OBJ, OFF, PLY); false for STL, whose facets repeat their
  /// corners' coordinates (CGAL welds them, numbering in order of first appearance: no file number exists).
  bool numbered = true;
  /// The number a file writes for points[0] in its faces: 1 for OBJ, 0 for OFF and PLY.
  std::size_t base = 1;
  std::string face_word = "face";  // "face" (the n-th f line of an OBJ, the n-th face of an OFF or PLY), "facet"
  /// The line of the file each polygon is written on (text formats: OBJ, OFF, ASCII PLY and STL); empty for binary.
  std::vector<std::size_t> face_lines;
};

// --- Tokens and coordinates, as typed ---------------------------------------------------------------------------

/// A token that is a whole number in the C locale (a leading '+' allowed, as C++ streams read it): the token entire,
/// not its numeric prefix (a stream reads "6D-1" as 6 and "0.3x" as 0.3).
bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc{} && end == token.data() + token.size();
}
bool parse_index(std::string_view token, std::size_t& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc{} && end == token.data() + token.size();
}

std::string_view next_line(std::string_view content, std::size_t& pos) {
  std::size_t eol = content.find('\n', pos);
  if (eol == std::string_view::npos) eol = content.size();
  std::string_view line = content.substr(pos, eol - pos);
  pos = eol + 1;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

/// A token as the user typed it, quoted, for a message: cut to 40 bytes, control bytes shown as \xNN (UTF-8 kept:
/// a Unicode minus is shown as typed).
std::string quoted(std::string_view token) {
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    out += c >= 0x20 && c != 0x7f ? std::string(1, static_cast<char>(c)) : fmt::format("\\x{:02x}", c);
  }
  return out + (token.size() > 40 ? "...'" : "'");
}

/// What is wrong with a coordinate token of a text file, in words that quote it as typed ("" when it is a finite
/// number within kMaxFileCoordinateM of the file's origin after --unit): the value read is `value`.
std::string coordinate_problem(std::string_view token, double unit_m, double& value) {
  std::string_view t = token;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  const bool whole = end == t.data() + t.size();
  if (ec == std::errc::result_out_of_range && whole) {
    return fmt::format("{} is beyond the range of a double (and beyond {:g} m of the file's origin)", quoted(token),
                       kMaxFileCoordinateM);
  }
  if (ec != std::errc{} || !whole) {
    if (token.find("\xe2\x88\x92") != std::string_view::npos) {
      return fmt::format("{} is not a number: it holds the Unicode minus sign U+2212; write the ASCII '-'",
                         quoted(token));
    }
    return fmt::format("{} is not a number", quoted(token));
  }
  if (!std::isfinite(value)) return fmt::format("{} is not a finite number", quoted(token));
  if (!(std::abs(value) * unit_m <= kMaxFileCoordinateM)) {
    return fmt::format("{} is beyond {:g} m of the file's origin (at --unit {:g} m): check --unit", quoted(token),
                       kMaxFileCoordinateM, unit_m);
  }
  return {};
}

constexpr std::array<const char*, 3> kAxes{"x", "y", "z"};

// --- PLY ---------------------------------------------------------------------------------------------------------

bool is_ply_type(std::string_view t) {
  for (std::string_view known : {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
                                 "int16", "uint16", "int32", "uint32", "float32", "float64"}) {
    if (t == known) return true;
  }
  return false;
}
bool is_ply_float(std::string_view t) { return t == "float" || t == "double" || t == "float32" || t == "float64"; }
bool is_ply_small_count(std::string_view t) {
  return t == "char" || t == "uchar" || t == "int8" || t == "uint8" || t == "short" || t == "ushort" ||
         t == "int16" || t == "uint16";
}
bool is_ply_index(std::string_view t) { return t == "int" || t == "uint" || t == "int32" || t == "uint32"; }

bool is_identifier(std::string_view t) {
  if (t.empty() || t.size() > 64) return false;
  return std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; });
}

/// The tokens of a line split at white space as a C++ stream sees it (space, \t, \r, \v, \f), as CGAL's readers do.
std::vector<std::string_view> split_blank(std::string_view line) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  std::vector<std::string_view> tokens;
  for (std::size_t i = 0; i < line.size();) {
    while (i < line.size() && blank(line[i])) ++i;
    std::size_t j = i;
    while (j < line.size() && !blank(line[j])) ++j;
    if (j > i) tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

/// A PLY element as its header declares it: name, count, the header line, and its properties (for a list: the
/// count's type and the items' type).
struct PlyProperty {
  std::string name, type;       // type: the scalar's, or the list items'
  std::string count_type;       // "" for a scalar
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::size_t line = 0;
  std::vector<PlyProperty> properties;
};

std::size_t ply_type_bytes(std::string_view t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;  // int, uint, float and their sized names
}
bool is_ply_integer(std::string_view t) { return !is_ply_float(t); }

/// The body of a PLY file checked against its header before CGAL reads it, element by element in the header's
/// order, so that a count the file does not hold, an element absent from the file or a value that is not of its
/// type is refused with the element, the record and (ASCII) the line, instead of CGAL's "cannot read". ASCII: every
/// value a whole token of its type (integers for integer types; the vertex coordinates finite and within
/// kMaxFileCoordinateM, quoted as typed); binary: the bytes each record takes, lists by their counts, and nothing
/// after the last element. Records the line of each face (ASCII) for messages.
void check_ply_body(std::string_view content, std::size_t pos, std::size_t line_no, bool ascii, bool big_endian,
                    const std::vector<PlyElement>& elements, const std::string& name, double unit_m,
                    std::vector<std::size_t>& face_lines) {
  const auto is_vertex = [](const std::string& e) { return e == "vertex" || e == "vertices"; };
  const auto is_face = [](const std::string& e) { return e == "face" || e == "faces"; };
  if (ascii) ++line_no;  // pos is at the start of the line after end_header
  const auto ends = [&](const PlyElement& e, std::uint64_t record) {
    return field_error(name, ascii ? line_no : 0, "element " + e.name,
                       fmt::format("the file ends in element '{}' (declared at line {} with {} records): {} of them "
                                   "are there",
                                   e.name, e.line, e.count, record));
  };
  if (ascii) {
    // Tokens as a C++ stream (CGAL's reader) sees them: separated by white space, lines counted for messages.
    const auto next_token = [&](std::string_view& token) {
      while (pos < content.size()) {
        const char c = content[pos];
        if (c == '\n') ++line_no;
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f') {
          ++pos;
          continue;
        }
        break;
      }
      if (pos >= content.size()) return false;
      const std::size_t begin = pos;
      while (pos < content.size() && !std::isspace(static_cast<unsigned char>(content[pos]))) ++pos;
      token = content.substr(begin, pos - begin);
      return true;
    };
    for (const PlyElement& e : elements) {
      const bool vertex = is_vertex(e.name), face = is_face(e.name);
      for (std::uint64_t r = 0; r < e.count; ++r) {
        std::size_t record_line = 0;
        for (const PlyProperty& p : e.properties) {
          const auto value = [&](const std::string& type, bool list_count) {
            std::string_view token;
            if (!next_token(token)) throw ends(e, r);
            if (record_line == 0) record_line = line_no;
            double v = 0.0;
            if (vertex && p.count_type.empty() && (p.name == "x" || p.name == "y" || p.name == "z")) {
              const std::string problem = coordinate_problem(token, unit_m, v);
              if (!problem.empty()) {
                throw field_error(name, line_no, fmt::format("vertex {} (index {}), {}", r + 1, r, p.name), problem);
              }
              return v;
            }
            std::int64_t i = 0;
            const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), i);
            const bool integer = ec == std::errc{} && end == token.data() + token.size();
            if (is_ply_integer(type) ? !integer : !(parse_double(token, v) && std::isfinite(v))) {
              throw field_error(name, line_no,
                                fmt::format("{} {}, {}{}", e.name, r + 1, p.name, list_count ? "'s count" : ""),
                                fmt::format("{} is not {} ({})", quoted(token),
                                                          is_ply_integer(type) ? "a whole number" : "a finite number",
                                                          type));
            }
            return is_ply_integer(type) ? static_cast<double>(i) : v;
          };
          if (p.count_type.empty()) {
            (void)value(p.type, false);
            continue;
          }
          const double n = value(p.count_type, true);
          const double most = p.count_type == "uchar" || p.count_type == "uint8" ? 255.0
                              : p.count_type == "char" || p.count_type == "int8" ? 127.0
                              : p.count_type == "short" || p.count_type == "int16" ? 32767.0 : 65535.0;
          if (!(n >= 0.0 && n <= most)) {
            throw field_error(name, line_no, fmt::format("{} {}, {}", e.name, r + 1, p.name),
                              fmt::format("the list's count is {}, outside [0, {}] ({})", n, most, p.count_type));
          }
          for (int k = 0; k < static_cast<int>(n); ++k) (void)value(p.type, false);
        }
        if (face) face_lines.push_back(record_line);
      }
    }
    std::string_view token;
    if (next_token(token)) {
      throw line_error(name, line_no, fmt::format("{} after the last record the header declares (element '{}'): the "
                                                  "header's counts are smaller than the data",
                                                  quoted(token), elements.back().name));
    }
    return;
  }
  const auto read_uint = [&](std::size_t at, std::size_t bytes) {
    std::uint64_t v = 0;
    for (std::size_t k = 0; k < bytes; ++k) {
      const auto byte = static_cast<unsigned char>(content[at + (big_endian ? k : bytes - 1 - k)]);
      v = (v << 8) | byte;
    }
    return v;
  };
  for (const PlyElement& e : elements) {
    const bool vertex = is_vertex(e.name);
    for (std::uint64_t r = 0; r < e.count; ++r) {
      for (const PlyProperty& p : e.properties) {
        const std::size_t size = ply_type_bytes(p.type);
        if (p.count_type.empty()) {
          if (content.size() - pos < size) throw ends(e, r);
          if (vertex && (p.name == "x" || p.name == "y" || p.name == "z")) {
            const std::uint64_t bits = read_uint(pos, size);
            double v = 0.0;
            if (size == 8) {
              v = std::bit_cast<double>(bits);
            } else {
              v = std::bit_cast<float>(static_cast<std::uint32_t>(bits));
            }
            if (!std::isfinite(v) || !(std::abs(v) * unit_m <= kMaxFileCoordinateM)) {
              throw field_error(name, 0, fmt::format("vertex {} (index {}), {}", r + 1, r, p.name),
                                fmt::format("{} is not a finite number within {:g} m of the file's origin (at --unit "
                                            "{:g} m)",
                                            v, kMaxFileCoordinateM, unit_m));
            }
          }
          pos += size;
          continue;
        }
        const std::size_t count_size = ply_type_bytes(p.count_type);
        if (content.size() - pos < count_size) throw ends(e, r);
        const std::uint64_t n = read_uint(pos, count_size);
        const bool negative = ((p.count_type == "char" || p.count_type == "int8") && n >= 0x80) ||
                              ((p.count_type == "short" || p.count_type == "int16") && n >= 0x8000);
        if (negative) {
          throw field_error(name, 0, fmt::format("{} {}, {}", e.name, r + 1, p.name),
                            fmt::format("the list's count is negative ({})", p.count_type));
        }
        pos += count_size;
        if ((content.size() - pos) / size < n) throw ends(e, r);
        pos += n * size;
      }
    }
  }
  if (pos != content.size()) {
    throw mesh_error(name, fmt::format("{} bytes after the last record the header declares (element '{}'): the "
                                       "header's counts are smaller than the data",
                                       content.size() - pos, elements.empty() ? "" : elements.back().name));
  }
}

/// The PLY header checked against the format's grammar (Turk 1994, "The PLY polygon file format": the lines "ply",
/// "format ascii|binary_little_endian|binary_big_endian 1.0", "comment ...", "obj_info ...", "element NAME COUNT",
/// "property TYPE NAME", "property list TYPE TYPE NAME", "end_header") and against what CGAL's PLY reader assumes
/// without checking (its release build reads through a null pointer otherwise): a vertex element has scalar x, y, z
/// of a floating type; a face's index list counts in 8 or 16 bits (CGAL allocates the count a 32-bit one gives before
/// reading the indices) and holds int or uint indices; a halfedge element's source and target are uint. Before any
/// record is read, each element's count times the least bytes a record of it takes (binary: its scalars' sizes and
/// its lists' counts; ASCII: two bytes a value, a digit and a separator) is bounded by the bytes the file holds after
/// its header: a count the file cannot hold is refused at its element line (a 2 kB file declaring 3e7 vertices took
/// minutes and gigabytes in a reader that allocates the count first). Then MeshLimits, then the body
/// (check_ply_body). A file with vertices but no faces is a point cloud, said so.
void check_ply(std::string_view content, const std::string& name, double unit_m, std::vector<std::size_t>& face_lines) {
  constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
  const auto fail = [&](std::size_t line, const std::string& problem) {
    throw line_error(name, line, "PLY header: " + problem);
  };
  std::size_t pos = 0, line_no = 0;
  std::vector<PlyElement> elements;
  std::string format;
  const auto finish_element = [&]() {
    if (elements.empty()) return;
    const PlyElement& e = elements.back();
    if ((e.name == "face" || e.name == "faces") &&
        std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) {
          return p.name == "vertex_indices" || p.name == "vertex_index";
        })) {
      // found by fuzz_mesh_ply: CGAL's reader then fails, printing "can't find vertex indices" to stderr
      fail(e.line, fmt::format("the {} element has no property 'vertex_indices' (the list of a face's vertex "
                               "indices)",
                               e.name));
    }
    if (e.name == "vertex" || e.name == "vertices") {
      for (const char* axis : kAxes) {
        const auto it = std::find_if(e.properties.begin(), e.properties.end(),
                                     [&](const PlyProperty& p) { return p.name == axis; });
        if (it == e.properties.end()) {
          fail(e.line, fmt::format("the {} element has no property '{}' (the vertices' coordinates are the "
                                   "properties x, y and z, of type float or double)",
                                   e.name, axis));
        }
        if (!it->count_type.empty() || !is_ply_float(it->type)) {
          fail(e.line, fmt::format("the {} element has no property '{}' of type float or double (it is {})", e.name,
                                   axis, it->count_type.empty() ? it->type : "a list"));
        }
      }
    }
  };
  while (true) {
    ++line_no;
    const std::size_t eol = content.find('\n', pos);
    if (eol == std::string_view::npos || eol > kMaxHeaderBytes) {
      fail(line_no, fmt::format("no end_header line within the first {} bytes", kMaxHeaderBytes));
    }
    std::string_view line = content.substr(pos, eol - pos);
    pos = eol + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (std::any_of(line.begin(), line.end(), [](unsigned char c) { return c < 0x20 ? c != '\t' : c >= 0x7f; })) {
      fail(line_no, "a header line holds a byte that is not printable ASCII");
    }
    const std::vector<std::string_view> tokens = split_blank(line);
    const std::string_view key = tokens.empty() ? std::string_view{} : tokens[0];
    if (line_no == 1) {
      if (tokens.size() != 1 || key != "ply") fail(line_no, "the file does not begin with the line 'ply'");
      continue;
    }
    if (line_no == 2) {
      if (tokens.size() != 3 || key != "format" ||
          (tokens[1] != "ascii" && tokens[1] != "binary_little_endian" && tokens[1] != "binary_big_endian") ||
          tokens[2] != "1.0") {
        fail(line_no, "the second line is not 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      format = std::string(tokens[1]);
      continue;
    }
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header" && tokens.size() == 1) break;
    if (key == "element") {
      std::uint64_t count = 0;
      const bool digits = tokens.size() == 3 && !tokens[2].empty() &&
                          std::all_of(tokens[2].begin(), tokens[2].end(), [](unsigned char c) { return std::isdigit(c); });
      if (!digits || !is_identifier(tokens[1])) fail(line_no, "an element line is not 'element NAME COUNT'");
      const auto [end, ec] = std::from_chars(tokens[2].data(), tokens[2].data() + tokens[2].size(), count);
      if (ec != std::errc{}) {
        fail(line_no, fmt::format("element {} {}: the count is too large for any file", tokens[1],
                                  std::string(tokens[2].substr(0, 40))));
      }
      finish_element();
      const std::string element(tokens[1]);
      if (std::any_of(elements.begin(), elements.end(), [&](const PlyElement& e) { return e.name == element; })) {
        fail(line_no, fmt::format("a second element '{}'", element));
      }
      elements.push_back({element, count, line_no, {}});
      continue;
    }
    if (key == "property") {
      const bool scalar = tokens.size() == 3 && is_ply_type(tokens[1]) && is_identifier(tokens[2]);
      const bool list = tokens.size() == 5 && tokens[1] == "list" && is_ply_type(tokens[2]) &&
                        is_ply_type(tokens[3]) && is_identifier(tokens[4]);
      if (!(scalar || list) || elements.empty()) {
        fail(line_no, "a property line is not 'property TYPE NAME' or 'property list TYPE TYPE NAME' after an "
                      "element line");
      }
      PlyElement& e = elements.back();
      if (list && !is_ply_small_count(tokens[2])) {
        fail(line_no, fmt::format("the list '{}' is counted by a {}: topple reads lists counted by 8- or 16-bit "
                                  "types (uchar, ushort, ...)",
                                  tokens[4], tokens[2]));
      }
      const std::string prop(scalar ? tokens[2] : tokens[4]);
      if (std::any_of(e.properties.begin(), e.properties.end(), [&](const PlyProperty& p) { return p.name == prop; })) {
        // CGAL takes the first of a name, topple's checks would see the last
        fail(line_no, fmt::format("the {} element has two properties named '{}'", e.name, prop));
      }
      e.properties.push_back({prop, std::string(scalar ? tokens[1] : tokens[3]),
                              scalar ? std::string() : std::string(tokens[2])});
      if ((e.name == "face" || e.name == "faces") && (prop == "vertex_indices" || prop == "vertex_index") &&
          !(list && is_ply_index(tokens[3]))) {
        fail(line_no, fmt::format("the face property '{}' is not a list of int or uint", prop));
      }
      if (e.name == "halfedge" && (prop == "source" || prop == "target") &&
          !(scalar && (tokens[1] == "uint" || tokens[1] == "uint32"))) {
        fail(line_no, fmt::format("the halfedge property '{}' is not a uint", prop));
      }
      continue;
    }
    fail(line_no, fmt::format("'{}' is not a PLY header line", std::string(line.substr(0, 60))));
  }
  finish_element();
  // Counts against the bytes after the header, saturating at 2^64 - 1 (a count of up to 1.8e19 times a record of up
  // to 64 kB).
  const bool ascii = format == "ascii";
  const std::uint64_t body = content.size() - pos;
  constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t total = 0;
  for (const PlyElement& e : elements) {
    std::uint64_t least = 0;  // bytes of one record at the least
    for (const PlyProperty& p : e.properties) {
      least += ascii ? 2 : ply_type_bytes(p.count_type.empty() ? p.type : p.count_type);
    }
    const std::uint64_t need = least != 0 && e.count > kSaturated / least ? kSaturated : e.count * least;
    total = need > kSaturated - total ? kSaturated : total + need;
    if (need > 0 && (ascii ? need - 1 : need) > body) {
      fail(e.line, fmt::format("element {} {}: the count is too large for the file: {} records of {} values need at "
                               "least {} bytes ({}), but the file holds {} bytes after its header",
                               e.name, e.count, e.count, e.properties.size(), need,
                               ascii ? "as ASCII, a digit and a separator a value" : "binary, by the property types",
                               body));
    }
    if (total > body + (ascii ? 1 : 0)) {
      fail(e.line, fmt::format("element {} {}: the counts so far need at least {} bytes, but the file holds {} bytes "
                               "after its header: a count is too large for the file",
                               e.name, e.count, total, body));
    }
  }
  std::uint64_t vertex_count = 0, face_count = 0;
  bool has_face_element = false;
  for (const PlyElement& e : elements) {
    const bool face = e.name == "face" || e.name == "faces";
    const std::uint64_t limit = face ? MeshLimits::max_triangles : 3 * std::uint64_t{MeshLimits::max_triangles};
    if (e.count > limit) {
      fail(e.line, fmt::format("{} {} elements: more than the {} topple reads (decimate the scan)", e.count, e.name,
                               limit));
    }
    if (face) {
      has_face_element = true;
      face_count += e.count;
    }
    if (e.name == "vertex" || e.name == "vertices") vertex_count += e.count;
  }
  if (vertex_count == 0 && face_count == 0) fail(line_no, "no vertex and no face elements");
  if (!has_face_element || face_count == 0) {
    throw line_error(name, line_no, fmt::format("{} vertices and no faces: {}", vertex_count, kPointCloud));
  }
  check_ply_body(content, pos, line_no, ascii, format == "binary_big_endian", elements, name, unit_m, face_lines);
}

// --- OBJ, STL, OFF: what CGAL's readers would read wrongly or without saying where ---------------------------------



/// The statements CGAL::IO::read_OBJ (CGAL 5.5, OBJ.h) passes over as valid; any other but v, vt, vn, f, l and a
/// comment makes it fail without saying where, so the line is named here first.
bool is_obj_statement(std::string_view key) {
  for (std::string_view known :
       {"v", "vt", "vn", "f", "vp", "bevel", "lod", "ctech", "c_interp", "usemap", "usemtl", "stech", "d_interp",
        "mtllib", "shadow_obj", "trace_obj", "o", "g", "s", "p", "cstype", "deg", "step", "bmat", "con", "curv",
        "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "surf_1", "q0_1", "q1_1", "curv2d_1", "surf_2",
        "q0_2", "q1_2", "curv2d_2", "bsp", "bzp", "cdc", "cdp", "res"}) {
    if (key == known) return true;
  }
  return false;
}

/// An OBJ face token: "v", "v/vt", "v//vn" or "v/vt/vn", each a whole integer (negative: relative), the token entire
/// (CGAL reads the vertex number with a stream, which takes "2.5" as 2 and "3x" as 3).
bool is_obj_face_token(std::string_view token) {
  int parts = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = token.find('/', start);
    const std::string_view part = token.substr(start, slash == std::string_view::npos ? std::string_view::npos
                                                                                     : slash - start);
    ++parts;
    if (parts > 3) return false;
    const bool optional_empty = parts > 1 && part.empty();  // "v//vn", "v/vt/"
    if (!optional_empty) {
      long long v = 0;
      const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
      if (ec != std::errc{} || end != part.data() + part.size() || (parts == 1 && v == 0)) return false;
    }
    if (slash == std::string_view::npos) return true;
    start = slash + 1;
  }
}

/// OBJ statements checked before CGAL reads the file, with their lines: a v line is x y z, x y z w with w = 1 (the
/// weight is for rational curves and surfaces, Wavefront's OBJ specification; CGAL ignores it, so any other w would
/// be a silent guess), or x y z r g b (the vertex colours MeshLab and Open3D write); each a whole token that is a
/// finite number within kMaxFileCoordinateM, quoted as typed when not (a stream reads the prefix: "6D-1" as 6). A
/// face token is a whole vertex reference. Vertices are numbered by the file's v lines, faces by its f lines (their
/// line numbers kept for messages); vertices (v) but no faces (f) is a point cloud; a polyline (l), which CGAL's
/// reader stops at without saying where, is refused with its line; an unknown statement is refused with its line.
/// mtllib is passed over and no material file is ever opened (CGAL 5.5's read_OBJ does not open it either: the
/// geometry needs none; a test proves it with a FIFO).
void check_obj(std::string_view content, const std::string& name, double unit_m, std::vector<std::size_t>& face_lines) {
  std::size_t pos = 0, line_no = 0, vertices = 0, first_l = 0;
  while (pos < content.size()) {
    ++line_no;
    const std::vector<std::string_view> tokens = split_blank(next_line(content, pos));
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      ++vertices;
      const auto vertex = [&]() { return fmt::format("vertex {}", vertices); };
      const std::size_t n = tokens.size() - 1;
      if (n != 3 && n != 4 && n != 6) {
        throw field_error(name, line_no, vertex(),
                          fmt::format("the v line holds {} value{} where it needs x y z (or x y z w with w = 1, or "
                                      "x y z r g b)",
                                      n, n == 1 ? "" : "s"));
      }
      for (std::size_t k = 0; k < n; ++k) {
        double value = 0.0;
        const auto field = [&]() {
          return k < 3 ? vertex() + ", " + kAxes[k] : n == 4 ? vertex() + ", w" : vertex() + ", " + "rgb"[k - 3];
        };
        const std::string problem = k < 3 ? coordinate_problem(tokens[1 + k], unit_m, value)
                                           : parse_double(tokens[1 + k], value) && std::isfinite(value)
                                                 ? std::string()
                                                 : quoted(tokens[1 + k]) + " is not a finite number";
        if (!problem.empty()) throw field_error(name, line_no, field(), problem);
        if (n == 4 && k == 3 && value != 1.0) {
          throw field_error(name, line_no, field(),
                            fmt::format("a weight w = {}: OBJ's fourth vertex number is the weight of rational "
                                        "curves and surfaces, which topple does not read; a polygon vertex is x y z "
                                        "(w = 1 or none)",
                                        quoted(tokens[4])));
        }
      }
    } else if (tokens[0] == "f") {
      face_lines.push_back(line_no);
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        if (!is_obj_face_token(tokens[k])) {
          throw field_error(name, line_no, fmt::format("face {}, vertex {}", face_lines.size(), k),
                            fmt::format("{} is not a vertex number (v, v/vt, v//vn or v/vt/vn, whole numbers, not "
                                        "0)",
                                        quoted(tokens[k])));
        }
      }
    } else if (tokens[0] == "l") {
      if (first_l == 0) first_l = line_no;
    } else if (tokens[0].front() != '#' && !is_obj_statement(tokens[0])) {
      throw line_error(name, line_no, fmt::format("{} is not an OBJ statement (v, vt, vn, f, g, o, s, usemtl, "
                                                  "mtllib, ...)",
                                                  quoted(tokens[0])));
    }
  }
  if (face_lines.empty()) {
    if (vertices == 0) throw mesh_error(name, "no vertices (v) and no faces (f): not a mesh");
    throw mesh_error(name, fmt::format("{} vertices and no faces (f lines): {}", vertices, kPointCloud));
  }
  if (first_l != 0) {
    throw line_error(name, first_l, "a polyline (l statement): topple reads a solid bounded by faces (f) only; "
                                    "remove the lines");
  }
}

/// An ASCII STL checked line by line against its grammar (3D Systems' StereoLithography Interface Specification,
/// 1989: "solid NAME", then facets of "facet normal ni nj nk", "outer loop", three "vertex x y z", "endloop",
/// "endfacet", then "endsolid NAME"), with the line of each facet kept for messages: a facet's fourth vertex (CGAL's
/// reader drops it without a word), a number that is not one (quoted as typed), a file cut short or a second solid
/// are refused at their line. Returns an empty string when the text is an ASCII STL, else what is wrong (the caller
/// may then say what the file would be as a binary STL).
std::string check_stl_ascii(std::string_view content, const std::string& name, double unit_m,
                            std::vector<std::size_t>& face_lines, std::size_t& bad_line) {
  enum class Want { solid, facet, loop, vertex, endloop, endfacet, end };
  Want want = Want::solid;
  std::size_t pos = 0, line_no = 0, corners = 0, facet_line = 0;
  while (pos < content.size()) {
    ++line_no;
    bad_line = line_no;
    const std::vector<std::string_view> t = split_blank(next_line(content, pos));
    if (t.empty()) continue;
    const auto facet_name = [&]() { return fmt::format("facet {} (line {})", face_lines.size(), facet_line); };
    switch (want) {
      case Want::solid:
        if (t[0] != "solid") return "the first line is not 'solid NAME'";
        want = Want::facet;
        continue;
      case Want::facet:
        if (t[0] == "endsolid") {
          want = Want::end;
          continue;
        }
        if (t[0] != "facet" || t.size() != 5 || t[1] != "normal") {
          return fmt::format("{} where 'facet normal ni nj nk' or 'endsolid' belongs", quoted(t[0]));
        }
        for (int k = 0; k < 3; ++k) {
          double v = 0.0;
          if (!parse_double(t[2 + k], v)) {
            throw field_error(name, line_no, fmt::format("facet {}, normal", face_lines.size() + 1),
                              quoted(t[2 + k]) + " is not a number");
          }
        }
        face_lines.push_back(line_no);
        facet_line = line_no;
        want = Want::loop;
        continue;
      case Want::loop:
        if (t.size() != 2 || t[0] != "outer" || t[1] != "loop") return facet_name() + ": 'outer loop' belongs here";
        corners = 0;
        want = Want::vertex;
        continue;
      case Want::vertex:
      case Want::endloop:
        if (t[0] == "vertex") {
          if (want == Want::endloop) {
            throw field_error(name, line_no, facet_name() + ", vertex 4",
                              "a fourth vertex: an STL facet is a triangle of three (split the polygon into "
                              "triangles in the program that wrote the file)");
          }
          ++corners;
          const auto field = [&]() { return fmt::format("facet {}, vertex {}", face_lines.size(), corners); };
          if (t.size() != 4) {
            throw field_error(name, line_no, field(),
                              fmt::format("the vertex line holds {} values where it needs x y z", t.size() - 1));
          }
          for (int k = 0; k < 3; ++k) {
            double v = 0.0;
            const std::string problem = coordinate_problem(t[1 + k], unit_m, v);
            if (!problem.empty()) throw field_error(name, line_no, field() + ", " + kAxes[k], problem);
          }
          if (corners == 3) want = Want::endloop;
          continue;
        }
        if (want == Want::vertex) {
          return fmt::format("{} has {} vertices: a facet is a triangle of three", facet_name(), corners);
        }
        if (t.size() != 1 || t[0] != "endloop") return facet_name() + ": 'endloop' belongs here";
        want = Want::endfacet;
        continue;
      case Want::endfacet:
        if (t.size() != 1 || t[0] != "endfacet") return facet_name() + ": 'endfacet' belongs here";
        want = Want::facet;
        continue;
      case Want::end:
        return fmt::format("{} after endsolid: topple reads one solid a file", quoted(t[0]));
    }
  }
  ++line_no;
  bad_line = line_no;
  if (want != Want::end) return "the file ends before its 'endsolid' line (cut short?)";
  return {};
}

/// STL. A file that begins with "solid" and is an ASCII STL by its grammar is read as ASCII (check_stl_ascii); any
/// other file is binary: 80 bytes of header, a facet count n (uint32, little-endian), and n records of 50 bytes, the
/// file's size exactly 84 + 50 n (a larger or smaller file is refused with both sizes: the count or the file is
/// wrong, and reading the count's facets of a longer file would drop the rest without a word; a binary STL whose
/// header begins with "solid", as some CAD programs write, is told apart by its size); its coordinates must be finite
/// (CGAL welds equal points in a std::map, whose order a NaN breaks).
void check_stl(std::string_view content, const std::string& name, double unit_m, std::vector<std::size_t>& face_lines) {
  static_assert(std::endian::native == std::endian::little, "binary STL is little-endian; topple reads it by memcpy");
  std::size_t i = 0;
  while (i < content.size() && std::isspace(static_cast<unsigned char>(content[i]))) ++i;
  const bool solid = content.substr(i, 5) == "solid" &&
                     (i + 5 == content.size() || std::isspace(static_cast<unsigned char>(content[i + 5])));
  std::uint32_t n = 0;
  if (content.size() >= 84) std::memcpy(&n, content.data() + 80, 4);
  const std::uint64_t binary_bytes = 84 + 50 * std::uint64_t{n};
  const bool binary_size = content.size() >= 84 && content.size() == binary_bytes;
  if (solid && !binary_size) {
    std::size_t bad_line = 0;
    const std::string problem = check_stl_ascii(content, name, unit_m, face_lines, bad_line);
    if (problem.empty()) return;
    const bool text = std::none_of(content.begin(), content.end(), [](char c) { return c == '\0'; });
    if (text || content.size() < 84) throw line_error(name, bad_line, "ASCII STL: " + problem);
    // NUL bytes after "solid": a binary STL whose header begins with "solid", of the wrong size
  }
  if (!binary_size) {
    if (content.size() < 84) {
      throw mesh_error(name, fmt::format("{} bytes: neither an ASCII STL (beginning with 'solid') nor a binary one "
                                         "(80 bytes of header and a facet count)",
                                         content.size()));
    }
    throw mesh_error(name, fmt::format("cannot be read as stl: as a binary STL of {} facets (the count at bytes 80-83) "
                                       "it would be 84 + 50 x {} = {} bytes, but the file is {} bytes ({}, or not an "
                                       "STL file)",
                                       n, n, binary_bytes, content.size(),
                                       content.size() < binary_bytes ? "truncated" : "data beyond the count"));
  }
  if (n > MeshLimits::max_triangles) {
    throw mesh_error(name, fmt::format("{} facets: more than the {} topple reads (decimate the scan)", n,
                                       MeshLimits::max_triangles));
  }
  for (std::uint64_t f = 0; f < n; ++f) {
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, content.data() + 84 + 50 * f + 12 + 12 * c, sizeof xyz);
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(xyz[k]) || !(std::abs(double{xyz[k]}) * unit_m <= kMaxFileCoordinateM)) {
          throw field_error(name, 0, fmt::format("facet {}, vertex {}, {}", f + 1, c + 1, kAxes[k]),
                            fmt::format("{} is not a finite number within {:g} m of the file's origin (at --unit {:g} "
                                        "m)",
                                        xyz[k], kMaxFileCoordinateM, unit_m));
        }
      }
    }
  }
}

/// OFF (ASCII, first keyword "OFF"): checked line by line before CGAL reads it, because CGAL's OFF scanner converts
/// each face's vertex count and indices from double to size_t unchecked (undefined for a negative or huge number) and
/// allocates the counts it is given. The grammar (Princeton Shape Benchmark; CGAL's File_scanner_OFF): '#' starts a
/// comment, blank lines are skipped; "OFF" (the counts may follow on its line); "nv nf ne"; nv lines of x y z; nf
/// lines of "n i_1 ... i_n" (indices from 0), optionally followed by a colour. A file with vertices and no faces is a
/// point cloud, said so.
void check_off(std::string_view content, const std::string& name, double unit_m, std::vector<std::size_t>& face_lines) {
  std::size_t pos = 0, line_no = 0;
  std::vector<std::string_view> tokens;
  const auto next = [&]() -> bool {  // the next line holding something, comments cut
    while (pos < content.size()) {
      ++line_no;
      std::string_view line = next_line(content, pos);
      const std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      tokens = split_blank(line);
      if (!tokens.empty()) return true;
    }
    return false;
  };
  if (!next() || tokens[0] != "OFF") {
    throw line_error(name, line_no, "the file does not begin with the keyword OFF (topple reads ASCII OFF; not "
                                    "COFF, NOFF, 4OFF or OFF BINARY)");
  }
  std::vector<std::string_view> counts(tokens.begin() + 1, tokens.end());
  if (counts.empty() && next()) counts = tokens;
  std::size_t nv = 0, nf = 0, ne = 0;
  if (counts.size() != 3 || !parse_index(counts[0], nv) || !parse_index(counts[1], nf) ||
      !parse_index(counts[2], ne)) {
    throw line_error(name, line_no, "the counts line is not 'vertices faces edges' (three whole numbers)");
  }
  if (nv > 3 * MeshLimits::max_triangles || nf > MeshLimits::max_triangles || ne > 3 * MeshLimits::max_triangles) {
    throw line_error(name, line_no, fmt::format("{} vertices and {} faces: more than the {} faces topple reads", nv,
                                                nf, MeshLimits::max_triangles));
  }
  if (nf == 0) throw line_error(name, line_no, fmt::format("{} vertices and no faces: {}", nv, kPointCloud));
  for (std::size_t v = 0; v < nv; ++v) {
    if (!next()) throw line_error(name, line_no, fmt::format("the file ends after {} of its {} vertices", v, nv));
    double x = 0.0;
    const auto vertex = [&]() { return fmt::format("vertex {} (index {})", v + 1, v); };
    if (tokens.size() < 3 || tokens.size() > 7) {  // x y z and an optional colour of 1, 3 or 4 numbers
      throw field_error(name, line_no, vertex(),
                        fmt::format("the line holds {} values where it needs x y z (and an optional colour of 1, 3 "
                                    "or 4 numbers)",
                                    tokens.size()));
    }
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      const std::string problem = k < 3 ? coordinate_problem(tokens[k], unit_m, x)
                                  : parse_double(tokens[k], x) && std::isfinite(x)
                                      ? std::string()
                                      : quoted(tokens[k]) + " is not a finite number";
      if (!problem.empty()) {
        throw field_error(name, line_no, vertex() + ", " + (k < 3 ? std::string(kAxes[k]) : "colour"), problem);
      }
    }
  }
  for (std::size_t f = 0; f < nf; ++f) {
    if (!next()) throw line_error(name, line_no, fmt::format("the file ends after {} of its {} faces", f, nf));
    face_lines.push_back(line_no);
    std::size_t n = 0, index = 0;
    bool ok = parse_index(tokens[0], n) && n >= 3 && n <= kMaxPolygonVertices && tokens.size() >= n + 1 &&
              tokens.size() <= n + 5;
    for (std::size_t k = 1; ok && k <= n; ++k) ok = parse_index(tokens[k], index) && index < nv;
    double colour = 0.0;
    for (std::size_t k = n + 1; ok && k < tokens.size(); ++k) ok = parse_double(tokens[k], colour) && std::isfinite(colour);
    if (!ok) {
      throw line_error(name, line_no, fmt::format("face {} is not 'n i_1 ... i_n' with 3 <= n <= {} and every index "
                                                  "in [0, {}) (the vertices, counted from 0)",
                                                  f + 1, kMaxPolygonVertices, nv));
    }
  }
}

Soup read_soup(std::string_view content, const std::string& format, const std::string& name, double unit_m) {
  ViewBuffer buffer(content);
  std::istream in(&buffer);
  Soup soup;
  bool ok = false;
  try {
    if (format == "obj") {
      check_obj(content, name, unit_m, soup.face_lines);
      ok = CGAL::IO::read_OBJ(in, soup.points, soup.polygons);
    } else if (format == "off") {
      check_off(content, name, unit_m, soup.face_lines);
      soup.base = 0;
      ok = CGAL::IO::read_OFF(in, soup.points, soup.polygons);
    } else if (format == "stl") {
      check_stl(content, name, unit_m, soup.face_lines);
      soup.numbered = false;
      soup.face_word = "facet";
      ok = CGAL::IO::read_STL(in, soup.points, soup.polygons);
      if (ok && soup.polygons.empty()) throw mesh_error(name, "an STL of no facets: " + kPointCloud);
    } else {
      check_ply(content, name, unit_m, soup.face_lines);
      soup.base = 0;
      ok = CGAL::IO::read_PLY(in, soup.points, soup.polygons);
    }
  } catch (const TooManyVertices&) {
    throw mesh_error(name, fmt::format("a face of more than {} vertices: triangulate the mesh in the program that "
                                       "wrote it",
                                       kMaxPolygonVertices));
  } catch (const std::bad_alloc&) {
    throw mesh_error(name, "the counts the file gives do not fit in memory");
  } catch (const std::length_error&) {
    throw mesh_error(name, "the counts the file gives do not fit in memory");
  }
  if (!ok) {
    throw mesh_error(name, fmt::format("cannot be read as {} (CGAL::IO::read_{}): a statement it does not know, a "
                                       "number it cannot read or a file cut short",
                                       format, format == "obj" ? "OBJ" : format == "off" ? "OFF" : format == "stl"
                                                                                                   ? "STL"
                                                                                                   : "PLY"));
  }
  if (soup.polygons.empty()) {
    if (soup.points.empty()) throw mesh_error(name, "no vertices and no faces: not a mesh");
    throw mesh_error(name, fmt::format("{} vertices and no faces: {}", soup.points.size(), kPointCloud));
  }
  if (soup.polygons.size() > MeshLimits::max_triangles) {
    throw mesh_error(name, fmt::format("{} faces: more than the {} topple reads (decimate the scan)",
                                       soup.polygons.size(), MeshLimits::max_triangles));
  }
  return soup;
}

// --- From the soup to a checked TriangleMesh, numbered as the file -----------------------------------------------

Vec3 sub3(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross3(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// Splits a soup into triangles and checks, in the file's numbering, what check_mesh would otherwise report in the
/// welded and triangulated numbering: faces of fewer than three vertices, indices out of range, repeated and
/// degenerate faces, duplicate faces, edges that are open, run twice the same way, or shared by more than two faces.
class Builder {
 public:
  Builder(Soup& soup, const std::string& name, double unit_m) : soup_(soup), name_(name), unit_m_(unit_m) {}

  TriangleMesh build() {
    check_faces();
    place();
    weld();
    triangulate();
    check_degenerate();
    check_duplicates();
    check_edges();
    return std::move(mesh_);
  }

 private:
  Soup& soup_;
  const std::string& name_;
  double unit_m_;
  TriangleMesh mesh_;
  std::vector<char> used_;                                // file vertex -> used by a face
  std::vector<std::uint32_t> rep_;                        // file vertex -> the first file vertex at the same point
  std::vector<std::uint32_t> tri_face_;                   // triangle -> file face (0-based)
  std::vector<std::array<std::uint32_t, 3>> tri_file_;    // triangle -> the file's vertex indices, before welding
  double size_m_ = 0.0;

  [[nodiscard]] std::string file_point(std::size_t v) const {
    const Point& p = soup_.points[v];
    return fmt::format("({}, {}, {})", p.x(), p.y(), p.z());
  }
  /// "vertex 7880" (OBJ: the number the f lines write), "vertex 8 (index 7)" (OFF, PLY: the n-th vertex and the
  /// 0-based index the faces write), "the corner at (x, y, z)" (STL: its facets repeat coordinates, no numbers).
  [[nodiscard]] std::string vertex_name(std::size_t v) const {
    if (!soup_.numbered) return "the corner at " + file_point(v);
    if (soup_.base == 1) return fmt::format("vertex {} {}", v + 1, file_point(v));
    return fmt::format("vertex {} (index {}) {}", v + 1, v, file_point(v));
  }
  /// "face 7 at line 16 (f 9 2 1)" (OBJ: the n-th f line, its vertex numbers as written), "face 3 at line 14
  /// (indices 0 1 3)" (OFF, PLY: the n-th face, its 0-based indices), "facet 5 at line 30" (STL); no line in a binary
  /// file.
  [[nodiscard]] std::string face_short(std::size_t f) const {
    return f < soup_.face_lines.size() && soup_.face_lines[f] != 0
               ? fmt::format("{} {} at line {}", soup_.face_word, f + 1, soup_.face_lines[f])
               : fmt::format("{} {}", soup_.face_word, f + 1);
  }
  [[nodiscard]] std::string face_name(std::size_t f) const {
    const auto& poly = soup_.polygons[f];
    const std::string at = f < soup_.face_lines.size() && soup_.face_lines[f] != 0
                               ? fmt::format(" at line {}", soup_.face_lines[f])
                               : std::string();
    if (!soup_.numbered) return fmt::format("facet {}{}", f + 1, at);
    std::string ids;
    for (std::size_t k = 0; k < poly.size() && k < 8; ++k) ids += fmt::format("{}{}", k ? " " : "", poly[k] + soup_.base);
    if (poly.size() > 8) ids += " ...";
    return soup_.base == 1 ? fmt::format("face {}{} (f {})", f + 1, at, ids)
                           : fmt::format("face {}{} (indices {})", f + 1, at, ids);
  }

  void check_faces() {
    const std::size_t nv = soup_.points.size();
    if (nv > std::numeric_limits<std::uint32_t>::max() - 1) throw mesh_error(name_, "too many vertices");
    std::size_t triangles = 0;
    for (std::size_t f = 0; f < soup_.polygons.size(); ++f) {
      const auto& poly = soup_.polygons[f];
      if (poly.size() < 3) {
        throw mesh_error(name_, fmt::format("{} has {} vertices: points or lines, not a face of a solid",
                                            face_short(f), poly.size()));
      }
      for (std::size_t v : poly) {
        if (v >= nv) {
          // OBJ's negative (relative) numbers that reach before the first vertex wrap around in CGAL's reader
          const std::string number = v < (std::size_t{1} << 40) ? fmt::format("vertex {}", v + soup_.base)
                                                                 : std::string("a vertex before the first");
          throw mesh_error(name_, fmt::format("{} refers to {}, but the file has {} vertices", face_short(f), number,
                                              nv));
        }
      }
      triangles += poly.size() - 2;
      if (triangles > MeshLimits::max_triangles) {
        throw mesh_error(name_, fmt::format("more than the {} triangles topple reads (decimate the scan)",
                                            MeshLimits::max_triangles));
      }
    }
  }

  /// Recentring before any arithmetic: the origin is the centre of the bounding box of the vertices the faces use,
  /// (lo + hi) / 2 per axis, in the file's units. Each local coordinate x - o is then exact (Sterbenz's lemma: o and x
  /// within a factor 2 of each other) whenever the mesh lies at least half its size from the file's origin, i.e. for
  /// every georeferenced scan; near the origin it rounds to 1e-16 of the mesh's size. Then scaled by --unit (one
  /// rounding, 1e-16 relative). The bounding box, not the vertices' centroid: it depends neither on how densely a
  /// part of the surface is sampled nor on the order of a sum, and it is the reference mass_properties uses.
  void place() {
    const std::size_t nv = soup_.points.size();
    used_.assign(nv, 0);
    std::vector<char>& used = used_;
    for (const auto& poly : soup_.polygons) {
      for (std::size_t v : poly) used[v] = 1;
    }
    Vec3 lo{}, hi{};
    bool first = true;
    std::size_t first_used = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      const Point& p = soup_.points[v];
      const Vec3 x{p.x(), p.y(), p.z()};
      for (int k = 0; k < 3; ++k) {  // every vertex, used or not: a bad number is bad input wherever it is
        if (!std::isfinite(x[k]) || !(std::abs(x[k]) * unit_m_ <= kMaxFileCoordinateM)) {
          throw mesh_error(name_, fmt::format("{} has a coordinate that is not a finite number within {:g} m of the "
                                              "file's origin: check --unit",
                                              vertex_name(v), kMaxFileCoordinateM));
        }
      }
      if (used[v] == 0) continue;
      if (first) {
        lo = hi = x;
        first_used = v;
        first = false;
      }
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], x[k]);
        hi[k] = std::max(hi[k], x[k]);
      }
    }
    const Vec3 origin{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    size_m_ = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) * unit_m_;
    if (!(size_m_ >= MeshLimits::min_extent_m && size_m_ <= MeshLimits::max_extent_m)) {
      throw mesh_error(name_, fmt::format("the mesh is {:.6g} m across (largest side of its bounding box), outside "
                                          "[{}, {}] m: check --unit (coordinates are read in metres unless told)",
                                          size_m_, MeshLimits::min_extent_m, MeshLimits::max_extent_m));
    }
    mesh_.origin_m = {origin[0] * unit_m_, origin[1] * unit_m_, origin[2] * unit_m_};
    mesh_.vertices_m.resize(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      // A vertex no face uses takes no part: it is given the place of a used one, so that nothing that looks at
      // every vertex (a bounding box, the lowest points) sees it; the numbering of the others is kept.
      const Point& p = soup_.points[used[v] != 0 ? v : first_used];
      mesh_.vertices_m[v] = {(p.x() - origin[0]) * unit_m_, (p.y() - origin[1]) * unit_m_,
                             (p.z() - origin[2]) * unit_m_};
    }
  }

  /// Vertices at bitwise-equal file coordinates (-0 and +0 one value) become one, the first in the file: an STL
  /// repeats every corner (CGAL welds those already), and OBJ or PLY writers split vertices at texture seams. Nothing
  /// is snapped within a tolerance. Sorting, not a tree: 4 bytes a vertex. Only the vertices faces use (place() has
  /// checked that they are finite: a NaN would break the sort's ordering); an unused one stays itself.
  void weld() {
    const std::size_t nv = soup_.points.size();
    const auto key = [this](std::uint32_t v) {
      const Point& p = soup_.points[v];
      return std::array<double, 3>{p.x() + 0.0, p.y() + 0.0, p.z() + 0.0};
    };
    std::vector<std::uint32_t> order;
    rep_.resize(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      rep_[v] = static_cast<std::uint32_t>(v);
      if (used_[v] != 0) order.push_back(static_cast<std::uint32_t>(v));
    }
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const auto ka = key(a), kb = key(b);
      return ka != kb ? ka < kb : a < b;
    });
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i + 1;  // order[i]: the first in the file of its run of equal points
      while (j < order.size() && key(order[j]) == key(order[i])) rep_[order[j++]] = order[i];
      i = j;
    }
  }

  /// Polygons split into the fan (0, k, k + 1), right for a convex polygon (an OBJ box's quads); one that is not
  /// convex about its Newell normal is refused (triangulate it in the program that wrote it).
  void triangulate() {
    for (std::size_t f = 0; f < soup_.polygons.size(); ++f) {
      const auto& poly = soup_.polygons[f];
      const std::size_t n = poly.size();
      if (n > 3 && !convex(poly)) {
        throw mesh_error(name_, fmt::format("{} has {} vertices and is not a convex polygon: triangulate it in the "
                                            "program that wrote the file",
                                            face_name(f), n));
      }
      for (std::size_t k = 1; k + 1 < n; ++k) {
        const std::array<std::uint32_t, 3> file{static_cast<std::uint32_t>(poly[0]), static_cast<std::uint32_t>(poly[k]),
                                                static_cast<std::uint32_t>(poly[k + 1])};
        mesh_.triangles.push_back({rep_[file[0]], rep_[file[1]], rep_[file[2]]});
        tri_file_.push_back(file);
        tri_face_.push_back(static_cast<std::uint32_t>(f));
      }
    }
  }

  [[nodiscard]] bool convex(const BoundedPolygon& poly) const {
    const std::size_t n = poly.size();
    const auto at = [&](std::size_t k) -> const Vec3& { return mesh_.vertices_m[poly[k % n]]; };
    Vec3 normal{};  // Newell's method: exact for a planar polygon
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 &a = at(k), &b = at(k + 1);
      normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 t = cross3(sub3(at(k + 1), at(k)), sub3(at(k + 2), at(k + 1)));
      if (t[0] * normal[0] + t[1] * normal[1] + t[2] * normal[2] < 0.0) return false;
    }
    return true;
  }

  /// As check_mesh: a repeated vertex (after welding) or an area below degenerate_area_fraction L^2.
  void check_degenerate() {
    const double min_area = MeshLimits::degenerate_area_fraction * size_m_ * size_m_;
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      const auto& tri = mesh_.triangles[t];
      const auto& file = tri_file_[t];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
        if (a == b) {
          throw mesh_error(name_, fmt::format("{} is degenerate: {} and {} are the same point (a repeated vertex)",
                                              face_name(tri_face_[t]), vertex_name(file[k]),
                                              vertex_name(file[(k + 1) % 3])));
        }
      }
      const Vec3& p = mesh_.vertices_m[tri[0]];
      const Vec3 c = cross3(sub3(mesh_.vertices_m[tri[1]], p), sub3(mesh_.vertices_m[tri[2]], p));
      const double area = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / 2;
      if (!(area > min_area)) {
        throw mesh_error(name_, fmt::format("{} is degenerate: the triangle of {}, {} and {} has area {:.3g} m^2, "
                                            "below {:.3g} m^2 = {:g} x the square of the mesh's size (a sliver)",
                                            face_name(tri_face_[t]), vertex_name(file[0]), vertex_name(file[1]),
                                            vertex_name(file[2]), area, min_area,
                                            MeshLimits::degenerate_area_fraction));
      }
    }
  }

  void check_duplicates() {
    std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> sorted(mesh_.triangles.size());
    for (std::size_t t = 0; t < sorted.size(); ++t) {
      auto s = mesh_.triangles[t];
      std::sort(s.begin(), s.end());
      sorted[t] = {s, static_cast<std::uint32_t>(t)};
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i) {
      if (sorted[i].first == sorted[i - 1].first) {
        throw mesh_error(name_, fmt::format("{} and {} have the same three vertices: a duplicate face",
                                            face_name(tri_face_[sorted[i - 1].second]),
                                            face_name(tri_face_[sorted[i].second])));
      }
    }
  }

  /// Every edge run once each way: closed, edge-manifold, consistently oriented (as check_mesh, in file numbers).
  void check_edges() {
    struct Directed {
      std::uint64_t key;
      std::uint32_t triangle, corner;
      bool operator<(const Directed& o) const { return key != o.key ? key < o.key : triangle < o.triangle; }
    };
    std::vector<Directed> edges;
    edges.reserve(mesh_.triangles.size() * 3);
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      for (std::uint32_t k = 0; k < 3; ++k) {
        const auto& tri = mesh_.triangles[t];
        edges.push_back({(std::uint64_t{tri[k]} << 32) | tri[(k + 1) % 3], static_cast<std::uint32_t>(t), k});
      }
    }
    std::sort(edges.begin(), edges.end());
    const auto from_to = [&](const Directed& e) {
      const auto& file = tri_file_[e.triangle];
      return std::pair{vertex_name(file[e.corner]), vertex_name(file[(e.corner + 1) % 3])};
    };
    for (std::size_t i = 1; i < edges.size(); ++i) {
      if (edges[i].key == edges[i - 1].key) {
        const auto [a, b] = from_to(edges[i]);
        throw mesh_error(name_, fmt::format("{} and {} both run along the edge from {} to {} in the same direction: "
                                            "the faces are not consistently oriented, or more than two faces meet at "
                                            "that edge (not a manifold solid)",
                                            face_name(tri_face_[edges[i - 1].triangle]),
                                            face_name(tri_face_[edges[i].triangle]), a, b));
      }
    }
    for (const Directed& e : edges) {
      const std::uint64_t reverse = (e.key << 32) | (e.key >> 32);
      const auto it = std::lower_bound(edges.begin(), edges.end(), Directed{reverse, 0, 0});
      if (it == edges.end() || it->key != reverse) {
        const auto [a, b] = from_to(e);
        throw mesh_error(name_, fmt::format("the mesh is open (not closed): the edge from {} to {} of {} belongs to no other face "
                                            "(a hole in the surface; a solid needs every edge shared by two faces). "
                                            "Close the holes (MeshLab: Filters > Remeshing, Simplification and "
                                            "Reconstruction > Close Holes; or rebuild a watertight surface by Poisson "
                                            "reconstruction) and read it again",
                                            a, b, face_name(tri_face_[e.triangle])));
      }
    }
  }
};

}  // namespace

double mesh_unit_m(const std::string& unit, const std::string& field) {
  // The text is read as a whole and only it is quoted: a unit name ("mm": one file unit is 1 mm), a length ("2cm":
  // one file unit is 2 cm; parse_length_m) or a bare number of metres ("0.001"). Prefixing "1" to any text made
  // "2cm" 12 cm and quoted "10.001" for "0.001".
  const auto refuse = [&] {
    throw parameter_error(field, fmt::format("'{}' is not a unit of length: give a unit (m, cm, mm, in, ft, km), a "
                                             "positive length per file unit (2cm) or a positive number of metres "
                                             "per file unit (0.001)",
                                             unit));
  };
  const std::size_t first = unit.find_first_not_of(" \t");
  if (first == std::string::npos) refuse();
  double factor = 0.0;
  if (std::isalpha(static_cast<unsigned char>(unit[first])) != 0) {
    try {
      factor = parse_length_m("1" + unit.substr(first), field);
    } catch (const InputError&) {
      refuse();
    }
  } else {
    const std::size_t last = unit.find_last_not_of(" \t") + 1;
    const auto [end, ec] = std::from_chars(unit.data() + first, unit.data() + last, factor);
    if (ec != std::errc{} || end != unit.data() + last) {
      try {
        factor = parse_length_m(unit, field);
      } catch (const InputError&) {
        refuse();
      }
    }
  }
  if (!(factor > 0.0) || !std::isfinite(factor)) refuse();
  return factor;
}

MeshBody read_mesh_body(const std::string& path, double unit_m, const BodyOptions& options) {
  check_body_options(options);  // before reading a file that may be large
  const TriangleMesh mesh = read_mesh(path, unit_m);
  MeshBody body = mesh_body(mesh, options, path);
  to_file_coordinates(body, mesh.origin_m);
  return body;
}

void to_file_coordinates(MeshBody& body, const Vec3& origin_m) {
  // At rest the body is turned about its CM (x, y kept) and lowered onto z = 0 (bodies/pose.hpp): its x, y go back to
  // the file's, its heights stay measured from the base it rests on. As scanned every coordinate is the file's.
  const int axes = body.pose.method == PoseMethod::rest ? 2 : 3;
  for (int k = 0; k < axes; ++k) {
    body.mass.centre_of_mass_m[k] += origin_m[k];
    body.planar.pivot1_m[k] += origin_m[k];
    body.planar.pivot2_m[k] += origin_m[k];
  }
  if (axes == 3) body.support.z_m += origin_m[2];
  for (auto& p : body.support.hull_xy_m) p = {p[0] + origin_m[0], p[1] + origin_m[1]};
}

TriangleMesh read_mesh(const std::string& path, double unit_m) {
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".stl" && ext != ".ply") {
    throw mesh_error(path, fmt::format("unknown mesh format '{}': topple reads .obj, .off, .stl (ASCII or binary) and "
                                       ".ply (ASCII or binary)",
                                       ext));
  }
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);  // follows links: a link to /dev/zero is a device
  if (ec || !std::filesystem::exists(status)) throw mesh_error(path, "no such file");
  if (!std::filesystem::is_regular_file(status)) throw mesh_error(path, "not a regular file");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) throw mesh_error(path, "cannot read its size: " + ec.message());
  if (bytes > kMaxMeshFileBytes) {
    throw mesh_error(path, fmt::format("{} bytes: larger than the {} bytes topple reads (decimate the scan)", bytes,
                                       kMaxMeshFileBytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw mesh_error(path, "cannot open the file");
  std::string content(static_cast<std::size_t>(bytes), '\0');
  in.read(content.data(), static_cast<std::streamsize>(content.size()));
  content.resize(static_cast<std::size_t>(in.gcount()));  // a file that shrank while read: what is there
  if (in.bad()) throw mesh_error(path, "cannot read the file");
  return parse_mesh(content, ext.substr(1), path, unit_m);
}

TriangleMesh parse_mesh(std::string_view content, const std::string& format, const std::string& name,
                        double unit_m) {
  if (!(unit_m > 0.0 && std::isfinite(unit_m))) {
    throw parameter_error("--unit", fmt::format("{} m is not a positive length", unit_m));
  }
  if (format != "obj" && format != "off" && format != "stl" && format != "ply") {
    throw mesh_error(name, fmt::format("unknown mesh format '{}': topple reads obj, off, stl and ply", format));
  }
  if (content.empty()) throw mesh_error(name, "the file is empty");
  if (content.size() > kMaxMeshFileBytes) {
    throw mesh_error(name, fmt::format("{} bytes: larger than the {} bytes topple reads (decimate the scan)",
                                       content.size(), kMaxMeshFileBytes));
  }
  Soup soup = read_soup(content, format, name, unit_m);
  TriangleMesh mesh = Builder(soup, name, unit_m).build();
  check_mesh(mesh, name);  // what is left: vertex manifoldness, volume and orientation, self-intersection
  return mesh;
}

}  // namespace topple::io
