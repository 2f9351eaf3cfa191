#pragma once
// The static resting poses of a rigid body on a level base, from its mesh (a 3-D scan), and the rotations that
// bring it there.
//
// A rigid body on a flat rigid base touches it on its convex hull: it rests on a face of the hull (a planar facet,
// or several coplanar ones), and it is in static equilibrium there when the vertical through its centre of mass
// meets the face's polygon strictly inside (the classic stability condition of a polyhedron on a plane: e.g.
// Moll and Erdmann 2002, "Manipulation of pose distributions", IJRR 21(3); Varkonyi and Domokos 2006, "Static
// equilibria of rigid bodies: dice, pebbles and the Poincare-Hopf theorem", J. Nonlinear Sci. 16).
//
// Faces. The hull is CGAL's convex_hull_3 (exact predicates) of the mesh's vertices; its triangular facets are
// merged into planar faces: from the largest facet not yet in a face, the adjacent facets whose three vertices all
// lie within the contact tolerance (a length) of the seed facet's plane join it. The face's outward unit normal n is
// the area-weighted mean of its facets' normals; its support plane is n . x = d, d = max over the hull's vertices
// of n . x (the whole body lies on one side); its contact points are its facets' vertices.
//
// Stability and static overturning. Levelled onto the base (n to -z), the face's contact points give the support
// polygon P (their 2-D convex hull) and the centre of mass c projects to c_xy, at the height h = d - n . c above
// it. The face is stable when c_xy lies inside P by more than the contact tolerance (the polygon's edges are only
// known to it). The static acceleration that tips the body toward the horizontal direction e (azimuth phi,
// clockwise from north, e = (sin phi, cos phi)) about P's edge on that side is (rigid body, no sliding; the
// quasi-static limit of Housner 1963, BSSA 53(2), a_static = g tan(alpha) = g b / h):
//   a(phi) / g = b(phi) / h,   b(phi) = max_{p in P} e . p - e . c_xy   (the support function of P about c_xy).
// Its minimum over all directions is the smallest distance from c_xy to an edge of P over h, at that edge's
// outward normal.
//
// Rotations. Quaternions are (w, x, y, z), w the scalar part, rotating a vector v as q v q*. The rotation that
// levels a face is the minimal rotation taking its outward normal n to -z (about the horizontal axis n x (-z), by
// the angle between them; 180 degrees about +x when n = +z): it turns no more than needed, so the mesh's x east,
// y north keep their meaning for a face near the scan's base. All rotations turn the mesh about its centre of
// mass; the levelled mesh keeps the centre of mass's x, y and has its support plane at z = 0.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "topple/bodies/body.hpp"

namespace topple {

/// q v q* for a unit quaternion q.
[[nodiscard]] Vec3 rotate(const Quaternion& q, const Vec3& v);
/// The product a b (apply b, then a).
[[nodiscard]] Quaternion multiply(const Quaternion& a, const Quaternion& b);
/// The rotation by angle_deg about `axis` (any non-zero length; right-handed).
[[nodiscard]] Quaternion axis_angle_quaternion(const Vec3& axis, double angle_deg);
/// The minimal rotation taking the direction `from` to the direction `to` (both non-zero; 180 degrees about the
/// axis perpendicular to `from` nearest +x, or +y, when they are opposite).
[[nodiscard]] Quaternion rotation_between(const Vec3& from, const Vec3& to);

/// The static overturning accelerations of the polygon `hull_xy` (counter-clockwise) with the centre of mass at
/// `c_xy`, h above it.
[[nodiscard]] StaticOverturning static_overturning(const std::vector<std::array<double, 2>>& hull_xy,
                                                   const std::array<double, 2>& c_xy, double h_m);

/// One planar face of the convex hull.
struct RestingFace {
  std::size_t number = 0;   ///< 1-based, in the listing (by tilt, then by area, largest first)
  Vec3 normal{};            ///< outward unit normal, in the coordinates the faces were found in
  double tilt_deg = 0.0;    ///< angle between `normal` and -z
  double area_m2 = 0.0;     ///< of the support polygon
  bool stable = false;      ///< the CM projects inside the polygon by more than the contact tolerance
  double margin_m = 0.0;    ///< signed distance from the CM's projection to the nearest edge (> 0 inside)
  double h_m = 0.0;         ///< height of the CM above the face's plane
  std::size_t contact_vertices = 0;
  std::vector<Vec3> contact_m;                   ///< the contact points, in the faces' coordinates
  std::vector<std::array<double, 2>> polygon_xy_m;  ///< support polygon once levelled (counter-clockwise)
  StaticOverturning overturning;                 ///< once levelled (azimuths in the levelled mesh)
};

/// The hull's faces of the mesh turned by `pre_rotation` about `centre_m` (faces in those turned coordinates),
/// merged within `contact_tolerance_m` (as given: effective_contact_tolerance_m applies the floor), numbered by tilt. No checks (mesh_body checks the mesh first).
[[nodiscard]] std::vector<RestingFace> resting_faces(const TriangleMesh& mesh, const Vec3& centre_m,
                                                     const Quaternion& pre_rotation, double contact_tolerance_m);

/// The contact tolerance used: the given one, at least 1e-9 x the mesh's largest bounding-box extent (rounding).
[[nodiscard]] double effective_contact_tolerance_m(const TriangleMesh& mesh, double contact_tolerance_m);

/// The rotation applied before the faces are found: the identity, the minimal rotation taking `up` to +z, the
/// given quaternion (normalised), or the axis-angle. Assumes checked options.
[[nodiscard]] Quaternion pre_rotation(const BodyOptions& options);

/// The mesh at rest (PoseMethod::rest): the faces of the pre-rotated mesh, the chosen stable face, and the mesh
/// levelled onto it (CM x, y kept, support plane z = 0). Throws parameter_error("--face") for a face number that is
/// not listed or not stable, InputError naming `file` when no face is stable.
struct RestedMesh {
  TriangleMesh mesh;
  Pose pose;
  RestingFace face;   ///< in the pre-rotated coordinates; its polygon_xy_m in the levelled ones
};
[[nodiscard]] RestedMesh rest_mesh(const TriangleMesh& mesh, const Vec3& centre_m, const BodyOptions& options,
                                   const std::string& file);

}  // namespace topple
