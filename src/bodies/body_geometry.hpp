#pragma once
// The two computational-geometry pieces of body.cpp, from CGAL (Debian libcgal-dev, headers only), kept in one
// translation unit (body_geometry.cpp) so that CGAL's headers and its -frounding-math touch nothing else. Not a
// public header.
#include <array>
#include <vector>

#include "topple/bodies/body.hpp"

namespace topple::detail {

/// The convex hull of `points` (x, y), counter-clockwise, without collinear points on its edges (CGAL::convex_hull_2
/// with exact predicates: Exact_predicates_inexact_constructions_kernel).
[[nodiscard]] std::vector<std::array<double, 2>> convex_hull_2d(const std::vector<std::array<double, 2>>& points);

/// Whether two triangles of a closed, edge-manifold mesh without degenerate triangles intersect other than along
/// the edge or at the vertex they share (CGAL::Polygon_mesh_processing::does_self_intersect on a Surface_mesh).
/// `vertex_manifold` is false when the mesh cannot be built as a Surface_mesh (a vertex whose triangles form two
/// fans): the caller refuses that first.
struct SelfIntersection {
  bool vertex_manifold = true;
  bool intersects = false;
};
[[nodiscard]] SelfIntersection self_intersection(const TriangleMesh& mesh);

}  // namespace topple::detail
