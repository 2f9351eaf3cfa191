#pragma once
// Test fixtures for topple/bodies/body.hpp: closed triangle meshes built in memory (boxes, prisms on any polygon, a wedge),
// rigid motions of them, and writers of OBJ, STL (ASCII and binary) and PLY files holding them.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "topple/bodies/body.hpp"

namespace topple::test {

/// The box [0, a] x [0, b] x [0, c] (m), outward-facing.
[[nodiscard]] TriangleMesh box_mesh(double a_m, double b_m, double c_m);

/// The prism with the horizontal cross-section `polygon` (x, y, counter-clockwise seen from above, star-shaped from
/// its first vertex: the caps are fans from it) from z = 0 to z = height_m.
[[nodiscard]] TriangleMesh prism_mesh(const std::vector<std::array<double, 2>>& polygon, double height_m);

/// The regular n-gon of circumradius r_m, vertex k at angle 2 pi k / n from +x.
[[nodiscard]] std::vector<std::array<double, 2>> regular_polygon(int n, double r_m);

/// A horizontal prism (the wedge of the tests): cross-section `polygon` in the (x, z) plane (counter-clockwise seen
/// from -y, i.e. x right and z up, star-shaped from its first vertex), from y = 0 to y = width_m.
[[nodiscard]] TriangleMesh xz_prism_mesh(const std::vector<std::array<double, 2>>& polygon_xz, double width_m);

/// The mesh rotated by angle_deg about the vertical axis (counter-clockwise seen from above) and then translated.
[[nodiscard]] TriangleMesh rotated_z(const TriangleMesh& mesh, double angle_deg, const Vec3& shift_m = {});

/// The mesh with every triangle's winding reversed (inside out).
[[nodiscard]] TriangleMesh inverted(const TriangleMesh& mesh);

/// Mesh files. The text forms print every coordinate as the shortest decimal that reads back to the same double
/// (fmt's "{}"), so a reader in double precision gets the mesh's numbers exactly; binary STL stores floats (the
/// format's own precision); binary PLY stores doubles, little- or big-endian.
[[nodiscard]] std::string obj_text(const TriangleMesh& mesh);
[[nodiscard]] std::string off_text(const TriangleMesh& mesh);
[[nodiscard]] std::string stl_ascii_text(const TriangleMesh& mesh);
[[nodiscard]] std::string stl_binary_bytes(const TriangleMesh& mesh);
[[nodiscard]] std::string ply_ascii_text(const TriangleMesh& mesh);
[[nodiscard]] std::string ply_binary_bytes(const TriangleMesh& mesh, bool big_endian);

}  // namespace topple::test
