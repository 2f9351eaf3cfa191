// OBJ, STL and PLY meshes through the Open Asset Import Library (assimp; Debian libassimp-dev). The only translation
// unit of topple that includes assimp's headers.
#include "topple/io/mesh.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <initializer_list>
#include <vector>

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/mesh.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple::io {
namespace {

InputError mesh_error(const std::string& file, const std::string& problem) {
  return InputError(InputLocation{.file = file, .line = {}, .field = {}}, problem);
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext;
}

/// An importer that knows only the one format `extension` names: every other loader of assimp is unregistered (and
/// deleted here: assimp's destructor deletes only the loaders still registered), so that a file whose content does
/// not match its extension is refused rather than tried as any of assimp's other formats.
class SingleFormatImporter {
 public:
  explicit SingleFormatImporter(const std::string& extension) {
    const std::size_t keep = importer_.GetImporterIndex(extension.c_str());
    std::vector<Assimp::BaseImporter*> others;
    for (std::size_t i = 0; i < importer_.GetImporterCount(); ++i) {
      if (i != keep) others.push_back(importer_.GetImporter(i));
    }
    for (auto* other : others) {
      if (importer_.UnregisterLoader(other) == aiReturn_SUCCESS) removed_.emplace_back(other);
    }
  }
  Assimp::Importer& get() { return importer_; }

 private:
  std::vector<std::unique_ptr<Assimp::BaseImporter>> removed_;  // destroyed after importer_ (declared first)
  Assimp::Importer importer_;
};

/// Cuts an assimp message to a readable length, printable ASCII only (its parse errors quote the rest of the file).
std::string short_message(const char* text) {
  std::string out;
  for (const char* c = text; *c != '\0' && out.size() < 200; ++c) {
    out += (*c >= 0x20 && *c < 0x7f) ? *c : ' ';
  }
  if (std::strlen(text) > out.size()) out += " ...";
  return out;
}

bool is_ply_type(std::string_view t) {
  for (std::string_view known : {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
                                 "int16", "uint16", "int32", "uint32", "float32", "float64"}) {
    if (t == known) return true;
  }
  return false;
}

bool is_identifier(std::string_view t) {
  if (t.empty() || t.size() > 64) return false;
  return std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; });
}

/// The PLY header checked against the format's grammar (Turk 1994, "The PLY polygon file format": the lines "ply",
/// "format ascii|binary_little_endian|binary_big_endian 1.0", "comment ...", "obj_info ...", "element NAME COUNT",
/// "property TYPE NAME", "property list TYPE TYPE NAME", "end_header"), before assimp sees the file: assimp 5.2's
/// header parser loops forever on some malformed headers (fuzz_mesh_ply found one: a property line running into
/// "end_header" without a newline), and it allocates for the element counts as given, so these are bounded here.
void check_ply_header(std::string_view content, const std::string& name) {
  constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
  const auto fail = [&](std::size_t line, const std::string& problem) {
    throw InputError(InputLocation{.file = name, .line = line, .field = {}}, "PLY header: " + problem);
  };
  std::size_t pos = 0, line_no = 0;
  bool in_element = false;
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
    std::vector<std::string_view> tokens;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      if (j > i) tokens.push_back(line.substr(i, j - i));
      i = j;
    }
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
    if (key == "end_header" && tokens.size() == 1) return;
    if (key == "element") {
      const bool count_ok = tokens.size() == 3 && !tokens[2].empty() && tokens[2].size() <= 9 &&
                            std::all_of(tokens[2].begin(), tokens[2].end(), [](unsigned char c) { return std::isdigit(c); });
      if (!count_ok || !is_identifier(tokens[1])) fail(line_no, "an element line is not 'element NAME COUNT'");
      const std::size_t count = std::stoul(std::string(tokens[2]));
      const std::size_t limit = tokens[1] == "face" ? MeshLimits::max_triangles : 3 * MeshLimits::max_triangles;
      if (count > limit) {
        fail(line_no, fmt::format("{} {} elements: more than the {} topple reads", count, tokens[1], limit));
      }
      in_element = true;
      continue;
    }
    if (key == "property") {
      const bool scalar = tokens.size() == 3 && is_ply_type(tokens[1]) && is_identifier(tokens[2]);
      const bool list = tokens.size() == 5 && tokens[1] == "list" && is_ply_type(tokens[2]) &&
                        is_ply_type(tokens[3]) && is_identifier(tokens[4]);
      if (!(scalar || list) || !in_element) {
        fail(line_no, "a property line is not 'property TYPE NAME' or 'property list TYPE TYPE NAME' after an "
                      "element line");
      }
      continue;
    }
    fail(line_no, fmt::format("'{}' is not a PLY header line", std::string(line.substr(0, 60))));
  }
}

/// Collects the triangles of an assimp scene into one TriangleMesh.
///
/// Polygons are split here rather than by assimp's aiProcess_Triangulate, which aborts the program (an ai_assert in
/// TriangulateProcess.cpp, enabled in Debian's build) on a scene whose primitive-type flags disagree with its faces,
/// as fuzz_mesh_ply made a truncated PLY face list give. A polygon of n > 3 vertices is split into the fan
/// (0, k, k + 1), which is right for a convex polygon (the quads of an OBJ box); a polygon that is not convex about its
/// Newell normal is refused (triangulate it in the program that wrote the file). Faces of 1 or 2 vertices (points,
/// lines) are refused.
struct MeshBuilder {
  const std::string& path;
  double unit_m;
  TriangleMesh mesh;
  std::map<std::array<float, 3>, std::uint32_t> index;

  static constexpr int kMaxNodeDepth = 64;

  void add_node(const aiScene& scene, const aiNode* node, const aiMatrix4x4& parent, int depth) {
    if (node == nullptr) return;
    if (depth > kMaxNodeDepth) throw mesh_error(path, fmt::format("nodes nested deeper than {}", kMaxNodeDepth));
    const aiMatrix4x4 transform = parent * node->mTransformation;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      if (node->mMeshes[i] < scene.mNumMeshes) add_mesh(*scene.mMeshes[node->mMeshes[i]], transform);
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) add_node(scene, node->mChildren[c], transform, depth + 1);
  }

  void add_mesh(const aiMesh& am, const aiMatrix4x4& transform) {
    std::vector<std::uint32_t> local(am.mNumVertices);
    for (unsigned v = 0; v < am.mNumVertices; ++v) {
      const aiVector3D p = transform * am.mVertices[v];
      const std::array<float, 3> key{p.x + 0.0f, p.y + 0.0f, p.z + 0.0f};
      for (float x : key) {
        if (!std::isfinite(x)) {
          throw mesh_error(path, fmt::format("a vertex has a coordinate that is not a finite number ({}, {}, {})", p.x,
                                             p.y, p.z));
        }
      }
      const auto [it, fresh] = index.emplace(key, static_cast<std::uint32_t>(mesh.vertices_m.size()));
      if (fresh) {
        mesh.vertices_m.push_back({static_cast<double>(key[0]) * unit_m, static_cast<double>(key[1]) * unit_m,
                                   static_cast<double>(key[2]) * unit_m});
      }
      local[v] = it->second;
    }
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
      const aiFace& face = am.mFaces[f];
      const unsigned n = face.mNumIndices;
      if (n < 3) {
        throw mesh_error(path, fmt::format("holds points or lines (a face of {} vertices): topple reads solids bounded "
                                           "by triangles or polygons only",
                                           n));
      }
      if (mesh.triangles.size() + (n - 2) > MeshLimits::max_triangles) {
        throw mesh_error(path, fmt::format("more than the {} triangles topple reads (decimate the scan)",
                                           MeshLimits::max_triangles));
      }
      std::vector<std::uint32_t> poly(n);
      for (unsigned k = 0; k < n; ++k) {
        if (face.mIndices[k] >= am.mNumVertices) throw mesh_error(path, "a face refers to a vertex that is not there");
        poly[k] = local[face.mIndices[k]];
      }
      if (n > 3 && !convex(poly)) {
        throw mesh_error(path, fmt::format("a face of {} vertices is not a convex polygon: triangulate it in the program "
                                           "that wrote the file",
                                           n));
      }
      for (unsigned k = 1; k + 1 < n; ++k) mesh.triangles.push_back({poly[0], poly[k], poly[k + 1]});
    }
  }

  /// Convex about its Newell normal (Newell's method: the normal of a polygon from its edges, exact for a planar one).
  [[nodiscard]] bool convex(const std::vector<std::uint32_t>& poly) const {
    const std::size_t n = poly.size();
    std::array<double, 3> normal{};
    for (std::size_t k = 0; k < n; ++k) {
      const auto& a = mesh.vertices_m[poly[k]];
      const auto& b = mesh.vertices_m[poly[(k + 1) % n]];
      normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const auto& a = mesh.vertices_m[poly[k]];
      const auto& b = mesh.vertices_m[poly[(k + 1) % n]];
      const auto& c = mesh.vertices_m[poly[(k + 2) % n]];
      const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const std::array<double, 3> w{c[0] - b[0], c[1] - b[1], c[2] - b[2]};
      const double turn = (u[1] * w[2] - u[2] * w[1]) * normal[0] + (u[2] * w[0] - u[0] * w[2]) * normal[1] +
                          (u[0] * w[1] - u[1] * w[0]) * normal[2];
      if (turn < 0.0) return false;
    }
    return true;
  }
};

}  // namespace

double mesh_unit_m(const std::string& unit, const std::string& field) {
  const double factor = parse_length_m("1" + unit, field);
  if (!(factor > 0.0)) throw parameter_error(field, fmt::format("'{}' is not a unit of length", unit));
  return factor;
}

MeshBody read_mesh_body(const std::string& path, double unit_m, const BodyOptions& options) {
  check_body_options(options);  // before reading a file that may be large
  return mesh_body(read_mesh(path, unit_m), options, path);
}

TriangleMesh read_mesh(const std::string& path, double unit_m) {
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".stl" && ext != ".ply") {
    throw mesh_error(path, fmt::format("unknown mesh format '{}': topple reads .obj, .stl (ASCII or binary) and .ply",
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
  const std::string ext = "." + format;
  if (ext != ".obj" && ext != ".stl" && ext != ".ply") {
    throw mesh_error(name, fmt::format("unknown mesh format '{}': topple reads obj, stl and ply", format));
  }
  if (content.empty()) throw mesh_error(name, "the file is empty");
  if (content.size() > kMaxMeshFileBytes) {
    throw mesh_error(name, fmt::format("{} bytes: larger than the {} bytes topple reads (decimate the scan)",
                                       content.size(), kMaxMeshFileBytes));
  }
  const std::string& path = name;
  if (format == "ply") check_ply_header(content, name);

  SingleFormatImporter single(ext);
  // Only assimp's validation of its own output (indices in range and the like): no post-processing step (see
  // MeshBuilder), no smoothing or repair: check_mesh judges the surface as the file has it. Normals are not read (the
  // winding order defines the outside).
  const aiScene* scene = single.get().ReadFileFromMemory(
      content.data(), content.size(),
      aiProcess_ValidateDataStructure, format.c_str());
  if (scene == nullptr) {
    throw mesh_error(path, fmt::format("cannot be read as {}: {}", format,
                                       short_message(single.get().GetErrorString())));
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mNumMeshes == 0) {
    throw mesh_error(path, "the mesh has no triangles (an empty file, or one holding only points or lines)");
  }

  // Every mesh placed by a node, with the node's accumulated transform (identity in what these three loaders give);
  // vertices with equal coordinates (as read, before scaling) welded, -0 and +0 being one value; polygons split.
  MeshBuilder builder{path, unit_m, {}, {}};
  builder.add_node(*scene, scene->mRootNode, aiMatrix4x4{}, 0);
  TriangleMesh mesh = std::move(builder.mesh);
  check_mesh(mesh, path);
  return mesh;
}

}  // namespace topple::io
