// topple/bodies/body.hpp: mass properties of closed meshes against closed forms (box, regular prism, cylinder, L-prism,
// wedge), the support polygon, the planar body (b1, b2, h, alpha, I_O, p), its invariance under rigid motions, and
// the refusal of meshes that are not solids.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/meshes.hpp"
#include "topple/bodies/body.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

using test::box_mesh;
using test::prism_mesh;
using test::regular_polygon;

constexpr double kG = 9.80665;
constexpr double kRho = 2700.0;
/// The sums are exact for a polyhedron; what remains is rounding over a few hundred terms: 1e-9 relative is the
/// brief's bound and leaves six orders of magnitude for rounding (measured: below 1e-14 on these meshes).
constexpr double kRel = 1e-9;

void expect_rel(double actual, double expected, double rel = kRel, double scale = 0.0) {
  EXPECT_NEAR(actual, expected, rel * std::max(std::abs(expected), scale)) << "expected " << expected;
}

MeshBody body_of(const TriangleMesh& mesh, double azimuth_deg) {
  BodyOptions o;
  o.azimuth_deg = azimuth_deg;
  o.density_kg_m3 = kRho;
  o.g_m_s2 = kG;
  return mesh_body(mesh, o, "test.obj");
}

/// The expected planar body from b1, b2, h, m and the CM inertia about the rocking axis (the definitions in
/// body.hpp, written out independently of the code).
void expect_planar(const PlanarBody& p, double b1, double b2, double h, double m, double icm) {
  const double scale = std::max({b1, b2, h});
  expect_rel(p.b1_m, b1, kRel, scale);
  expect_rel(p.b2_m, b2, kRel, scale);
  expect_rel(p.h_m, h);
  expect_rel(p.alpha1_rad, std::atan(b1 / h));
  expect_rel(p.alpha2_rad, std::atan(b2 / h));
  const double r1 = std::sqrt(b1 * b1 + h * h), r2 = std::sqrt(b2 * b2 + h * h);
  expect_rel(p.r1_m, r1);
  expect_rel(p.r2_m, r2);
  expect_rel(p.inertia_cm_kg_m2, icm);
  expect_rel(p.inertia_o1_kg_m2, icm + m * r1 * r1);
  expect_rel(p.inertia_o2_kg_m2, icm + m * r2 * r2);
  expect_rel(p.p1_rad_s, std::sqrt(m * kG * r1 / (icm + m * r1 * r1)));
  expect_rel(p.p2_rad_s, std::sqrt(m * kG * r2 / (icm + m * r2 * r2)));
  expect_rel(p.b_sym_m, (b1 + b2) / 2);
}

// ---- Box a x b x c: V = abc, CM at the centre, I = m diag(b^2 + c^2, a^2 + c^2, a^2 + b^2) / 12.
TEST(BodyMass, BoxClosedForms) {
  const double a = 0.3, b = 0.2, c = 0.9;
  const auto mp = mass_properties(box_mesh(a, b, c), kRho);
  const double m = kRho * a * b * c;
  expect_rel(mp.volume_m3, a * b * c);
  expect_rel(mp.mass_kg, m);
  expect_rel(mp.centre_of_mass_m[0], a / 2);
  expect_rel(mp.centre_of_mass_m[1], b / 2);
  expect_rel(mp.centre_of_mass_m[2], c / 2);
  const double ixx = m * (b * b + c * c) / 12, iyy = m * (a * a + c * c) / 12, izz = m * (a * a + b * b) / 12;
  expect_rel(mp.inertia_cm_kg_m2[0][0], ixx);
  expect_rel(mp.inertia_cm_kg_m2[1][1], iyy);
  expect_rel(mp.inertia_cm_kg_m2[2][2], izz);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != j) {
        EXPECT_NEAR(mp.inertia_cm_kg_m2[i][j], 0.0, kRel * izz) << i << j;
      }
    }
  }
}

// A box is the rectangular block of the rocking engine (rocking.hpp): D = (4/3)(a^2 + h^2) about a base edge
// (thesis eq 3.14), p = sqrt(g R / D) = sqrt(3 g / (4 R)).
TEST(BodyPlanar, BoxIsTheRockingBlock) {
  const double a = 0.3, b = 0.2, c = 0.9;
  const auto r = body_of(box_mesh(a, b, c), 90.0);  // e = +x (east)
  const double m = kRho * a * b * c;
  expect_planar(r.planar, a / 2, a / 2, c / 2, m, m * (a * a + c * c) / 12);
  const double half_a = a / 2, half_c = c / 2, big_r = std::hypot(half_a, half_c);
  expect_rel(r.planar.alpha1_rad, std::atan(half_a / half_c));
  expect_rel(r.planar.d1_m2, 4.0 / 3.0 * big_r * big_r);
  expect_rel(r.planar.p1_rad_s, std::sqrt(3 * kG / (4 * big_r)));
  // Along y (azimuth 0 and 180), the depth b is the base.
  const auto n = body_of(box_mesh(a, b, c), 180.0);
  expect_planar(n.planar, b / 2, b / 2, c / 2, m, m * (b * b + c * c) / 12);
  EXPECT_EQ(r.support.hull_xy_m.size(), 4u);
  EXPECT_EQ(r.support.contact_vertices, 4u);
}

// ---- Regular n-gon prism, circumradius r, height H (exact closed forms of the polyhedron):
//   A = (n/2) r^2 sin(t), t = 2 pi / n;  J = integral of (x^2 + y^2) dA = (n r^4 / 12) sin(t) (2 + cos(t))
//   (n triangles (0, p, q) with |p| = |q| = r: A_t (|p|^2 + |q|^2 + p.q) / 6); the section's second moment is
//   isotropic for n >= 3, so I_xx = I_yy = m (J / (2A) + H^2 / 12), I_zz = m J / A.
struct PrismForms {
  double volume, ixx, izz;
};
PrismForms ngon_prism(int n, double r, double height) {
  const double t = 2.0 * kPi / n;
  const double area = n / 2.0 * r * r * std::sin(t);
  const double j = n * std::pow(r, 4) / 12.0 * std::sin(t) * (2.0 + std::cos(t));
  const double m = kRho * area * height;
  return {area * height, m * (j / (2 * area) + height * height / 12), m * j / area};
}

TEST(BodyMass, RegularPrismClosedForms) {
  for (int n : {3, 5, 8, 64, 257}) {
    SCOPED_TRACE(n);
    const double r = 0.25, height = 1.1;
    const auto mp = mass_properties(prism_mesh(regular_polygon(n, r), height), kRho);
    const auto f = ngon_prism(n, r, height);
    expect_rel(mp.volume_m3, f.volume);
    // The centroid of a regular polygon is its centre: |c_xy| against the size r.
    EXPECT_NEAR(mp.centre_of_mass_m[0], 0.0, kRel * r);
    EXPECT_NEAR(mp.centre_of_mass_m[1], 0.0, kRel * r);
    expect_rel(mp.centre_of_mass_m[2], height / 2);
    expect_rel(mp.inertia_cm_kg_m2[0][0], f.ixx);
    expect_rel(mp.inertia_cm_kg_m2[1][1], f.ixx);
    expect_rel(mp.inertia_cm_kg_m2[2][2], f.izz);
  }
}

// The 64-gon prism's planar body against the exact prism forms to 1e-9, and against the solid cylinder (the rocking
// engine's cylinder, rocking.hpp: D = (15 a^2 + 16 h^2) / 12, thesis eq 3.13) within the discretisation error: the inscribed polygon's area is
// pi r^2 (1 - t^2/6 + O(t^4)) and its J / A is (r^2 / 2)(1 - t^2/6 + O(t^4)), t = 2 pi / n, so V, I and p differ
// from the cylinder's by at most t^2 / 6 relative (the bound used, 1.6e-3 at n = 64), and by a factor of 4 less at
// n = 128 (second order).
TEST(BodyPlanar, PolygonPrismAndCylinder) {
  const double r = 0.25, height = 1.1;
  std::vector<double> p_errors;
  for (int n : {64, 128}) {
    SCOPED_TRACE(n);
    const auto body = body_of(prism_mesh(regular_polygon(n, r), height), 90.0);  // e = +x: vertices at x = +-r
    const auto f = ngon_prism(n, r, height);
    const double m = kRho * f.volume;
    expect_planar(body.planar, r, r, height / 2, m, f.ixx);
    const double t = 2.0 * kPi / n;
    const double bound = t * t / 6.0;
    const double h = height / 2, cyl_d = (15 * r * r + 16 * h * h) / 12, cyl_r = std::hypot(r, h);
    const double v_cyl = kPi * r * r * height;
    EXPECT_LE(std::abs(body.mass.volume_m3 / v_cyl - 1.0), bound);
    EXPECT_GE(std::abs(body.mass.volume_m3 / v_cyl - 1.0), 0.9 * bound);  // it is the discretisation, not noise
    EXPECT_LE(std::abs(body.planar.d1_m2 / cyl_d - 1.0), bound);
    EXPECT_DOUBLE_EQ(body.planar.alpha1_rad, std::atan(r / h));  // same b = r and h: the same angle
    const double p_err = std::abs(body.planar.p1_rad_s / std::sqrt(kG * cyl_r / cyl_d) - 1.0);
    EXPECT_LE(p_err, bound);
    p_errors.push_back(p_err);
  }
  // Second order: doubling n divides the error by 4 (to within the O(t^4) terms: 3.9 to 4.1).
  EXPECT_NEAR(p_errors[0] / p_errors[1], 4.0, 0.1);
}

// ---- An L-shaped prism: footprint [0,2]x[0,1] plus [0,1]x[1,2] (m), height H. Composite of two boxes (parallel
// axis theorem by hand): area 3, centroid (5/6, 5/6). Along +x: b1 = 5/6, b2 = 2 - 5/6 = 7/6 (the hull's extremes
// are x = 0 and x = 2).
std::vector<std::array<double, 2>> l_footprint() {
  // Starts at the reflex corner (1, 1), from which the whole L is visible (the caps are fans from it).
  return {{1, 1}, {1, 2}, {0, 2}, {0, 0}, {2, 0}, {2, 1}};
}

TEST(BodyPlanar, LShapedPrismIsAsymmetric) {
  const double height = 3.0;
  const auto body = body_of(prism_mesh(l_footprint(), height), 90.0);
  // Box A: [0,2]x[0,1]x[0,H], mass mA, centre (1, 0.5); box B: [0,1]x[1,2]x[0,H], mass mB, centre (0.5, 1.5).
  const double mA = kRho * 2 * height, mB = kRho * 1 * height, m = mA + mB;
  const double cx = (mA * 1.0 + mB * 0.5) / m, cy = (mA * 0.5 + mB * 1.5) / m;
  expect_rel(body.mass.mass_kg, m);
  expect_rel(body.mass.centre_of_mass_m[0], cx);
  expect_rel(body.mass.centre_of_mass_m[1], cy);
  // Rocking axis n = (0, -1, 0) at azimuth 90: I about y through the CM.
  const double iyy = mA * (4 + height * height) / 12 + mA * (1.0 - cx) * (1.0 - cx) + mB * (1 + height * height) / 12 +
                     mB * (0.5 - cx) * (0.5 - cx);
  expect_planar(body.planar, cx, 2.0 - cx, height / 2, m, iyy);
  EXPECT_GT(body.planar.b2_m - body.planar.b1_m, 0.3);  // 7/6 - 5/6 = 1/3: truly asymmetric
  // The product of inertia: I_xy = -integral (x - cx)(y - cy) dm, by parts.
  const double ixy = -(mA * (1.0 - cx) * (0.5 - cy) + mB * (0.5 - cx) * (1.5 - cy));
  expect_rel(body.mass.inertia_cm_kg_m2[0][1], ixy);
  // The hull is the L's hull: the reflex corner (1, 1) is not on it.
  EXPECT_EQ(body.support.hull_xy_m.size(), 5u);
  // The diagonal plane (azimuth 45): e = (1, 1)/sqrt 2; extremes at (0, 0) and at the hull's edge (2,1)-(1,2).
  const auto diag = body_of(prism_mesh(l_footprint(), height), 45.0);
  const double s = (cx + cy) / std::sqrt(2.0);
  const double n_icm = (body.mass.inertia_cm_kg_m2[0][0] + body.mass.inertia_cm_kg_m2[1][1]) / 2 -
                       body.mass.inertia_cm_kg_m2[0][1];  // n = (1, -1)/sqrt 2: n^T I n
  expect_planar(diag.planar, s, 3.0 / std::sqrt(2.0) - s, height / 2, m, n_icm);
}

// ---- A wedge: cross-section the right triangle (0,0), (L,0), (0,H) in the (x, z) plane, width W along y. CM at
// (L/3, W/2, H/3); about the y axis through the CM, I = m (L^2 + H^2) / 18 (the triangle's polar moment about its
// centroid per unit area). Along +x: b1 = L/3, b2 = 2L/3, h = H/3.
TEST(BodyPlanar, WedgeIsAsymmetric) {
  const double L = 0.6, H = 0.9, W = 0.4;
  const auto body = body_of(test::xz_prism_mesh({{0, 0}, {L, 0}, {0, H}}, W), 90.0);
  const double m = kRho * L * H / 2 * W;
  expect_rel(body.mass.volume_m3, L * H / 2 * W);
  expect_rel(body.mass.centre_of_mass_m[0], L / 3);
  expect_rel(body.mass.centre_of_mass_m[1], W / 2);
  expect_rel(body.mass.centre_of_mass_m[2], H / 3);
  expect_planar(body.planar, L / 3, 2 * L / 3, H / 3, m, m * (L * L + H * H) / 18);
  // Azimuth 270 looks the other way: the pivots swap.
  const auto back = body_of(test::xz_prism_mesh({{0, 0}, {L, 0}, {0, H}}, W), 270.0);
  expect_planar(back.planar, 2 * L / 3, L / 3, H / 3, m, m * (L * L + H * H) / 18);
}

// ---- Rigid motions: the mesh rotated by psi about a vertical axis and translated gives, in the plane at azimuth
// phi - psi (a counter-clockwise turn lowers the azimuth), the same planar body. Tolerance: 1e-9 relative to the
// body's size, the coordinates being of order 100 m after the shift (rounding 1e-14 relative of those).
TEST(BodyPlanar, RotatedAndTranslatedCopyIsTheSameBody) {
  const TriangleMesh l = prism_mesh(l_footprint(), 3.0);
  for (double phi : {0.0, 45.0, 90.0, 200.0}) {
    for (double psi : {37.0, -90.0, 123.4}) {
      SCOPED_TRACE(testing::Message() << "phi " << phi << " psi " << psi);
      const auto a = body_of(l, phi).planar;
      const auto b = body_of(test::rotated_z(l, psi, {103.25, -48.5, 7.0}), phi - psi).planar;
      const double tol = kRel * 3.0;
      EXPECT_NEAR(b.b1_m, a.b1_m, tol);
      EXPECT_NEAR(b.b2_m, a.b2_m, tol);
      EXPECT_NEAR(b.h_m, a.h_m, tol);
      expect_rel(b.alpha1_rad, a.alpha1_rad);
      expect_rel(b.alpha2_rad, a.alpha2_rad);
      expect_rel(b.inertia_o1_kg_m2, a.inertia_o1_kg_m2);
      expect_rel(b.inertia_o2_kg_m2, a.inertia_o2_kg_m2);
      expect_rel(b.p1_rad_s, a.p1_rad_s);
      expect_rel(b.p2_rad_s, a.p2_rad_s);
    }
  }
}

TEST(BodyPlanar, AzimuthIsNormalised) {
  const auto a = body_of(box_mesh(0.3, 0.2, 0.9), -90.0).planar;
  EXPECT_DOUBLE_EQ(a.azimuth_deg, 270.0);
  const auto b = body_of(box_mesh(0.3, 0.2, 0.9), 450.0).planar;
  EXPECT_NEAR(b.azimuth_deg, 90.0, 1e-12);
}

// The density scales the mass and the inertia, not alpha or p.
TEST(BodyPlanar, DensityScalesOutOfRocking) {
  BodyOptions o;
  o.azimuth_deg = 90.0;
  o.density_kg_m3 = 1000.0;
  const auto light = mesh_body(prism_mesh(l_footprint(), 3.0), o, "l.obj");
  o.density_kg_m3 = 3000.0;
  const auto heavy = mesh_body(prism_mesh(l_footprint(), 3.0), o, "l.obj");
  expect_rel(heavy.mass.mass_kg, 3 * light.mass.mass_kg);
  expect_rel(heavy.planar.inertia_o2_kg_m2, 3 * light.planar.inertia_o2_kg_m2);
  expect_rel(heavy.planar.p1_rad_s, light.planar.p1_rad_s);
  expect_rel(heavy.planar.alpha2_rad, light.planar.alpha2_rad);
}

// ---- Refusals: each names the file and says what is wrong.
void expect_refused(const TriangleMesh& mesh, const std::string& words, const BodyOptions& o = {}) {
  try {
    (void)mesh_body(mesh, o, "scan.stl");
    FAIL() << "accepted; expected an InputError saying '" << words << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "scan.stl") << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(BodyRefuses, EmptyMesh) { expect_refused(TriangleMesh{}, "no triangles"); }

TEST(BodyRefuses, OpenMesh) {
  TriangleMesh m = box_mesh(1, 1, 1);
  m.triangles.pop_back();
  expect_refused(m, "not closed");
}

TEST(BodyRefuses, InconsistentOrientation) {
  TriangleMesh m = box_mesh(1, 1, 1);
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  expect_refused(m, "not consistently oriented");
}

TEST(BodyRefuses, InsideOut) { expect_refused(test::inverted(box_mesh(1, 1, 1)), "inside out"); }

TEST(BodyRefuses, DegenerateTriangles) {
  TriangleMesh m = box_mesh(1, 1, 1);
  m.triangles[0][1] = m.triangles[0][0];  // a repeated vertex
  expect_refused(m, "degenerate");
  TriangleMesh sliver = box_mesh(1, 1, 1);
  sliver.vertices_m.push_back({0.5, 0.0, 0.0});  // on the edge from vertex 1 to vertex 2: zero area
  sliver.triangles.push_back({0, 1, static_cast<std::uint32_t>(sliver.vertices_m.size() - 1)});
  expect_refused(sliver, "degenerate");
}

TEST(BodyRefuses, DuplicateFace) {
  TriangleMesh m = box_mesh(1, 1, 1);
  m.triangles.push_back({m.triangles[5][0], m.triangles[5][2], m.triangles[5][1]});
  expect_refused(m, "duplicate face");
}

TEST(BodyRefuses, SelfIntersection) {
  // Two closed, outward boxes that overlap, in one mesh: closed, oriented and of positive volume, but not a solid.
  TriangleMesh m = box_mesh(1, 1, 1);
  const TriangleMesh other = test::rotated_z(box_mesh(1, 1, 1), 30.0, {0.5, 0.25, 0.25});
  const auto offset = static_cast<std::uint32_t>(m.vertices_m.size());
  for (const auto& p : other.vertices_m) m.vertices_m.push_back(p);
  for (auto t : other.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  expect_refused(m, "intersects itself");
}

TEST(BodyRefuses, NonManifoldVertex) {
  // Two tetrahedra touching at one vertex (the origin).
  TriangleMesh m;
  m.vertices_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  // The second is the first reflected through the origin (det -1), so its windings are reversed to face out.
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  expect_refused(m, "two separate sheets");
}

TEST(BodyRefuses, NonFiniteAndAbsurdSizes) {
  TriangleMesh nan = box_mesh(1, 1, 1);
  nan.vertices_m[3][2] = std::nan("");
  expect_refused(nan, "not a finite number");
  expect_refused(box_mesh(2000, 1000, 3000), "check --unit");      // a scan in mm read as metres
  expect_refused(box_mesh(1e-4, 1e-4, 2e-4), "check --unit");      // 0.2 mm across
  expect_refused(test::rotated_z(box_mesh(1, 1, 1), 0.0, {2e4, 0, 0}), "from the origin");
}

TEST(BodyRefuses, RestingOnAnEdgeOrAPoint) {
  // A box turned 45 degrees about x rests on its bottom edge along x: the contact points are collinear.
  TriangleMesh edge = box_mesh(1, 1, 1);
  const double c = std::sqrt(0.5);
  for (auto& p : edge.vertices_m) p = {p[0], c * p[1] - c * p[2], c * p[1] + c * p[2]};
  BodyOptions as_scanned;
  as_scanned.pose = PoseMethod::as_scanned;  // the lowest plane as given (at rest, the body lies on a face)
  expect_refused(edge, "a line (an edge)", as_scanned);
  // A tetrahedron standing on a vertex.
  TriangleMesh tip;
  tip.vertices_m = {{0, 0, 0}, {1, 0, 1}, {-0.5, 0.8, 1}, {-0.5, -0.8, 1}};
  tip.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
  expect_refused(test::inverted(tip), "a single point", as_scanned);  // as listed the faces point in: inverted to face out
}

TEST(BodyRefuses, CentreOfMassOutsideTheBase) {
  // A leaning parallelepiped: base x in [0, 0.2], top x in [1.0, 1.2]; its CM (x = 0.6) is far past the base.
  // As scanned (at rest it lies on its slanted face: tests/bodies/test_pose.cpp).
  BodyOptions as_scanned;
  as_scanned.pose = PoseMethod::as_scanned;
  expect_refused(test::xz_prism_mesh({{0, 0}, {0.2, 0}, {1.2, 1}, {1.0, 1}}, 0.5), "not standing", as_scanned);
}

TEST(BodyRefuses, BadOptions) {
  BodyOptions o;
  o.density_kg_m3 = -1.0;
  EXPECT_THROW(check_body_options(o), InputError);
  o = {};
  o.azimuth_deg = std::nan("");
  EXPECT_THROW(check_body_options(o), InputError);
  o = {};
  o.base_tolerance_fraction = 0.5;
  EXPECT_THROW(check_body_options(o), InputError);
  o = {};
  o.g_m_s2 = 0.0;
  EXPECT_THROW(check_body_options(o), InputError);
  EXPECT_NO_THROW(check_body_options(BodyOptions{}));
}

}  // namespace
}  // namespace topple
