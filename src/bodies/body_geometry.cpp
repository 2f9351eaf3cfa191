#include "bodies/body_geometry.hpp"

#include <iterator>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_2.h>

namespace topple::detail {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
}  // namespace

std::vector<std::array<double, 2>> convex_hull_2d(const std::vector<std::array<double, 2>>& points) {
  std::vector<Kernel::Point_2> in;
  in.reserve(points.size());
  for (const auto& p : points) in.emplace_back(p[0], p[1]);
  std::vector<Kernel::Point_2> hull;
  CGAL::convex_hull_2(in.begin(), in.end(), std::back_inserter(hull));
  std::vector<std::array<double, 2>> out;
  out.reserve(hull.size());
  for (const auto& p : hull) out.push_back({p.x(), p.y()});
  return out;
}

SelfIntersection self_intersection(const TriangleMesh& mesh) {
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh sm;
  std::vector<Mesh::Vertex_index> v;
  v.reserve(mesh.vertices_m.size());
  for (const auto& p : mesh.vertices_m) v.push_back(sm.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
  for (const auto& t : mesh.triangles) {
    // add_face refuses a face that would make a vertex non-manifold (two fans meeting at one vertex).
    if (sm.add_face(v[t[0]], v[t[1]], v[t[2]]) == Mesh::null_face()) return {.vertex_manifold = false};
  }
  return {.vertex_manifold = true, .intersects = CGAL::Polygon_mesh_processing::does_self_intersect(sm)};
}

}  // namespace topple::detail
