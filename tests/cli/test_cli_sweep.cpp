// `topple sweep`: rows equal to single runs of `topple slide` / `topple rock`, identical files whatever the threads
// and MPI ranks, kill -9 and resume, bad sweep files (exit 2 naming file and key), changed sweeps, quiet output.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/csv_table.hpp"
#include "support/meshes.hpp"
#include "support/shared_data.hpp"

extern char** environ;

namespace topple {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::TempDir;
using test::write_file;

std::string quote(const std::string& s) { return "'" + s + "'"; }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

using test::expect_same;
using test::read_table;
using test::Table;

const char* kPulseSweep = R"(# pulses x sliding blocks and rocking blocks
[motions]
polarity = ["normal", "inverse"]
[[motions.pulse]]
kind = ["sine", "rect", "tri"]
amp_g = [0.3, 0.6]
freq_hz = [1, 4]

[[object]]
model = "slide"
mu = [0.05, 0.1, 0.2]

[[object]]
model = "slide"
mu = 0.3
mu_kinetic = 0.2
slope_deg = 10
mode = "one-way"

[[object]]
model = "rock"
shape = "block"
width_m = 0.04
height_m = 0.4
e = ["housner", 0.9]
mu = 0.5

[output]
path = "results.csv"
chunk_runs = 10
)";

/// Runs `topple slide` or `topple rock` on the inputs of row `r` and compares its JSON summary with the row.
void check_row_against_single_run(const Table& t, std::size_t r, const std::string& motion_args) {
  const std::string model = t.at(r, "model");
  SCOPED_TRACE("row " + t.at(r, "run") + " (" + model + ", " + t.at(r, "motion") + ")");
  std::string args = motion_args + (t.at(r, "polarity") == "inverse" ? " --invert" : "");
  std::vector<std::string> keys;
  if (model == "slide") {
    args = "slide " + args + " --mu " + t.at(r, "mu") + " --mu-kinetic " + t.at(r, "mu_kinetic") + " --slope-deg " +
           t.at(r, "slope_deg") + (t.at(r, "mode") == "one-way" ? " --one-way" : "");
    keys = {"max_abs_displacement_m", "max_displacement_time_s", "residual_displacement_m", "max_abs_velocity_m_s",
            "slip_episodes",          "first_slip_time_s",       "total_slip_duration_s",   "end_time_s",
            "at_rest_at_end",         "contact_lost_time_s",     "yield_down_g",            "yield_up_g"};
  } else {
    const std::string e = t.at(r, "restitution") == "housner" ? "housner" : t.at(r, "e");
    args = "rock " + args + " --shape block --width " + t.at(r, "width_m") + "m --height " + t.at(r, "height_m") +
           "m --e " + e + (t.at(r, "mu").empty() ? "" : " --mu " + t.at(r, "mu"));
    keys = {"max_abs_rotation_rad", "max_rotation_over_alpha", "max_rotation_time_s", "max_abs_theta_dot_rad_s",
            "impacts",              "uplifts",                 "uplift_time_s",       "exceeded_alpha_time_s",
            "overturned",           "overturn_time_s",         "energy_lost_j_per_kg", "end_time_s",
            "end_state",            "still_rocking_at_end",    "onset_mode",          "critical_mu",
            "alpha_rad",            "p_rad_s",                 "e"};
  }
  const auto out = run_cli(args + " --json");
  ASSERT_EQ(out.exit_code, 0) << args << "\n" << out.err;
  const auto j = nlohmann::json::parse(out.out);
  for (const auto& k : keys) expect_same(t.at(r, k), j.at(k), k);
}

TEST(CliSweep, RowsEqualSingleRunsOfSlideAndRock) {
  TempDir dir;
  write_file(dir.path() / "s.toml", kPulseSweep);
  const auto r = run_cli("sweep " + quote((dir.path() / "s.toml").string()) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const Table t = read_table(dir.path() / "results.csv");
  ASSERT_EQ(t.rows.size(), 3u * 2u * 2u * 2u * 6u);
  // Rows picked at random (fixed seed), six sliding and four rocking ones.
  std::mt19937 rng(2024);
  std::uniform_int_distribution<std::size_t> pick(0, t.rows.size() - 1);
  int slides = 0;
  int rocks = 0;
  while (slides < 6 || rocks < 4) {
    const std::size_t row = pick(rng);
    const bool slide = t.at(row, "model") == "slide";
    if ((slide && slides >= 6) || (!slide && rocks >= 4)) continue;
    (slide ? slides : rocks)++;
    const std::string pulse = "--pulse " + t.at(row, "pulse_kind") + " --amp-g " + t.at(row, "pulse_amp_g") +
                              " --duration " + t.at(row, "pulse_duration_s");
    check_row_against_single_run(t, row, pulse);
  }
}

// Issue 31: `mesh_unit = "2cm"` is one file unit of 2 cm (was "1" + "2cm" = 12 cm); a bare number is metres per file
// unit; `mesh_azimuth_deg = 1e308` is the direction fmod(1e308, 360) (was "internal error: b1 came out as -nan").
// The box 10 x 5 x 40 file units at 2 cm is 0.2 x 0.1 x 0.8 m: along north (azimuth 0) b1 = b2 = 0.05 m, h = 0.4 m.
TEST(CliSweep, MeshUnitIsALengthAndHugeAzimuthsAreReduced) {
  TempDir dir;
  write_file(dir.path() / "box.obj", test::obj_text(test::box_mesh(10, 5, 40)));
  write_file(dir.path() / "a.toml", fmt::format(R"(
[motions]
[[motions.pulse]]
kind = "sine"
amp_g = 0.3
freq_hz = 2
[[object]]
model = "rock"
mesh = "box.obj"
mesh_azimuth_deg = 0
mesh_unit = "2cm"
[[object]]
model = "rock"
mesh = "box.obj"
mesh_azimuth_deg = 0
mesh_unit = "0.02"
[[object]]
model = "rock"
mesh = "box.obj"
mesh_azimuth_deg = [1e308, {}]
mesh_unit = "cm"
)", std::fmod(1e308, 360.0)));
  const auto r = run_cli("sweep " + quote((dir.path() / "a.toml").string()) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = read_table(dir.path() / "a.csv");
  ASSERT_EQ(t.rows.size(), 4u);
  for (const std::size_t row : {0u, 1u}) {
    EXPECT_NEAR(std::stod(t.at(row, "b1_m")), 0.05, 1e-12);
    EXPECT_NEAR(std::stod(t.at(row, "b2_m")), 0.05, 1e-12);
    EXPECT_NEAR(std::stod(t.at(row, "h_m")), 0.4, 1e-12);
  }
  for (const char* k : {"b1_m", "b2_m", "h_m", "inertia_m2", "max_abs_rotation_rad"}) {
    EXPECT_EQ(t.at(2, k), t.at(3, k)) << k;
  }
}

// Asymmetric general bodies, given by their numbers or by a mesh (the wedge of test_body, azimuths 90 and 270), give
// per run the numbers `topple rock --shape general --b1 --b2 --h --inertia` gives for the body in the row's columns
// (printed to 17 digits, so the same doubles): every result, and the side it fell to or first passed alpha on.
TEST(CliSweep, AsymmetricAndMeshRowsEqualSingleRunsOfRock) {
  TempDir dir;
  write_file(dir.path() / "wedge.obj", test::obj_text(test::xz_prism_mesh({{0, 0}, {0.5, 0}, {0, 0.75}}, 0.25)));
  write_file(dir.path() / "a.toml", R"(
[motions]
polarity = ["normal", "inverse"]
[[motions.pulse]]
kind = ["sine", "rect"]
amp_g = [0.3, 0.6]
freq_hz = 2
[[object]]
model = "rock"
shape = "general"
b1 = "5cm"
b2_m = [0.03, 0.08]
h = "20cm"
inertia_m2 = 0.004
e = ["housner", 0.8]
[[object]]
model = "rock"
mesh = "wedge.obj"
mesh_azimuth_deg = [90, 270]
)");
  const auto r = run_cli("sweep " + quote((dir.path() / "a.toml").string()) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = read_table(dir.path() / "a.csv");
  ASSERT_EQ(t.rows.size(), 2u * 2u * 2u * (2u * 2u + 2u));
  std::size_t fell[2] = {0, 0};  // rows that fell toward -x / +x: both sides must be exercised
  for (std::size_t row = 0; row < t.rows.size(); row += 3) {
    SCOPED_TRACE("row " + t.at(row, "run") + " (" + t.at(row, "motion") + ", mesh '" + t.at(row, "mesh") + "')");
    const std::string e = t.at(row, "restitution") == "housner" ? "housner" : t.at(row, "e");
    const std::string args = "rock --pulse " + t.at(row, "pulse_kind") + " --amp-g " + t.at(row, "pulse_amp_g") +
                             " --duration " + t.at(row, "pulse_duration_s") +
                             (t.at(row, "polarity") == "inverse" ? " --invert" : "") + " --shape general --b1 " +
                             t.at(row, "b1_m") + "m --b2 " + t.at(row, "b2_m") + "m --h " + t.at(row, "h_m") +
                             "m --inertia " + t.at(row, "inertia_m2") + "m2 --e " + e + " --json";
    const auto out = run_cli(args);
    ASSERT_EQ(out.exit_code, 0) << args << "\n" << out.err;
    const auto j = nlohmann::json::parse(out.out);
    for (const char* k : {"max_abs_rotation_rad", "max_rotation_over_alpha", "max_rotation_time_s",
                          "max_abs_theta_dot_rad_s", "impacts", "uplifts", "uplift_time_s", "exceeded_alpha_time_s",
                          "overturned", "overturn_time_s", "energy_lost_j_per_kg", "end_time_s", "end_state",
                          "alpha_rad", "p_rad_s", "e"}) {
      expect_same(t.at(row, k), j.at(k), k);
    }
    const auto& sides = j.at("sides");
    expect_same(t.at(row, "overturned_side"), sides.at("overturned_side"), "overturned_side");
    expect_same(t.at(row, "exceeded_alpha_side"), sides.at("exceeded_alpha_side"), "exceeded_alpha_side");
    expect_same(t.at(row, "alpha_negative_rad"), sides.at("negative").at("alpha_rad"), "alpha_negative_rad");
    expect_same(t.at(row, "max_rotation_negative_rad"), sides.at("negative").at("max_rotation_rad"),
                "max_rotation_negative_rad");
    expect_same(t.at(row, "max_rotation_over_alpha_positive"), sides.at("positive").at("max_rotation_over_alpha"),
                "max_rotation_over_alpha_positive");
    expect_same(t.at(row, "e_onto_negative"), sides.at("negative").at("e_onto"), "e_onto_negative");
    if (t.at(row, "overturned_side") == "negative") ++fell[0];
    if (t.at(row, "overturned_side") == "positive") ++fell[1];
  }
  EXPECT_GT(fell[0], 0u);
  EXPECT_GT(fell[1], 0u);
}

// model = "coupled" (sweep.hpp): each row equals `topple rock --model coupled --mu --mu-k` on the same pulse or
// record (a synthetic record the test writes), every coupled result column the JSON's (printed to 17 digits: the
// same doubles); a rocking object beside it keeps its columns; a coupled object needs mu, takes mu_kinetic, and is
// refused under [[motions.set]] naming the key.
TEST(CliSweep, CoupledRowsEqualSingleRunsOfRockModelCoupled) {
  TempDir dir;
  const fs::path record = dir.path() / "synthetic.csv";
  const auto synth = run_cli("synth --pga 0.4g --freq 2Hz --duration 6s --seed 3 --out " + quote(record.string()));
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  write_file(dir.path() / "c.toml", R"(
[motions]
files = ["synthetic.csv"]
scale_pga_g = [0.3, 0.8]
polarity = ["normal", "inverse"]
[[motions.pulse]]
kind = ["sine", "rect"]
amp_g = 0.6
freq_hz = 2
[[object]]
model = "coupled"
shape = "block"
width = "20cm"
height = "60cm"
mu = [0.25, 0.6]
mu_kinetic = 0.2
[[object]]
model = "coupled"
shape = "general"
b1 = "5cm"
b2 = "8cm"
h = "30cm"
inertia_m2 = 0.02
mu = 0.5
[[object]]
model = "rock"
shape = "block"
width_m = 0.2
height_m = 0.6
)");
  const auto r = run_cli("sweep " + quote((dir.path() / "c.toml").string()) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = read_table(dir.path() / "c.csv");
  ASSERT_EQ(t.rows.size(), (2u * 2u + 2u * 2u) * 4u);
  const std::vector<std::string> keys{
      "overturned", "overturned_side", "overturn_time_s", "max_rotation_over_alpha", "max_rotation_positive_rad",
      "max_rotation_negative_rad", "exceeded_alpha_time_s", "residual_slide_m", "max_abs_slide_m", "slip_episodes",
      "impacts", "uplifts", "tangential_impacts", "onset_mode", "end_mode", "end_time_s", "moving_at_end",
      "friction_energy_j_per_kg", "impact_energy_j_per_kg", "alpha_positive_deg", "alpha_negative_deg",
      "used_sliding_kernel"};
  int coupled = 0;
  int fell = 0;
  int slid = 0;
  for (std::size_t row = 0; row < t.rows.size(); ++row) {
    const std::string model = t.at(row, "model");
    if (model == "rock") {
      EXPECT_NE(t.at(row, "max_abs_rotation_rad"), "");
      EXPECT_EQ(t.at(row, "residual_slide_m"), "");
      continue;
    }
    ASSERT_EQ(model, "coupled");
    ++coupled;
    SCOPED_TRACE("row " + t.at(row, "run") + " (" + t.at(row, "motion") + ")");
    std::string motion;
    if (t.at(row, "pulse_kind").empty()) {
      const double target = std::round(std::strtod(t.at(row, "pga_g").c_str(), nullptr) * 10.0) / 10.0;
      motion = quote(record.string()) + fmt::format(" --scale-pga {}g", target);
    } else {
      motion = "--pulse " + t.at(row, "pulse_kind") + " --amp-g " + t.at(row, "pulse_amp_g") + " --duration " +
               t.at(row, "pulse_duration_s");
    }
    const std::string body = t.at(row, "shape") == "block"
                                 ? " --shape block --width " + t.at(row, "width_m") + "m --height " +
                                       t.at(row, "height_m") + "m"
                                 : " --shape general --b1 " + t.at(row, "b1_m") + "m --b2 " + t.at(row, "b2_m") +
                                       "m --h " + t.at(row, "h_m") + "m --inertia " + t.at(row, "inertia_m2") + "m2";
    const std::string args = "rock " + motion + (t.at(row, "polarity") == "inverse" ? " --invert" : "") + body +
                             " --model coupled --mu " + t.at(row, "mu") + " --mu-k " + t.at(row, "mu_kinetic") +
                             " --json";
    const auto out = run_cli(args);
    ASSERT_EQ(out.exit_code, 0) << args << "\n" << out.err;
    const auto j = nlohmann::json::parse(out.out);
    for (const auto& k : keys) expect_same(t.at(row, k), j.at(k), k);
    fell += t.at(row, "overturned") == "true" ? 1 : 0;
    slid += std::abs(std::strtod(t.at(row, "max_abs_slide_m").c_str(), nullptr)) > 1e-3 ? 1 : 0;
  }
  EXPECT_EQ(coupled, 8 * 3);
  EXPECT_GT(fell, 0);  // both outcomes and real sliding are exercised
  EXPECT_LT(fell, coupled);
  EXPECT_GT(slid, 0);

  const std::string pulse = "[motions]\n[[motions.pulse]]\nkind = \"sine\"\namp_g = 0.3\nfreq_hz = 2\n";
  const std::string block = "shape = \"block\"\nwidth = \"20cm\"\nheight = \"60cm\"\n";
  const std::vector<std::pair<std::string, std::string>> bad{
      {pulse + "[[object]]\nmodel = \"coupled\"\n" + block, "object[1].mu"},
      {pulse + "[[object]]\nmodel = \"coupled\"\n" + block + "mu = 0.3\nmu_kinetic = 0.5\n", "object[1].mu_kinetic"},
      {pulse + "[[object]]\nmodel = \"rock\"\n" + block + "mu = 0.3\nmu_kinetic = 0.2\n", "object[1].mu_kinetic"},
      {pulse + "[[object]]\nmodel = \"bounce\"\n" + block, "object[1].model"},
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    const fs::path p = dir.path() / fmt::format("bad{}.toml", i);
    write_file(p, bad[i].first);
    const auto b = run_cli("sweep " + quote(p.string()));
    SCOPED_TRACE(bad[i].first);
    EXPECT_EQ(b.exit_code, 2) << b.err;
    EXPECT_NE(b.err.find(p.string()), std::string::npos) << b.err;
    EXPECT_NE(b.err.find(bad[i].second + ":"), std::string::npos) << b.err;
  }
}

TEST(CliSweep, RecordRowsEqualSingleRuns) {
  if (!test::have_shared()) GTEST_SKIP() << "shared/records not found";
  TempDir dir;
  const std::string a = test::shared_record("RSN6_IMPVALL.I_I-ELC180.AT2").string();
  const std::string b = test::shared_record("Rinaldi228.AT2").string();
  write_file(dir.path() / "r.toml", fmt::format(R"(
[motions]
files = ["{}", "{}"]
scale_pga_g = [0.2, 0.5]
polarity = ["normal", "inverse"]
[[object]]
model = "slide"
mu = [0.05, 0.15]
[[object]]
model = "rock"
shape = "block"
width_m = 0.1
height_m = 0.5
)", a, b));
  const auto r = run_cli("sweep " + quote((dir.path() / "r.toml").string()) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = read_table(dir.path() / "r.csv");
  ASSERT_EQ(t.rows.size(), 2u * 2u * 2u * 3u);
  for (const std::size_t row : {0u, 7u, 13u, 20u, 23u}) {
    const double target = std::round(std::strtod(t.at(row, "pga_g").c_str(), nullptr) * 10.0) / 10.0;
    check_row_against_single_run(t, row, quote(t.at(row, "motion")) + fmt::format(" --scale-pga {}g", target));
  }
}

TEST(CliSweep, SameBytesForOneThreadAllThreadsAndMpiRanks) {
  TempDir dir;
  write_file(dir.path() / "s.toml", kPulseSweep);
  const std::string sweep = quote((dir.path() / "s.toml").string());
  std::vector<std::string> outputs;
  for (const std::string threads : {"1", "2", "0"}) {
    const std::string out = (dir.path() / ("t" + threads + ".csv")).string();
    const auto r = run_cli("sweep " + sweep + " --threads " + threads + " --jsonl --quiet --out " + quote(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    outputs.push_back(out);
  }
  const bool mpi = test::mpi_tests_enabled();
  if (mpi) {
    for (const int ranks : {2, 3}) {
      const std::string out = (dir.path() / fmt::format("mpi{}.csv", ranks)).string();
      const std::string cmd = fmt::format(
          "mpirun -n {} --oversubscribe --allow-run-as-root --mca btl self,vader '{}' sweep {} --jsonl --verbose "
          "--out {} >{} 2>&1",
          ranks, TOPPLE_CLI_PATH, sweep, quote(out), quote(out + ".log"));
      const int status = std::system(cmd.c_str());
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd << "\n" << slurp(out + ".log");
      EXPECT_NE(slurp(out + ".log").find(fmt::format("ranks={}", ranks)), std::string::npos) << slurp(out + ".log");
      outputs.push_back(out);
    }
  }
  const std::string csv = slurp(outputs[0]);
  const std::string jsonl = slurp(fs::path(outputs[0]).replace_extension(".jsonl"));
  ASSERT_GT(csv.size(), 1000u);
  for (std::size_t i = 1; i < outputs.size(); ++i) {
    SCOPED_TRACE(outputs[i]);
    EXPECT_EQ(slurp(outputs[i]), csv);
    EXPECT_EQ(slurp(fs::path(outputs[i]).replace_extension(".jsonl")), jsonl);
  }
  // JSON lines: one object per row, the same keys as the CSV header, values as in the CSV.
  const Table t = read_table(outputs[0]);
  std::istringstream lines(jsonl);
  std::string line;
  std::size_t n = 0;
  while (std::getline(lines, line)) {
    const auto j = nlohmann::ordered_json::parse(line);
    ASSERT_EQ(j.size(), t.header.size());
    std::size_t k = 0;
    for (const auto& [key, value] : j.items()) {
      ASSERT_EQ(key, t.header[k]);
      expect_same(t.rows[n][k], value, key);
      ++k;
    }
    ++n;
  }
  EXPECT_EQ(n, t.rows.size());
  if (!mpi) GTEST_SKIP() << "threads compared; mpirun absent, topple built without MPI, or a sanitizer build";
}

using test::spawn_cli;

std::set<std::string> chunk_files(const fs::path& dir) {
  std::set<std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const auto name = e.path().filename().string();
    if (std::regex_match(name, std::regex("[0-9]{8}\\.csv"))) out.insert(name);
  }
  return out;
}

std::size_t verbose_count(const std::string& err, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(err, m, std::regex(key + "=([0-9]+)"))) return static_cast<std::size_t>(-1);
  return std::stoul(m[1]);
}

// A real `topple sweep` killed with SIGKILL once some chunks are committed, then rerun: the file equals an
// uninterrupted run byte for byte, and the chunks found finished were not computed again.
TEST(CliSweep, KillNineAndResume) {
  TempDir dir;
  // About 3 s on one core: 160 motions x 30 rocking blocks, 60 runs per chunk (80 chunks).
  write_file(dir.path() / "k.toml", R"(
[motions]
[[motions.pulse]]
kind = "sine"
amp_g = { from = 0.1, to = 0.6, count = 40 }
freq_hz = [0.5, 1, 2, 4]
[[object]]
model = "rock"
shape = "block"
width = { from = "3cm", to = "12cm", count = 30 }
height = "40cm"
[output]
path = "k.csv"
chunk_runs = 60
)");
  const std::string sweep = (dir.path() / "k.toml").string();
  const fs::path ref = dir.path() / "ref.csv";
  const auto r0 = run_cli("sweep " + quote(sweep) + " --quiet --out " + quote(ref.string()));
  ASSERT_EQ(r0.exit_code, 0) << r0.err;

  const fs::path out = dir.path() / "k.csv";
  const fs::path parts = dir.path() / "k.csv.parts";
  const pid_t pid = spawn_cli({"sweep", sweep, "--threads", "1", "--quiet"}, dir.path() / "err1.txt");
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (chunk_files(parts).size() < 3 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep ended before it was killed: make it longer";
  EXPECT_FALSE(fs::exists(out));
  const std::set<std::string> finished = chunk_files(parts);
  ASSERT_GE(finished.size(), 3u);
  ASSERT_LT(finished.size(), 80u);
  // A chunk file is its header line (format, fingerprint, index, checksums) and then its rows.
  std::map<std::string, std::string> finished_text;
  for (const auto& f : finished) {
    const std::string text = slurp(parts / f);
    ASSERT_EQ(text.rfind("# topple-sweep-chunk/2 fingerprint=", 0), 0u) << f;
    finished_text[f] = text.substr(text.find('\n') + 1);
  }

  const auto r = run_cli("sweep " + quote(sweep) + " --verbose");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(verbose_count(r.err, "total"), 80u) << r.err;
  EXPECT_EQ(verbose_count(r.err, "already_done"), finished.size()) << r.err;
  EXPECT_EQ(verbose_count(r.err, "computed"), 80u - finished.size()) << r.err;
  EXPECT_EQ(verbose_count(r.err, "runs_computed"), 4800u - 60u * finished.size()) << r.err;
  EXPECT_NE(r.err.find("resumed"), std::string::npos) << r.err;
  const std::string result = slurp(out);
  EXPECT_EQ(result, slurp(ref));
  // The committed chunks' rows are in the result as they were written before the kill.
  for (const auto& [name, text] : finished_text) EXPECT_NE(result.find(text), std::string::npos) << name;
  // A third run has nothing to do.
  const auto again = run_cli("sweep " + quote(sweep) + " --verbose");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("already complete"), std::string::npos) << again.err;
  EXPECT_EQ(slurp(out), result);
}

TEST(CliSweep, BadSweepFilesExitTwoNamingFileAndKey) {
  TempDir dir;
  const std::string pulse = "[motions]\n[[motions.pulse]]\nkind = \"sine\"\namp_g = 0.3\nfreq_hz = 2\n";
  const std::string slide = "[[object]]\nmodel = \"slide\"\nmu = 0.1\n";
  const std::vector<std::pair<std::string, std::string>> cases{
      {pulse + "[[object]]\nmodel = \"slide\"\nmu = 0.1\nfriction = 3\n", "object[1].friction"},
      {"[motions]\nfiles = [\"records/missing.AT2\"]\n" + slide, "motions.files[1]"},
      {"[motions]\nfiles = [\"records/*.AT2\"]\n" + slide, "motions.files[1]"},
      {pulse + "[[object]]\nmodel = \"slide\"\nmu = { from = 0.2, to = 0.1, count = 3 }\n", "object[1].mu"},
      {pulse + slide + "[[object]]\nmodel = \"rock\"\nshape = \"block\"\nwidth = [0.04]\nheight = \"20cm\"\n",
       "object[2].width"},
      {pulse + "[[object]]\nmodel = \"slide\"\nmu = [\"0.1\"]\n", "object[1].mu"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path p = dir.path() / fmt::format("bad{}.toml", i);
    write_file(p, cases[i].first);
    const auto r = run_cli("sweep " + quote(p.string()));
    SCOPED_TRACE(cases[i].first);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(p.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(cases[i].second + ":"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / fmt::format("bad{}.csv.parts", i))) << "work started";
  }
}

TEST(CliSweep, AChangedSweepIsRefusedUntilRestart) {
  TempDir dir;
  const fs::path p = dir.path() / "s.toml";
  write_file(p, kPulseSweep);
  ASSERT_EQ(run_cli("sweep " + quote(p.string()) + " --quiet").exit_code, 0);
  std::string changed = kPulseSweep;
  changed.replace(changed.find("[0.05, 0.1, 0.2]"), 16, "[0.05, 0.1, 0.25]");
  write_file(p, changed);
  const auto refused = run_cli("sweep " + quote(p.string()));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--restart"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("output.path"), std::string::npos) << refused.err;
  const auto restarted = run_cli("sweep " + quote(p.string()) + " --restart --verbose");
  ASSERT_EQ(restarted.exit_code, 0) << restarted.err;
  EXPECT_NE(restarted.err.find("(restarted)"), std::string::npos) << restarted.err;
  EXPECT_NE(slurp(dir.path() / "results.csv").find(",0.25,"), std::string::npos);
}

TEST(CliSweep, QuietAndSummaryOutput) {
  TempDir dir;
  const fs::path p = dir.path() / "s.toml";
  write_file(p, kPulseSweep);
  const auto r = run_cli("sweep " + quote(p.string()) + " --out " + quote((dir.path() / "x.csv").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("wrote"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "no progress bar when stderr is not a terminal";
  const auto q = run_cli("sweep " + quote(p.string()) + " --quiet --restart --out " +
                         quote((dir.path() / "x.csv").string()));
  ASSERT_EQ(q.exit_code, 0) << q.err;
  EXPECT_EQ(q.err, "");
  EXPECT_EQ(run_cli("sweep " + quote(p.string()) + " --threads -1").exit_code, 2);
}

/// FNV-1a, 64 bits, over a file's bytes: a fixed, dependency-free fingerprint of an output for the pins below.
std::uint64_t fnv1a64(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return h;
}

/// The outputs of the example sweeps are an interface promise: the same bytes from one version to the next. The
/// pinned sizes and FNV-1a hashes were computed by running the example sweeps with the build of main before the
/// ensemble engine was split into units (commit 4fefb96; sha256 of pulses.csv 56c16de6...cab006d, pulses.jsonl
/// 540dd25e...ad7c6ab1, records.csv c919db16...c372e18, records.jsonl 12a2c297...28bea). The numbers are exact
/// (shortest round-trip text of IEEE doubles), so any change of a digit, a column or an order shows here; a
/// platform whose libm rounds a transcendental differently would also show, which is what a pin is for.
/// Re-pinned once, after the rocking integrator's per-step sincos became a series (branch solvers): the rows were
/// compared with the earlier build's column by column, every difference was in a rocking result column and at most
/// 1.5e-7 relative (energy_lost_j_per_kg of 7.8e-6 J/kg), inside the integrator's tolerance; the format, the order
/// and every sliding column stayed byte-identical.
/// Re-pinned a second time, after the rocking Dormand-Prince stepper was written out by hand and its events located
/// by Newton on the dense polynomial (branch speed, issue 12 item 8): compared column by column with the outputs of
/// the previous pins, no integer or text column changed (impacts, uplifts, overturned, states), every sliding column
/// stayed byte-identical, and the rocking columns moved by at most 2.5e-7 relative (energy_lost_j_per_kg of
/// 7.8e-6 J/kg, 2e-10 J/kg absolute), 2.2e-8 relative in max_abs_theta_dot_rad_s and 1.4e-8 in event times
/// (6.5e-8 s), the level of rel_tol = 1e-8; values below 1e-9 (a rotation of 1e-41 rad) aside.
/// Re-pinned a third time, after the stages of that stepper took the rotation from the step's increment and formed
/// the forcing's combination with the reference sin/cos apart from the state (branch rockspeed, issue 12 item 8;
/// the same method, steps and tolerance, the arithmetic reordered): compared column by column with the previous
/// pin's outputs, no integer or text column changed and every sliding column stayed byte-identical; in pulses the
/// rocking columns moved by at most 1.1e-13 relative (round-off), in records by at most 6.3e-8 relative
/// (energy_lost_j_per_kg of 3.0e-6 J/kg, 1.9e-13 J/kg absolute), 8.6e-10 in max_abs_theta_dot_rad_s and 5.6e-10 in
/// event times (2.6e-9 s). Set aside: the 8 pulse rows whose amplitude is exactly the uplift level g tan(alpha)
/// (0.2 g on a/h = 0.2), where the lift-off is driven by the round-off of g sin(alpha) - a cos(alpha) and the
/// "motion" is noise (|theta| <= 6e-13 rad, |theta'| <= 3e-6 rad/s): those values changed by up to 20 %.
struct PinnedOutput {
  const char* file;
  std::size_t bytes;
  std::uint64_t fnv1a;
};

void expect_pinned(const fs::path& dir, const std::vector<PinnedOutput>& pins) {
  for (const auto& pin : pins) {
    SCOPED_TRACE(pin.file);
    const std::string bytes = slurp(dir / pin.file);
    EXPECT_EQ(bytes.size(), pin.bytes);
    EXPECT_EQ(fnv1a64(bytes), pin.fnv1a) << fmt::format("got {:#x}", fnv1a64(bytes));
  }
}

/// A tmpfs of a given size mounted on a directory for the life of the object (needs CAP_SYS_ADMIN: root).
class SmallDisk {
 public:
  SmallDisk(const fs::path& dir, const char* size) : dir_(dir) {
    fs::create_directories(dir);
    mounted_ = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, (std::string("size=") + size).c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  [[nodiscard]] bool mounted() const { return mounted_; }

 private:
  fs::path dir_;
  bool mounted_ = false;
};

// A disk that fills up while the output is assembled (the chunks fit, the output beside them does not): exit status 4
// (an output failure, not bad input), the system's reason, no partial output and no temporary file left behind;
// the chunks stay, so the same sweep finishes once there is room.
TEST(CliSweep, DiskFullDuringAssemblyIsAnOutputFailure) {
  TempDir dir;
  const fs::path disk = dir.path() / "disk";
  SmallDisk small(disk, "3m");  // pulses.toml: 2.3 MB of chunks, then 2.3 MB more of output
  if (!small.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const fs::path example = fs::path(TOPPLE_SOURCE_DIR) / "examples" / "sweep" / "pulses.toml";
  const auto r = run_cli("sweep " + quote(example.string()) + " --quiet --out " + quote((disk / "p.csv").string()));
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(disk / "p.csv"));
  for (const auto& e : fs::recursive_directory_iterator(disk)) {
    EXPECT_NE(e.path().filename().string().rfind(".tmp-", 0), 0u) << e.path();
  }
  const fs::path parts = disk / "p.csv.parts";
  ASSERT_TRUE(fs::exists(parts));
  // Room again: move the store to a normal disk; the sweep resumes from its chunks.
  const fs::path out = dir.path() / "p.csv";
  fs::copy(parts, dir.path() / "p.csv.parts", fs::copy_options::recursive);
  const auto again = run_cli("sweep " + quote(example.string()) + " --verbose --out " + quote(out.string()));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(verbose_count(again.err, "computed"), 0u) << again.err;
  expect_pinned(dir.path(), {{"p.csv", 2313507, 0x89fe2c3dbaefa2cfULL}});
}

/// Runs examples/sweep/<name>.toml with JSON lines into a fresh directory and checks the outputs against the pins.
void expect_example_pinned(const std::string& name, const std::vector<PinnedOutput>& pins) {
  TempDir dir;
  const fs::path example = fs::path(TOPPLE_SOURCE_DIR) / "examples" / "sweep" / (name + ".toml");
  const auto r = run_cli("sweep " + quote(example.string()) + " --jsonl --quiet --out " +
                         quote((dir.path() / (name + ".csv")).string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_pinned(dir.path(), pins);
}

TEST(CliSweep, ExamplePulseSweepGivesThePinnedBytes) {
  expect_example_pinned("pulses", {{"pulses.csv", 2313507, 0x89fe2c3dbaefa2cfULL},
                                   {"pulses.jsonl", 9804597, 0x426caed1c84a1652ULL}});
}

TEST(CliSweep, ExampleRecordSweepGivesThePinnedBytes) {
  if (!test::have_shared()) GTEST_SKIP() << "shared/records not found";
  expect_example_pinned("records", {{"records.csv", 820472, 0x548b1d76420871c4ULL},
                                    {"records.jsonl", 3122034, 0x31c7775ee2ad9367ULL}});
}

}  // namespace
}  // namespace topple
