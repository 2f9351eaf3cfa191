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
};

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

/// The PLY header checked against the format's grammar (Turk 1994, "The PLY polygon file format": the lines "ply",
/// "format ascii|binary_little_endian|binary_big_endian 1.0", "comment ...", "obj_info ...", "element NAME COUNT",
/// "property TYPE NAME", "property list TYPE TYPE NAME", "end_header") and against what CGAL's PLY reader assumes
/// without checking (its release build reads through a null pointer otherwise): a vertex element has scalar x, y, z
/// of a floating type; a face's index list counts in 8 or 16 bits (CGAL allocates the count a 32-bit one gives before
/// reading the indices) and holds int or uint indices; a halfedge element's source and target are uint. Element
/// counts are bounded by MeshLimits. A file with vertices but no faces is a point cloud, said so.
void check_ply_header(std::string_view content, const std::string& name) {
  constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
  const auto fail = [&](std::size_t line, const std::string& problem) {
    throw line_error(name, line, "PLY header: " + problem);
  };
  std::size_t pos = 0, line_no = 0;
  std::string element;             // the element whose properties follow
  std::size_t vertex_count = 0, face_count = 0;
  bool has_face_element = false;
  std::map<std::string, std::string, std::less<>> vertex_props;  // name -> type, of the vertex element
  std::size_t element_line = 0;
  std::vector<std::string> element_props;  // property names of the current element: a repeated one is refused (CGAL
                                           // takes the first of a name, topple's checks would see the last)
  const auto finish_element = [&]() {
    if (element == "vertex" || element == "vertices") {
      for (const char* axis : {"x", "y", "z"}) {
        const auto it = vertex_props.find(axis);
        if (it == vertex_props.end() || !is_ply_float(it->second)) {
          fail(element_line, fmt::format("the {} element has no property '{}' of type float or double", element,
                                         axis));
        }
      }
      vertex_props.clear();
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
      continue;
    }
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header" && tokens.size() == 1) {
      finish_element();
      if (vertex_count == 0 && face_count == 0) fail(line_no, "no vertex and no face elements");
      if (!has_face_element || face_count == 0) {
        throw line_error(name, line_no, fmt::format("{} vertices and no faces: {}", vertex_count, kPointCloud));
      }
      return;
    }
    if (key == "element") {
      const bool count_ok = tokens.size() == 3 && !tokens[2].empty() && tokens[2].size() <= 9 &&
                            std::all_of(tokens[2].begin(), tokens[2].end(), [](unsigned char c) { return std::isdigit(c); });
      if (!count_ok || !is_identifier(tokens[1])) fail(line_no, "an element line is not 'element NAME COUNT'");
      finish_element();
      element = std::string(tokens[1]);
      element_line = line_no;
      element_props.clear();
      const std::size_t count = std::stoul(std::string(tokens[2]));
      const bool face = element == "face" || element == "faces";
      const std::size_t limit = face ? MeshLimits::max_triangles : 3 * MeshLimits::max_triangles;
      if (count > limit) {
        fail(line_no, fmt::format("{} {} elements: more than the {} topple reads", count, element, limit));
      }
      if (face) {
        has_face_element = true;
        face_count += count;
      }
      if (element == "vertex" || element == "vertices") vertex_count += count;
      continue;
    }
    if (key == "property") {
      const bool scalar = tokens.size() == 3 && is_ply_type(tokens[1]) && is_identifier(tokens[2]);
      const bool list = tokens.size() == 5 && tokens[1] == "list" && is_ply_type(tokens[2]) &&
                        is_ply_type(tokens[3]) && is_identifier(tokens[4]);
      if (!(scalar || list) || element.empty()) {
        fail(line_no, "a property line is not 'property TYPE NAME' or 'property list TYPE TYPE NAME' after an "
                      "element line");
      }
      if (list && !is_ply_small_count(tokens[2])) {
        fail(line_no, fmt::format("the list '{}' is counted by a {}: topple reads lists counted by 8- or 16-bit "
                                  "types (uchar, ushort, ...)",
                                  tokens[4], tokens[2]));
      }
      const std::string_view prop = scalar ? tokens[2] : tokens[4];
      if (std::find(element_props.begin(), element_props.end(), prop) != element_props.end()) {
        fail(line_no, fmt::format("the {} element has two properties named '{}'", element, prop));
      }
      element_props.emplace_back(prop);
      if (element == "vertex" || element == "vertices") {
        vertex_props[std::string(prop)] = scalar ? std::string(tokens[1]) : std::string("list");
      }
      if ((element == "face" || element == "faces") && (prop == "vertex_indices" || prop == "vertex_index") &&
          !(list && is_ply_index(tokens[3]))) {
        fail(line_no, fmt::format("the face property '{}' is not a list of int or uint", prop));
      }
      if (element == "halfedge" && (prop == "source" || prop == "target") &&
          !(scalar && (tokens[1] == "uint" || tokens[1] == "uint32"))) {
        fail(line_no, fmt::format("the halfedge property '{}' is not a uint", prop));
      }
      continue;
    }
    fail(line_no, fmt::format("'{}' is not a PLY header line", std::string(line.substr(0, 60))));
  }
}

// --- OBJ, STL, OFF: what CGAL's readers would read wrongly or without saying where ---------------------------------

std::string_view next_line(std::string_view content, std::size_t& pos) {
  std::size_t eol = content.find('\n', pos);
  if (eol == std::string_view::npos) eol = content.size();
  std::string_view line = content.substr(pos, eol - pos);
  pos = eol + 1;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

/// A token that is a whole number in the C locale (a leading '+' allowed, as C++ streams read it).
bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc{} && end == token.data() + token.size();
}
bool parse_index(std::string_view token, std::size_t& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc{} && end == token.data() + token.size();
}

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

/// OBJ statements counted before CGAL reads the file: vertices (v) but no faces (f) is a point cloud; a polyline (l),
/// which CGAL's reader stops at without saying where, is refused with its line; a v line must hold three finite
/// numbers (CGAL reads them with a stream, and does not say which line it could not read); an unknown statement is
/// refused with its line.
void check_obj(std::string_view content, const std::string& name) {
  std::size_t pos = 0, line_no = 0, vertices = 0, faces = 0, first_l = 0;
  while (pos < content.size()) {
    ++line_no;
    const std::vector<std::string_view> tokens = split_blank(next_line(content, pos));
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      ++vertices;
      double xyz[3];
      for (int k = 0; k < 3; ++k) {
        if (tokens.size() < 4 || !parse_double(tokens[1 + k], xyz[k]) || !std::isfinite(xyz[k])) {
          throw line_error(name, line_no, fmt::format("vertex {} (this v line) does not hold three finite numbers",
                                                      vertices));
        }
      }
    } else if (tokens[0] == "f") {
      ++faces;
    } else if (tokens[0] == "l") {
      if (first_l == 0) first_l = line_no;
    } else if (tokens[0].front() != '#' && !is_obj_statement(tokens[0])) {
      throw line_error(name, line_no, fmt::format("'{}' is not an OBJ statement (v, vt, vn, f, g, o, s, usemtl, "
                                                  "mtllib, ...)",
                                                  std::string(tokens[0].substr(0, 40))));
    }
  }
  if (faces == 0) {
    if (vertices == 0) throw mesh_error(name, "no vertices (v) and no faces (f): not a mesh");
    throw mesh_error(name, fmt::format("{} vertices and no faces (f lines): {}", vertices, kPointCloud));
  }
  if (first_l != 0) {
    throw line_error(name, first_l, "a polyline (l statement): topple reads a solid bounded by faces (f) only; "
                                    "remove the lines");
  }
}

/// STL: a file that does not begin with "solid" is binary, and must hold the 84 + 50 n bytes its facet count n says
/// (CGAL's reader takes a file shorter than 80 bytes as an empty binary STL); a binary STL's coordinates must be
/// finite (CGAL welds equal points in a std::map, whose order a NaN breaks).
void check_stl(std::string_view content, const std::string& name) {
  static_assert(std::endian::native == std::endian::little, "binary STL is little-endian; topple reads it by memcpy");
  std::size_t i = 0;
  while (i < content.size() && std::isspace(static_cast<unsigned char>(content[i]))) ++i;
  const bool solid = content.substr(i, 5) == "solid" && i + 5 < content.size() &&
                     (content[i + 5] == ' ' || content[i + 5] == '\n' || content[i + 5] == '\r');
  std::uint32_t n = 0;
  if (content.size() >= 84) std::memcpy(&n, content.data() + 80, 4);
  const std::uint64_t binary_bytes = 84 + 50 * std::uint64_t{n};
  const bool binary = content.size() >= 84 && (solid ? content.size() == binary_bytes : content.size() >= binary_bytes);
  if (!binary) {
    if (solid) return;  // ASCII: CGAL reads it
    if (content.size() < 84) {
      throw mesh_error(name, fmt::format("{} bytes: neither an ASCII STL (beginning with 'solid') nor a binary one "
                                         "(80 bytes of header and a facet count)",
                                         content.size()));
    }
    throw mesh_error(name, fmt::format("cannot be read as stl: as a binary STL of {} facets it would be {} bytes, but "
                                       "the file is {} bytes (truncated, or not an STL file)",
                                       n, binary_bytes, content.size()));
  }
  if (n > MeshLimits::max_triangles) {
    throw mesh_error(name, fmt::format("{} facets: more than the {} topple reads (decimate the scan)", n,
                                       MeshLimits::max_triangles));
  }
  for (std::uint64_t f = 0; f < n; ++f) {
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, content.data() + 84 + 50 * f + 12 + 12 * c, sizeof xyz);
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
        throw mesh_error(name, fmt::format("facet {}, corner {} has a coordinate that is not a finite number "
                                           "({}, {}, {})",
                                           f + 1, c + 1, xyz[0], xyz[1], xyz[2]));
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
void check_off(std::string_view content, const std::string& name) {
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
    bool ok = tokens.size() >= 3 && tokens.size() <= 7;  // x y z and an optional colour of 1, 3 or 4 numbers
    for (std::size_t k = 0; ok && k < tokens.size(); ++k) ok = parse_double(tokens[k], x) && std::isfinite(x);
    if (!ok) {
      throw line_error(name, line_no, fmt::format("vertex {} (index {}) is not a line of three finite numbers", v + 1,
                                                  v));
    }
  }
  for (std::size_t f = 0; f < nf; ++f) {
    if (!next()) throw line_error(name, line_no, fmt::format("the file ends after {} of its {} faces", f, nf));
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

Soup read_soup(std::string_view content, const std::string& format, const std::string& name) {
  ViewBuffer buffer(content);
  std::istream in(&buffer);
  Soup soup;
  bool ok = false;
  try {
    if (format == "obj") {
      check_obj(content, name);
      ok = CGAL::IO::read_OBJ(in, soup.points, soup.polygons);
    } else if (format == "off") {
      check_off(content, name);
      soup.base = 0;
      ok = CGAL::IO::read_OFF(in, soup.points, soup.polygons);
    } else if (format == "stl") {
      check_stl(content, name);
      soup.numbered = false;
      soup.face_word = "facet";
      ok = CGAL::IO::read_STL(in, soup.points, soup.polygons);
      if (ok && soup.polygons.empty()) throw mesh_error(name, "an STL of no facets: " + kPointCloud);
    } else {
      check_ply_header(content, name);
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
  [[nodiscard]] std::string face_name(std::size_t f) const {
    const auto& poly = soup_.polygons[f];
    if (!soup_.numbered) return fmt::format("facet {}", f + 1);
    std::string ids;
    for (std::size_t k = 0; k < poly.size() && k < 8; ++k) ids += fmt::format("{}{}", k ? " " : "", poly[k] + soup_.base);
    if (poly.size() > 8) ids += " ...";
    return soup_.base == 1 ? fmt::format("face {} (f {})", f + 1, ids) : fmt::format("face {} (indices {})", f + 1, ids);
  }

  void check_faces() {
    const std::size_t nv = soup_.points.size();
    if (nv > std::numeric_limits<std::uint32_t>::max() - 1) throw mesh_error(name_, "too many vertices");
    std::size_t triangles = 0;
    for (std::size_t f = 0; f < soup_.polygons.size(); ++f) {
      const auto& poly = soup_.polygons[f];
      if (poly.size() < 3) {
        throw mesh_error(name_, fmt::format("{} {} has {} vertices: points or lines, not a face of a solid",
                                            soup_.face_word, f + 1, poly.size()));
      }
      for (std::size_t v : poly) {
        if (v >= nv) {
          // OBJ's negative (relative) numbers that reach before the first vertex wrap around in CGAL's reader
          const std::string number = v < (std::size_t{1} << 40) ? fmt::format("vertex {}", v + soup_.base)
                                                                 : std::string("a vertex before the first");
          throw mesh_error(name_, fmt::format("face {} refers to {}, but the file has {} vertices", f + 1, number,
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
  Soup soup = read_soup(content, format, name);
  TriangleMesh mesh = Builder(soup, name, unit_m).build();
  check_mesh(mesh, name);  // what is left: vertex manifoldness, volume and orientation, self-intersection
  return mesh;
}

}  // namespace topple::io
