#pragma once
// A rigid body from a closed triangle mesh (a 3-D scan of a rock or a museum object), and the planar body it gives
// in a chosen vertical plane: the two pivots, the height of the centre of mass, the inertia about each pivot.
//
// Axes. The mesh's axes are taken as x east, y north, z up (metres; io/mesh.hpp converts other units).
//
// Pose (BodyOptions::pose). By default (PoseMethod::rest) the body rests on the stable face of its convex hull
// nearest the scanned pose (or nearest a given up direction or rotation, or a face chosen by number), levelled onto
// it by the minimal rotation (bodies/pose.hpp); the support polygon is that face's, and every quantity below is of
// the levelled mesh. PoseMethod::as_scanned is the earlier behaviour, bit for bit: the body stands on its lowest
// plane z = z_min of the mesh as given, with the contact points within base_tolerance_fraction of its size.
//
// Mass properties (exact for the polyhedron, up to rounding). Each triangle (a, b, c), wound counter-clockwise seen
// from outside, closes with a reference point r (the bounding-box centre, to limit cancellation) a signed
// tetrahedron (r, a, b, c); with u = a - r, v = b - r, w = c - r:
//   V_t = u . (v x w) / 6                                          (signed volume)
//   integral of x dV over it      = V_t (u + v + w) / 4
//   integral of x_i x_j dV over it = V_t / 20 [ sum_k u_k,i u_k,j + (sum_k u_k,i)(sum_k u_k,j) ]   (k over u, v, w)
// Summed over the triangles these are the integrals over the solid (the divergence theorem: Mirtich 1996, "Fast and
// accurate computation of polyhedral mass properties", J. Graphics Tools 1(2); the tetrahedron sums are Tonon 2005,
// "Explicit exact formulas for the 3-D tetrahedron inertia tensor in terms of its vertex coordinates", J. Math.
// Stat. 1(1), eq 2, and Eberly 2002, "Polyhedral mass properties (revisited)"). With the uniform density rho:
//   m = rho V,  c = (integral of x dV) / V,  C = rho (integral of x x^T dV) - m (c - r)(c - r)^T  (about the CM),
//   I_cm = tr(C) 1 - C  (the inertia tensor about the centre of mass, kg m^2).
//
// Support polygon (as scanned). The vertices with z <= z_min + tol (tol = base_tolerance_fraction times the largest extent of the
// mesh's bounding box) are the contact points; their 2-D convex hull (CGAL's convex_hull_2, exact predicates) is the
// support polygon. A body whose contact points are one point or collinear (a rock on a point or on an edge) is
// refused: it cannot stand in 3-D (neutral at best). A body whose centre of mass does not project strictly inside
// the support polygon (more than tol from every edge) is refused: it is not standing.
//
// Planar body. The vertical plane of shaking at azimuth phi (degrees clockwise from north) has the horizontal unit
// direction e = (sin phi, cos phi, 0) and the normal n = (cos phi, -sin phi, 0) (the rocking axis). With s = e . c
// the CM's coordinate along e, and the support polygon's extremes along e:
//   b1 = s - min_P (e . P)   (pivot 1, the rear corner, on the -e side; the body overturns toward -e about it)
//   b2 = max_P (e . P) - s   (pivot 2, the front corner, on the +e side; the body overturns toward +e about it)
//   h = c_z - z_min,  R_i = sqrt(b_i^2 + h^2),  alpha_i = atan(b_i / h),
//   I_Oi = n^T I_cm n + m R_i^2   (the axis through pivot i along n; parallel-axis theorem),
//   p_i = sqrt(m g R_i / I_Oi)   (Housner 1963's frequency parameter about pivot i),  D_i = I_Oi / m.
// b1 and b2 need not be equal. The symmetric equivalent (b1 + b2) / 2 with the same h and inertia about the CM is
// given for information: it is the `rock --shape general` body (a, h, D) of the symmetric rocking engine. Using b1,
// b2 themselves needs the asymmetric rocking engine (not part of this unit).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "topple/bodies/rocking_body.hpp"

namespace topple {

using Vec3 = std::array<double, 3>;

/// A triangle mesh as read: vertices (m, x east, y north, z up) and triangles (indices into vertices, wound
/// counter-clockwise seen from outside).
struct TriangleMesh {
  std::vector<Vec3> vertices_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// The file's coordinates (m) of the point vertices_m are measured from: io::read_mesh recentres a file on its
  /// bounding box's centre before any arithmetic, so that a georeferenced scan (UTM-size coordinates) keeps double
  /// precision; zero for a mesh built in memory.
  Vec3 origin_m{};
};

/// The limits a mesh must keep (check_mesh). A mesh outside them is refused as bad input, never computed on.
struct MeshLimits {
  static constexpr std::size_t max_triangles = 10'000'000;  ///< a 1 mm scan of a 2 m rock is about 10^7 triangles
  static constexpr double min_extent_m = 1e-3;              ///< largest bounding-box side: 1 mm ...
  static constexpr double max_extent_m = 1e3;               ///< ... to 1 km
  static constexpr double max_abs_coordinate_m = 1e4;       ///< |x|, |y|, |z| of every vertex
  /// A triangle is degenerate when its area is below this fraction of L^2 (L the largest extent): a sliver that
  /// makes the normal and the intersection tests meaningless. 1e-12 L^2 is a 1e-6 L by 1e-6 L triangle.
  static constexpr double degenerate_area_fraction = 1e-12;
};

/// Checks that `mesh` is a closed, consistently oriented, outward-facing solid (throws InputError naming `file`,
/// with the first offending triangle or edge, 1-based vertex numbers and coordinates):
///   not empty; every coordinate finite and within MeshLimits; the bounding box within MeshLimits; no triangle
///   repeating a vertex or of zero area (degenerate_area_fraction); no duplicate triangle (same three vertices);
///   every edge shared by exactly two triangles that traverse it in opposite directions (closed, edge-manifold,
///   consistently oriented); every vertex manifold; positive signed volume (an inverted mesh is refused with the
///   hint to flip its faces, not flipped silently); no two non-adjacent triangles intersecting (CGAL's
///   Polygon_mesh_processing::does_self_intersect).
void check_mesh(const TriangleMesh& mesh, const std::string& file);

/// Volume, mass, centre of mass and inertia of a uniform solid bounded by `mesh` (the sums in the header; no checks:
/// call check_mesh first).
struct MassProperties {
  double volume_m3 = 0.0;
  double density_kg_m3 = 0.0;
  double mass_kg = 0.0;
  Vec3 centre_of_mass_m{};
  std::array<Vec3, 3> inertia_cm_kg_m2{};  ///< about the CM, along x, y, z (symmetric)
};
[[nodiscard]] MassProperties mass_properties(const TriangleMesh& mesh, double density_kg_m3);

/// The contact points on the lowest plane and their convex hull.
struct SupportPolygon {
  double z_m = 0.0;                               ///< the lowest plane, z_min
  double tolerance_m = 0.0;                       ///< vertices with z <= z_m + tolerance_m are in contact
  std::size_t contact_vertices = 0;               ///< how many vertices that is
  std::vector<std::array<double, 2>> hull_xy_m;   ///< the convex hull, counter-clockwise seen from above
};

/// The contact points of `mesh` and their convex hull (CGAL convex_hull_2). Throws InputError naming `file` when they
/// are fewer than 3 or collinear (the body rests on a point or an edge).
[[nodiscard]] SupportPolygon support_polygon(const TriangleMesh& mesh, double base_tolerance_fraction,
                                             const std::string& file);

/// The planar rocking body in the vertical plane at `azimuth_deg` (definitions in the header).
struct PlanarBody {
  double azimuth_deg = 0.0;          ///< of the plane's +e direction, clockwise from north, in [0, 360)
  double h_m = 0.0;                  ///< height of the CM above the support plane
  double b1_m = 0.0, b2_m = 0.0;     ///< CM to the rear (-e) and the front (+e) pivot, along e
  double r1_m = 0.0, r2_m = 0.0;     ///< CM to each pivot, in the plane
  double alpha1_rad = 0.0, alpha2_rad = 0.0;  ///< atan(b_i / h)
  double inertia_cm_kg_m2 = 0.0;     ///< about the horizontal axis n through the CM
  double inertia_o1_kg_m2 = 0.0, inertia_o2_kg_m2 = 0.0;  ///< about the axis n through each pivot
  double p1_rad_s = 0.0, p2_rad_s = 0.0;  ///< sqrt(m g R_i / I_Oi)
  double d1_m2 = 0.0, d2_m2 = 0.0;   ///< I_Oi / m
  Vec3 pivot1_m{}, pivot2_m{};       ///< a support-polygon vertex at each extreme (on the support plane)
  // The symmetric equivalent, for information: b = (b1 + b2) / 2, same h and I_cm (`rock --shape general`).
  double b_sym_m = 0.0, r_sym_m = 0.0, alpha_sym_rad = 0.0, d_sym_m2 = 0.0, p_sym_rad_s = 0.0;
};

/// How the body is posed on the base (bodies/pose.hpp).
enum class PoseMethod {
  rest,        ///< on a stable face of the convex hull, levelled (the default)
  as_scanned,  ///< on the lowest plane of the mesh as given (the earlier behaviour)
};

/// A unit quaternion (w, x, y, z), w the scalar part: v -> q v q*.
using Quaternion = std::array<double, 4>;
inline constexpr Quaternion kIdentityQuaternion{1.0, 0.0, 0.0, 0.0};

/// What `topple body` computes.
struct BodyOptions {
  double azimuth_deg = 0.0;                 ///< plane of shaking, clockwise from north; any finite value
  double density_kg_m3 = 2700.0;            ///< uniform; 2700 kg/m^3 is granite (typical of balanced rocks)
  double base_tolerance_fraction = 1e-6;    ///< as-scanned only: contact tolerance / largest extent, in [0, 0.1]
  double g_m_s2 = 9.80665;
  PoseMethod pose = PoseMethod::rest;
  /// rest only: hull facets within this distance of a face's plane are one face; its contact points (bodies/pose.hpp)
  /// in [0, 0.1] m. 1 mm: the resolution of a photogrammetry or lidar scan of a boulder-size object, and the scale
  /// of the roughness a rock and a shake table's top leave between them; a floor of 1e-9 x the mesh's size holds
  /// coplanar facets together against rounding.
  double contact_tolerance_m = 1e-3;
  std::optional<Vec3> up;                          ///< rest: this mesh direction becomes +z (non-zero)
  std::optional<Quaternion> rotation_wxyz;         ///< rest: turn the mesh by this unit quaternion first
  std::optional<std::array<double, 4>> axis_angle_deg;  ///< rest: or by this rotation (axis x, y, z; angle deg)
  std::optional<std::size_t> face;                 ///< rest: the face of this number (1-based) in the listing
};

/// Checks the options before any work: density in (0, 1e5] kg/m^3, azimuth finite, g positive and finite, base
/// tolerance in [0, 0.1], contact tolerance in [0, 0.1] m, up finite and non-zero, the quaternion finite and of unit
/// norm within 1e-3 (it is normalised), the axis finite and non-zero and the angle finite, the face >= 1; at most
/// one of up, rotation, axis-angle and face; none of them with the as-scanned pose. Throws InputError naming the
/// option (--density, --azimuth, --g, --base-tolerance, --contact-tolerance, --up, --rotation, --axis-angle,
/// --face, --pose).
void check_body_options(const BodyOptions& options);

/// The static overturning accelerations of a body on its support polygon (bodies/pose.hpp): b / h per direction.
struct StaticOverturning {
  double min_g = 0.0;            ///< min over all directions of b / h
  double min_azimuth_deg = 0.0;  ///< the direction the body tips toward there, clockwise from north, [0, 360)
  std::array<double, 4> principal_g{};  ///< b / h toward north (azimuth 0), east (90), south (180), west (270)
};

/// The pose mesh_body used.
struct Pose {
  PoseMethod method = PoseMethod::rest;
  /// What chose it: "nearest the scan", "nearest up", "nearest the rotation", "face number", "as-scanned".
  std::string chosen_by;
  Quaternion rotation_wxyz = kIdentityQuaternion;  ///< mesh as given -> as rested, about the CM
  std::optional<std::size_t> face;                 ///< the face's number in the listing (none as-scanned)
  double tilt_deg = 0.0;           ///< of that face from the (pre-rotated) scan's -z; 0 as-scanned
  double contact_tolerance_m = 0.0;  ///< used (the floor applied); as-scanned: the base tolerance in metres
  std::size_t faces = 0, stable_faces = 0;  ///< in the listing (0 as-scanned)
  StaticOverturning overturning;            ///< of the support polygon used
};

/// The planar body of a checked solid: refuses (InputError naming `file`) a CM outside the support polygon.
[[nodiscard]] PlanarBody planar_body(const MassProperties& mass, const SupportPolygon& support, double azimuth_deg,
                                     double g_m_s2, const std::string& file);

/// Everything for one mesh.
struct MeshBody {
  MassProperties mass;     ///< of the mesh as posed
  SupportPolygon support;
  PlanarBody planar;
  Pose pose;
};

/// check_mesh, the pose (rest_mesh of bodies/pose.hpp, or as scanned), mass_properties, support_polygon (as
/// scanned; at rest the face's polygon) and planar_body in turn. Throws InputError naming `file` (the mesh)
/// or the option (--density, --azimuth, --base-tolerance, --g) that is wrong.
[[nodiscard]] MeshBody mesh_body(const TriangleMesh& mesh, const BodyOptions& options, const std::string& file);

/// The asymmetric rocking body (rocking.hpp) of a mesh's planar body, +x toward the azimuth: pivot 1 (the rear) is
/// O- (b1, theta < 0), pivot 2 is O+ (b2), inertia k2 = I_cm / m about the rocking axis through the CM, so that
/// RockingBody::general_asymmetric(b1, b2, h, k2) gives D- = I_O1 / m and D+ = I_O2 / m (parallel axes). This is
/// the body `topple body` prints as a `rock --shape general --b1 --b2 --h --inertia` command, and the body a survey
/// or a sweep object with `mesh = "..."` rocks as. Independent of the density (every term is per unit mass).
[[nodiscard]] RockingBody rocking_body(const MeshBody& body);

}  // namespace topple
