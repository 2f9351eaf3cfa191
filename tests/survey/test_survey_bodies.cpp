// Asymmetric general bodies and bodies from 3-D scans in surveys (issue 15, docs/survey.md "Asymmetric bodies and
// bodies from 3-D scans"): the parsed bodies against the factories and against the closed forms of a wedge, the
// inversion on them, refusals that name the survey file, the line and the field (and the mesh file), and old
// surveys that keep their bodies and thresholds bit for bit.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "support/meshes.hpp"
#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/io/mesh.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/output/inversion_output.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rocking.hpp"

namespace topple {
namespace {

using test::TempDir;
using test::write_file;

/// The wedge of test_body: right triangle (0,0), (L,0), (0,H) in (x, z), width W along y (float-exact coordinates).
/// Seen along +x (azimuth 90): b1 = L/3, b2 = 2L/3, h = H/3, I_cm / m about y = (L^2 + H^2) / 18.
constexpr double kL = 0.5, kH = 0.75, kW = 0.25;

/// The body's pivots, height and inertia agree with `expected` to `rel` (relative).
void expect_body(const RockingBody& body, const RockingBody& expected, double rel) {
  ASSERT_FALSE(body.symmetric());
  EXPECT_EQ(body.shape, RockingBody::Shape::general);
  for (const int side : {-1, 1}) {
    EXPECT_NEAR(body.pivot_b_m(side), expected.pivot_b_m(side), rel * expected.pivot_b_m(side)) << side;
    EXPECT_NEAR(body.pivot_D_m2(side), expected.pivot_D_m2(side), rel * expected.pivot_D_m2(side)) << side;
  }
  EXPECT_NEAR(body.h_m, expected.h_m, rel * expected.h_m);
}

const char* kObjectTail = R"(mu = 0.6
outcome = "overturned"
)";

/// The [[object]] table of the asymmetric body b1 = 10 cm, b2 = 20 cm, h = 40 cm, inertia 0.02 m^2.
std::string ledge_object(const std::string& id, const std::string& outcome) {
  return "[[object]]\nid = \"" + id + "\"\nshape = \"general\"\nb1 = \"10cm\"\nb2 = \"20cm\"\nh = \"40cm\"\n"
         "inertia = \"0.02m2\"\nmu = 0.6\noutcome = \"" + outcome + "\"\n";
}

// b1 = 10 cm to O-, b2 = 20 cm to O+, h = 40 cm, inertia 0.02 m^2: D- = 0.02 + 0.01 + 0.16 = 0.19 m^2,
// D+ = 0.02 + 0.04 + 0.16 = 0.22 m^2. The reader converts "10cm" as 10 * 0.01, so the body equals the factory's on
// those converted numbers bit for bit; against the decimal closed forms 1e-15 relative is a few roundings.
TEST(SurveyBodies, GeneralAsymmetricParsesToItsPivots) {
  const Survey s = io::parse_survey(ledge_object("ledge", "overturned"), "s.toml");
  const ObservedObject& o = s.sites.at(0).objects.at(0);
  const RockingBody expected = RockingBody::general_asymmetric(0.10, 0.20, 0.40, 0.02);
  expect_body(o.body, expected, 1e-15);
  EXPECT_NEAR(o.body.pivot_D_m2(-1), 0.19, 1e-15);
  EXPECT_NEAR(o.body.pivot_D_m2(1), 0.22, 1e-15);
  EXPECT_TRUE(o.mesh_file.empty());
  EXPECT_FALSE(o.mesh_azimuth_deg.has_value());
}

// A CSV survey names the same keys as columns with their units (b1_cm, inertia_cm2).
TEST(SurveyBodies, GeneralAsymmetricFromCsvColumns) {
  const Survey s = io::parse_survey("id,shape,b1_cm,b2_cm,h_cm,inertia_cm2,mu,outcome\n"
                                    "ledge,general,10,20,40,200,0.6,overturned\n",
                                    "s.csv");
  expect_body(s.sites.at(0).objects.at(0).body, RockingBody::general_asymmetric(0.10, 0.20, 0.40, 0.02), 1e-15);
}

// mesh = "wedge.obj" (relative to the survey file) at azimuth 90 gives the wedge's closed forms. The mass sums are
// exact up to rounding on float-exact coordinates: 1e-12 relative, as test_body's closed-form tests. At azimuth 270
// the plane is reversed: the pivots swap.
TEST(SurveyBodies, MeshObjectIsTheWedgesBody) {
  TempDir dir;
  write_file(dir.path() / "wedge.obj", test::obj_text(test::xz_prism_mesh({{0, 0}, {kL, 0}, {0, kH}}, kW)));
  const auto survey = dir.path() / "survey.toml";
  write_file(survey, std::string(R"([[object]]
id = "wedge"
mesh = "wedge.obj"
mesh_azimuth_deg = 90
)") + kObjectTail + R"(
[[object]]
id = "wedge-back"
mesh = "wedge.obj"
mesh_azimuth_deg = 270
mesh_density_kg_m3 = 1000
mesh_unit = "m"
shape = "general"
)" + kObjectTail);
  const Survey s = io::read_survey(survey);
  const auto& objects = s.sites.at(0).objects;
  const double k2 = (kL * kL + kH * kH) / 18.0;
  expect_body(objects.at(0).body, RockingBody::general_asymmetric(kL / 3, 2 * kL / 3, kH / 3, k2), 1e-12);
  expect_body(objects.at(1).body, RockingBody::general_asymmetric(2 * kL / 3, kL / 3, kH / 3, k2), 1e-12);
  EXPECT_EQ(objects.at(0).mesh_file, (dir.path() / "wedge.obj").string());
  EXPECT_EQ(objects.at(0).mesh_azimuth_deg.value_or(-1.0), 90.0);
  EXPECT_EQ(objects.at(1).mesh_azimuth_deg.value_or(-1.0), 270.0);
}

/// The error parse_survey throws for `text` (a test failure when it throws none).
InputError refusal(const std::string& text, const std::filesystem::path& base_dir) {
  try {
    (void)io::parse_survey(text, "bad.toml", base_dir);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError("none");
}

// model = "3d" on a mesh (three components): the mesh as posed in three dimensions, turned so that its direction
// mesh_azimuth_deg (clockwise from its +y) is the body's +x axis, the one the bearing places. A box 20 cm along x,
// 30 cm along y, 80 cm high, standing as scanned: at mesh_azimuth_deg = 90 the body's +x is the mesh's x (static
// limit atan(10/40) toward +x, azimuth 90, and atan(15/40) toward +y); at 0 its +x is the mesh's +y (the limits
// swap). Without model = "3d" no three-dimensional body is made (the planar section as before).
TEST(SurveyBodies, ThreeDimensionalMeshObjectIsThePosedMeshAtItsAzimuth) {
  TempDir dir;
  write_file(dir.path() / "box.obj", test::obj_text(test::box_mesh(0.2, 0.3, 0.8)));
  const auto survey = dir.path() / "survey.toml";
  const std::string object = "mesh = \"box.obj\"\nmesh_pose = \"as-scanned\"\nmu = 0.6\noutcome = \"overturned\"\n";
  write_file(survey, "[inversion]\ncomponents = 3\n[[object]]\nid = \"x\"\nmesh_azimuth_deg = 90\nmodel = \"3d\"\n" +
                         object + "[[object]]\nid = \"y\"\nmesh_azimuth_deg = 0\nmodel = \"3d\"\n" + object +
                         "[[object]]\nid = \"planar\"\nmesh_azimuth_deg = 0\n" + object);
  const Survey s = io::read_survey(survey);
  const auto& objects = s.sites.at(0).objects;
  ASSERT_EQ(objects.size(), 3U);
  for (std::size_t i = 0; i < 2; ++i) {
    SCOPED_TRACE(objects[i].id);
    ASSERT_TRUE(objects[i].body_3d);
    const RigidBody3D& b = *objects[i].body_3d;
    EXPECT_NEAR(b.height_m(), 0.4, 1e-12);
    const double along = i == 0 ? 0.1 : 0.15, across = i == 0 ? 0.15 : 0.1;
    EXPECT_NEAR(b.static_tilt_limit_rad(90.0), std::atan(along / 0.4), 1e-12);
    EXPECT_NEAR(b.static_tilt_limit_rad(270.0), std::atan(along / 0.4), 1e-12);
    EXPECT_NEAR(b.static_tilt_limit_rad(0.0), std::atan(across / 0.4), 1e-12);
  }
  EXPECT_FALSE(objects[2].body_3d);
  EXPECT_EQ(object_model(objects[2]), ObjectModel::rock);
}

TEST(SurveyBodies, RefusalsNameTheFileTheLineAndTheField) {
  TempDir dir;
  write_file(dir.path() / "wedge.obj", test::obj_text(test::xz_prism_mesh({{0, 0}, {kL, 0}, {0, kH}}, kW)));
  write_file(dir.path() / "open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  struct Case {
    std::string body;      // the object's keys after id (line 3 on)
    std::size_t line;      // where the error points
    std::string field;     // object[1](x).<field>
    std::string contains;  // in the message
  };
  const Case cases[] = {
      {"mesh = \"missing.obj\"\nmesh_azimuth_deg = 0\n", 3, "mesh", "missing.obj"},
      {"mesh = \"open.obj\"\nmesh_azimuth_deg = 0\n", 3, "mesh", "open.obj"},
      {"mesh = \"wedge.obj\"\n", 1, "mesh_azimuth_deg", "azimuth"},
      {"mesh = \"wedge.obj\"\nmesh_azimuth_deg = 0\nshape = \"block\"\n", 5, "shape", "general"},
      {"mesh = \"wedge.obj\"\nmesh_azimuth_deg = 0\nwidth = \"3cm\"\n", 5, "width", "does not apply"},
      {"mesh = \"wedge.obj\"\nmesh_azimuth_deg = 0\nmesh_density_kg_m3 = -1\n", 5, "mesh_density_kg_m3", "density"},
      {"mesh = \"wedge.obj\"\nmesh_azimuth_deg = 0\nmesh_unit = \"parsec\"\n", 5, "mesh_unit", "parsec"},
      {"width = \"3cm\"\nheight = \"9cm\"\nmesh_azimuth_deg = 10\n", 5, "mesh_azimuth_deg", "mesh"},
      {"b1 = \"3cm\"\nb2 = \"3cm\"\nh = \"9cm\"\ninertia = \"1cm2\"\n", 1, "shape", "general"},
      {"shape = \"general\"\nb1 = \"3cm\"\nh = \"9cm\"\ninertia = \"1cm2\"\n", 1, "b2", "b2"},
      {"shape = \"general\"\nb1 = \"3cm\"\nb2 = \"-3cm\"\nh = \"9cm\"\ninertia = \"1cm2\"\n", 5, "b2", "positive"},
      {"shape = \"general\"\nb1 = \"3cm\"\nb2 = \"3cm\"\nh = \"9cm\"\ninertia = 0.01\n", 7, "inertia", "unit"},
      {"shape = \"general\"\nb1 = \"3cm\"\nb2 = \"3cm\"\nh = \"9cm\"\ninertia = \"0.01\"\n", 7, "inertia", "unit"},
      {"shape = \"general\"\nb1 = \"3cm\"\nb2 = \"3cm\"\nh = \"9cm\"\ninertia = \"-1cm2\"\n", 7, "inertia", ""},
      {"shape = \"general\"\nb1 = \"3cm\"\nb2 = \"3cm\"\na = \"3cm\"\nh = \"9cm\"\ninertia = \"1cm2\"\n", 6, "a",
       "does not apply"},
      // Housner's e on landing on O+, 1 - b2 (b1 + b2) / D+, is negative when b1 b2 > k2 + h^2 (and then so is the
      // landing on O-: the same condition), here 0.09 > 0.0101 m^2.
      {"shape = \"general\"\nb1 = \"30cm\"\nb2 = \"30cm\"\nh = \"10cm\"\ninertia = \"1cm2\"\n", 1, "e",
       "negative"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.body);
    const InputError e = refusal("[[object]]\nid = \"x\"\n" + c.body + "mu = 0.5\noutcome = \"overturned\"\n",
                                 dir.path());
    EXPECT_EQ(e.where().file, "bad.toml");
    EXPECT_EQ(e.where().line.value_or(0), c.line);
    EXPECT_EQ(e.where().field, "object[1](x)." + c.field);
    EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.what();
  }
}

// The inversion runs on asymmetric and mesh bodies. The static thresholds take the weaker claim: an overturned
// asymmetric body bounds PGA from below by g min(b1, b2)/h = 0.25 g, one that did not rock from above by
// g max(b1, b2)/h = 0.5 g (tan(atan(x)) is x to a rounding or two: 1e-15).
TEST(SurveyBodies, InvertsWithGeneralAndMeshObjects) {
  TempDir dir;
  write_file(dir.path() / "wedge.obj", test::obj_text(test::xz_prism_mesh({{0, 0}, {kL, 0}, {0, kH}}, kW)));
  const auto survey = dir.path() / "survey.toml";
  write_file(survey, R"([inversion]
pga_g = [0.05, 1.0, 4]
freq_hz = [0.5, 5.0, 3]
motions_per_cell = 3

)" + ledge_object("fell", "overturned") + ledge_object("still", "not_rocked") + R"(
[[object]]
id = "scan"
mesh = "wedge.obj"
mesh_azimuth_deg = 90
mu = 0.7
outcome = "not_overturned"
)");
  const Survey s = io::read_survey(survey);
  const InversionResult r = invert_site(s.sites.at(0), s.inversion, InversionOptions{1});
  EXPECT_EQ(r.runs, 4u * 3u * 3u * 3u);  // cells x motions x objects
  ASSERT_TRUE(r.bounds.hard_lower_g.has_value());
  EXPECT_NEAR(*r.bounds.hard_lower_g, 0.25, 1e-15);
  ASSERT_TRUE(r.bounds.upper_g.has_value());
  EXPECT_NEAR(*r.bounds.upper_g, 0.5, 1e-15);
  double total = 0.0;
  for (const double p : r.posterior) {
    ASSERT_TRUE(std::isfinite(p));
    total += p;
  }
  EXPECT_NEAR(total, 1.0, 1e-12);  // normalised over 12 cells: a few roundings
  ASSERT_EQ(r.objects.size(), 3u);
  // The asymmetric body that fell cannot have done so below its uplift threshold: at the lowest PGA (0.05 g) no
  // run reproduces it, so its probability there is the smoothing floor, below that at the highest PGA.
  EXPECT_LT(r.objects[0].probability.front(), r.objects[0].probability.back());
  // The JSON says which pose a scanned body was given (issue 28), and only for bodies from meshes: the wedge rests on
  // its base, the face of least tilt (0: its base is level in the file), numbered 1.
  const nlohmann::ordered_json j = io::inversion_json(r, s.sites.at(0));
  EXPECT_FALSE(j["objects"][0].contains("mesh_pose"));
  EXPECT_EQ(j["objects"][2]["mesh_pose"], "rest on face 1 (tilt 0 deg from the scan)");
}

// An asymmetric body's run in the inversion is the rocking engine's run of that body: observation_match says
// "overturned" exactly when rock_summary does (a 0.6 g, 2 Hz sine: it falls; 0.1 g: it does not uplift).
TEST(SurveyBodies, ObservationMatchIsTheAsymmetricEngine) {
  const Survey s = io::parse_survey(std::string(R"([[object]]
id = "ledge"
shape = "general"
b1 = "5cm"
b2 = "3cm"
h = "20cm"
inertia = "0.004m2"
)") + kObjectTail, "s.toml");
  const ObservedObject& o = s.sites.at(0).objects.at(0);
  DrawnParameters p;
  p.mu = 0.6;
  p.amplification = 1.0;
  for (const double amp_g : {0.1, 0.6}) {
    PulseSpec spec;
    spec.kind = PulseKind::sine;
    spec.amplitude_m_s2 = amp_g * kStandardGravity;
    spec.duration_s = 0.5;
    spec.tail_s = 2.5;
    const GroundMotion motion = make_pulse(spec);
    RockingOptions options;
    options.max_run_out_s = 20.0;  // as observation_match runs it
    options.rel_tol = 1e-6;
    const RockingSummary direct = rock_summary(motion, o.body, options);
    EXPECT_EQ(observation_match(o, p, motion, kStandardGravity), direct.overturned ? 1.0 : 0.0) << amp_g;
    EXPECT_EQ(direct.overturned, amp_g > 0.5) << amp_g;
  }
}

// Old surveys keep their meaning: examples/survey.toml's bodies are the factories' bodies bit for bit, symmetric,
// with no mesh, and every rocking threshold is g tan(alpha) as before. (Its whole `topple invert --json` output was
// compared with main's before this change: identical but for the run time and provenance.)
TEST(SurveyBodies, OldSurveyKeepsItsBodiesAndThresholds) {
  const Survey s = io::read_survey(std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "survey.toml");
  for (const ObservedObject& o : s.sites.at(0).objects) {
    SCOPED_TRACE(o.id);
    EXPECT_TRUE(o.body.symmetric());
    EXPECT_TRUE(o.mesh_file.empty());
    const RockingBody expected = o.body.shape == RockingBody::Shape::cylinder
                                     ? RockingBody::cylinder(*o.diameter_m, *o.height_m)
                                     : RockingBody::block(*o.width_m, *o.height_m);
    EXPECT_EQ(o.body.a_m, expected.a_m);
    EXPECT_EQ(o.body.h_m, expected.h_m);
    EXPECT_EQ(o.body.D_m2, expected.D_m2);
  }
  const StaticBounds b = static_bounds(s.sites.at(0));
  for (const StaticBound& t : b.lower) {
    const auto& objects = s.sites.at(0).objects;
    const auto it = std::find_if(objects.begin(), objects.end(), [&](const auto& o) { return o.id == t.object_id; });
    ASSERT_NE(it, objects.end());
    if (it->outcome == Outcome::overturned || it->outcome == Outcome::rocked) {
      EXPECT_EQ(t.pga_g, std::tan(it->body.alpha_rad()) / it->amplification.high) << t.object_id;
    }
  }
  // A symmetric general body (a, h, D) is the factory's too.
  const Survey g = io::parse_survey(std::string(R"([[object]]
id = "g"
shape = "general"
a = "3cm"
h = "12cm"
D = "200cm2"
)") + kObjectTail, "s.toml");
  const RockingBody& body = g.sites.at(0).objects.at(0).body;
  const RockingBody expected = RockingBody::general(0.03, 0.12, 0.02);
  EXPECT_TRUE(body.symmetric());
  EXPECT_EQ(body.a_m, expected.a_m);
  EXPECT_EQ(body.h_m, expected.h_m);
  EXPECT_NEAR(body.D_m2, expected.D_m2, 1e-17);  // "200cm2" is 200 * 1e-4: one rounding from 0.02
}

// The example survey with a scan (examples/scanned_rock_survey.toml) reads the committed rock through the mesh
// pipeline: the same body as rocking_body(read_mesh_body(...)) at azimuth 90, bit for bit (one pipeline), and the
// ledge boulder's lower threshold g min(b1, b2)/h = 12/45 g (1e-15: tan(atan(x)) is x to a rounding or two).
TEST(SurveyBodies, ExampleScannedRockSurvey) {
  const std::filesystem::path examples = std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples";
  const Survey s = io::read_survey(examples / "scanned_rock_survey.toml");
  const auto& objects = s.sites.at(0).objects;
  ASSERT_EQ(objects.size(), 2u);
  BodyOptions options;
  options.azimuth_deg = 90.0;
  const RockingBody rock = rocking_body(io::read_mesh_body((examples / "mesh" / "balanced_rock.obj").string(), 1.0,
                                                           options));
  expect_body(objects[0].body, rock, 0.0);
  EXPECT_EQ(objects[0].mesh_file, (examples / "mesh" / "balanced_rock.obj").string());
  const StaticBounds b = static_bounds(s.sites.at(0));
  ASSERT_TRUE(b.hard_lower_g.has_value());
  EXPECT_NEAR(*b.hard_lower_g, 12.0 / 45.0, 1e-15);
}

}  // namespace
}  // namespace topple
