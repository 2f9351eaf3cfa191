#include "support/meshes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "topple/core/units.hpp"

namespace topple::test {

TriangleMesh box_mesh(double a_m, double b_m, double c_m) {
  return prism_mesh({{0.0, 0.0}, {a_m, 0.0}, {a_m, b_m}, {0.0, b_m}}, c_m);
}

TriangleMesh prism_mesh(const std::vector<std::array<double, 2>>& polygon, double height_m) {
  TriangleMesh m;
  const auto n = static_cast<std::uint32_t>(polygon.size());
  for (const auto& p : polygon) m.vertices_m.push_back({p[0], p[1], 0.0});
  for (const auto& p : polygon) m.vertices_m.push_back({p[0], p[1], height_m});
  for (std::uint32_t k = 1; k + 1 < n; ++k) {
    m.triangles.push_back({0, k + 1, k});          // bottom, facing down
    m.triangles.push_back({n, n + k, n + k + 1});  // top, facing up
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t j = (k + 1) % n;
    m.triangles.push_back({k, j, n + j});  // sides, facing out of a counter-clockwise polygon
    m.triangles.push_back({k, n + j, n + k});
  }
  return m;
}

std::vector<std::array<double, 2>> regular_polygon(int n, double r_m) {
  std::vector<std::array<double, 2>> p;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * kPi * k / n;
    p.push_back({r_m * std::cos(t), r_m * std::sin(t)});
  }
  return p;
}

TriangleMesh xz_prism_mesh(const std::vector<std::array<double, 2>>& polygon_xz, double width_m) {
  // A prism along z on the polygon (u, v) = (x, z), then (u, v, w) -> (x, y, z) = (u, w, v): an odd permutation of
  // the axes, so the windings are reversed to keep the faces outward.
  std::vector<std::array<double, 2>> poly = polygon_xz;
  TriangleMesh m = prism_mesh(poly, width_m);
  for (auto& p : m.vertices_m) p = {p[0], p[2], p[1]};
  return inverted(m);
}

TriangleMesh rotated_z(const TriangleMesh& mesh, double angle_deg, const Vec3& shift_m) {
  TriangleMesh out = mesh;
  const double t = angle_deg * kPi / 180.0;
  const double c = std::cos(t), s = std::sin(t);
  for (auto& p : out.vertices_m) {
    p = {c * p[0] - s * p[1] + shift_m[0], s * p[0] + c * p[1] + shift_m[1], p[2] + shift_m[2]};
  }
  return out;
}

TriangleMesh inverted(const TriangleMesh& mesh) {
  TriangleMesh out = mesh;
  for (auto& t : out.triangles) std::swap(t[1], t[2]);
  return out;
}

std::string obj_text(const TriangleMesh& mesh) {
  std::string s = "# written by topple's tests\no body\n";
  for (const auto& p : mesh.vertices_m) s += fmt::format("v {} {} {}\n", p[0], p[1], p[2]);
  for (const auto& t : mesh.triangles) s += fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  return s;
}

std::string stl_ascii_text(const TriangleMesh& mesh) {
  std::string s = "solid body\n";
  for (const auto& t : mesh.triangles) {
    s += " facet normal 0 0 0\n  outer loop\n";
    for (auto v : t) {
      const auto& p = mesh.vertices_m[v];
      s += fmt::format("   vertex {} {} {}\n", p[0], p[1], p[2]);
    }
    s += "  endloop\n endfacet\n";
  }
  return s + "endsolid body\n";
}

std::string stl_binary_bytes(const TriangleMesh& mesh) {
  std::string s(80, ' ');
  s.replace(0, 21, "binary STL from tests");  // must not begin with "solid" (the ASCII form's keyword)
  const auto append = [&s](const void* data, std::size_t n) { s.append(static_cast<const char*>(data), n); };
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  append(&count, 4);  // little-endian on the machines topple builds on (x86-64, aarch64)
  for (const auto& t : mesh.triangles) {
    const float normal[3] = {0.0f, 0.0f, 0.0f};
    append(normal, sizeof normal);
    for (auto v : t) {
      const auto& p = mesh.vertices_m[v];
      const float xyz[3] = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
      append(xyz, sizeof xyz);
    }
    const std::uint16_t attributes = 0;
    append(&attributes, 2);
  }
  return s;
}

std::string ply_ascii_text(const TriangleMesh& mesh) {
  std::string s = fmt::format(
      "ply\nformat ascii 1.0\ncomment written by topple's tests\nelement vertex {}\nproperty double x\n"
      "property double y\nproperty double z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
      mesh.vertices_m.size(), mesh.triangles.size());
  for (const auto& p : mesh.vertices_m) s += fmt::format("{} {} {}\n", p[0], p[1], p[2]);
  for (const auto& t : mesh.triangles) s += fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
  return s;
}

std::string off_text(const TriangleMesh& mesh) {
  std::string s = fmt::format("OFF\n# written by topple's tests\n{} {} 0\n", mesh.vertices_m.size(), mesh.triangles.size());
  for (const auto& p : mesh.vertices_m) s += fmt::format("{} {} {}\n", p[0], p[1], p[2]);
  for (const auto& t : mesh.triangles) s += fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
  return s;
}

std::string ply_binary_bytes(const TriangleMesh& mesh, bool big_endian) {
  std::string s = fmt::format(
      "ply\nformat {} 1.0\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      big_endian ? "binary_big_endian" : "binary_little_endian", mesh.vertices_m.size(), mesh.triangles.size());
  // Bytes in the file's order: the host is little-endian (x86-64, aarch64), so big-endian reverses each number.
  const auto append = [&s, big_endian](const void* data, std::size_t n) {
    std::string bytes(static_cast<const char*>(data), n);
    if (big_endian) std::reverse(bytes.begin(), bytes.end());
    s += bytes;
  };
  for (const auto& p : mesh.vertices_m) {
    for (double x : p) append(&x, sizeof x);
  }
  for (const auto& t : mesh.triangles) {
    const std::uint8_t n = 3;
    append(&n, 1);
    for (auto v : t) {
      const auto i = static_cast<std::int32_t>(v);
      append(&i, sizeof i);
    }
  }
  return s;
}

}  // namespace topple::test
