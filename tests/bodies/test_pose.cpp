// topple/bodies/pose.hpp: the resting pose of a mesh on a level base against geometry worked by hand: a box at any
// pose and offset comes back to the box; a box tilted by a known angle rests on the face the geometry says, with that
// tilt; a leaning prism whose base is unstable rests on its one stable slanted face; the options are checked; the
// as-scanned pose is the earlier pipeline bit for bit.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/meshes.hpp"
#include "topple/bodies/body.hpp"
#include "topple/bodies/pose.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/io/mesh.hpp"

namespace topple {
namespace {

using test::box_mesh;

/// The brief's bound for a box at any pose: 1e-9 (m, or relative); rounding of a few rotations of coordinates of
/// order 100 m is about 1e-13 m.
constexpr double kTol = 1e-9;

/// The mesh turned by q about the origin, then shifted.
TriangleMesh turned(const TriangleMesh& mesh, const Quaternion& q, const Vec3& shift = {}) {
  TriangleMesh out = mesh;
  for (auto& p : out.vertices_m) {
    const Vec3 r = rotate(q, p);
    p = {r[0] + shift[0], r[1] + shift[1], r[2] + shift[2]};
  }
  return out;
}

Quaternion conjugate(const Quaternion& q) { return {q[0], -q[1], -q[2], -q[3]}; }

MeshBody rest(const TriangleMesh& mesh, double azimuth_deg, BodyOptions o = {}) {
  o.azimuth_deg = azimuth_deg;
  return mesh_body(mesh, o, "rock.obj");
}

// ---- Quaternions against rotations worked by hand.
TEST(PoseRotation, QuaternionsRotateAsStated) {
  const Vec3 x{1, 0, 0};
  const Vec3 y = rotate(axis_angle_quaternion({0, 0, 2}, 90.0), x);  // a quarter turn about +z takes x to y
  EXPECT_NEAR(y[0], 0.0, 1e-15);
  EXPECT_NEAR(y[1], 1.0, 1e-15);
  EXPECT_NEAR(y[2], 0.0, 1e-15);
  // The minimal rotation from a to b is about a x b by the angle between them: (1,0,-1)/sqrt2 to -z is 45 degrees
  // about +y, which takes +x to (cos 45, 0, -sin 45).
  const Quaternion q = rotation_between({1, 0, -1}, {0, 0, -1});
  const Vec3 r = rotate(q, x);
  EXPECT_NEAR(r[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(r[1], 0.0, 1e-15);
  EXPECT_NEAR(r[2], -std::sqrt(0.5), 1e-15);
  // Opposite directions: half a turn about an axis perpendicular to them.
  const Vec3 down = rotate(rotation_between({0, 0, 1}, {0, 0, -1}), {0, 0, 1});
  EXPECT_NEAR(down[2], -1.0, 1e-15);
  // a b applies b first.
  const Quaternion ab = multiply(axis_angle_quaternion({1, 0, 0}, 90), axis_angle_quaternion({0, 0, 1}, 90));
  const Vec3 z = rotate(ab, x);  // x -> y (about z) -> z (about x)
  EXPECT_NEAR(z[2], 1.0, 1e-15);
}

// ---- A box a x b x c (on its a x b face) turned by a known quaternion and moved far from the origin, rested with the
// inverse rotation, is the box again: b1 = b2 = a/2 along x, h = c/2, to 1e-9.
TEST(PoseBox, AnyPoseAndOffsetComesBackToTheBox) {
  const double a = 0.3, b = 0.5, c = 1.2;
  const Quaternion q = axis_angle_quaternion({1.0, -2.0, 3.0}, 123.0);
  const TriangleMesh scan = turned(box_mesh(a, b, c), q, {103.25, -48.5, 7.0});
  BodyOptions o;
  o.rotation_wxyz = conjugate(q);
  for (double az : {90.0, 0.0}) {
    const MeshBody body = rest(scan, az, o);
    const double half = az == 90.0 ? a / 2 : b / 2;
    EXPECT_NEAR(body.planar.b1_m, half, kTol);
    EXPECT_NEAR(body.planar.b2_m, half, kTol);
    EXPECT_NEAR(body.planar.h_m, c / 2, kTol);
    EXPECT_NEAR(body.pose.tilt_deg, 0.0, 1e-6);
    EXPECT_EQ(body.pose.chosen_by, "nearest the rotation");
    // The rotation used is q's inverse (up to sign).
    const double sign = body.pose.rotation_wxyz[0] * q[0] > 0 ? 1.0 : -1.0;
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(sign * body.pose.rotation_wxyz[k], conjugate(q)[k], 1e-12);
    // Static overturning: b / h toward north is (b/2)/(c/2), toward east (a/2)/(c/2); the least is the narrow side.
    EXPECT_NEAR(body.pose.overturning.principal_g[0], b / c, kTol);
    EXPECT_NEAR(body.pose.overturning.principal_g[1], a / c, kTol);
    EXPECT_NEAR(body.pose.overturning.principal_g[2], b / c, kTol);
    EXPECT_NEAR(body.pose.overturning.principal_g[3], a / c, kTol);
    EXPECT_NEAR(body.pose.overturning.min_g, a / c, kTol);
    const double az_min = body.pose.overturning.min_azimuth_deg;
    EXPECT_TRUE(std::abs(az_min - 90.0) < 1e-6 || std::abs(az_min - 270.0) < 1e-6) << az_min;
    EXPECT_EQ(body.pose.faces, 6u);
    EXPECT_EQ(body.pose.stable_faces, 6u);
    EXPECT_EQ(body.support.contact_vertices, 4u);
  }
  // The same with the axis-angle form, and with the up direction (q's +z): the up direction leaves a turn about the
  // vertical free, so only what does not depend on it is the box's: h and the least b / h.
  BodyOptions aa;
  aa.axis_angle_deg = std::array<double, 4>{1.0, -2.0, 3.0, -123.0};
  EXPECT_NEAR(rest(scan, 90.0, aa).planar.b1_m, a / 2, kTol);
  BodyOptions up;
  up.up = rotate(q, {0, 0, 1});
  const MeshBody by_up = rest(scan, 90.0, up);
  EXPECT_NEAR(by_up.planar.h_m, c / 2, kTol);
  EXPECT_NEAR(by_up.pose.overturning.min_g, a / c, kTol);
  EXPECT_EQ(by_up.pose.chosen_by, "nearest up");
}

// ---- A box tilted by 20 degrees about a horizontal axis (the scan's pose) rests on its base, tilted 20 degrees
// from the scan; the minimal rotation that levels it undoes the tilt exactly (no turn about the vertical), so the
// box's x is east again: b1 = b2 = a/2 at azimuth 90.
TEST(PoseTilted, RestsOnTheFaceTheGeometrySays) {
  const double a = 0.4, b = 0.6, c = 1.0;
  const TriangleMesh box = box_mesh(a, b, c);
  const Quaternion tilt20 = axis_angle_quaternion({1.0, 1.0, 0.0}, 20.0);
  const MeshBody small = rest(turned(box, tilt20, {5.0, 6.0, -2.0}), 90.0);
  EXPECT_NEAR(small.pose.tilt_deg, 20.0, 1e-9);
  EXPECT_EQ(small.pose.face, 1u);
  EXPECT_EQ(small.pose.chosen_by, "nearest the scan");
  EXPECT_NEAR(small.planar.b1_m, a / 2, kTol);
  EXPECT_NEAR(small.planar.b2_m, a / 2, kTol);
  EXPECT_NEAR(small.planar.h_m, c / 2, kTol);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(small.pose.rotation_wxyz[k], conjugate(tilt20)[k], 1e-12);
  // Tilted 60 degrees about +x: the base's normal is 60 degrees from down, the -y side's 30: it lies on that side
  // (b x c... the a x c face), 30 degrees from the scan, with h = b/2 and x still east.
  const MeshBody far = rest(turned(box, axis_angle_quaternion({1.0, 0.0, 0.0}, 60.0)), 90.0);
  EXPECT_NEAR(far.pose.tilt_deg, 30.0, 1e-9);
  EXPECT_NEAR(far.planar.h_m, b / 2, kTol);
  EXPECT_NEAR(far.planar.b1_m, a / 2, kTol);
  EXPECT_NEAR(far.planar.b2_m, a / 2, kTol);
  EXPECT_NEAR(rest(turned(box, axis_angle_quaternion({1.0, 0.0, 0.0}, 60.0)), 0.0).planar.b1_m, c / 2, kTol);
}

// ---- A leaning prism (cross-section (0,0), (0.2,0), (1.2,1), (1,1) in x-z, 0.5 deep in y): its base (tilt 0) is
// unstable (the CM, x = 0.6, is past the base's x in [0, 0.2]), and so is the top (x in [1, 1.2]); the stable faces
// are the two slanted sides (the CM projects 0.9/sqrt2 and 1.1/sqrt2 along them, of sqrt2) and the two ends (the CM
// is inside the cross-section). The nearest stable one is the slanted side from (0.2, 0) to (1.2, 1), outward normal
// (1, 0, -1)/sqrt2, 45 degrees from down. Levelled by the turn of 45 degrees about +y the
// face's upward direction becomes +x; the CM (0.6, 0.5) is 0.9/sqrt2 along the face from its lower end and
// 0.1/sqrt2 from its plane: b1 = 0.9/sqrt2, b2 = sqrt2 - 0.9/sqrt2 = 1.1/sqrt2, h = 0.1/sqrt2 at azimuth 90; the
// least b / h is the half depth 0.25 over h, toward north or south.
TEST(PoseLeaning, OnlyStableFaceIsNotTheNearest) {
  const TriangleMesh lean = test::xz_prism_mesh({{0, 0}, {0.2, 0}, {1.2, 1}, {1.0, 1}}, 0.5);
  const MeshBody body = rest(lean, 90.0);
  const double r2 = std::sqrt(2.0);
  EXPECT_NEAR(body.pose.tilt_deg, 45.0, 1e-9);
  EXPECT_NEAR(body.planar.h_m, 0.1 / r2, kTol);
  EXPECT_NEAR(body.planar.b1_m, 0.9 / r2, kTol);
  EXPECT_NEAR(body.planar.b2_m, 1.1 / r2, kTol);
  EXPECT_NEAR(body.pose.overturning.min_g, 0.25 / (0.1 / r2), 1e-9);
  EXPECT_EQ(body.pose.stable_faces, 4u);
  EXPECT_EQ(body.pose.faces, 6u);
  const std::vector<RestingFace> faces =
      resting_faces(lean, mass_properties(lean, 1.0).centre_of_mass_m, kIdentityQuaternion, 1e-3);
  ASSERT_EQ(faces.size(), 6u);
  EXPECT_NEAR(faces[0].tilt_deg, 0.0, 1e-12);
  EXPECT_FALSE(faces[0].stable);
  EXPECT_NEAR(faces[0].margin_m, -0.4, 1e-12);  // CM x 0.6, base edge x 0.2
  EXPECT_NEAR(faces[0].area_m2, 0.2 * 0.5, 1e-12);
  EXPECT_NEAR(faces[1].tilt_deg, 45.0, 1e-9);
  EXPECT_TRUE(faces[1].stable);
  EXPECT_NEAR(faces[1].area_m2, std::sqrt(2.0) * 0.5, 1e-12);
  EXPECT_NEAR(faces[2].tilt_deg, 90.0, 1e-9);  // the two ends
  EXPECT_TRUE(faces[2].stable);
  EXPECT_NEAR(faces[3].tilt_deg, 90.0, 1e-9);
  EXPECT_TRUE(faces[3].stable);
  EXPECT_NEAR(faces[4].tilt_deg, 135.0, 1e-9);
  EXPECT_TRUE(faces[4].stable);
  EXPECT_NEAR(faces[5].tilt_deg, 180.0, 1e-9);  // the top: its x in [1, 1.2], the CM's 0.6
  EXPECT_FALSE(faces[5].stable);
  // Asking for the unstable base by number is refused, naming --face.
  BodyOptions o;
  o.face = 1;
  try {
    (void)rest(lean, 90.0, o);
    FAIL() << "an unstable face was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "--face");
    EXPECT_NE(std::string(e.what()).find("not stable"), std::string::npos) << e.what();
  }
  o.face = 2;
  EXPECT_NEAR(rest(lean, 90.0, o).planar.h_m, 0.1 / r2, kTol);
  EXPECT_EQ(rest(lean, 90.0, o).pose.chosen_by, "face number");
}

// ---- A scan whose base is rough at the sub-millimetre scale: one base corner 0.5 mm low. At the 1 mm contact
// tolerance the base is one face (four contact points), as if flat; at 0.1 mm it is not, and the body rests on a
// face tilted by the corner's drop over the diagonal.
TEST(PoseTolerance, ContactToleranceIsALength) {
  TriangleMesh box = box_mesh(0.5, 0.5, 1.0);
  for (auto& p : box.vertices_m) {
    if (p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0) p[2] = -0.5e-3;
  }
  const MeshBody rough = rest(box, 90.0);
  EXPECT_EQ(rough.support.contact_vertices, 4u);
  EXPECT_LT(rough.pose.tilt_deg, 0.1);
  BodyOptions fine;
  fine.contact_tolerance_m = 1e-4;
  const MeshBody exact = rest(box, 90.0, fine);
  EXPECT_EQ(exact.support.contact_vertices, 3u);
  EXPECT_GT(exact.pose.tilt_deg, 0.01);
}

// ---- Options refused, each naming the option.
void expect_option_refused(const BodyOptions& o, const std::string& field, const std::string& words) {
  try {
    check_body_options(o);
    FAIL() << "accepted; expected " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, field) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(PoseOptions, BadOnesAreRefusedNamingTheOption) {
  BodyOptions o;
  o.rotation_wxyz = Quaternion{0, 0, 0, 0};
  expect_option_refused(o, "--rotation", "unit quaternion");
  o = {};
  o.rotation_wxyz = Quaternion{1, 1, 0, 0};  // norm sqrt2: not a rotation as written
  expect_option_refused(o, "--rotation", "unit quaternion");
  o = {};
  o.up = Vec3{0, 0, 0};
  expect_option_refused(o, "--up", "not a direction");
  o = {};
  o.axis_angle_deg = std::array<double, 4>{0, 0, 0, 30};
  expect_option_refused(o, "--axis-angle", "axis");
  o = {};
  o.face = 0;
  expect_option_refused(o, "--face", "start at 1");
  o = {};
  o.contact_tolerance_m = -1e-3;
  expect_option_refused(o, "--contact-tolerance", "[0, 0.1] m");
  o = {};
  o.up = Vec3{0, 0, 1};
  o.face = 2;
  expect_option_refused(o, "--up", "not several");
  o = {};
  o.pose = PoseMethod::as_scanned;
  o.rotation_wxyz = kIdentityQuaternion;
  expect_option_refused(o, "--rotation", "as-scanned");
  // A face number beyond the listing: refused when the faces are known.
  o = {};
  o.face = 7;
  try {
    (void)rest(box_mesh(1, 1, 1), 0.0, o);
    FAIL() << "face 7 of a box accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "--face");
    EXPECT_NE(std::string(e.what()).find("6 faces"), std::string::npos) << e.what();
  }
}

// ---- As scanned: the earlier pipeline (support_polygon at the base tolerance, planar_body) bit for bit, on the
// example's scanned rock and on a tilted mesh that stands on its lowest corner region.
void expect_as_scanned_is_old(const TriangleMesh& mesh, double base_tolerance_fraction) {
  BodyOptions o;
  o.pose = PoseMethod::as_scanned;
  o.azimuth_deg = 90.0;
  o.base_tolerance_fraction = base_tolerance_fraction;
  const MeshBody now = mesh_body(mesh, o, "rock.obj");
  const MassProperties mass = mass_properties(mesh, o.density_kg_m3);
  const SupportPolygon support = support_polygon(mesh, base_tolerance_fraction, "rock.obj");
  const PlanarBody old = planar_body(mass, support, 90.0, o.g_m_s2, "rock.obj");
  EXPECT_EQ(now.planar.b1_m, old.b1_m);
  EXPECT_EQ(now.planar.b2_m, old.b2_m);
  EXPECT_EQ(now.planar.h_m, old.h_m);
  EXPECT_EQ(now.planar.inertia_cm_kg_m2, old.inertia_cm_kg_m2);
  EXPECT_EQ(now.planar.p1_rad_s, old.p1_rad_s);
  EXPECT_EQ(now.support.hull_xy_m, support.hull_xy_m);
  EXPECT_EQ(now.mass.centre_of_mass_m, mass.centre_of_mass_m);
  EXPECT_EQ(now.pose.method, PoseMethod::as_scanned);
  EXPECT_FALSE(now.pose.face.has_value());
  EXPECT_EQ(now.pose.rotation_wxyz, kIdentityQuaternion);
}

TEST(PoseAsScanned, IsTheEarlierAnswerBitForBit) {
  const auto rock = std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "mesh" / "balanced_rock.obj";
  expect_as_scanned_is_old(io::read_mesh(rock.string(), 1.0), 1e-6);
  // A box tilted 3 degrees: as scanned it needs a wide base tolerance to stand (4% of its size takes in the low
  // edge's neighbourhood); at rest it lies on its base, 3 degrees from the scan.
  const TriangleMesh tilted = turned(box_mesh(1.0, 1.0, 1.5), axis_angle_quaternion({1, 0, 0}, 3.0));
  expect_as_scanned_is_old(tilted, 0.04);
  EXPECT_NEAR(rest(tilted, 90.0).pose.tilt_deg, 3.0, 1e-9);
}

}  // namespace
}  // namespace topple
