#include "topple/bodies/body.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>

#include "bodies/body_geometry.hpp"
#include "topple/bodies/pose.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

InputError mesh_error(const std::string& file, const std::string& problem) {
  return InputError(InputLocation{.file = file, .line = {}, .field = {}}, problem);
}

std::string vertex_text(const TriangleMesh& mesh, std::uint32_t i) {
  const auto& p = mesh.vertices_m[i];
  return fmt::format("vertex {} ({:.9g}, {:.9g}, {:.9g}) m", std::size_t{i} + 1, p[0], p[1], p[2]);
}

std::string triangle_text(const TriangleMesh& mesh, std::size_t t) {
  const auto& tri = mesh.triangles[t];
  return fmt::format("triangle {} (vertices {}, {}, {})", t + 1, std::size_t{tri[0]} + 1, std::size_t{tri[1]} + 1,
                     std::size_t{tri[2]} + 1);
}

struct Box {
  Vec3 lo{}, hi{};
  [[nodiscard]] double largest_extent() const { return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}); }
  [[nodiscard]] Vec3 centre() const { return {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2}; }
};

Box bounding_box(const TriangleMesh& mesh) {
  Box b{mesh.vertices_m.front(), mesh.vertices_m.front()};
  for (const auto& p : mesh.vertices_m) {
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = std::min(b.lo[k], p[k]);
      b.hi[k] = std::max(b.hi[k], p[k]);
    }
  }
  return b;
}

std::uint64_t edge_key(std::uint32_t from, std::uint32_t to) { return (std::uint64_t{from} << 32) | to; }

/// Every edge used by exactly two triangles, in opposite directions: each directed edge once, and its reverse once.
void check_closed_and_oriented(const TriangleMesh& mesh, const std::string& file) {
  std::unordered_map<std::uint64_t, std::size_t> directed;  // directed edge -> first triangle using it
  directed.reserve(mesh.triangles.size() * 3);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      const auto [it, fresh] = directed.emplace(edge_key(a, b), t);
      if (!fresh) {
        throw mesh_error(file, fmt::format("{} and {} both run along the edge from {} to {} in the same direction: "
                                           "the faces are not consistently oriented, or more than two faces meet at "
                                           "that edge (not a manifold solid)",
                                           triangle_text(mesh, it->second), triangle_text(mesh, t),
                                           vertex_text(mesh, a), vertex_text(mesh, b)));
      }
    }
  }
  for (const auto& [key, t] : directed) {
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
    if (!directed.contains(edge_key(b, a))) {
      throw mesh_error(file, fmt::format("the mesh is not closed: the edge from {} to {} of {} belongs to no other "
                                         "triangle (a hole in the surface; a solid needs every edge shared by two "
                                         "triangles)",
                                         vertex_text(mesh, a), vertex_text(mesh, b), triangle_text(mesh, t)));
    }
  }
}

/// Each vertex's triangles form one fan (its link is one cycle), given a closed, consistently oriented mesh.
void check_vertex_manifold(const TriangleMesh& mesh, const std::string& file) {
  const std::size_t nv = mesh.vertices_m.size();
  std::vector<std::size_t> start(nv + 1, 0);
  for (const auto& tri : mesh.triangles) {
    for (auto v : tri) ++start[v + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  // link[start[v] + j] = (a, b): the edge opposite v in one of v's triangles, in the triangle's winding.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> link(start[nv]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const auto& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) link[fill[tri[k]]++] = {tri[(k + 1) % 3], tri[(k + 2) % 3]};
  }
  std::unordered_map<std::uint32_t, std::uint32_t> next;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::size_t degree = start[v + 1] - start[v];
    if (degree == 0) continue;  // an unused vertex: harmless (it takes no part in any sum)
    next.clear();
    for (std::size_t j = start[v]; j < start[v + 1]; ++j) next.emplace(link[j].first, link[j].second);
    std::size_t steps = 0;
    std::uint32_t at = link[start[v]].first;
    do {
      at = next.at(at);  // present: every link edge's end starts another one (the mesh is closed and oriented)
      ++steps;
    } while (at != link[start[v]].first && steps <= degree);
    if (steps != degree) {
      throw mesh_error(file, fmt::format("{} is where two separate sheets of the surface touch (its {} triangles "
                                         "form more than one fan): not a manifold solid",
                                         vertex_text(mesh, static_cast<std::uint32_t>(v)), degree));
    }
  }
}

void check_base_tolerance(double fraction) {
  if (!(fraction >= 0.0 && fraction <= 0.1)) {
    throw parameter_error("--base-tolerance", fmt::format("{} is not a fraction of the mesh's size in [0, 0.1]",
                                                          fraction));
  }
}

void check_azimuth_and_g(double azimuth_deg, double g_m_s2) {
  if (!std::isfinite(azimuth_deg)) throw parameter_error("--azimuth", fmt::format("{} is not finite", azimuth_deg));
  if (!(g_m_s2 > 0.0 && std::isfinite(g_m_s2))) {
    throw parameter_error("--g", fmt::format("{} m/s2 is not a positive finite acceleration", g_m_s2));
  }
}

bool finite_all(const auto& values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

void check_pose_options(const BodyOptions& o) {
  if (!(o.contact_tolerance_m >= 0.0 && o.contact_tolerance_m <= 0.1)) {
    throw parameter_error("--contact-tolerance", fmt::format("{} m is not a length in [0, 0.1] m (e.g. 1mm)",
                                                             o.contact_tolerance_m));
  }
  if (o.up) {
    if (!finite_all(*o.up) || norm(*o.up) == 0.0) {
      throw parameter_error("--up", fmt::format("({}, {}, {}) is not a direction: three finite numbers, not all zero",
                                                (*o.up)[0], (*o.up)[1], (*o.up)[2]));
    }
  }
  if (o.rotation_wxyz) {
    const auto& q = *o.rotation_wxyz;
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!finite_all(q) || !(std::abs(n - 1.0) <= 1e-3)) {
      throw parameter_error("--rotation", fmt::format("({}, {}, {}, {}) is not a unit quaternion w, x, y, z (its norm "
                                                      "is {:.6g}; a rotation's is 1, to within 1e-3)",
                                                      q[0], q[1], q[2], q[3], n));
    }
  }
  if (o.axis_angle_deg) {
    const auto& a = *o.axis_angle_deg;
    if (!finite_all(a) || norm({a[0], a[1], a[2]}) == 0.0) {
      throw parameter_error("--axis-angle", fmt::format("({}, {}, {}, {}) is not an axis x, y, z (finite, not all "
                                                        "zero) and a finite angle in degrees",
                                                        a[0], a[1], a[2], a[3]));
    }
  }
  if (o.face && *o.face < 1) throw parameter_error("--face", "face numbers start at 1 (see --list-faces)");
  const int given = (o.up ? 1 : 0) + (o.rotation_wxyz ? 1 : 0) + (o.axis_angle_deg ? 1 : 0) + (o.face ? 1 : 0);
  const char* first = o.up ? "--up" : o.rotation_wxyz ? "--rotation" : o.axis_angle_deg ? "--axis-angle" : "--face";
  if (o.pose == PoseMethod::as_scanned && given > 0) {
    throw parameter_error(first, "applies to the resting pose (--pose rest); the as-scanned pose takes the mesh as "
                                 "given");
  }
  if (given > 1) {
    throw parameter_error(first, "give one of --up, --rotation, --axis-angle and --face, not several");
  }
}

}  // namespace

void check_body_options(const BodyOptions& options) {
  if (!(options.density_kg_m3 > 0.0 && options.density_kg_m3 <= 1e5)) {
    throw parameter_error("--density", fmt::format("{} kg/m^3 is not a density in (0, 1e5] kg/m^3",
                                                   options.density_kg_m3));
  }
  check_azimuth_and_g(options.azimuth_deg, options.g_m_s2);
  check_base_tolerance(options.base_tolerance_fraction);
  check_pose_options(options);
}

void check_mesh(const TriangleMesh& mesh, const std::string& file) {
  if (mesh.triangles.empty() || mesh.vertices_m.empty()) {
    throw mesh_error(file, "the mesh has no triangles (an empty file, or one holding only points or lines)");
  }
  if (mesh.triangles.size() > MeshLimits::max_triangles) {
    throw mesh_error(file, fmt::format("{} triangles: more than the {} topple reads (decimate the scan)",
                                       mesh.triangles.size(), MeshLimits::max_triangles));
  }
  for (std::size_t i = 0; i < mesh.vertices_m.size(); ++i) {
    for (double x : mesh.vertices_m[i]) {
      if (!std::isfinite(x)) {
        throw mesh_error(file, fmt::format("vertex {} has a coordinate that is not a finite number ({})", i + 1, x));
      }
      if (std::abs(x) > MeshLimits::max_abs_coordinate_m) {
        throw mesh_error(file, fmt::format("{} lies more than {} m from the origin: check --unit (coordinates are "
                                           "read in metres unless told)",
                                           vertex_text(mesh, static_cast<std::uint32_t>(i)),
                                           MeshLimits::max_abs_coordinate_m));
      }
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (auto v : mesh.triangles[t]) {
      if (v >= mesh.vertices_m.size()) {
        throw mesh_error(file, fmt::format("{} refers to vertex {}, but there are {} vertices", triangle_text(mesh, t),
                                           std::size_t{v} + 1, mesh.vertices_m.size()));
      }
    }
  }
  const Box box = bounding_box(mesh);
  const double size = box.largest_extent();
  if (!(size >= MeshLimits::min_extent_m && size <= MeshLimits::max_extent_m)) {
    throw mesh_error(file, fmt::format("the mesh is {:.6g} m across (largest side of its bounding box), outside [{}, {}] "
                                       "m: check --unit (coordinates are read in metres unless told)",
                                       size, MeshLimits::min_extent_m, MeshLimits::max_extent_m));
  }
  // Degenerate triangles: a repeated vertex, or an area below degenerate_area_fraction L^2.
  const double min_area = MeshLimits::degenerate_area_fraction * size * size;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const auto& a = mesh.vertices_m[tri[0]];
    const double area = norm(cross(sub(mesh.vertices_m[tri[1]], a), sub(mesh.vertices_m[tri[2]], a))) / 2;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || !(area > min_area)) {
      throw mesh_error(file, fmt::format("{} is degenerate (area {:.3g} m^2, below {:.3g} m^2 = {:g} x the square of "
                                         "the mesh's size): a sliver or a repeated vertex",
                                         triangle_text(mesh, t), area, min_area,
                                         MeshLimits::degenerate_area_fraction));
    }
  }
  // Duplicate triangles (the same three vertices, in any order or winding).
  {
    std::unordered_map<std::uint64_t, std::size_t> seen;  // hash of the sorted triple -> triangle; checked on hit
    seen.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      auto s = mesh.triangles[t];
      std::sort(s.begin(), s.end());
      const std::uint64_t key = (std::uint64_t{s[0]} * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t{s[1]} << 21) ^
                                (std::uint64_t{s[2]} * 0xC2B2AE3D27D4EB4Full);
      const auto [it, fresh] = seen.emplace(key, t);
      if (fresh) continue;
      auto o = mesh.triangles[it->second];
      std::sort(o.begin(), o.end());
      if (o == s) {
        throw mesh_error(file, fmt::format("{} and {} have the same three vertices: a duplicate face",
                                           triangle_text(mesh, it->second), triangle_text(mesh, t)));
      }
    }
  }
  check_closed_and_oriented(mesh, file);
  check_vertex_manifold(mesh, file);
  const MassProperties unit = mass_properties(mesh, 1.0);
  const double min_volume = MeshLimits::degenerate_area_fraction * size * size * size;
  if (unit.volume_m3 < 0.0 && -unit.volume_m3 > min_volume) {
    throw mesh_error(file, fmt::format("the mesh is inside out: its signed volume is {:.6g} m^3 (its faces are wound "
                                       "clockwise seen from outside). Flip the faces' orientation (e.g. MeshLab: "
                                       "Normals > Invert Faces Orientation) and read it again",
                                       unit.volume_m3));
  }
  if (!(unit.volume_m3 > min_volume)) {
    throw mesh_error(file, fmt::format("the mesh encloses no volume ({:.3g} m^3)", unit.volume_m3));
  }
  const detail::SelfIntersection si = detail::self_intersection(mesh);
  if (!si.vertex_manifold) {
    throw mesh_error(file, "the mesh is not a manifold surface (CGAL could not build it as a Surface_mesh)");
  }
  if (si.intersects) {
    throw mesh_error(file, "the surface intersects itself (two triangles that share no edge or vertex cross; "
                           "CGAL Polygon_mesh_processing::does_self_intersect): repair the scan first");
  }
}

MassProperties mass_properties(const TriangleMesh& mesh, double density_kg_m3) {
  MassProperties out;
  out.density_kg_m3 = density_kg_m3;
  if (mesh.vertices_m.empty()) return out;
  const Vec3 r = bounding_box(mesh).centre();
  double volume = 0.0;
  Vec3 first{};                           // integral of (x - r) dV
  std::array<Vec3, 3> second{};           // integral of (x - r)(x - r)^T dV
  for (const auto& tri : mesh.triangles) {
    const Vec3 u = sub(mesh.vertices_m[tri[0]], r);
    const Vec3 v = sub(mesh.vertices_m[tri[1]], r);
    const Vec3 w = sub(mesh.vertices_m[tri[2]], r);
    const double vol = dot(u, cross(v, w)) / 6.0;  // signed tetrahedron (r, a, b, c)
    volume += vol;
    Vec3 s{};
    for (int i = 0; i < 3; ++i) {
      s[i] = u[i] + v[i] + w[i];
      first[i] += vol * s[i] / 4.0;
    }
    // Tonon 2005 eq 2 / Eberly 2002: integral x_i x_j = V/20 [sum_k p_k,i p_k,j + (sum_k p_k,i)(sum_k p_k,j)],
    // the fourth vertex r being the origin.
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) {
        second[i][j] += vol / 20.0 * (u[i] * u[j] + v[i] * v[j] + w[i] * w[j] + s[i] * s[j]);
      }
    }
  }
  out.volume_m3 = volume;
  out.mass_kg = density_kg_m3 * volume;
  if (volume == 0.0) return out;
  Vec3 c_rel{};
  for (int i = 0; i < 3; ++i) {
    c_rel[i] = first[i] / volume;
    out.centre_of_mass_m[i] = r[i] + c_rel[i];
  }
  // Second moments about the CM (parallel axis), then I = tr(C) 1 - C.
  std::array<Vec3, 3> c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      c[i][j] = density_kg_m3 * (second[i][j] - volume * c_rel[i] * c_rel[j]);
      c[j][i] = c[i][j];
    }
  }
  const double trace = c[0][0] + c[1][1] + c[2][2];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out.inertia_cm_kg_m2[i][j] = (i == j ? trace : 0.0) - c[i][j];
  }
  return out;
}

SupportPolygon support_polygon(const TriangleMesh& mesh, double base_tolerance_fraction, const std::string& file) {
  check_base_tolerance(base_tolerance_fraction);
  const Box box = bounding_box(mesh);
  SupportPolygon out;
  out.z_m = box.lo[2];
  out.tolerance_m = base_tolerance_fraction * box.largest_extent();
  std::vector<std::array<double, 2>> contact;
  for (const auto& p : mesh.vertices_m) {
    if (p[2] <= out.z_m + out.tolerance_m) contact.push_back({p[0], p[1]});
  }
  out.contact_vertices = contact.size();
  out.hull_xy_m = detail::convex_hull_2d(contact);
  if (out.hull_xy_m.size() < 3) {
    throw mesh_error(file, fmt::format("the body rests on {} ({} vertices within {:.3g} m of its lowest point z = "
                                       "{:.9g} m): it cannot stand. Level the mesh so that it sits on its base, or "
                                       "widen the contact with --base-tolerance (a fraction of its size)",
                                       out.hull_xy_m.size() <= 1 ? "a single point" : "a line (an edge)",
                                       out.contact_vertices, out.tolerance_m, out.z_m));
  }
  return out;
}

PlanarBody planar_body(const MassProperties& mass, const SupportPolygon& support, double azimuth_deg, double g_m_s2,
                       const std::string& file) {
  check_azimuth_and_g(azimuth_deg, g_m_s2);
  const auto& c = mass.centre_of_mass_m;
  const auto& hull = support.hull_xy_m;
  // The CM must project strictly inside the support polygon (more than the contact tolerance from every edge; the
  // hull is counter-clockwise, so inside is to the left of each edge).
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& p = hull[i];
    const auto& q = hull[(i + 1) % hull.size()];
    const double ex = q[0] - p[0], ey = q[1] - p[1];
    const double left = (ex * (c[1] - p[1]) - ey * (c[0] - p[0])) / std::hypot(ex, ey);
    if (!(left > support.tolerance_m)) {
      throw mesh_error(file, fmt::format("the centre of mass ({:.6g}, {:.6g}) m projects {} the support polygon (the "
                                         "edge from ({:.6g}, {:.6g}) to ({:.6g}, {:.6g}) m, {:.3g} m away): the body "
                                         "as meshed is not standing",
                                         c[0], c[1], left < -support.tolerance_m ? "outside" : "onto the edge of",
                                         p[0], p[1], q[0], q[1], std::abs(left)));
    }
  }
  PlanarBody b;
  b.azimuth_deg = std::fmod(azimuth_deg, 360.0);
  if (b.azimuth_deg < 0.0) b.azimuth_deg += 360.0;
  // Reduced exactly (fmod) before radians: any finite azimuth is a direction, and 1e308 deg * pi overflows to inf
  // (a NaN body); within (-360, 360) fmod returns the value itself, so those keep their bits.
  const double phi = deg_to_rad(std::fmod(azimuth_deg, 360.0));
  const Vec3 e{std::sin(phi), std::cos(phi), 0.0};   // clockwise from north (+y), x east
  const Vec3 n{std::cos(phi), -std::sin(phi), 0.0};  // horizontal, perpendicular to the plane: the rocking axis
  const double s = e[0] * c[0] + e[1] * c[1];
  std::size_t rear = 0, front = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const double d = e[0] * hull[i][0] + e[1] * hull[i][1];
    if (d < e[0] * hull[rear][0] + e[1] * hull[rear][1]) rear = i;
    if (d > e[0] * hull[front][0] + e[1] * hull[front][1]) front = i;
  }
  b.b1_m = s - (e[0] * hull[rear][0] + e[1] * hull[rear][1]);
  b.b2_m = (e[0] * hull[front][0] + e[1] * hull[front][1]) - s;
  b.pivot1_m = {hull[rear][0], hull[rear][1], support.z_m};
  b.pivot2_m = {hull[front][0], hull[front][1], support.z_m};
  b.h_m = c[2] - support.z_m;
  const auto& I = mass.inertia_cm_kg_m2;
  double icm = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) icm += n[i] * I[i][j] * n[j];
  }
  b.inertia_cm_kg_m2 = icm;
  const double m = mass.mass_kg;
  b.r1_m = std::hypot(b.b1_m, b.h_m);
  b.r2_m = std::hypot(b.b2_m, b.h_m);
  b.alpha1_rad = std::atan2(b.b1_m, b.h_m);
  b.alpha2_rad = std::atan2(b.b2_m, b.h_m);
  b.inertia_o1_kg_m2 = icm + m * b.r1_m * b.r1_m;
  b.inertia_o2_kg_m2 = icm + m * b.r2_m * b.r2_m;
  b.d1_m2 = b.inertia_o1_kg_m2 / m;
  b.d2_m2 = b.inertia_o2_kg_m2 / m;
  b.p1_rad_s = std::sqrt(g_m_s2 * b.r1_m / b.d1_m2);
  b.p2_rad_s = std::sqrt(g_m_s2 * b.r2_m / b.d2_m2);
  b.b_sym_m = (b.b1_m + b.b2_m) / 2;
  b.r_sym_m = std::hypot(b.b_sym_m, b.h_m);
  b.alpha_sym_rad = std::atan2(b.b_sym_m, b.h_m);
  b.d_sym_m2 = icm / m + b.r_sym_m * b.r_sym_m;
  b.p_sym_rad_s = std::sqrt(g_m_s2 * b.r_sym_m / b.d_sym_m2);
  return b;
}

MeshBody mesh_body(const TriangleMesh& mesh, const BodyOptions& options, const std::string& file) {
  check_body_options(options);
  check_mesh(mesh, file);
  MeshBody out;
  if (options.pose == PoseMethod::as_scanned) {
    out.mass = mass_properties(mesh, options.density_kg_m3);
    out.support = support_polygon(mesh, options.base_tolerance_fraction, file);
    out.planar = planar_body(out.mass, out.support, options.azimuth_deg, options.g_m_s2, file);
    out.pose.method = PoseMethod::as_scanned;
    out.pose.chosen_by = "as-scanned";
    out.pose.contact_tolerance_m = out.support.tolerance_m;
    out.pose.overturning = static_overturning(out.support.hull_xy_m,
                                              {out.mass.centre_of_mass_m[0], out.mass.centre_of_mass_m[1]},
                                              out.planar.h_m);
    return out;
  }
  // At rest (bodies/pose.hpp): the stable hull face chosen, the mesh levelled onto it, the support polygon that
  // face's (not a fraction of the mesh's size).
  const Vec3 centre = mass_properties(mesh, 1.0).centre_of_mass_m;
  RestedMesh rested = rest_mesh(mesh, centre, options, file);
  out.mass = mass_properties(rested.mesh, options.density_kg_m3);
  out.support.z_m = 0.0;
  out.support.tolerance_m = rested.pose.contact_tolerance_m;
  out.support.contact_vertices = rested.face.contact_vertices;
  out.support.hull_xy_m = rested.face.polygon_xy_m;
  out.planar = planar_body(out.mass, out.support, options.azimuth_deg, options.g_m_s2, file);
  out.pose = std::move(rested.pose);
  return out;
}

RockingBody rocking_body(const MeshBody& body) {
  const PlanarBody& b = body.planar;
  return RockingBody::general_asymmetric(b.b1_m, b.b2_m, b.h_m, b.inertia_cm_kg_m2 / body.mass.mass_kg);
}

}  // namespace topple
