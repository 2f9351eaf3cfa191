// The ensemble engine: plan expansion, rows equal to direct solver calls, determinism over threads, the resumable
// store (resume after a failure, truncated chunks, changed plans, locks) and the formats.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/noise_record.hpp"
#include "support/shared_data.hpp"
#include "topple/ensemble/sweep.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/summary_fields.hpp"

namespace topple::ensemble {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

constexpr double kG = kStandardGravity;

/// A reproducible broadband record (tests/support): filtered noise near 2.5 Hz, n samples at dt, PGA 0.4 g.
std::shared_ptr<const GroundMotion> noise_record(unsigned seed, std::size_t n = 1500, double dt = 0.01) {
  return std::make_shared<const GroundMotion>(test::noise_record({.seed = seed, .samples = n, .dt_s = dt,
                                                                  .pga_m_s2 = 0.4 * kG, .resonance_hz = 2.5,
                                                                  .pole_radius = 0.95, .envelope_peak_s = 4.0}));
}

/// Record `rec` along east (azimuth 90) with a still north partner on its grid: a collinear set, whose projection on
/// bearing 90 is the record itself (MotionSet::projected).
std::shared_ptr<const MotionSet> collinear_set(const GroundMotion& rec) {
  const GroundMotion quiet = GroundMotion::uniform(std::vector<double>(rec.size(), 0.0), rec.dt_s(), rec.start_time_s());
  return std::make_shared<const MotionSet>(MotionSet::make(rec, &quiet, ComponentAzimuths{90.0, 0.0}));
}

/// The field of the InputError make_plan refuses `spec` with; "(none)" when it accepts it.
std::string refused_field(const SweepSpec& spec) {
  try {
    (void)make_plan(spec);
  } catch (const InputError& e) {
    return e.where().field;
  }
  return "(none)";
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Two records and two pulses; level and inclined blocks (a run of mu for the batched kernel, one with mu_kinetic
/// below mu_static), one-way; two rocking blocks and a cylinder.
SweepSpec mixed_spec() {
  SweepSpec s;
  s.records.push_back({"rec-a", noise_record(1)});
  s.records.push_back({"rec-b", noise_record(2, 900, 0.02)});
  PulseInput p;
  p.spec.kind = PulseKind::sine;
  p.spec.amplitude_m_s2 = 0.5 * kG;
  p.spec.duration_s = 0.5;
  p.spec.tail_s = 2.5;
  p.name = "sine";
  s.pulses.push_back(p);
  p.spec.kind = PulseKind::rectangular;
  p.spec.amplitude_m_s2 = 0.3 * kG;
  p.spec.duration_s = 0.2;
  p.spec.tail_s = 1.0;
  p.name = "rect";
  s.pulses.push_back(p);
  s.time_scales = {1.0, 1.5};
  s.scales = {{ScaleSpec::Kind::pga, 0.3 * kG}, {ScaleSpec::Kind::factor, 0.8}};
  s.inverse = {false, true};
  for (const double mu : {0.05, 0.1, 0.15, 0.2}) s.objects.emplace_back(SlideObject{SlidingBlock::make(mu), 0.0});
  s.objects.emplace_back(SlideObject{SlidingBlock::make(0.2, 0.15), 0.0});
  for (const double mu : {0.3, 0.4}) {
    s.objects.emplace_back(SlideObject{SlidingBlock::make(mu, mu, 10.0 * kPi / 180.0, SlidingMode::one_way), 10.0});
  }
  RockObject r;
  r.body = RockingBody::block(0.08, 0.4);
  r.width_m = 0.08;
  r.height_m = 0.4;
  s.objects.emplace_back(r);
  r.options.restitution = RestitutionMode::given;
  r.options.e = 0.9;
  r.options.mu = 0.5;
  s.objects.emplace_back(r);
  RockObject c;
  c.body = RockingBody::cylinder(0.1, 0.3);
  c.diameter_m = 0.1;
  c.height_m = 0.3;
  s.objects.emplace_back(c);
  s.chunk_runs = 7;  // chunks straddle motions
  return s;
}

std::size_t column(const ResultTable& t, const std::string& name) {
  const auto it = std::find(t.columns.begin(), t.columns.end(), name);
  if (it == t.columns.end()) throw std::runtime_error("no column " + name);
  return static_cast<std::size_t>(it - t.columns.begin());
}

double number(const Value& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  throw std::runtime_error("not a number");
}

TEST(EnsemblePlan, ExpansionOrderAndColumns) {
  const SweepSpec spec = mixed_spec();
  const Plan plan = make_plan(spec);
  // records x time scales x scales x polarities, then pulses x polarities
  ASSERT_EQ(plan.motions.size(), 2u * 2u * 2u * 2u + 2u * 2u);
  ASSERT_EQ(plan.objects.size(), spec.objects.size());
  EXPECT_EQ(plan.runs(), plan.motions.size() * plan.objects.size());
  EXPECT_EQ(plan.chunk_size(), 7u);
  EXPECT_EQ(plan.chunks(), (plan.runs() + 6) / 7);
  const std::vector<std::string> motion_cols{"motion",     "pulse_kind",   "pulse_amp_g", "pulse_duration_s",
                                             "time_scale", "scale_factor", "pga_g",       "polarity"};
  EXPECT_EQ(plan.motion_columns, motion_cols);
  const std::vector<std::string> object_cols{"model",    "g_m_s2",     "mu",       "mu_kinetic",
                                             "slope_deg", "mode",      "shape",    "width_m",
                                             "diameter_m", "height_m", "restitution"};
  EXPECT_EQ(plan.object_columns, object_cols);
  EXPECT_EQ(plan.columns().front(), "run");
  // The third motion is record a, time scale 1, factor 0.8, normal polarity.
  const auto& m2 = plan.motions[2].values;
  EXPECT_EQ(std::get<std::string>(m2[0]), "rec-a");
  EXPECT_TRUE(std::holds_alternative<std::monostate>(m2[1]));  // no pulse kind for a record
  EXPECT_EQ(std::get<double>(m2[5]), 0.8);
  EXPECT_EQ(std::get<double>(m2[6]), spec.records[0].motion->pga_m_s2() * 0.8 / kG);
  EXPECT_EQ(std::get<std::string>(m2[7]), "normal");
  EXPECT_EQ(std::get<std::string>(plan.motions[3].values[7]), "inverse");
  const auto& pulse = plan.motions[16].values;
  EXPECT_EQ(std::get<std::string>(pulse[0]), "sine");
  EXPECT_EQ(std::get<std::string>(pulse[1]), "sine");
  EXPECT_EQ(std::get<double>(pulse[2]), 0.5);
  EXPECT_EQ(std::get<double>(pulse[3]), 0.5);
}

// The result columns are the field tables' sweep fields (summary_fields.hpp), in the order of the sweep outputs
// written before the tables existed (the CSV header is an interface): sliding, then rocking, end_time_s once.
TEST(EnsemblePlan, ResultColumnsComeFromTheFieldTables) {
  const Plan plan = make_plan(mixed_spec());
  const std::vector<std::string> expected{
      "max_abs_displacement_m", "max_displacement_time_s", "residual_displacement_m", "max_abs_velocity_m_s",
      "slip_episodes",          "first_slip_time_s",       "total_slip_duration_s",   "end_time_s",
      "at_rest_at_end",         "contact_lost_time_s",     "yield_down_g",            "yield_up_g",
      "max_abs_rotation_rad",   "max_rotation_over_alpha", "max_rotation_time_s",     "max_abs_theta_dot_rad_s",
      "impacts",                "uplifts",                 "uplift_time_s",           "exceeded_alpha_time_s",
      "overturned",             "overturn_time_s",         "energy_lost_j_per_kg",    "end_state",
      "still_rocking_at_end",   "onset_mode",              "critical_mu",             "alpha_rad",
      "p_rad_s",                "e"};
  EXPECT_EQ(plan.result_columns, expected);
  // Each table's sweep positions are 0..k-1, each once, and its names are unique.
  const auto check = [](const auto& table, int sweep_count) {
    std::vector<int> positions;
    std::set<std::string> names;
    for (const auto& f : table) {
      EXPECT_TRUE(names.insert(f.name).second) << f.name;
      if (f.sweep_column >= 0) positions.push_back(f.sweep_column);
    }
    std::sort(positions.begin(), positions.end());
    ASSERT_EQ(positions.size(), static_cast<std::size_t>(sweep_count));
    for (int i = 0; i < sweep_count; ++i) EXPECT_EQ(positions[static_cast<std::size_t>(i)], i);
  };
  check(kSlidingFields, 12);
  check(kRockingFields, 19);
  check(kSliding2dFields, 14);
}

// Sliding objects under a record set are bidirectional sliders. The columns: a sweep of single records keeps its
// columns (above); a set adds residual_azimuth_deg, residual_east_m, residual_north_m and path_length_m after the
// 1-D sliding columns, sharing the others. A record on the first component (east) with a zero second component is
// collinear input: the 2-D row is the 1-D row of that record, the block moving west where the 1-D d is positive
// (sliding2d.hpp); the 2-D solver matches the exact 1-D one to 1e-9 relative (test_sliding2d).
TEST(EnsembleRun, SlidersUnderASetAreBidirectionalAndCollinearInputIsThe1dRow) {
  SweepSpec spec;
  const auto rec = noise_record(3);
  spec.records.push_back({"rec", rec});
  spec.record_sets.push_back({"rec+zero", collinear_set(*rec)});
  spec.scales = {{ScaleSpec::Kind::factor, 1.0}, {ScaleSpec::Kind::factor, 0.7}};
  spec.inverse = {false, true};
  for (const double mu : {0.05, 0.1}) spec.objects.emplace_back(SlideObject{SlidingBlock::make(mu), 0.0});
  spec.objects.emplace_back(SlideObject{SlidingBlock::make(0.2, 0.15), 0.0});
  const Plan plan = make_plan(spec);
  const std::vector<std::string> expected{
      "max_abs_displacement_m", "max_displacement_time_s", "residual_displacement_m", "max_abs_velocity_m_s",
      "slip_episodes",          "first_slip_time_s",       "total_slip_duration_s",   "end_time_s",
      "at_rest_at_end",         "contact_lost_time_s",     "yield_down_g",            "yield_up_g",
      "residual_azimuth_deg",   "residual_east_m",         "residual_north_m",        "path_length_m"};
  EXPECT_EQ(plan.result_columns, expected);
  EXPECT_EQ(plan.motion_columns.back(), "bearing_deg");  // no bearing given: its cells are empty
  const ResultTable t = run_in_memory(plan);
  const std::size_t n_obj = spec.objects.size();
  const std::size_t n_cases = spec.scales.size() * spec.inverse.size();
  ASSERT_EQ(t.rows.size(), 2 * n_cases * n_obj);
  const auto cell = [&](std::size_t run, const std::string& name) { return t.rows[run][column(t, name)]; };
  int moved = 0;
  for (std::size_t run = 0; run < n_cases * n_obj; ++run) {
    SCOPED_TRACE("run " + std::to_string(run));
    const std::size_t two = run + n_cases * n_obj;  // the set's runs follow the record's, in the same order
    const double d = number(cell(run, "residual_displacement_m"));
    const double scale = number(cell(run, "max_abs_displacement_m"));
    const double tol = 1e-9 * std::max(scale, 1e-6);
    EXPECT_NEAR(number(cell(two, "residual_displacement_m")), std::abs(d), tol);
    EXPECT_NEAR(number(cell(two, "residual_east_m")), -d, tol);
    EXPECT_NEAR(number(cell(two, "residual_north_m")), 0.0, tol);
    EXPECT_NEAR(number(cell(two, "max_abs_displacement_m")), scale, tol);
    EXPECT_EQ(number(cell(two, "slip_episodes")), number(cell(run, "slip_episodes")));
    if (std::abs(d) > 1e-6) {
      ++moved;
      EXPECT_NEAR(number(cell(two, "residual_azimuth_deg")), d > 0.0 ? 270.0 : 90.0, 1e-6);
    }
    EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(run, "path_length_m")));  // a 1-D row
    EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(two, "yield_down_g")));   // a 2-D row
    EXPECT_GE(number(cell(two, "path_length_m")), scale);  // the track is at least as long as the farthest point
  }
  EXPECT_GT(moved, 4);
  // One-way and inclined sliders have no 2-D meaning under a set (sliding2d.hpp): refused naming the object's field.
  spec.objects.emplace_back(SlideObject{SlidingBlock::make(0.3, 0.3, 0.1, SlidingMode::one_way), 0.1 * 180.0 / kPi});
  EXPECT_EQ(refused_field(spec), "object[4].mode");  // a one-way slider under a set
  spec.objects.back() = SlideObject{SlidingBlock::make(0.3, 0.3, 0.1), 0.1 * 180.0 / kPi};
  EXPECT_EQ(refused_field(spec), "object[4].slope_deg");  // an inclined slider under a set
}

// A three-dimensional object (model "3d": a box with its depth) under a set whose second component is zero, at the
// bearing of the first component (east): the input lies in the box's plane of symmetry across its width, where the
// three-dimensional engine is the planar one (rigid3d.hpp; test_rigid3d: 1e-6 at rel_tol 1e-10). The planar
// oriented box beside it sees the same projection along its bearing and nothing across: the verdicts are equal, the
// tilt over the static limit is the planar theta / alpha (both engines at the default rel_tol 1e-8: 1e-5), and the
// fall azimuth is the bearing's side the planar body fell to (theta > 0: toward the bearing). The 3-D columns are
// added after the others (a sweep without a 3-D object keeps its columns) and a planar row leaves them empty.
TEST(EnsembleRun, ThreeDimensionalBoxInItsPlaneOfSymmetryGivesThePlanarVerdicts) {
  SweepSpec spec;
  const auto rec = noise_record(5);
  spec.record_sets.push_back({"rec+zero", collinear_set(*rec)});
  spec.bearings_deg = {90.0};
  spec.scales = {{ScaleSpec::Kind::factor, 0.4}, {ScaleSpec::Kind::factor, 0.8}, {ScaleSpec::Kind::factor, 1.6}};
  spec.inverse = {false, true};
  RockObject planar{.body = RockingBody::block(0.2, 0.8), .options = {}, .width_m = 0.2, .height_m = 0.8,
                    .diameter_m = std::nullopt};
  planar.depth_m = 0.3;
  RockObject three_d = planar;
  three_d.body_3d = RigidBody3D::box(0.2, 0.3, 0.8);
  spec.objects = {planar};
  const Plan planar_plan = make_plan(spec);
  spec.objects = {planar, three_d};
  const Plan plan = make_plan(spec);
  std::vector<std::string> expected = planar_plan.result_columns;
  for (const char* c : {"overturn_azimuth_deg", "max_tilt_rad", "max_tilt_azimuth_deg", "max_tilt_time_s",
                        "max_tilt_over_limit", "exceeded_limit_time_s", "flight_time_s", "end_mode"}) {
    expected.emplace_back(c);
  }
  EXPECT_EQ(plan.result_columns, expected);
  EXPECT_NE(plan.identity, planar_plan.identity);
  const ResultTable t = run_in_memory(plan);
  ASSERT_EQ(t.rows.size(), 12U);
  const auto cell = [&](std::size_t run, const std::string& name) { return t.rows[run][column(t, name)]; };
  int fell = 0;
  for (std::size_t run = 0; run < t.rows.size(); run += 2) {
    SCOPED_TRACE("run " + std::to_string(run));
    const std::size_t r3 = run + 1;
    EXPECT_EQ(std::get<std::string>(cell(run, "model")), "rock");
    EXPECT_EQ(std::get<std::string>(cell(r3, "model")), "3d");
    EXPECT_EQ(std::get<std::string>(cell(run, "governing_axis")), "bearing");
    EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(r3, "governing_axis")));
    EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(run, "max_tilt_over_limit")));
    const bool over = std::get<bool>(cell(run, "overturned"));
    EXPECT_EQ(std::get<bool>(cell(r3, "overturned")), over);
    EXPECT_NEAR(number(cell(r3, "max_tilt_over_limit")), number(cell(run, "max_rotation_over_alpha")), 1e-5);
    EXPECT_NEAR(number(cell(r3, "max_tilt_rad")), number(cell(run, "max_abs_rotation_rad")), 1e-5);
    EXPECT_EQ(number(cell(r3, "impacts")), number(cell(run, "impacts")));
    if (over) {
      ++fell;
      EXPECT_NEAR(number(cell(r3, "overturn_time_s")), number(cell(run, "overturn_time_s")), 1e-5);
      // The planar replay tells the side: theta > 0 is toward the bearing (oriented.hpp).
      RockingOptions po;
      const double factor = number(cell(run, "scale_factor"));
      const bool inverse = std::get<std::string>(cell(run, "polarity")) == "inverse";
      const RockingSummary p = rock_summary(rec->scaled(inverse ? -factor : factor), planar.body, po);
      ASSERT_TRUE(p.overturned);
      EXPECT_NEAR(number(cell(r3, "overturn_azimuth_deg")), p.overturned_side > 0 ? 90.0 : 270.0, 1e-3);
    } else {
      EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(r3, "overturn_azimuth_deg")));
    }
  }
  EXPECT_GT(fell, 0);
  EXPECT_LT(fell, 6);
  // Under a single record a 3-D object has no second component: refused naming its model.
  spec.records.push_back({"rec", rec});
  spec.objects = {three_d};
  EXPECT_EQ(refused_field(spec), "object[1].model");  // a 3-D object under a single record
  spec.records.clear();
  // Friction (Rigid3DOptions::mu_s, mu_k) is taken; out of the engine's range it is refused before any run.
  three_d.options.mu = 0.5;
  spec.objects = {three_d};
  EXPECT_NO_THROW((void)make_plan(spec));
  three_d.mu_kinetic = 0.6;
  spec.objects = {three_d};
  EXPECT_EQ(refused_field(spec), "object[1].mu_kinetic");  // mu_kinetic above mu
  three_d.options.mu = std::nullopt;
  three_d.mu_kinetic = 0.3;
  spec.objects = {three_d};
  EXPECT_EQ(refused_field(spec), "object[1].mu_kinetic");  // mu_kinetic without mu
}

/// The cell as a number (bool, integer or double), NaN if empty.
double number_or_nan(const Value& v) {
  if (std::holds_alternative<std::monostate>(v)) return std::nan("");
  if (const auto* b = std::get_if<bool>(&v)) return *b ? 1.0 : 0.0;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  return std::get<double>(v);
}

// A solid cylinder under model "3d" (the rim engine, rigid3d_disc.hpp) under a set whose second component is zero:
// the motion stays in the vertical plane of the input, where the rim engine is the planar cylinder (rocking.hpp;
// test_rigid3d_disc: 1e-6 at rel_tol 1e-12). Here both at the default rel_tol 1e-8: the verdict equal, the max tilt
// and tilt over the limit within 1e-5 of the planar rock_summary's on the same component (and of the planar
// model = "rock" row beside it, the worst of its directions). Axisymmetric: no bearing needed, and at two bearings
// the rows are one run.
TEST(EnsembleRun, ThreeDimensionalCylinderUnderOneComponentIsThePlanarCylinder) {
  SweepSpec spec;
  const auto rec = noise_record(5);
  spec.record_sets.push_back({"rec+zero", collinear_set(*rec)});
  spec.scales = {{ScaleSpec::Kind::factor, 0.4}, {ScaleSpec::Kind::factor, 0.8}, {ScaleSpec::Kind::factor, 1.6}};
  spec.inverse = {false, true};
  RockObject planar{.body = RockingBody::cylinder(0.3, 1.0), .options = {}, .width_m = std::nullopt,
                    .height_m = 1.0, .diameter_m = 0.3};
  RockObject three_d = planar;
  three_d.cylinder_3d = CylinderBody3D::solid(0.3, 1.0);
  spec.objects = {planar, three_d};
  const Plan plan = make_plan(spec);  // no bearing: cylinders need none
  const ResultTable t = run_in_memory(plan);
  ASSERT_EQ(t.rows.size(), 12U);
  const auto cell = [&](std::size_t run, const std::string& name) { return t.rows[run][column(t, name)]; };
  int fell = 0, stood = 0;
  for (std::size_t run = 0; run < t.rows.size(); run += 2) {
    SCOPED_TRACE("run " + std::to_string(run));
    const std::size_t r3 = run + 1;
    EXPECT_EQ(std::get<std::string>(cell(r3, "model")), "3d");
    EXPECT_EQ(std::get<std::string>(cell(r3, "shape")), "cylinder");
    const double factor = number(cell(run, "scale_factor"));
    const bool inverse = std::get<std::string>(cell(run, "polarity")) == "inverse";
    const RockingSummary p = rock_summary(rec->scaled(inverse ? -factor : factor), planar.body, RockingOptions{});
    EXPECT_EQ(std::get<bool>(cell(r3, "overturned")), p.overturned);
    EXPECT_EQ(std::get<bool>(cell(run, "overturned")), p.overturned);
    EXPECT_NEAR(number(cell(r3, "max_tilt_rad")), p.max_abs_rotation_rad, 1e-5);
    EXPECT_NEAR(number(cell(r3, "max_tilt_over_limit")), p.max_rotation_over_alpha, 1e-5);
    EXPECT_NEAR(number(cell(r3, "max_tilt_rad")), number(cell(run, "max_abs_rotation_rad")), 1e-5);
    EXPECT_EQ(number(cell(r3, "impacts")), static_cast<double>(p.impacts));
    if (p.overturned) {
      ++fell;
      EXPECT_NEAR(number(cell(r3, "overturn_time_s")), *p.overturn_time_s, 1e-5);
      // along the input: east (90) or west (270)
      const double az = number(cell(r3, "overturn_azimuth_deg"));
      EXPECT_LT(std::min(std::abs(az - 90.0), std::abs(az - 270.0)), 1e-3);
    } else {
      ++stood;
    }
  }
  EXPECT_GT(fell, 0);
  EXPECT_GT(stood, 0);
  // At two bearings the cylinder's rows are the same run (its bearing does not enter).
  spec.bearings_deg = {0.0, 37.0};
  spec.objects = {three_d};
  const ResultTable tb = run_in_memory(make_plan(spec));
  ASSERT_EQ(tb.rows.size(), 12U);
  const std::size_t tilt = column(tb, "max_tilt_rad");
  for (std::size_t run = 0; run < 6; ++run) EXPECT_EQ(number(tb.rows[run][tilt]), number(tb.rows[run + 6][tilt]));
  // With friction (mu, mu_kinetic: Rigid3DOptions::mu_s, mu_k; rigid3d_disc.hpp) each row is rock3d_cylinder's own
  // run with them on the pair along east and north (called here directly); a bad mu_kinetic is refused by name.
  three_d.options.mu = 0.5;
  three_d.mu_kinetic = 0.4;
  spec.objects = {three_d};
  spec.bearings_deg = {0.0};
  const ResultTable tf = run_in_memory(make_plan(spec));
  ASSERT_EQ(tf.rows.size(), 6U);
  const std::size_t fell_col = column(tf, "overturned");
  for (std::size_t run = 0; run < 6; ++run) {
    const double factor = number(tf.rows[run][column(tf, "scale_factor")]);
    const bool inverse = std::get<std::string>(tf.rows[run][column(tf, "polarity")]) == "inverse";
    const GroundMotion east = rec->scaled(inverse ? -factor : factor);
    Rigid3DOptions o = rigid3d_options(three_d.options);
    o.mu_s = 0.5;
    o.mu_k = 0.4;
    const GroundMotion quiet = GroundMotion::uniform(std::vector<double>(rec->size(), 0.0), rec->dt_s(),
                                                     rec->start_time_s());  // collinear_set's still north
    const Rigid3DSummary s = rock3d_cylinder(east, &quiet, nullptr, CylinderBody3D::solid(0.3, 1.0), o).summary;
    EXPECT_EQ(std::get<bool>(tf.rows[run][fell_col]), s.overturned) << run;
    EXPECT_EQ(number(tf.rows[run][column(tf, "max_tilt_rad")]), s.max_tilt_rad) << run;
  }
  three_d.mu_kinetic = 0.6;
  spec.objects = {three_d};
  EXPECT_EQ(refused_field(spec), "object[1].mu_kinetic");  // mu_kinetic above mu
}

// Two horizontal components: the cylinder on its rim (model "3d") against the planar cylinder in the worst of its
// directions (model "rock"). Each 3-D row is rock3d_cylinder's own run on the pair along east and north (called here
// directly, not through the sweep), and at some scale the two models' verdicts differ (the 3-D body wobbles and rolls
// round its rim, which no plane of rocking has).
TEST(EnsembleRun, ThreeDimensionalCylinderUnderTwoComponentsIsTheRimEngine) {
  SweepSpec spec;
  const auto h1 = noise_record(11), h2 = noise_record(12);
  const auto set = std::make_shared<const MotionSet>(MotionSet::make(*h1, h2.get(), ComponentAzimuths{30.0, 120.0}));
  spec.record_sets.push_back({"pair", set});
  spec.scales.clear();
  for (const double f : {0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.4}) spec.scales.push_back({ScaleSpec::Kind::factor, f});
  RockObject planar{.body = RockingBody::cylinder(0.3, 1.0), .options = {}, .width_m = std::nullopt,
                    .height_m = 1.0, .diameter_m = 0.3};
  RockObject three_d = planar;
  three_d.cylinder_3d = CylinderBody3D::solid(0.3, 1.0);
  spec.objects = {planar, three_d};
  const ResultTable t = run_in_memory(make_plan(spec));
  ASSERT_EQ(t.rows.size(), 18U);
  const auto cell = [&](std::size_t run, const std::string& name) { return t.rows[run][column(t, name)]; };
  int differ = 0;
  for (std::size_t run = 0; run < t.rows.size(); run += 2) {
    const double factor = number(cell(run, "scale_factor"));
    SCOPED_TRACE("factor " + std::to_string(factor));
    const GroundMotion a = h1->scaled(factor), b = h2->scaled(factor);
    const MotionSet scaled = MotionSet::make(a, &b, ComponentAzimuths{30.0, 120.0});
    const GroundMotion east = scaled.projected(90.0), north = scaled.projected(0.0);
    const Rigid3DSummary s = rock3d_cylinder(east, &north, nullptr, *three_d.cylinder_3d, Rigid3DOptions{}).summary;
    const std::size_t r3 = run + 1;
    EXPECT_EQ(std::get<bool>(cell(r3, "overturned")), s.overturned);
    EXPECT_EQ(number(cell(r3, "max_tilt_rad")), s.max_tilt_rad);
    EXPECT_EQ(number(cell(r3, "impacts")), static_cast<double>(s.impacts));
    if (s.overturned) {
      EXPECT_EQ(number(cell(r3, "overturn_azimuth_deg")), s.overturn_azimuth_deg);
    }
    const bool planar_fell = std::get<bool>(cell(run, "overturned"));
    std::printf("factor %.2f: planar worst direction %s (max %.4f rad), 3-D %s (max tilt %.4f rad)\n", factor,
                planar_fell ? "fell" : "stood", number_or_nan(cell(run, "max_abs_rotation_rad")),
                s.overturned ? "fell" : "stood", s.max_tilt_rad);
    differ += planar_fell != s.overturned ? 1 : 0;
  }
  EXPECT_GT(differ, 0);
}

// Friction under model "3d" (Rigid3DOptions::mu_s, mu_k): a box with mu and mu_kinetic is rock3d's run with those
// (called directly), with its sliding columns; without mu the row is the no-slip engine's and the sliding columns
// are not there (a sweep without friction keeps its columns).
TEST(EnsembleRun, ThreeDimensionalFrictionIsPassedToTheEngine) {
  SweepSpec spec;
  const auto h1 = noise_record(21), h2 = noise_record(22);
  const auto set = std::make_shared<const MotionSet>(MotionSet::make(*h1, h2.get(), ComponentAzimuths{0.0, 90.0}));
  spec.record_sets.push_back({"pair", set});
  spec.bearings_deg = {20.0};
  RockObject box{.body = RockingBody::block(0.4, 0.8), .options = {}, .width_m = 0.4, .height_m = 0.8,
                 .diameter_m = std::nullopt};
  box.depth_m = 0.5;
  box.body_3d = RigidBody3D::box(0.4, 0.5, 0.8);
  spec.objects = {box};
  const std::vector<std::string> dry = make_plan(spec).columns();
  for (const char* c : {"residual_slide_east_m", "slide_path_length_m", "slide_rock_time_s", "mu_kinetic",
                        "slide_rock_duration_s", "flights", "flight_duration_s", "residual_yaw_deg", "painleve_events"}) {
    EXPECT_EQ(std::count(dry.begin(), dry.end(), c), 0) << c;
  }
  RockObject slippery = box;
  slippery.options.mu = 0.25;
  slippery.mu_kinetic = 0.2;
  spec.objects = {box, slippery};
  const ResultTable t = run_in_memory(make_plan(spec));
  ASSERT_EQ(t.rows.size(), 2U);
  const auto cell = [&](std::size_t run, const std::string& name) { return t.rows[run][column(t, name)]; };
  const GroundMotion east = set->projected(90.0), north = set->projected(0.0);
  const RigidBody3D turned = box.body_3d->rotated_about_vertical((90.0 - 20.0) * kPi / 180.0);
  const Rigid3DSummary no_slip = rock3d(east, &north, nullptr, turned, Rigid3DOptions{}).summary;
  Rigid3DOptions o;
  o.mu_s = 0.25;
  o.mu_k = 0.2;
  const Rigid3DSummary slid = rock3d(east, &north, nullptr, turned, o).summary;
  EXPECT_EQ(number(cell(0, "max_tilt_rad")), no_slip.max_tilt_rad);
  EXPECT_EQ(std::get<bool>(cell(0, "overturned")), no_slip.overturned);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(0, "residual_slide_east_m")));  // no friction: n/a
  EXPECT_EQ(number(cell(1, "mu")), 0.25);
  EXPECT_EQ(number(cell(1, "mu_kinetic")), 0.2);
  EXPECT_EQ(number(cell(1, "max_tilt_rad")), slid.max_tilt_rad);
  EXPECT_EQ(number(cell(1, "residual_slide_east_m")), slid.residual_slide_east_m);
  EXPECT_EQ(number(cell(1, "residual_slide_north_m")), slid.residual_slide_north_m);
  EXPECT_EQ(number(cell(1, "slide_path_length_m")), slid.slide_path_length_m);
  EXPECT_EQ(number(cell(1, "slip_episodes")), static_cast<double>(slid.slip_episodes));
  // the slide-rock and flight columns (issue 29), appended after the eight sliding columns, at the end of the header
  const std::vector<std::string> wet = make_plan(spec).columns();
  const std::vector<std::string> last(wet.end() - 6, wet.end());
  EXPECT_EQ(last, (std::vector<std::string>{"slide_rock_time_s", "slide_rock_duration_s", "flights",
                                            "flight_duration_s", "residual_yaw_deg", "painleve_events"}));
  EXPECT_EQ(number(cell(1, "slide_rock_duration_s")), slid.slide_rock_duration_s);
  EXPECT_EQ(number(cell(1, "flights")), static_cast<double>(slid.flights));
  EXPECT_EQ(number(cell(1, "flight_duration_s")), slid.flight_duration_s);
  EXPECT_EQ(number(cell(1, "residual_yaw_deg")), slid.residual_yaw_deg);
  EXPECT_EQ(number(cell(1, "painleve_events")), static_cast<double>(slid.painleve_events));
  EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(0, "residual_yaw_deg")));  // no friction: n/a
  EXPECT_GT(slid.slide_path_length_m, 1e-3);  // a PGA of 0.4 g over mu_s = 0.25: it slides
  std::printf("box 0.4 x 0.5 x 0.8 m, mu 0.25/0.2: path %.4g m, residual (%.4g, %.4g) m, max tilt %.4g rad%s\n",
              slid.slide_path_length_m, slid.residual_slide_east_m, slid.residual_slide_north_m, slid.max_tilt_rad,
              slid.slide_rock_time_s ? " (stopped at slide-rock)" : "");
}

TEST(EnsemblePlan, DefaultChunkSizeDependsOnRunsOnly) {
  EXPECT_EQ(default_chunk_runs(10), 1024u);
  EXPECT_EQ(default_chunk_runs(10'000), 1024u);
  EXPECT_EQ(default_chunk_runs(4'194'304), 1024u);
  EXPECT_EQ(default_chunk_runs(4'194'305), 1025u);
  EXPECT_EQ(default_chunk_runs(10'000'000), 2442u);
  EXPECT_EQ(default_chunk_runs(10'000'000'000), 100'000u);
}

// A transform is the chain time_scaled, scaled_to_pga, scaled, inverted in that order (ensemble.hpp); apply makes it
// without copying the base first (issue 32, performance only): the same samples, bit for bit, for every combination.
TEST(EnsemblePlan, TransformIsTheChainOfItsSteps) {
  test::NoiseRecordSpec ns;
  ns.pga_m_s2 = 2.0;
  const GroundMotion base = test::noise_record(ns);
  for (int mask = 0; mask < 16; ++mask) {
    MotionTransform t;
    GroundMotion want = base;
    if ((mask & 1) != 0) want = want.time_scaled(t.time_scale = 0.8);
    if ((mask & 2) != 0) want = want.scaled_to_pga(*(t.target_pga_m_s2 = 3.3));
    if ((mask & 4) != 0) want = want.scaled(*(t.factor = 0.7));
    if ((mask & 8) != 0) want = want.inverted();
    t.invert = (mask & 8) != 0;
    const GroundMotion got = t.apply(base);
    SCOPED_TRACE(mask);
    ASSERT_EQ(got.size(), want.size());
    EXPECT_EQ(got.dt_s(), want.dt_s());
    EXPECT_TRUE(std::equal(got.accel_m_s2().begin(), got.accel_m_s2().end(), want.accel_m_s2().begin()));
    if (mask == 0) {
      EXPECT_TRUE(t.is_identity());
    }
  }
}

TEST(EnsemblePlan, EmptySpecsAreRefused) {
  SweepSpec s = mixed_spec();
  s.objects.clear();
  EXPECT_THROW(static_cast<void>(make_plan(s)), InputError);
  s = mixed_spec();
  s.records.clear();
  s.pulses.clear();
  EXPECT_THROW(static_cast<void>(make_plan(s)), InputError);
  s = mixed_spec();
  s.records.push_back({"zero", std::make_shared<const GroundMotion>(GroundMotion::uniform({0.0, 0.0, 0.0}, 0.01))});
  try {
    static_cast<void>(make_plan(s));
    FAIL() << "a zero record scaled to a PGA must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("zero"), std::string::npos) << e.what();
  }
}

TEST(EnsemblePlan, MalformedPlansAreProgrammingErrors) {
  Plan p = make_plan(mixed_spec());
  p.objects[0].values.pop_back();
  EXPECT_THROW(check_plan(p), std::invalid_argument);
  p = make_plan(mixed_spec());
  p.motions[0].values[0] = std::string("two\nlines");
  EXPECT_THROW(check_plan(p), std::invalid_argument);
  p = make_plan(mixed_spec());
  p.result_columns.push_back("mu");
  EXPECT_THROW(check_plan(p), std::invalid_argument);
}

// Every row equals the solver called directly on the same transformed motion: exact equality (same operations in
// the same order), for the batched kernel (a run of mu on one motion) as for single blocks and rocking bodies.
TEST(EnsembleRun, RowsEqualDirectSolverCalls) {
  const SweepSpec spec = mixed_spec();
  const Plan plan = make_plan(spec);
  const ResultTable t = run_in_memory(plan);
  ASSERT_EQ(t.rows.size(), plan.runs());
  const std::size_t n_obj = plan.objects.size();
  const auto c_disp = column(t, "max_abs_displacement_m");
  const auto c_res = column(t, "residual_displacement_m");
  const auto c_vel = column(t, "max_abs_velocity_m_s");
  const auto c_ep = column(t, "slip_episodes");
  const auto c_tot = column(t, "total_slip_duration_s");
  const auto c_end = column(t, "end_time_s");
  const auto c_first = column(t, "first_slip_time_s");
  const auto c_rot = column(t, "max_abs_rotation_rad");
  const auto c_imp = column(t, "impacts");
  const auto c_over = column(t, "overturned");
  const auto c_e = column(t, "e");
  for (std::size_t run = 0; run < t.rows.size(); ++run) {
    SCOPED_TRACE("run " + std::to_string(run));
    const auto& row = t.rows[run];
    EXPECT_EQ(std::get<std::int64_t>(row[0]), static_cast<std::int64_t>(run));
    const MotionCase& mc = plan.motions[run / n_obj];
    const GroundMotion motion = mc.transform.apply(*mc.base);
    const ObjectSpec& o = spec.objects[run % n_obj];
    if (const auto* s = std::get_if<SlideObject>(&o)) {
      const SlidingSummary d = slide_summary(motion, s->block);
      EXPECT_EQ(number(row[c_disp]), d.max_abs_displacement_m);
      EXPECT_EQ(number(row[c_res]), d.residual_displacement_m);
      EXPECT_EQ(number(row[c_vel]), d.max_abs_velocity_m_s);
      EXPECT_EQ(number(row[c_ep]), d.slip_episodes);
      EXPECT_EQ(number(row[c_tot]), d.total_slip_duration_s);
      EXPECT_EQ(number(row[c_end]), d.end_time_s);
      if (d.first_slip_time_s) {
        EXPECT_EQ(number(row[c_first]), *d.first_slip_time_s);
      } else {
        EXPECT_TRUE(std::holds_alternative<std::monostate>(row[c_first]));
      }
      EXPECT_TRUE(std::holds_alternative<std::monostate>(row[c_rot]));
    } else {
      const auto& r = std::get<RockObject>(o);
      const RockingSummary d = rock_summary(motion, r.body, r.options);
      EXPECT_EQ(number(row[c_rot]), d.max_abs_rotation_rad);
      EXPECT_EQ(number(row[c_imp]), static_cast<double>(d.impacts));
      EXPECT_EQ(std::get<bool>(row[c_over]), d.overturned);
      EXPECT_EQ(number(row[c_end]), d.end_time_s);
      EXPECT_EQ(number(row[c_e]), d.e);
      EXPECT_TRUE(std::holds_alternative<std::monostate>(row[c_disp]));
    }
  }
  // The sweep is not trivial: some blocks slid, some did not.
  std::size_t slid = 0;
  for (const auto& row : t.rows) {
    if (const auto* d = std::get_if<double>(&row[c_disp]); d != nullptr && *d > 0.0) ++slid;
  }
  EXPECT_GT(slid, 10u);
}

TEST(EnsembleRun, SameBytesForAnyNumberOfThreads) {
  const Plan plan = make_plan(mixed_spec());
  ExecuteOptions one;
  one.threads = 1;
  ExecuteOptions all;  // every core
  ExecuteOptions four;
  four.threads = 4;  // more threads than cores
  const std::string a = to_csv(run_in_memory(plan, one));
  EXPECT_EQ(a, to_csv(run_in_memory(plan, all)));
  EXPECT_EQ(a, to_csv(run_in_memory(plan, four)));
  EXPECT_EQ(to_jsonl(run_in_memory(plan, one)), to_jsonl(run_in_memory(plan, four)));
}

TEST(EnsembleRun, ProgressReachesTheTotal) {
  const Plan plan = make_plan(mixed_spec());
  std::atomic<std::size_t> last{0};
  std::atomic<std::size_t> calls{0};
  ExecuteOptions o;
  o.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(total, plan.runs());
    EXPECT_LE(done, total);
    std::size_t prev = last.load();
    while (done > prev && !last.compare_exchange_weak(prev, done)) {
    }
    ++calls;
  };
  static_cast<void>(run_in_memory(plan, o));
  EXPECT_EQ(last.load(), plan.runs());
  EXPECT_GT(calls.load(), 0u);
}

TEST(EnsembleFormat, CsvAndJsonValues) {
  std::string s;
  append_csv_value(s, Value{});
  append_csv_value(s, Value{true});
  append_csv_value(s, Value{std::int64_t{-3}});
  append_csv_value(s, Value{0.1});
  append_csv_value(s, Value{1e-5});
  append_csv_value(s, Value{std::nan("")});
  append_csv_value(s, Value{std::string("a,b \"c\"")});
  append_csv_value(s, Value{std::string("plain")});
  EXPECT_EQ(s, "true-30.11e-05\"a,b \"\"c\"\"\"plain");
  std::string j;
  append_json_value(j, Value{});
  append_json_value(j, Value{false});
  append_json_value(j, Value{std::numeric_limits<double>::infinity()});
  append_json_value(j, Value{std::string("q\"\\\t\x01")});
  EXPECT_EQ(j, "nullfalsenull\"q\\\"\\\\\\t\\u0001\"");
  // Shortest round trip: every double reads back to itself.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int i = 0; i < 1000; ++i) {
    const double x = u(rng) * std::pow(10.0, static_cast<double>(i % 40 - 20));
    std::string t;
    append_csv_value(t, Value{x});
    EXPECT_EQ(std::strtod(t.c_str(), nullptr), x) << t;
  }
}

// ---- The store ----

/// A plan whose run function counts its calls and, while `fail_from` is set, throws on that run and after.
struct CountingPlan {
  std::shared_ptr<std::atomic<std::size_t>> calls = std::make_shared<std::atomic<std::size_t>>(0);
  std::shared_ptr<std::atomic<std::size_t>> fail_from =
      std::make_shared<std::atomic<std::size_t>>(std::numeric_limits<std::size_t>::max());
  Plan plan;

  explicit CountingPlan(std::size_t n_motions = 12, std::size_t n_objects = 10, std::size_t chunk = 8) {
    plan.motion_columns = {"motion"};
    plan.object_columns = {"k"};
    plan.result_columns = {"value", "note"};
    auto base = std::make_shared<const GroundMotion>(GroundMotion::uniform({0.0, 1.0, 0.0}, 0.01));
    for (std::size_t m = 0; m < n_motions; ++m) {
      std::string name = "m";  // (not "m" + to_string: GCC 12 warns falsely on that, -Wrestrict)
      name += std::to_string(m);
      plan.motions.push_back({base, {}, {Value{name}}});
    }
    for (std::size_t o = 0; o < n_objects; ++o) plan.objects.push_back({{Value{std::int64_t(o)}}});
    plan.chunk_runs = chunk;
    plan.run = [calls = calls, fail_from = fail_from, n_objects](const GroundMotion&, std::size_t m, std::size_t b,
                                                                 std::size_t e, std::span<Value> out) {
      for (std::size_t o = b; o < e; ++o) {
        if (m * n_objects + o >= fail_from->load()) throw std::runtime_error("injected failure");
        ++*calls;
        out[(o - b) * 2] = std::sqrt(static_cast<double>(m * 100 + o));
        out[(o - b) * 2 + 1] = (o % 3 == 0) ? Value{std::string("x,y")} : Value{};
      }
    };
  }
};

std::vector<fs::path> chunk_files(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const auto name = e.path().filename().string();
    if (name.size() == 12 && name.substr(8) == ".csv") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// A store in a fresh folder (its CSV out.csv) for CountingPlan's plan, on this process alone: the set-up of most
/// store tests, each of which binds the four by name.
struct StoreCase {
  TempDir tmp;
  CountingPlan cp;
  SingleProcess one;
  StoreOptions store;
  StoreCase() { store.csv_path = tmp.path() / "out.csv"; }

  /// Runs the plan on one thread with every run from `fail_from` on failing (CountingPlan's injected failure), as
  /// a sweep killed part-way, then lifts the failure; the chunk files that run finished.
  std::vector<fs::path> interrupt_at(std::size_t fail_from) {
    cp.fail_from->store(fail_from);
    ExecuteOptions single;
    single.threads = 1;
    EXPECT_THROW(static_cast<void>(run_to_files(cp.plan, store, single, one)), std::runtime_error);
    cp.fail_from->store(std::numeric_limits<std::size_t>::max());
    return chunk_files(parts_directory(store.csv_path));
  }
};

TEST(EnsembleStore, FilesEqualTheInMemoryTable) {
  TempDir tmp;
  CountingPlan cp;
  SingleProcess one;
  StoreOptions store;
  store.csv_path = tmp.path() / "sub" / "out.csv";
  store.jsonl_path = tmp.path() / "sub" / "out.jsonl";
  const SweepReport r = run_to_files(cp.plan, store, {}, one);
  EXPECT_EQ(r.runs, 120u);
  EXPECT_EQ(r.chunks, 15u);
  EXPECT_EQ(r.chunks_computed, 15u);
  EXPECT_EQ(r.runs_computed, 120u);
  const ResultTable t = run_in_memory(cp.plan);
  EXPECT_EQ(slurp(store.csv_path), to_csv(t));
  EXPECT_EQ(slurp(*store.jsonl_path), to_jsonl(t));
  EXPECT_EQ(slurp(store.csv_path).substr(0, 29), "run,motion,k,value,note\n0,m0,");
  // Every JSON line parses and carries every column.
  std::istringstream lines(slurp(*store.jsonl_path));
  std::string line;
  std::size_t n = 0;
  while (std::getline(lines, line)) {
    const auto j = nlohmann::json::parse(line);
    EXPECT_EQ(j.size(), 5u);
    EXPECT_EQ(j["run"].get<std::size_t>(), n);
    ++n;
  }
  EXPECT_EQ(n, 120u);
  // The store keeps its manifest (complete) and no chunk.
  EXPECT_TRUE(chunk_files(parts_directory(store.csv_path)).empty());
  const auto manifest = nlohmann::json::parse(slurp(parts_directory(store.csv_path) / "manifest.json"));
  EXPECT_TRUE(manifest["complete"].get<bool>());
  EXPECT_EQ(manifest["fingerprint"].get<std::string>(), plan_fingerprint(cp.plan));

  // Rerun: nothing to do.
  const std::size_t calls = cp.calls->load();
  const SweepReport again = run_to_files(cp.plan, store, {}, one);
  EXPECT_TRUE(again.was_complete);
  EXPECT_EQ(cp.calls->load(), calls);
  // Outputs removed: computed again, same bytes.
  const std::string before = slurp(store.csv_path);
  fs::remove(store.csv_path);
  const SweepReport redo = run_to_files(cp.plan, store, {}, one);
  EXPECT_FALSE(redo.was_complete);
  EXPECT_EQ(redo.chunks_computed, 15u);
  EXPECT_EQ(slurp(store.csv_path), before);
}

TEST(EnsembleStore, ResumesAfterAFailureWithoutRecomputing) {
  StoreCase c;
  auto& [tmp, cp, one, store] = c;
  const std::string expected = to_csv(run_in_memory(cp.plan));
  cp.calls->store(0);

  const auto done = c.interrupt_at(60);  // runs 60.. fail: chunks 0-6 (runs 0-55) can finish
  EXPECT_FALSE(fs::exists(store.csv_path));
  ASSERT_GE(done.size(), 1u);
  ASSERT_LE(done.size(), 7u);

  cp.calls->store(0);
  const SweepReport r = run_to_files(cp.plan, store, {}, one);
  EXPECT_EQ(r.chunks_already_done, done.size());
  EXPECT_EQ(r.chunks_computed, 15u - done.size());
  EXPECT_EQ(r.runs_computed, 120u - 8u * done.size());
  EXPECT_EQ(cp.calls->load(), r.runs_computed);  // finished chunks were not recomputed
  EXPECT_EQ(slurp(store.csv_path), expected);
}

TEST(EnsembleStore, CutShortChunksAreRecomputed) {
  StoreCase c;
  auto& [tmp, cp, one, store] = c;
  const std::string expected = to_csv(run_in_memory(cp.plan));
  const auto done = c.interrupt_at(100);
  ASSERT_GE(done.size(), 2u);
  // A machine crash can leave a renamed file without its last bytes, or empty; a killed writer leaves a temporary.
  const std::string text = slurp(done[0]);
  test::write_file(done[0], text.substr(0, text.size() - 5));
  test::write_file(done[1], "");
  test::write_file(parts_directory(store.csv_path) / ".tmp-0-1-00000003.csv", "partial");
  const SweepReport r = run_to_files(cp.plan, store, {}, one);
  EXPECT_EQ(r.chunks_already_done, done.size() - 2);
  EXPECT_EQ(slurp(store.csv_path), expected);
  EXPECT_FALSE(fs::exists(parts_directory(store.csv_path) / ".tmp-0-1-00000003.csv"));
}

TEST(EnsembleStore, AChangedPlanIsRefusedUnlessRestarted) {
  StoreCase c;
  auto& [tmp, cp, one, store] = c;
  store.field = "output.path";
  cp.fail_from->store(50);
  EXPECT_THROW(static_cast<void>(run_to_files(cp.plan, store, {}, one)), std::runtime_error);
  cp.fail_from->store(std::numeric_limits<std::size_t>::max());

  CountingPlan changed;
  changed.plan.objects.pop_back();  // one object fewer
  try {
    static_cast<void>(run_to_files(changed.plan, store, {}, one));
    FAIL() << "a store of another plan must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, store.csv_path.string());
    EXPECT_EQ(e.where().field, "output.path");
    EXPECT_NE(e.problem().find("--restart"), std::string::npos) << e.what();
  }
  // Another chunk size is another plan too.
  CountingPlan rechunked(12, 10, 9);
  EXPECT_THROW(static_cast<void>(run_to_files(rechunked.plan, store, {}, one)), InputError);
  store.restart = true;
  const SweepReport r = run_to_files(changed.plan, store, {}, one);
  EXPECT_TRUE(r.restarted);
  EXPECT_EQ(r.chunks_already_done, 0u);
  EXPECT_EQ(slurp(store.csv_path), to_csv(run_in_memory(changed.plan)));
}

TEST(EnsembleStore, ALockedStoreIsRefused) {
  StoreCase c;
  auto& [tmp, cp, one, store] = c;
  const fs::path dir = parts_directory(store.csv_path);
  fs::create_directories(dir);
  const int fd = ::open((dir / "lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  try {
    static_cast<void>(run_to_files(cp.plan, store, {}, one));
    FAIL() << "a locked store must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("another topple sweep"), std::string::npos) << e.what();
  }
  ::close(fd);
  EXPECT_NO_THROW(static_cast<void>(run_to_files(cp.plan, store, {}, one)));
}

/// run_to_files refuses the store with an InputError whose message holds every phrase.
void expect_refused(const Plan& plan, const StoreOptions& store, std::initializer_list<const char*> phrases) {
  SingleProcess one;
  try {
    static_cast<void>(run_to_files(plan, store, {}, one));
    FAIL() << "the store must be refused";
  } catch (const InputError& e) {
    for (const char* phrase : phrases) EXPECT_NE(e.problem().find(phrase), std::string::npos) << e.what();
  }
}

// ---- Corruption of the store (docs/sweeps.md, "The result store") ----

/// A store left by a sweep that failed at run 70 (one thread): chunks 0-7 of 15 are there, with JSON lines.
struct InterruptedStore {
  TempDir tmp;
  CountingPlan cp;
  SingleProcess one;
  StoreOptions store;
  std::string expected_csv;
  std::string expected_jsonl;
  std::vector<fs::path> chunks;

  InterruptedStore() {
    store.csv_path = tmp.path() / "out.csv";
    store.jsonl_path = tmp.path() / "out.jsonl";
    const ResultTable t = run_in_memory(cp.plan);
    expected_csv = to_csv(t);
    expected_jsonl = to_jsonl(t);
    cp.fail_from->store(70);
    ExecuteOptions single;
    single.threads = 1;
    EXPECT_THROW(static_cast<void>(run_to_files(cp.plan, store, single, one)), std::runtime_error);
    cp.fail_from->store(std::numeric_limits<std::size_t>::max());
    chunks = chunk_files(parts_directory(store.csv_path));
  }
  [[nodiscard]] fs::path dir() const { return parts_directory(store.csv_path); }
};

/// The offset of the first row of a chunk file (after its header line).
std::size_t rows_offset(const std::string& chunk) { return chunk.find('\n') + 1; }

struct Corruption {
  const char* name;
  void (*apply)(const InterruptedStore& s);
};

void flip_digit(const InterruptedStore& s) {
  std::string t = slurp(s.chunks[1]);
  const std::size_t i = t.find_first_of("123456789", rows_offset(t) + 10);  // a digit of a value, not the run index
  t[i] = t[i] == '9' ? '8' : static_cast<char>(t[i] + 1);
  test::write_file(s.chunks[1], t);
}
void xor_byte(const InterruptedStore& s) {
  std::string t = slurp(s.chunks[1]);
  t[rows_offset(t) + (t.size() - rows_offset(t)) / 2] ^= 0x5a;
  test::write_file(s.chunks[1], t);
}
void xor_header_fingerprint(const InterruptedStore& s) {  // damage, not another sweep: computed again, not refused
  std::string t = slurp(s.chunks[1]);
  t[t.find("fingerprint=") + 14] ^= 0x01;
  test::write_file(s.chunks[1], t);
}
void swap_lines(const InterruptedStore& s) {
  std::string t = slurp(s.chunks[1]);
  const std::size_t a = rows_offset(t);
  const std::size_t b = t.find('\n', a) + 1;
  const std::size_t c = t.find('\n', b) + 1;
  t = t.substr(0, a) + t.substr(b, c - b) + t.substr(a, b - a) + t.substr(c);
  test::write_file(s.chunks[1], t);
}
void copy_over_another(const InterruptedStore& s) {
  fs::copy_file(s.chunks[0], s.chunks[1], fs::copy_options::overwrite_existing);
  fs::copy_file(fs::path(s.chunks[0]).replace_extension(".jsonl"), fs::path(s.chunks[1]).replace_extension(".jsonl"),
                fs::copy_options::overwrite_existing);
}
void truncate_chunk(const InterruptedStore& s) {
  const std::string t = slurp(s.chunks[1]);
  test::write_file(s.chunks[1], t.substr(0, t.size() / 2));
}
void truncate_header(const InterruptedStore& s) {
  const std::string t = slurp(s.chunks[1]);
  test::write_file(s.chunks[1], t.substr(0, 20));
}
void xor_jsonl(const InterruptedStore& s) {
  const fs::path p = fs::path(s.chunks[1]).replace_extension(".jsonl");
  std::string t = slurp(p);
  t[t.size() / 2] ^= 0x01;
  test::write_file(p, t);
}
void delete_jsonl(const InterruptedStore& s) { fs::remove(fs::path(s.chunks[1]).replace_extension(".jsonl")); }

class EnsembleStoreCorruption : public ::testing::TestWithParam<Corruption> {};

// Each kind of damage to one committed chunk: the resumed sweep detects it, computes that chunk (only) again, and
// writes the same bytes as an uninterrupted sweep.
TEST_P(EnsembleStoreCorruption, IsDetectedAndTheChunkComputedAgain) {
  InterruptedStore s;
  ASSERT_GE(s.chunks.size(), 3u);
  ASSERT_LE(s.chunks.size(), 9u);
  GetParam().apply(s);
  const SweepReport r = run_to_files(s.cp.plan, s.store, {}, s.one);
  EXPECT_EQ(r.chunks_failed_verification, 1u);
  EXPECT_EQ(r.chunks_already_done, s.chunks.size() - 1);
  EXPECT_EQ(r.chunks_computed, 15u - s.chunks.size() + 1);
  EXPECT_EQ(slurp(s.store.csv_path), s.expected_csv);
  EXPECT_EQ(slurp(*s.store.jsonl_path), s.expected_jsonl);
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, EnsembleStoreCorruption,
    ::testing::Values(Corruption{"flipped_digit", flip_digit}, Corruption{"xored_byte", xor_byte},
                      Corruption{"xored_fingerprint", xor_header_fingerprint}, Corruption{"swapped_lines", swap_lines},
                      Corruption{"chunk_copied_over_another", copy_over_another},
                      Corruption{"truncated_chunk", truncate_chunk}, Corruption{"truncated_header", truncate_header},
                      Corruption{"xored_jsonl", xor_jsonl}, Corruption{"deleted_jsonl", delete_jsonl}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

// The manifest records every verified chunk's checksum (the one in the chunk's header), and a chunk that checks out
// on its own but differs from that record is computed again.
TEST(EnsembleStore, TheManifestRecordsEveryChunkChecksum) {
  InterruptedStore s;
  ASSERT_GE(s.chunks.size(), 2u);
  // A resume that computes nothing new records the chunks found (then fails again at run 70).
  s.cp.fail_from->store(70);
  ExecuteOptions single;
  single.threads = 1;
  EXPECT_THROW(static_cast<void>(run_to_files(s.cp.plan, s.store, single, s.one)), std::runtime_error);
  s.cp.fail_from->store(std::numeric_limits<std::size_t>::max());
  const auto m = nlohmann::json::parse(slurp(s.dir() / "manifest.json"));
  EXPECT_EQ(m["format"], "topple-sweep-parts/2");
  EXPECT_EQ(m["checksum"], "xxh3-64");
  const std::string first = slurp(s.chunks[0]);
  const std::string recorded = m["chunk_checksums"][s.chunks[0].filename().string()].get<std::string>();
  EXPECT_EQ(recorded.size(), 16u);
  EXPECT_NE(first.find(" xxh3=" + recorded + "\n"), std::string::npos) << "the header's checksum is the record";
  // A record that differs from chunk 0's own checksum: the chunk is not trusted.
  nlohmann::json forged = m;
  forged["chunk_checksums"][s.chunks[0].filename().string()] = "0123456789abcdef";
  test::write_file(s.dir() / "manifest.json", forged.dump(2));
  const SweepReport r = run_to_files(s.cp.plan, s.store, {}, s.one);
  EXPECT_EQ(r.chunks_failed_verification, 1u);
  EXPECT_EQ(slurp(s.store.csv_path), s.expected_csv);
}

// With the manifest deleted, a different sweep resumed into the same output must not take the other's rows.
TEST(EnsembleStore, ChunksOfAnotherSweepAreRefusedWithoutAManifest) {
  InterruptedStore s;
  fs::remove(s.dir() / "manifest.json");
  CountingPlan other;
  other.plan.motions[0].values[0] = Value{std::string("another record")};  // same runs and chunks, other sweep
  StoreOptions store = s.store;
  expect_refused(other.plan, store, {"different sweep", "no manifest", "--restart"});
  EXPECT_FALSE(fs::exists(store.csv_path));
  EXPECT_EQ(other.calls->load(), 0u) << "nothing computed before the refusal";
  // The same sweep resumes without its manifest: its chunks carry its fingerprint.
  const SweepReport same = run_to_files(s.cp.plan, s.store, {}, s.one);
  EXPECT_EQ(same.chunks_already_done, s.chunks.size());
  EXPECT_EQ(slurp(s.store.csv_path), s.expected_csv);
  // --restart discards the store for the other sweep.
  fs::remove(store.csv_path);
  store.restart = true;
  static_cast<void>(run_to_files(other.plan, store, {}, s.one));
  const ResultTable t = run_in_memory(other.plan);
  EXPECT_EQ(slurp(store.csv_path), to_csv(t));
}

/// A finished sweep's outputs damaged afterwards.
class EnsembleStoreFinishedOutput : public ::testing::TestWithParam<const char*> {};

TEST_P(EnsembleStoreFinishedOutput, IsNotReportedCompleteButRefused) {
  StoreCase c;
  auto& [tmp, cp, one, store] = c;
  store.jsonl_path = tmp.path() / "out.jsonl";
  static_cast<void>(run_to_files(cp.plan, store, {}, one));
  const std::string csv = slurp(store.csv_path);
  const std::string kind = GetParam();
  if (kind == std::string("corrupted_csv")) {
    std::string t = csv;
    t[t.size() / 2] ^= 0x01;
    test::write_file(store.csv_path, t);
  } else if (kind == std::string("truncated_csv")) {
    test::write_file(store.csv_path, csv.substr(0, csv.size() - 1));
  } else {
    std::string t = slurp(*store.jsonl_path);
    t[10] ^= 0x01;
    test::write_file(*store.jsonl_path, t);
  }
  // Not reported complete: refused.
  expect_refused(cp.plan, store, {"has changed since this sweep finished", "--restart"});
  store.restart = true;
  const SweepReport r = run_to_files(cp.plan, store, {}, one);
  EXPECT_FALSE(r.was_complete);
  EXPECT_EQ(slurp(store.csv_path), csv);
  store.restart = false;
  EXPECT_TRUE(run_to_files(cp.plan, store, {}, one).was_complete);
}

INSTANTIATE_TEST_SUITE_P(Kinds, EnsembleStoreFinishedOutput,
                         ::testing::Values("corrupted_csv", "truncated_csv", "corrupted_jsonl"));

// A store of the earlier format (no checksums) is refused with a message that says what to do.
TEST(EnsembleStore, AStoreOfTheEarlierFormatIsRefused) {
  StoreCase c;
  auto& [tmp, cp, one, store] = c;
  fs::create_directories(parts_directory(store.csv_path));
  test::write_file(parts_directory(store.csv_path) / "manifest.json",
                   R"({"format": "topple-sweep-parts/1", "fingerprint": ")" + plan_fingerprint(cp.plan) +
                       R"(", "runs": 120, "chunk_runs": 8, "chunks": 15, "complete": true})");
  test::write_file(store.csv_path, "run,motion,k,value,note\n");
  expect_refused(cp.plan, store, {"topple-sweep-parts/1", "--restart"});
  store.restart = true;
  static_cast<void>(run_to_files(cp.plan, store, {}, one));
  EXPECT_EQ(slurp(store.csv_path), to_csv(run_in_memory(cp.plan)));
}

TEST(EnsembleStore, FingerprintFollowsRecordSamples) {
  SweepSpec a = mixed_spec();
  SweepSpec b = mixed_spec();
  EXPECT_EQ(plan_fingerprint(make_plan(a)), plan_fingerprint(make_plan(b)));
  b.records[1].motion = noise_record(3, 900, 0.02);  // same name, other samples
  EXPECT_NE(plan_fingerprint(make_plan(a)), plan_fingerprint(make_plan(b)));
  b = mixed_spec();
  std::get<RockObject>(b.objects.back()).options.rel_tol = 1e-9;  // not a column, still an input
  EXPECT_NE(plan_fingerprint(make_plan(a)), plan_fingerprint(make_plan(b)));
}

}  // namespace
}  // namespace topple::ensemble
