// Campaign files (io/campaign_file.hpp): the keys as read, every refusal naming the file, the line and the key (and a
// missing file the test's id), and a scanned body (a box written as OFF by the test) that runs as the block of the
// same dimensions under both models.
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/meshes.hpp"
#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/ensemble/campaign.hpp"
#include "topple/io/campaign_file.hpp"

namespace topple::io {
namespace {

namespace fs = std::filesystem;
using test::TempDir;
using test::write_file;

/// A plain record (time_s, accel_g): `amp_g` for 2 s, then 3 s of still ground, dt 0.005 s.
std::string pulse_csv(double amp_g) {
  std::string s = "time_s,accel_g\n";
  for (int i = 0; i <= 1000; ++i) s += fmt::format("{:.3f},{}\n", i * 0.005, i * 0.005 < 2.0 ? amp_g : 0.0);
  return s;
}

struct Dir {
  TempDir tmp;
  Dir() {
    write_file(tmp.path() / "low.csv", pulse_csv(0.1));
    write_file(tmp.path() / "high.csv", pulse_csv(1.0));
  }
  fs::path write(const std::string& toml) const {
    const fs::path p = tmp.path() / "campaign.toml";
    write_file(p, toml);
    return p;
  }
};

TEST(CampaignFile, KeysAsReadWithDefaultsAndRelativePaths) {
  Dir d;
  write_file(d.tmp.path() / "rock.off", test::off_text(test::box_mesh(200.0, 300.0, 800.0)));
  const fs::path p = d.write(R"(
[campaign]
name = "table"
models = ["planar", "coupled", "3d"]
mu = 0.6
mu_k = 0.5
restitution = 0.9
g_m_s2 = 9.81
units = "g"

[[test]]
id = "b1"
block = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }
x = "low.csv"
y = "low.csv"
z = "low.csv"
scale = 2
bearing_deg = 30
observed = "standing"

[[test]]
id = "c1"
cylinder = { diameter_m = 0.2, height_m = 0.8 }
x = "high.csv"
observed = "overturned"
observed_azimuth_deg = 185

[[test]]
id = "r1"
mesh = "rock.off"
mesh_unit = "mm"
mesh_pose = "rest"
mesh_up = [0, 0, 1]
x = "high.csv"
format = "plain"
observed = "overturned"
)");
  const CampaignFile c = read_campaign_file(p);
  EXPECT_EQ(c.settings.name, "table");
  ASSERT_EQ(c.settings.models.size(), 3u);
  EXPECT_EQ(c.settings.models[1], ensemble::CampaignModel::coupled);
  EXPECT_EQ(*c.settings.mu, 0.6);
  EXPECT_EQ(*c.settings.mu_k, 0.5);
  EXPECT_EQ(c.settings.restitution, RestitutionMode::given);
  EXPECT_EQ(c.settings.e, 0.9);
  EXPECT_EQ(c.settings.g_m_s2, 9.81);
  ASSERT_EQ(c.tests.size(), 3u);
  const auto& block = std::get<ensemble::CampaignBlock>(c.tests[0].body);
  EXPECT_EQ(block.width_m, 0.2);
  EXPECT_EQ(block.depth_m, 0.3);
  EXPECT_EQ(block.height_m, 0.8);
  EXPECT_EQ(c.tests[0].bearing_deg, 30.0);
  EXPECT_FALSE(c.tests[0].observed_overturned);
  EXPECT_EQ(c.files[0].x, d.tmp.path() / "low.csv");
  EXPECT_EQ(c.files[0].scale, 2.0);
  EXPECT_EQ(c.files[0].read.units, "g");  // the campaign's default
  EXPECT_EQ(c.files[0].read.g_m_s2, 9.81);
  EXPECT_EQ(c.files[0].line, 11u);
  EXPECT_TRUE(c.tests[1].observed_overturned);
  EXPECT_EQ(*c.tests[1].observed_azimuth_deg, 185.0);
  EXPECT_TRUE(c.files[1].y.empty());
  EXPECT_EQ(std::get<ensemble::CampaignMesh>(c.tests[2].body).path, (d.tmp.path() / "rock.off").string());
  EXPECT_EQ(c.files[2].mesh_unit_m, 1e-3);
  EXPECT_EQ(c.files[2].read.format, Format::plain);
  // The loaded inputs: the scale multiplies every component; the mesh is posed, 0.8 m tall.
  const ensemble::CampaignInput in = load_campaign_input(c, 0);
  ASSERT_TRUE(in.y && in.z);
  EXPECT_NEAR(in.x.pga_m_s2(), 2.0 * 0.1 * 9.81, 1e-12);
  EXPECT_NEAR(in.z->pga_m_s2(), 2.0 * 0.1 * 9.81, 1e-12);
  const ensemble::CampaignInput rock = load_campaign_input(c, 2);
  ASSERT_TRUE(rock.mesh);
  EXPECT_NEAR(rock.mesh->mass.volume_m3, 0.2 * 0.3 * 0.8, 1e-12);
}

TEST(CampaignFile, DefaultsWithoutACampaignTable) {
  Dir d;
  const CampaignFile c = read_campaign_file(d.write(
      "[[test]]\nid = \"a\"\nblock = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }\nx = \"low.csv\"\n"
      "observed = \"standing\"\n"));
  EXPECT_EQ(c.settings.name, "campaign");  // the file's stem
  ASSERT_EQ(c.settings.models.size(), 2u);
  EXPECT_EQ(c.settings.models[0], ensemble::CampaignModel::planar);
  EXPECT_EQ(c.settings.models[1], ensemble::CampaignModel::three_d);
  EXPECT_FALSE(c.settings.mu);
  EXPECT_EQ(c.settings.restitution, RestitutionMode::housner);
  EXPECT_EQ(c.settings.g_m_s2, kStandardGravity);
}

struct Refusal {
  std::string toml;
  std::string key;
  std::optional<std::size_t> line;
  std::string text;
};

TEST(CampaignFile, RefusalsNameFileLineAndKey) {
  const std::string block = "block = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }\n";
  const std::string ok = "[[test]]\nid = \"a\"\n" + block + "x = \"low.csv\"\nobserved = \"standing\"\n";
  const std::vector<Refusal> cases{
      {"[[test]]\nid = \"a\"\n" + block + "x = \"low.csv\"\nobserved = \"standing\"\ncolour = 1\n", "test[1].colour", 6,
       "unknown key 'colour'"},
      {"[[test]]\nid = \"b7\"\n" + block + "x = \"missing.csv\"\nobserved = \"standing\"\n", "test[1].x", 4,
       "test 'b7': file"},
      {"[[test]]\nid = \"b7\"\n" + block + "x = \"low.csv\"\ny = \"nope.csv\"\nobserved = \"standing\"\n", "test[1].y",
       5, "not found"},
      {"[[test]]\nid = \"m\"\nmesh = \"none.obj\"\nx = \"low.csv\"\nobserved = \"standing\"\n", "test[1].mesh", 3,
       "test 'm': file"},
      {"[[test]]\nid = \"a\"\n" + block + "cylinder = { diameter_m = 0.2, height_m = 0.8 }\nx = \"low.csv\"\n"
       "observed = \"standing\"\n", "test[1].body", 1, "exactly one body"},
      {"[[test]]\nid = \"a\"\nx = \"low.csv\"\nobserved = \"standing\"\n", "test[1].body", 1, "exactly one body"},
      {"[[test]]\nid = \"a\"\n" + block + "x = \"low.csv\"\nobserved = \"fell\"\n", "test[1].observed", 5,
       "expected \"overturned\" or \"standing\""},
      {"[[test]]\nid = \"a\"\n" + block + "x = \"low.csv\"\n", "test[1].observed", 1, "required"},
      {"[[test]]\nid = \"a\"\n" + block + "observed = \"standing\"\n", "test[1].x", 1, "x record is required"},
      {"[[test]]\nid = \"a\"\nblock = { width_m = -0.2, depth_m = 0.3, height_m = 0.8 }\nx = \"low.csv\"\n"
       "observed = \"standing\"\n", "test[1].block.width_m", 3, "must be > 0"},
      {"[[test]]\nid = \"a\"\nblock = { width_m = 0.2, height_m = 0.8 }\nx = \"low.csv\"\nobserved = \"standing\"\n",
       "test[1].block.depth_m", 3, "required"},
      {"[[test]]\nid = \"a\"\n" + block + "mesh_up = [0, 0, 1]\nx = \"low.csv\"\nobserved = \"standing\"\n",
       "test[1].mesh_up", 4, "mesh body only"},
      {"[[test]]\nid = \"a\"\n" + block + "x = \"low.csv\"\nobserved = \"standing\"\nobserved_azimuth_deg = 10\n",
       "test[1].observed_azimuth_deg", 6, "observed standing"},
      {"[[test]]\nid = \"a\"\n" + block + "x = \"low.csv\"\nformat = \"at3\"\nobserved = \"standing\"\n",
       "test[1].format", 5, "at3"},
      {"[[test]]\nid = \"a\"\n" + block + "x = \"low.csv\"\nscale = 0\nobserved = \"standing\"\n", "test[1].scale", 5,
       "must be > 0"},
      {ok + ok, "test[2].id", 7, "already test[1]'s"},
      {"[campaign]\nmodels = [\"planar\", \"coupled\"]\n" + ok, "campaign.models", 2, "needs mu"},
      {"[campaign]\nmodels = [\"planar\", \"rigid\"]\n" + ok, "campaign.models", 2, "unknown model 'rigid'"},
      {"[campaign]\nmodels = [\"3d\", \"3d\"]\n" + ok, "campaign.models", 2, "listed twice"},
      {"[campaign]\nmu = 0.5\nmu_k = 0.6\n" + ok, "campaign.mu_k", 3, "must be in [0, mu"},
      {"[campaign]\nmu_k = 0.6\n" + ok, "campaign.mu_k", 2, "needs mu"},
      {"[campaign]\nrestitution = \"newton\"\n" + ok, "campaign.restitution", 2, "housner"},
      {"[campaign]\nrestitution = 1.5\n" + ok, "campaign.restitution", 2, "[0, 1]"},
      {"[campaign]\ng_m_s2 = -9.8\n" + ok, "campaign.g_m_s2", 2, "must be > 0"},
      // format and units: the words of the sweep reader too (io/toml_reader.hpp, test_sweep_file.cpp).
      {"[campaign]\nunits = \"furlong\"\n" + ok, "campaign.units", 2, "unknown acceleration unit 'furlong'"},
      {"[campaign]\nformat = 3\n" + ok, "campaign.format", 2, "expected a string, got an integer"},
      {"[campaign]\nname = \"x\"\n", "test", std::nullopt, "no [[test]]"},
      {"[campaign]\nname = \"x\"\nspeed = 3\n" + ok, "campaign.speed", 3, "unknown key"},
      {"[campaign\n", "", 1, "not valid TOML"},
      {"[[test]]\nid = \"a,b\"\n" + block + "x = \"low.csv\"\nobserved = \"standing\"\n", "test[1].id", 2,
       "CSV field"},
  };
  for (const Refusal& c : cases) {
    Dir d;
    const fs::path p = d.write(c.toml);
    try {
      (void)read_campaign_file(p);
      ADD_FAILURE() << "accepted:\n" << c.toml;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, p.string()) << e.what();
      EXPECT_EQ(e.where().field, c.key) << e.what();
      EXPECT_EQ(e.where().line, c.line) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.text), std::string::npos) << e.what();
    }
  }
}

TEST(CampaignFile, ARecordThatDoesNotReadNamesTheTestKeyAndRecord) {
  Dir d;
  write_file(d.tmp.path() / "broken.csv", "time_s,accel_g\n0,0.1\n0.005,abc\n");
  const fs::path p = d.write("[[test]]\nid = \"t9\"\nblock = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }\n"
                             "x = \"low.csv\"\ny = \"broken.csv\"\nobserved = \"standing\"\n");
  const CampaignFile c = read_campaign_file(p);
  try {
    (void)load_campaign_input(c, 0);
    FAIL() << "a broken record was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, p.string());
    EXPECT_EQ(e.where().field, "test[1].y");
    EXPECT_EQ(e.where().line, 5u);
    const std::string what = e.what();
    EXPECT_NE(what.find("test 't9'"), std::string::npos) << what;
    EXPECT_NE(what.find("broken.csv:3"), std::string::npos) << what;  // the record's own file and line
  }
}

TEST(CampaignFile, AScannedBoxRunsAsTheBlockOfItsDimensions) {
  // A box 0.2 x 0.3 x 0.8 m written as OFF (and as OBJ, turned and shifted: the pose and the frame must not matter),
  // next to the block of the same dimensions, under a pulse that overturns it and one that does not move it, at
  // bearings 0 and 90.
  Dir d;
  write_file(d.tmp.path() / "box.off", test::off_text(test::box_mesh(0.2, 0.3, 0.8)));
  write_file(d.tmp.path() / "box.obj",
             test::obj_text(test::rotated_z(test::box_mesh(0.2, 0.3, 0.8), 90.0, {5.0, -3.0, 1.0})));
  std::string toml = "[campaign]\nmodels = [\"planar\", \"3d\"]\n";
  for (const char* bearing : {"0", "90"}) {
    for (const char* rec : {"low.csv", "high.csv"}) {
      toml += fmt::format("[[test]]\nid = \"block-{0}-{1}\"\nblock = {{ width_m = 0.2, depth_m = 0.3, height_m = 0.8 }}\n"
                          "x = \"{1}\"\nbearing_deg = {0}\nobserved = \"standing\"\n"
                          "[[test]]\nid = \"off-{0}-{1}\"\nmesh = \"box.off\"\nx = \"{1}\"\nbearing_deg = {0}\n"
                          "observed = \"standing\"\n",
                          bearing, rec);
    }
  }
  // The OBJ box was turned by 90 degrees: at bearing 90 - 90 = 0 it stands as the block at bearing 0... and its
  // body x axis is the block's y: so at bearing -90 it is the block at bearing 0.
  toml += "[[test]]\nid = \"obj-turned\"\nmesh = \"box.obj\"\nx = \"high.csv\"\nbearing_deg = -90\n"
          "observed = \"standing\"\n";
  const CampaignFile c = read_campaign_file(d.write(toml));
  const std::vector<ensemble::CampaignRow> rows = ensemble::run_campaign(
      c.tests, c.settings, [&](std::size_t i) { return load_campaign_input(c, i); }, 0);
  ASSERT_EQ(rows.size(), 2u * 9u);
  for (std::size_t k = 0; k < 4; ++k) {  // pairs (block, mesh) of tests, two models each
    for (std::size_t m = 0; m < 2; ++m) {
      const ensemble::CampaignRow& block = rows[4 * k + m];
      const ensemble::CampaignRow& mesh = rows[4 * k + 2 + m];
      EXPECT_EQ(block.predicted_overturned, mesh.predicted_overturned) << mesh.id;
      EXPECT_NEAR(block.max_tilt_over_limit, mesh.max_tilt_over_limit, 1e-6) << mesh.id;
      ASSERT_EQ(block.overturn_time_s.has_value(), mesh.overturn_time_s.has_value()) << mesh.id;
      if (block.overturn_time_s) {
        EXPECT_NEAR(*block.overturn_time_s, *mesh.overturn_time_s, 1e-6) << mesh.id;
        EXPECT_NEAR(*block.overturn_azimuth_deg, *mesh.overturn_azimuth_deg, 1e-6) << mesh.id;
      }
    }
  }
  EXPECT_FALSE(rows[0].predicted_overturned);  // 0.1 g < b / h = 0.25
  EXPECT_TRUE(rows[4].predicted_overturned);   // 1 g for 2 s
  for (std::size_t m = 0; m < 2; ++m) {
    const ensemble::CampaignRow& block = rows[4 + m];  // block-0-high.csv
    const ensemble::CampaignRow& turned = rows[16 + m];
    EXPECT_EQ(turned.predicted_overturned, block.predicted_overturned);
    EXPECT_NEAR(*turned.overturn_time_s, *block.overturn_time_s, 1e-6);
  }
}

}  // namespace
}  // namespace topple::io
