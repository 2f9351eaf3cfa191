// The resting poses of a mesh on a level base (bodies/pose.hpp). CGAL's convex_hull_3 and convex_hull_2 (exact
// predicates) are used here; like body_geometry.cpp this file is compiled with -frounding-math.
#include "topple/bodies/pose.hpp"
#include "bodies/body_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <iterator>
#include <limits>
#include <numbers>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using HullMesh = CGAL::Surface_mesh<Kernel::Point_3>;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 scale(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

double azimuth_of(double ex, double ny) {  // of the horizontal direction (ex east, ny north), clockwise from north
  double a = rad_to_deg(std::atan2(ex, ny));
  if (a < 0.0) a += 360.0;
  if (a >= 360.0) a -= 360.0;
  return a;
}


/// Signed distance from c to the nearest edge of the counter-clockwise polygon (> 0 inside).
double inside_margin(const std::vector<std::array<double, 2>>& hull, const std::array<double, 2>& c) {
  double margin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& p = hull[i];
    const auto& q = hull[(i + 1) % hull.size()];
    const double ex = q[0] - p[0], ey = q[1] - p[1];
    margin = std::min(margin, (ex * (c[1] - p[1]) - ey * (c[0] - p[0])) / std::hypot(ex, ey));
  }
  return hull.size() < 3 ? -std::numeric_limits<double>::infinity() : margin;
}

double polygon_area(const std::vector<std::array<double, 2>>& hull) {
  double twice = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& p = hull[i];
    const auto& q = hull[(i + 1) % hull.size()];
    twice += p[0] * q[1] - q[0] * p[1];
  }
  return twice / 2;
}

struct Key {  // a vertex by its bits: the hull's points are copies of the mesh's
  std::array<std::uint64_t, 3> bits;
  bool operator==(const Key&) const = default;
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return static_cast<std::size_t>(k.bits[0] * 0x9E3779B97F4A7C15ull ^ (k.bits[1] + 0x7F4A7C15ull) * 31 ^
                                    k.bits[2] * 0xC2B2AE3D27D4EB4Full);
  }
};

}  // namespace

Vec3 rotate(const Quaternion& q, const Vec3& v) {
  // v' = v + 2 w (u x v) + 2 u x (u x v), u the vector part (the expansion of q v q* for a unit q).
  const Vec3 u{q[1], q[2], q[3]};
  const Vec3 t = scale(cross(u, v), 2.0);
  return add(add(v, scale(t, q[0])), cross(u, t));
}

Quaternion multiply(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

Quaternion axis_angle_quaternion(const Vec3& axis, double angle_deg) {
  const Vec3 u = scale(axis, 1.0 / norm(axis));
  // Reduced exactly (fmod) before radians: 1e308 deg * pi overflows to inf, and a NaN rotation reached CGAL's exact
  // predicates (GMP raised SIGFPE); within (-360, 360) the angle keeps its bits.
  const double half = deg_to_rad(std::fmod(angle_deg, 360.0)) / 2;
  const double s = std::sin(half);
  return {std::cos(half), u[0] * s, u[1] * s, u[2] * s};
}

Quaternion rotation_between(const Vec3& from, const Vec3& to) {
  const Vec3 a = scale(from, 1.0 / norm(from));
  const Vec3 b = scale(to, 1.0 / norm(to));
  const double c = dot(a, b);
  if (c >= 1.0) return kIdentityQuaternion;
  if (c <= -1.0 + 1e-15) {
    // Opposite: half a turn about the axis perpendicular to a nearest +x (or +y when a is along x).
    const Vec3 ref = std::abs(a[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    Vec3 axis = sub(ref, scale(a, dot(ref, a)));
    axis = scale(axis, 1.0 / norm(axis));
    return {0.0, axis[0], axis[1], axis[2]};
  }
  // q = (1 + a.b, a x b) normalised: the rotation by acos(a.b) about a x b (half-angle form).
  const Vec3 x = cross(a, b);
  Quaternion q{1.0 + c, x[0], x[1], x[2]};
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (auto& v : q) v /= n;
  return q;
}

StaticOverturning static_overturning(const std::vector<std::array<double, 2>>& hull,
                                     const std::array<double, 2>& c, double h_m) {
  StaticOverturning out;
  // b(phi) = max_P e . p - e . c: the support function of P about c (pose.hpp).
  auto b_toward = [&](double azimuth_deg) {
    const double phi = deg_to_rad(azimuth_deg);
    const double ex = std::sin(phi), ey = std::cos(phi);
    double best = -std::numeric_limits<double>::infinity();
    for (const auto& p : hull) best = std::max(best, ex * (p[0] - c[0]) + ey * (p[1] - c[1]));
    return best;
  };
  for (int k = 0; k < 4; ++k) out.principal_g[k] = b_toward(90.0 * k) / h_m;
  // The minimum over directions: at an edge's outward normal, the distance from c to that edge's line.
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& p = hull[i];
    const auto& q = hull[(i + 1) % hull.size()];
    const double ex = q[0] - p[0], ey = q[1] - p[1], len = std::hypot(ex, ey);
    const double nx = ey / len, ny = -ex / len;  // outward for a counter-clockwise polygon
    const double d = nx * (p[0] - c[0]) + ny * (p[1] - c[1]);
    if (d < best) {
      best = d;
      out.min_azimuth_deg = azimuth_of(nx, ny);
    }
  }
  out.min_g = best / h_m;
  return out;
}

/// A face's outward unit normal from its contact points alone: the vector area (Newell's method, from the smallest
/// point) of the points in their angular order about their centroid in the plane of `provisional`, oriented as it.
/// The sum of the hull facets' area normals (`provisional`) is the same vector in exact arithmetic, but CGAL
/// triangulates a planar region differently with the input's order and its handles' addresses, and the rounding of
/// that sum then moved h and b by an ulp from run to run. The points are sorted first, so the result depends on the
/// set, not on any order; a level face's points share their z, so its normal comes out exactly vertical.
static Vec3 canonical_normal(std::vector<Vec3>& points, const Vec3& provisional) {
  std::sort(points.begin(), points.end());
  if (points.size() < 3) return provisional;
  Vec3 mean{};
  for (const auto& p : points) mean = add(mean, p);
  mean = scale(mean, 1.0 / static_cast<double>(points.size()));
  // An orthonormal basis (u, v) of the plane: u across the axis least aligned with the normal.
  const int k = std::abs(provisional[0]) <= std::abs(provisional[1])
                    ? (std::abs(provisional[0]) <= std::abs(provisional[2]) ? 0 : 2)
                    : (std::abs(provisional[1]) <= std::abs(provisional[2]) ? 1 : 2);
  Vec3 axis{};
  axis[static_cast<std::size_t>(k)] = 1.0;
  const Vec3 w = cross(provisional, axis);
  const Vec3 u = scale(w, 1.0 / norm(w));
  const Vec3 v = cross(provisional, u);
  std::vector<std::pair<double, std::size_t>> angle(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = sub(points[i], mean);
    angle[i] = {std::atan2(dot(d, v), dot(d, u)), i};
  }
  std::sort(angle.begin(), angle.end());  // ties (points in line with the centroid) by their sorted index
  std::vector<Vec3> ring(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) ring[i] = points[angle[i].second];
  std::rotate(ring.begin(), std::min_element(ring.begin(), ring.end()), ring.end());
  Vec3 area{};
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
    area = add(area, cross(sub(ring[i], ring[0]), sub(ring[i + 1], ring[0])));
  }
  const double n = norm(area);
  if (!(n > 0.0)) return provisional;
  return scale(area, (dot(area, provisional) >= 0.0 ? 1.0 : -1.0) / n);
}

std::vector<RestingFace> resting_faces(const TriangleMesh& mesh, const Vec3& centre, const Quaternion& pre,
                                       double contact_tolerance_m) {
  std::vector<Vec3> turned;
  turned.reserve(mesh.vertices_m.size());
  for (const auto& v : mesh.vertices_m) turned.push_back(add(centre, rotate(pre, sub(v, centre))));

  std::vector<Kernel::Point_3> points;
  points.reserve(turned.size());
  for (const auto& v : turned) points.emplace_back(v[0], v[1], v[2]);
  HullMesh hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);

  auto point_of = [&](HullMesh::Vertex_index v) {
    const auto& p = hull.point(v);
    return Vec3{p.x(), p.y(), p.z()};
  };
  const std::size_t nf = hull.number_of_faces();
  std::vector<HullMesh::Face_index> faces(hull.faces().begin(), hull.faces().end());
  std::vector<std::array<Vec3, 3>> corners(nf);
  std::vector<Vec3> area_normal(nf);  // cross product: twice the area times the unit normal
  std::unordered_map<std::uint32_t, std::size_t> slot;  // face index -> position
  for (std::size_t i = 0; i < nf; ++i) {
    slot[static_cast<std::uint32_t>(faces[i])] = i;
    int k = 0;
    for (auto v : hull.vertices_around_face(hull.halfedge(faces[i]))) {
      if (k < 3) corners[i][k] = point_of(v);
      ++k;
    }
    // The cross product from the smallest corner (a cyclic turn keeps the winding): CGAL starts the facet at whichever
    // halfedge its allocation gave, and the product's last bits depend on the starting corner, so that without this
    // the same mesh gave bodies that differ by an ulp from run to run.
    std::rotate(corners[i].begin(), std::min_element(corners[i].begin(), corners[i].end()), corners[i].end());
    area_normal[i] = cross(sub(corners[i][1], corners[i][0]), sub(corners[i][2], corners[i][0]));
  }
  std::vector<Vec3> hull_points;
  for (auto v : hull.vertices()) hull_points.push_back(point_of(v));
  const double tol = contact_tolerance_m;

  // Merge: seeds by area, largest first; a flood over adjacent facets whose corners lie within tol of the seed plane.
  // The order is made canonical (area, then the facet's corners sorted): CGAL's output order of the facets depends on
  // where its handles were allocated, and equal areas (a symmetric scan) must not leave the seeds to it.
  for (auto& c : corners) std::sort(c.begin(), c.end());  // the normal is already taken from the winding
  std::vector<std::size_t> order(nf);
  for (std::size_t i = 0; i < nf; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double na = norm(area_normal[a]), nb = norm(area_normal[b]);
    if (na != nb) return na > nb;
    return corners[a] < corners[b];
  });
  std::vector<std::size_t> rank(nf);
  for (std::size_t i = 0; i < nf; ++i) rank[order[i]] = i;
  std::vector<long> owner(nf, -1);
  std::vector<RestingFace> out;
  for (std::size_t seed : order) {
    if (owner[seed] >= 0) continue;
    // A facet whose cross product rounds to zero (a sliver of a near-degenerate hull) has no normal to seed a face:
    // it stays out of every face (its corners belong to its neighbours' faces).
    if (!(norm(area_normal[seed]) > 0.0)) continue;
    const long id = static_cast<long>(out.size());
    const Vec3 ns = scale(area_normal[seed], 1.0 / norm(area_normal[seed]));
    const double ds = dot(ns, corners[seed][0]);
    auto near_plane = [&](std::size_t f) {
      return std::all_of(corners[f].begin(), corners[f].end(),
                         [&](const Vec3& p) { return std::abs(ds - dot(ns, p)) <= tol; });
    };
    std::deque<std::size_t> queue{seed};
    owner[seed] = id;
    std::vector<std::size_t> members;
    while (!queue.empty()) {
      const std::size_t f = queue.front();
      queue.pop_front();
      members.push_back(f);
      for (auto h : hull.halfedges_around_face(hull.halfedge(faces[f]))) {
        const auto g = hull.face(hull.opposite(h));
        if (g == HullMesh::null_face()) continue;
        const std::size_t j = slot.at(static_cast<std::uint32_t>(g));
        if (owner[j] < 0 && near_plane(j)) {
          owner[j] = id;
          queue.push_back(j);
        }
      }
    }
    // Summed in the canonical order, so that the face's normal does not depend on the flood's order either.
    std::sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
    Vec3 sum{};
    std::vector<Vec3> contact;
    std::unordered_map<Key, bool, KeyHash> seen;
    for (const std::size_t f : members) {
      sum = add(sum, area_normal[f]);
      for (const auto& p : corners[f]) {
        Key key{};
        std::memcpy(key.bits.data(), p.data(), sizeof(key.bits));
        if (seen.emplace(key, true).second) contact.push_back(p);
      }
    }
    RestingFace face;
    face.normal = canonical_normal(contact, scale(sum, 1.0 / norm(sum)));
    // The angle from -z as atan2(horizontal, vertical): acos(-n_z) is ill-conditioned near 0 (a normal one ulp short of
    // unit length read as 8.5e-7 deg), atan2 gives exactly 0 for a level face and full precision at every angle.
    face.tilt_deg = rad_to_deg(std::atan2(std::hypot(face.normal[0], face.normal[1]), -face.normal[2]));
    double d = -std::numeric_limits<double>::infinity();
    for (const auto& p : hull_points) d = std::max(d, dot(face.normal, p));
    face.h_m = d - dot(face.normal, centre);
    // Levelled by the minimal rotation n -> -z about the CM: the contact points' x, y there.
    const Quaternion level = rotation_between(face.normal, {0.0, 0.0, -1.0});
    std::vector<std::array<double, 2>> xy;
    xy.reserve(contact.size());
    for (const auto& p : contact) {
      const Vec3 q = add(centre, rotate(level, sub(p, centre)));
      xy.push_back({q[0], q[1]});
    }
    face.contact_vertices = contact.size();
    face.contact_m = std::move(contact);
    face.polygon_xy_m = detail::convex_hull_2d(xy);  // body_geometry.hpp: CGAL, exact predicates
    face.area_m2 = polygon_area(face.polygon_xy_m);
    const std::array<double, 2> c_xy{centre[0], centre[1]};  // the CM is the centre of rotation
    face.margin_m = inside_margin(face.polygon_xy_m, c_xy);
    face.stable = face.margin_m > tol;
    if (face.polygon_xy_m.size() >= 3) face.overturning = static_overturning(face.polygon_xy_m, c_xy, face.h_m);
    out.push_back(std::move(face));
  }
  // Numbered by tilt, then by area (largest first), then by the normal (a total order: the listing is reproducible).
  std::sort(out.begin(), out.end(), [](const RestingFace& a, const RestingFace& b) {
    if (a.tilt_deg != b.tilt_deg) return a.tilt_deg < b.tilt_deg;
    if (a.area_m2 != b.area_m2) return a.area_m2 > b.area_m2;
    return a.normal < b.normal;
  });
  for (std::size_t i = 0; i < out.size(); ++i) out[i].number = i + 1;
  return out;
}

Quaternion pre_rotation(const BodyOptions& o) {
  if (o.up) return rotation_between(*o.up, {0.0, 0.0, 1.0});
  if (o.rotation_wxyz) {
    Quaternion q = *o.rotation_wxyz;
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (auto& v : q) v /= n;
    return q;
  }
  if (o.axis_angle_deg) {
    const auto& a = *o.axis_angle_deg;
    return axis_angle_quaternion({a[0], a[1], a[2]}, a[3]);
  }
  return kIdentityQuaternion;
}

double effective_contact_tolerance_m(const TriangleMesh& mesh, double contact_tolerance_m) {
  if (mesh.vertices_m.empty()) return contact_tolerance_m;
  Vec3 lo = mesh.vertices_m.front(), hi = lo;
  for (const auto& p : mesh.vertices_m) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  return std::max(contact_tolerance_m, 1e-9 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}));
}

RestedMesh rest_mesh(const TriangleMesh& mesh, const Vec3& centre, const BodyOptions& options,
                     const std::string& file) {
  const Quaternion pre = pre_rotation(options);
  const double tol = effective_contact_tolerance_m(mesh, options.contact_tolerance_m);
  std::vector<RestingFace> faces = resting_faces(mesh, centre, pre, tol);
  std::size_t stable = 0;
  for (const auto& f : faces) stable += f.stable ? 1 : 0;
  const RestingFace* chosen = nullptr;
  RestedMesh out;
  if (options.face) {
    const std::size_t n = *options.face;
    if (n < 1 || n > faces.size()) {
      throw parameter_error("--face", fmt::format("face {} is not listed: the hull has {} faces (1 to {}; see "
                                                  "--list-faces)",
                                                  n, faces.size(), faces.size()));
    }
    chosen = &faces[n - 1];
    if (!chosen->stable) {
      throw parameter_error(
          "--face", fmt::format("face {} is not stable: the centre of mass projects {:.3g} m {} its support polygon "
                                "(a stable face needs more than the contact tolerance {:.3g} m inside); the stable "
                                "faces are listed by --list-faces",
                                n, std::abs(chosen->margin_m), chosen->margin_m > 0 ? "inside, too near the edge of"
                                                                                    : "outside",
                                tol));
    }
    out.pose.chosen_by = "face number";
  } else {
    for (const auto& f : faces) {  // sorted by tilt: the first stable one is the nearest
      if (f.stable) {
        chosen = &f;
        break;
      }
    }
    if (chosen == nullptr) {
      throw InputError(InputLocation{.file = file, .line = {}, .field = {}},
                       fmt::format("no face of the convex hull is stable within the contact tolerance {:.3g} m "
                                   "({} faces): give a smaller --contact-tolerance",
                                   tol, faces.size()));
    }
    out.pose.chosen_by = options.up ? "nearest up"
                         : (options.rotation_wxyz || options.axis_angle_deg) ? "nearest the rotation"
                                                                              : "nearest the scan";
  }
  const Quaternion level = rotation_between(chosen->normal, {0.0, 0.0, -1.0});
  const Quaternion total = multiply(level, pre);
  // The levelled mesh: turned about the CM (x, y kept) and lowered so that the support plane is z = 0.
  out.mesh.triangles = mesh.triangles;
  out.mesh.vertices_m.reserve(mesh.vertices_m.size());
  const double z0 = centre[2] - chosen->h_m;
  for (const auto& v : mesh.vertices_m) {
    const Vec3 turned = add(centre, rotate(pre, sub(v, centre)));  // as resting_faces turns them
    Vec3 p = add(centre, rotate(level, sub(turned, centre)));
    p[2] -= z0;
    out.mesh.vertices_m.push_back(p);
  }
  out.pose.method = PoseMethod::rest;
  out.pose.rotation_wxyz = total;
  out.pose.face = chosen->number;
  out.pose.tilt_deg = chosen->tilt_deg;
  out.pose.faces = faces.size();
  out.pose.stable_faces = stable;
  out.pose.contact_tolerance_m = tol;
  out.pose.overturning = chosen->overturning;
  out.face = *chosen;
  return out;
}

}  // namespace topple
