// topple/bodies/pose.hpp: the resting pose of a mesh on a level base against geometry worked by hand: a box at any
// pose and offset comes back to the box; a box tilted by a known angle rests on the face the geometry says, with that
// tilt; a leaning prism whose base is unstable rests on its one stable slanted face; the options are checked; the
// as-scanned pose is the earlier pipeline bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/meshes.hpp"
#include "topple/bodies/body.hpp"
#include "topple/bodies/pose.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "support/shared_data.hpp"
#include "topple/ensemble/sweep.hpp"
#include "topple/io/mesh.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/io/sweep_file.hpp"

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

// ---- The listing does not depend on the order of the mesh's vertices and triangles (CGAL's hull gives its facets in
// an order of its own; a symmetric body has many facets of equal area): the same faces in the same order. The caps'
// coplanar points are triangulated by the hull as their order falls, so a cap's normal (a sum over its facets) may
// differ by a rounding: 1e-15.
/// `mesh` with its vertices renumbered (i -> (7 i + 3) mod n) and its triangles listed backwards, each from its second
/// corner: the same solid, given to CGAL in another order.
TriangleMesh reordered(const TriangleMesh& mesh) {
  TriangleMesh shuffled;
  const std::size_t n = mesh.vertices_m.size();
  EXPECT_EQ(std::gcd(n, std::size_t{7}), 1u);
  for (std::size_t i = 0; i < n; ++i) shuffled.vertices_m.push_back(mesh.vertices_m[(i * 7 + 3) % n]);
  std::vector<std::uint32_t> where(n);  // old index -> new index
  for (std::size_t i = 0; i < n; ++i) where[(i * 7 + 3) % n] = static_cast<std::uint32_t>(i);
  for (auto it = mesh.triangles.rbegin(); it != mesh.triangles.rend(); ++it) {
    shuffled.triangles.push_back({where[(*it)[1]], where[(*it)[2]], where[(*it)[0]]});
  }
  return shuffled;
}

// The faces and the resting body depend on the solid, not on the order of its vertices and triangles, to the bit:
// CGAL's hull (and its triangulation of a planar region) follows the input order and its handles' addresses, so the
// face normals are taken from each face's points alone (pose.cpp, canonical_normal). Before that, the example rock's
// body differed by an ulp from one run of the same test to the next.
TEST(PoseFaces, ListingIsIndependentOfTheMeshOrder) {
  const TriangleMesh prism = test::prism_mesh(test::regular_polygon(12, 0.5), 1.0);
  const TriangleMesh shuffled = reordered(prism);
  const Vec3 c = mass_properties(prism, 1.0).centre_of_mass_m;
  const auto a = resting_faces(prism, c, kIdentityQuaternion, 1e-3);
  const auto b = resting_faces(shuffled, c, kIdentityQuaternion, 1e-3);
  ASSERT_EQ(a.size(), 14u);  // 12 sides, the base and the top
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].normal, b[i].normal) << i;
    EXPECT_EQ(a[i].h_m, b[i].h_m) << i;
    EXPECT_NEAR(a[i].area_m2, b[i].area_m2, 1e-15) << i;
    EXPECT_EQ(a[i].contact_vertices, b[i].contact_vertices) << i;
    EXPECT_EQ(a[i].stable, b[i].stable) << i;
  }
  EXPECT_EQ(a.front().tilt_deg, 0.0);  // the base: its points share their z, so its normal is exactly -z
}

TEST(PoseFaces, TheExampleRockRestsTheSameInAnyOrder) {
  // The same centre of mass for both (the mass sums follow the triangles' order, by design: rounding only), so that
  // what is compared is the hull's faces.
  const auto rock = std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "mesh" / "balanced_rock.obj";
  const TriangleMesh mesh = io::read_mesh(rock.string(), 1.0);
  const Vec3 c = mass_properties(mesh, 1.0).centre_of_mass_m;
  const auto a = resting_faces(mesh, c, kIdentityQuaternion, 1e-3);
  const auto b = resting_faces(reordered(mesh), c, kIdentityQuaternion, 1e-3);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.front().tilt_deg, 0.0);  // the rock's flat base (examples/mesh/make_rock.py): level, exactly
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i].stable) continue;
    EXPECT_EQ(a[i].normal, b[i].normal) << i;
    EXPECT_EQ(a[i].h_m, b[i].h_m) << i;
    EXPECT_EQ(a[i].polygon_xy_m, b[i].polygon_xy_m) << i;
  }
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

// ---- Surveys: an old file (no pose keys) rests the mesh; mesh_pose = "as-scanned" is the earlier body bit for bit,
// on the example's scanned rock and on a tilted box (which, as scanned, stands on a point and is refused, as
// before); the pose keys reach the pipeline and their errors name the key.
std::string survey_text(const std::string& mesh, const std::string& keys) {
  return "[site]\nname = \"t\"\n\n[inversion]\npga_g = [0.05, 2.0, 20]\nfreq_hz = [0.3, 10.0, 12]\n\n[[object]]\nid = \"r\"\n"
         "mesh = \"" + mesh + "\"\nmesh_azimuth_deg = 90\nmu = 0.7\noutcome = \"not_overturned\"\n" + keys;
}

Survey survey_of(const test::TempDir& dir, const std::string& text) {
  test::write_file(dir.path() / "s.toml", text);
  return io::read_survey(dir.path() / "s.toml");
}

void expect_same_body(const RockingBody& a, const RockingBody& b) {
  EXPECT_EQ(a.pivot_b_m(-1), b.pivot_b_m(-1));
  EXPECT_EQ(a.pivot_b_m(1), b.pivot_b_m(1));
  EXPECT_EQ(a.h_m, b.h_m);
  EXPECT_EQ(a.pivot_D_m2(-1), b.pivot_D_m2(-1));
  EXPECT_EQ(a.pivot_D_m2(1), b.pivot_D_m2(1));
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.where().field + ": " + e.what();
  }
  return "accepted";
}

TEST(PoseSurvey, OldFilesRestAndAsScannedIsTheEarlierBody) {
  test::TempDir dir;
  const std::string rock = (std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "mesh" / "balanced_rock.obj").string();
  BodyOptions old;
  old.azimuth_deg = 90.0;
  old.pose = PoseMethod::as_scanned;
  const TriangleMesh mesh = io::read_mesh(rock, 1.0);
  const MassProperties mass = mass_properties(mesh, old.density_kg_m3);
  const PlanarBody p = planar_body(mass, support_polygon(mesh, 1e-6, rock), 90.0, old.g_m_s2, rock);
  const RockingBody earlier = RockingBody::general_asymmetric(p.b1_m, p.b2_m, p.h_m, p.inertia_cm_kg_m2 / mass.mass_kg);
  const Survey as_scanned = survey_of(dir, survey_text(rock, "mesh_pose = \"as-scanned\"\n"));
  expect_same_body(as_scanned.sites.at(0).objects.at(0).body, earlier);
  BodyOptions rest_options;
  rest_options.azimuth_deg = 90.0;
  const Survey plain = survey_of(dir, survey_text(rock, ""));
  expect_same_body(plain.sites.at(0).objects.at(0).body, rocking_body(io::read_mesh_body(rock, 1.0, rest_options)));

  // A box 1 x 1 x 1.5 m tilted 3 degrees about x and 2 about y stands on a corner as scanned: refused as before.
  const TriangleMesh tilted =
      turned(turned(box_mesh(1.0, 1.0, 1.5), axis_angle_quaternion({1, 0, 0}, 3.0)), axis_angle_quaternion({0, 1, 0}, 2.0));
  test::write_file(dir.path() / "tilted.obj", test::obj_text(tilted));
  const std::string tilted_path = (dir.path() / "tilted.obj").string();
  const std::string refused = error_of([&] { (void)survey_of(dir, survey_text(tilted_path, "mesh_pose = \"as-scanned\"\n")); });
  EXPECT_NE(refused.find("a single point"), std::string::npos) << refused;
  // At rest (the default) it is the box on its base, h = 0.75 (1e-6: the reader's single precision). The minimal
  // rotation undoes the two tilts but for a turn about the vertical of psi = t1 t2 / 2 to second order (two small
  // rotations about x and y compose to one about z of their product's half: 0.0524 x 0.0349 / 2 = 9.14e-4 rad), so
  // along east b = 0.5 (cos psi + sin psi) (1e-5: the third-order terms).
  const RockingBody box = survey_of(dir, survey_text(tilted_path, "")).sites.at(0).objects.at(0).body;
  const double psi = deg_to_rad(3.0) * deg_to_rad(2.0) / 2;
  EXPECT_NEAR(box.pivot_b_m(-1), 0.5 * (std::cos(psi) + std::sin(psi)), 1e-5);
  EXPECT_NEAR(box.pivot_b_m(1), 0.5 * (std::cos(psi) + std::sin(psi)), 1e-5);
  EXPECT_NEAR(box.h_m, 0.75, 1e-6);
  // The keys reach the pipeline: face 2 of the listing is a side (tilt 87-88 degrees), h = 0.5 there.
  const RockingBody side = survey_of(dir, survey_text(tilted_path, "mesh_face = 2\nmesh_contact_tolerance = \"2mm\"\n"))
                               .sites.at(0).objects.at(0).body;
  EXPECT_NEAR(side.h_m, 0.5, 1e-6);
  for (const auto& [keys, key] : std::vector<std::pair<std::string, std::string>>{
           {"mesh_rotation_wxyz = [0, 0, 0, 0]\n", "mesh_rotation_wxyz"},
           {"mesh_up = [0, 0]\n", "mesh_up"},
           {"mesh_up = [0, 0, 0]\n", "mesh_up"},
           {"mesh_axis_angle_deg = [0, 0, 0, 5]\n", "mesh_axis_angle_deg"},
           {"mesh_face = 0\n", "mesh_face"},
           {"mesh_face = 99\n", "mesh_face"},
           {"mesh_contact_tolerance = 2\n", "mesh_contact_tolerance"},
           {"mesh_pose = \"upright\"\n", "mesh_pose"},
           {"mesh_pose = \"as-scanned\"\nmesh_up = [0, 0, 1]\n", "mesh_up"}}) {
    const std::string e = error_of([&] { (void)survey_of(dir, survey_text(tilted_path, keys)); });
    EXPECT_NE(e.find(key), std::string::npos) << keys << " -> " << e;
    EXPECT_NE(e.find("s.toml"), std::string::npos) << keys << " -> " << e;
  }
}

// ---- Sweeps: the same keys with the mesh_ prefix.
TEST(PoseSweep, MeshKeysPoseTheBodies) {
  test::TempDir dir;
  const TriangleMesh tilted = turned(box_mesh(1.0, 1.0, 1.5), axis_angle_quaternion({1, 0, 0}, 3.0));
  test::write_file(dir.path() / "tilted.obj", test::obj_text(tilted));
  const auto sweep = [&](const std::string& keys) {
    test::write_file(dir.path() / "w.toml", "[motions]\n[[motions.pulse]]\nkind = \"sine\"\namp_g = 0.3\nfreq_hz = 2\n\n"
                                            "[[object]]\nmodel = \"rock\"\ne = 0\nmesh = \"tilted.obj\"\nmesh_azimuth_deg = 0\n" + keys);
    return io::read_sweep_file(dir.path() / "w.toml");
  };
  const auto body = [](const io::SweepFile& f) { return std::get<ensemble::RockObject>(f.spec.objects.at(0)).body; };
  // Old file: at rest on the base; along north b = 0.5, h = 0.75; the output says which pose (column mesh_pose).
  const io::SweepFile plain = sweep("");
  EXPECT_NEAR(body(plain).pivot_b_m(1), 0.5, 1e-6);
  EXPECT_NEAR(body(plain).h_m, 0.75, 1e-6);
  EXPECT_EQ(std::get<ensemble::RockObject>(plain.spec.objects.at(0)).mesh_pose, "rest");
  const auto cols = ensemble::make_plan(plain.spec).columns();
  EXPECT_NE(std::find(cols.begin(), cols.end(), "mesh_pose"), cols.end());
  // As scanned it rests on an edge: refused naming the mesh, as before.
  const std::string e = error_of([&] { (void)sweep("mesh_pose = \"as-scanned\"\n"); });
  EXPECT_NE(e.find("a line (an edge)"), std::string::npos) << e;
  // Turned 90 degrees about x first: the nearest stable face is then a side, h = 0.5.
  EXPECT_NEAR(body(sweep("mesh_axis_angle_deg = [1, 0, 0, 87]\nmesh_contact_tolerance_m = 0.002\n")).h_m, 0.5, 1e-6);
  for (const auto& [keys, key] : std::vector<std::pair<std::string, std::string>>{
           {"mesh_rotation_wxyz = [2, 0, 0, 0]\n", "object[1].mesh_rotation_wxyz"},
           {"mesh_up = [1, 2]\n", "object[1].mesh_up"},
           {"mesh_face = 0\n", "object[1].mesh_face"},
           {"mesh_face = 40\n", "object[1].mesh_face"},
           {"mesh_contact_tolerance = \"1 furlong\"\n", "object[1].mesh_contact_tolerance"},
           {"mesh_contact_tolerance_m = 1\n", "object[1].mesh_contact_tolerance_m"},
           {"mesh_pose = \"flat\"\n", "object[1].mesh_pose"}}) {
    try {
      (void)sweep(keys);
      ADD_FAILURE() << keys << " accepted";
    } catch (const InputError& err) {
      EXPECT_EQ(err.where().field, key) << keys << " -> " << err.what();
    }
  }
}

}  // namespace
}  // namespace topple
