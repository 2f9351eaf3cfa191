// The three-dimensional engine on an inclined base (rigid3d.hpp, "Inclined base"; Rigid3DOptions::base_incline_deg;
// docs/method.md, "An inclined base"): a level base is today's engine; an incline of 1e-9 degrees through the rotated
// path is the level answer; a box tips downhill with no shaking past atan(b / h) and not below; the onset under a ramp
// along the fall line is the hand formula with gravity's slope component (downhill g tan(alpha - beta), uphill
// g tan(alpha + beta)); a body slides from rest down the plane at g (sin beta - mu_k cos beta) when tan(beta) > mu_s
// and stays put below; the body, the downhill azimuth and the record turned together about the vertical move the same
// in the base frame; the energy with the slope's potential never increases on still ground.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "support/noise_record.hpp"
#include "topple/core/error.hpp"
#include "topple/solvers/rigid3d.hpp"

namespace topple {
namespace {

constexpr double kG = 9.80665;

GroundMotion noise(unsigned seed, double pga_m_s2, std::size_t n = 1500, double dt = 0.005) {
  return test::noise_record({.seed = seed, .samples = n, .dt_s = dt, .pga_m_s2 = pga_m_s2, .resonance_hz = 2.5,
                             .pole_radius = 0.97, .envelope_peak_s = 0.2 * static_cast<double>(n) * dt});
}

/// `cycles` periods of a sine starting at t0, zero elsewhere, on [0, total] sampled at dt.
GroundMotion pulse(double amplitude, double period, double cycles, double t0, double dt, double total) {
  const auto n = static_cast<std::size_t>(std::llround(total / dt)) + 1;
  std::vector<double> a(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt - t0;
    if (t >= 0.0 && t <= cycles * period) a[i] = amplitude * std::sin(2.0 * M_PI * t / period);
  }
  return GroundMotion::uniform(a, dt);
}

GroundMotion combine(const GroundMotion& a, double ka, const GroundMotion& b, double kb) {
  std::vector<double> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = ka * a.accel_m_s2()[i] + kb * b.accel_m_s2()[i];
  return GroundMotion::uniform(out, a.dt_s(), a.start_time_s());
}

GroundMotion zeros(double duration, double dt) {
  const auto n = static_cast<std::size_t>(std::llround(duration / dt)) + 1;
  return GroundMotion::uniform(std::vector<double>(n, 0.0), dt);
}

Rigid3DOptions incline(double deg, double azimuth_deg) {
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.base_incline_deg = deg;
  o.base_incline_azimuth_deg = azimuth_deg;
  return o;
}

double angle_diff(double a, double b) { return std::remainder(a - b, 360.0); }

// Level is today's engine: the azimuth of a zero incline is not read (bit for bit, with and without friction); an
// incline of 1e-9 degrees goes through the base frame's records and rotations and gives the level answer to 1e-7
// (without friction: a box rocking and pivoting under two noise records; with mu_s = 0.45, mu_k = 0.4 a box 0.4 x
// 0.3 x 0.8 m that slides under a pulse along x and rocks under one along y, Rigid3DSlide's case: impact sequences
// under strong noise with slide-rock hang on the records' last digits, which the rotation changes).
TEST(Rigid3DIncline, LevelIsTodaysEngineAndATinyInclineIsLevel) {
  for (const bool with_friction : {false, true}) {
    SCOPED_TRACE(with_friction ? "friction 0.45" : "no slip");
    const RigidBody3D box = with_friction ? RigidBody3D::box(0.4, 0.3, 0.8) : RigidBody3D::box(0.2, 0.3, 0.8);
    const GroundMotion mx = with_friction ? pulse(0.7 * kG, 0.4, 2.0, 0.0, 0.005, 3.0) : noise(7, 0.5 * kG);
    const GroundMotion my = with_friction ? pulse(0.42 * kG, 0.4, 2.0, 1.2, 0.005, 3.0) : noise(8, 0.4 * kG);
    Rigid3DOptions level;
    level.g_m_s2 = kG;
    if (with_friction) {
      level.mu_s = 0.45;
      level.mu_k = 0.4;
    }
    Rigid3DOptions zero = level;
    zero.base_incline_azimuth_deg = 123.0;
    Rigid3DOptions tiny = zero;
    tiny.base_incline_deg = 1e-9;
    const Rigid3DSummary a = rock3d(mx, &my, nullptr, box, level).summary;
    const Rigid3DSummary b = rock3d(mx, &my, nullptr, box, zero).summary;
    const Rigid3DSummary c = rock3d(mx, &my, nullptr, box, tiny).summary;
    EXPECT_GT(a.impacts, 0U);
    if (with_friction) {
      EXPECT_GT(a.slip_episodes, 0);
    }
    EXPECT_EQ(a.max_tilt_rad, b.max_tilt_rad);
    EXPECT_EQ(a.impacts, b.impacts);
    EXPECT_EQ(a.modes.size(), b.modes.size());
    EXPECT_EQ(a.end_time_s, b.end_time_s);
    EXPECT_EQ(a.residual_slide_east_m, b.residual_slide_east_m);
    EXPECT_EQ(a.overturned, c.overturned);
    EXPECT_EQ(a.impacts, c.impacts);
    EXPECT_NEAR(c.max_tilt_rad, a.max_tilt_rad, 1e-7 * a.max_tilt_rad + 1e-12);
    EXPECT_NEAR(c.residual_slide_east_m, a.residual_slide_east_m, 1e-7);
    EXPECT_NEAR(c.residual_slide_north_m, a.residual_slide_north_m, 1e-7);
  }
  // A vertical on another grid, shorter than the horizontals (the union grid is irregular, with the vertical's jump to
  // still ground at its end): the base frame's records on that grid, the same answer.
  const RigidBody3D box = RigidBody3D::box(0.2, 0.3, 0.8);
  const GroundMotion mx = noise(7, 0.5 * kG);
  const GroundMotion my = noise(8, 0.4 * kG);
  const GroundMotion mz = noise(9, 0.2 * kG, 1000, 0.004);
  Rigid3DOptions level;
  level.g_m_s2 = kG;
  Rigid3DOptions tiny = level;
  tiny.base_incline_deg = 1e-9;
  const Rigid3DSummary a = rock3d(mx, &my, &mz, box, level).summary;
  const Rigid3DSummary c = rock3d(mx, &my, &mz, box, tiny).summary;
  EXPECT_GT(a.impacts, 0U);
  EXPECT_EQ(a.impacts, c.impacts);
  EXPECT_EQ(a.modes.size(), c.modes.size());
  EXPECT_NEAR(c.max_tilt_rad, a.max_tilt_rad, 1e-7 * a.max_tilt_rad);
}

// No shaking: a box (b = 0.1 m across its x edges, h = 0.3 m: alpha = atan(1/3) = 18.43 degrees) on a plane falling
// toward the east stays at rest at beta = alpha - 0.1 degree and tips downhill at once at alpha + 0.1 degree (the
// resultant of gravity, g (sin(beta), -cos(beta)) in the base frame, leaves the base past the downhill edge when
// h tan(beta) > b) and falls downhill (azimuth 90 in the base frame), with or without friction (mu_s = 0.8 >
// tan(beta): no sliding).
TEST(Rigid3DIncline, BoxTipsDownhillWithNoShakingPastItsStaticLimit) {
  const RigidBody3D box = RigidBody3D::box(0.2, 0.4, 0.6);
  const double alpha = std::atan(0.1 / 0.3) * 180.0 / M_PI;
  const GroundMotion still = zeros(1.0, 0.01);
  for (const bool with_friction : {false, true}) {
    SCOPED_TRACE(with_friction ? "mu 0.8" : "no slip");
    Rigid3DOptions below = incline(alpha - 0.1, 90.0);
    if (with_friction) below.mu_s = 0.8;
    Rigid3DOptions above = below;
    above.base_incline_deg = alpha + 0.1;
    above.max_run_out_s = 20.0;
    const Rigid3DSummary s = rock3d(still, nullptr, nullptr, box, below).summary;
    EXPECT_EQ(s.uplifts, 0U);
    EXPECT_EQ(s.max_tilt_rad, 0.0);
    EXPECT_FALSE(s.overturned);
    EXPECT_EQ(s.residual_slide_east_m, 0.0);
    const Rigid3DSummary t = rock3d(still, nullptr, nullptr, box, above).summary;
    ASSERT_TRUE(t.uplift_time_s);
    EXPECT_EQ(*t.uplift_time_s, 0.0);
    ASSERT_GE(t.modes.size(), 2U);
    EXPECT_EQ(t.modes[1].mode, Rigid3DMode::rocking);
    EXPECT_EQ(t.modes[1].vertex_a, 1);  // the +x (downhill) edge
    EXPECT_TRUE(t.overturned);
    EXPECT_NEAR(angle_diff(t.overturn_azimuth_deg, 90.0), 0.0, 1e-6);
  }
  // A plane falling toward azimuth 30 (e_d = (sin 30, cos 30) on the base's axes): the centre of pressure
  // c + h tan(beta) e_d leaves the base past x = a = 0.1 m first (h tan(beta) sin 30 = a at tan(beta) = 0.6667, before
  // y = 0.2 m at 0.7698): tips about the +x edge from beta = atan(2/3) = 33.69 degrees, not below.
  const double oblique = std::atan(0.1 / (0.3 * std::sin(M_PI / 6.0))) * 180.0 / M_PI;
  const Rigid3DSummary below = rock3d(still, nullptr, nullptr, box, incline(oblique - 0.05, 30.0)).summary;
  EXPECT_EQ(below.uplifts, 0U);
  const Rigid3DSummary above = rock3d(still, nullptr, nullptr, box, incline(oblique + 0.05, 30.0)).summary;
  ASSERT_GE(above.modes.size(), 2U);
  EXPECT_EQ(above.modes[1].time_s, 0.0);
  EXPECT_EQ(above.modes[1].mode, Rigid3DMode::rocking);
  EXPECT_EQ(above.modes[1].vertex_a, 1);
}

// The onset under a horizontal ramp a(t) = -+k t along the fall line (downhill east, beta = 10 degrees): in the base
// frame the load is (a cos(beta) - g sin(beta), g cos(beta) + a sin(beta)); the resultant leaves the base past the
// downhill edge when (g sin(beta) - a cos(beta)) h > (g cos(beta) + a sin(beta)) b, i.e. a < -g tan(alpha - beta), and
// past the uphill edge when a > g tan(alpha + beta) (alpha = atan(b / h)): t* = g tan(alpha -+ beta) / k. The rest
// phase locates the linear crossing exactly: 1e-9.
TEST(Rigid3DIncline, OnsetUnderARampIsTheHandFormulaWithTheSlope) {
  const double b = 0.15, h = 0.45;
  const RigidBody3D box = RigidBody3D::box(2.0 * b, 0.5, 2.0 * h);
  const double alpha = std::atan(b / h);
  const double beta_deg = 10.0;
  const double beta = beta_deg * M_PI / 180.0;
  const double k = 2.0;  // m/s^3
  const double dt = 0.01;
  const std::size_t n = 400;
  for (const bool downhill : {true, false}) {
    SCOPED_TRACE(downhill ? "downhill" : "uphill");
    std::vector<double> ax(n);
    for (std::size_t i = 0; i < n; ++i) ax[i] = (downhill ? -k : k) * static_cast<double>(i) * dt;
    const GroundMotion mx = GroundMotion::uniform(ax, dt);
    Rigid3DOptions o = incline(beta_deg, 90.0);
    o.max_run_out_s = 0.0;
    const Rigid3DSummary s = rock3d(mx, nullptr, nullptr, box, o).summary;
    const double t_star = kG * std::tan(downhill ? alpha - beta : alpha + beta) / k;
    ASSERT_TRUE(s.uplift_time_s);
    EXPECT_NEAR(*s.uplift_time_s, t_star, 1e-9 * t_star);
    ASSERT_GE(s.modes.size(), 2U);
    EXPECT_EQ(s.modes[1].mode, Rigid3DMode::rocking);
    EXPECT_EQ(s.modes[1].vertex_a, downhill ? 1 : 3);  // +x edge (v1 -> v2) or -x edge (v3 -> v0)
    // level ground's threshold g tan(alpha) lies between the two: the slope matters
    EXPECT_LT(kG * std::tan(alpha - beta) / k, kG * std::tan(alpha) / k);
  }
}

// Sliding from rest on still ground (a wide, low box that cannot tip: b / h = 2): with tan(beta) > mu_s it slides
// down the fall line at a = g (sin(beta) - mu_k cos(beta)) from t = 0, x = a t^2 / 2 along the plane (the residual's
// components on the base's axes: x sin(A) east, x cos(A) north) to 1e-9; it can never stop (tan(beta) > mu_k), so the
// run ends at the record's end with a warning. With tan(beta) < mu_s it stays put.
TEST(Rigid3DIncline, SlidesDownThePlaneAtTheClosedFormOrStaysPut) {
  const RigidBody3D box = RigidBody3D::box(1.0, 0.8, 0.4);
  const double T = 1.5;
  const GroundMotion still = zeros(T, 0.01);
  const double beta_deg = 25.0, beta = beta_deg * M_PI / 180.0;
  const double mu_s = 0.35, mu_k = 0.3;
  for (const double azimuth : {90.0, 0.0, 210.0}) {
    SCOPED_TRACE(azimuth);
    Rigid3DOptions o = incline(beta_deg, azimuth);
    o.mu_s = mu_s;
    o.mu_k = mu_k;
    const Rigid3DSummary s = rock3d(still, nullptr, nullptr, box, o).summary;
    const double a = kG * (std::sin(beta) - mu_k * std::cos(beta));
    const double x = 0.5 * a * T * T;
    const double A = azimuth * M_PI / 180.0;
    EXPECT_NEAR(s.residual_slide_east_m, x * std::sin(A), 1e-9 * x);
    EXPECT_NEAR(s.residual_slide_north_m, x * std::cos(A), 1e-9 * x);
    EXPECT_NEAR(s.max_slide_speed_m_s, a * T, 1e-9 * a * T);
    ASSERT_TRUE(s.first_slip_time_s);
    EXPECT_EQ(*s.first_slip_time_s, 0.0);
    EXPECT_EQ(s.uplifts, 0U);
    EXPECT_EQ(s.end_mode, Rigid3DMode::sliding);
    EXPECT_FALSE(s.warnings.empty());
    // friction's work mu_k g cos(beta) x
    EXPECT_NEAR(s.friction_energy_j_per_kg, mu_k * kG * std::cos(beta) * x, 1e-9 * x);
  }
  Rigid3DOptions gentle = incline(15.0, 40.0);  // tan 15 deg = 0.268 < mu_s
  gentle.mu_s = mu_s;
  gentle.mu_k = mu_k;
  const Rigid3DSummary s = rock3d(still, nullptr, nullptr, box, gentle).summary;
  EXPECT_EQ(s.residual_slide_east_m, 0.0);
  EXPECT_EQ(s.residual_slide_north_m, 0.0);
  EXPECT_EQ(s.slip_episodes, 0);
  EXPECT_EQ(s.uplifts, 0U);
  EXPECT_EQ(s.end_mode, Rigid3DMode::rest);
}

// Frame invariance: the body turned by 35 degrees counter-clockwise about the vertical, the downhill azimuth turned
// with it (A - 35, azimuths being clockwise) and the record turned the same move as the original in the base frame:
// the same modes and impacts, the tilt to 1e-7, the azimuths less 35 degrees, the residual slide turned.
TEST(Rigid3DIncline, TurnedBodySlopeAndRecordMoveTheSame) {
  const double phi_deg = 35.0, phi = phi_deg * M_PI / 180.0;
  for (const bool with_friction : {false, true}) {
    SCOPED_TRACE(with_friction ? "mu 0.45" : "no slip");
    // without friction a box rocking and pivoting under noise; with it Rigid3DSlide's slide-then-rock pulses
    const RigidBody3D box = with_friction ? RigidBody3D::box(0.4, 0.3, 0.8) : RigidBody3D::box(0.2, 0.3, 0.8);
    const RigidBody3D turned = box.rotated_about_vertical(phi);
    const GroundMotion m1 = with_friction ? pulse(0.6 * kG, 0.4, 2.0, 0.0, 0.005, 3.0) : noise(7, 0.45 * kG);
    const GroundMotion m2 = with_friction ? pulse(0.4 * kG, 0.4, 2.0, 1.2, 0.005, 3.0) : noise(8, 0.35 * kG);
    const GroundMotion rx = combine(m1, std::cos(phi), m2, -std::sin(phi));
    const GroundMotion ry = combine(m1, std::sin(phi), m2, std::cos(phi));
    Rigid3DOptions o = incline(8.0, 70.0);
    o.rel_tol = 1e-10;
    if (with_friction) {
      o.mu_s = 0.45;
      o.mu_k = 0.4;
    }
    Rigid3DOptions t_o = o;
    t_o.base_incline_azimuth_deg = 70.0 - phi_deg;
    const Rigid3DSummary s = rock3d(m1, &m2, nullptr, box, o).summary;
    const Rigid3DSummary t = rock3d(rx, &ry, nullptr, turned, t_o).summary;
    EXPECT_GT(s.uplifts, 0U);
    EXPECT_EQ(s.overturned, t.overturned);
    EXPECT_EQ(s.impacts, t.impacts);
    ASSERT_EQ(s.modes.size(), t.modes.size());
    for (std::size_t i = 0; i < s.modes.size(); ++i) EXPECT_EQ(s.modes[i].mode, t.modes[i].mode);
    EXPECT_NEAR(s.max_tilt_rad, t.max_tilt_rad, 1e-7);
    EXPECT_NEAR(angle_diff(t.max_tilt_azimuth_deg, s.max_tilt_azimuth_deg - phi_deg), 0.0, 1e-5);
    if (s.overturned) {
      EXPECT_NEAR(angle_diff(t.overturn_azimuth_deg, s.overturn_azimuth_deg - phi_deg), 0.0, 1e-5);
    }
    const double e = std::cos(phi) * s.residual_slide_east_m - std::sin(phi) * s.residual_slide_north_m;
    const double nn = std::sin(phi) * s.residual_slide_east_m + std::cos(phi) * s.residual_slide_north_m;
    EXPECT_NEAR(t.residual_slide_east_m, e, 1e-7);
    EXPECT_NEAR(t.residual_slide_north_m, nn, 1e-7);
    if (with_friction) {
      EXPECT_GT(std::hypot(s.residual_slide_east_m, s.residual_slide_north_m), 1e-4);
    }
  }
}

// Energy with the slope's potential (still ground's load in the base frame times the displacement of c) never
// increases on still ground: a box rocking after a pulse on a 6 degree plane (it sticks), and a box sliding down a
// 25 degree plane with mu = 0.3 (kinetic energy grows, the potential falls faster: dE/dt = -mu_k g cos(beta) |w|).
TEST(Rigid3DIncline, EnergyWithTheSlopeNeverIncreasesOnStillGround) {
  {
    const RigidBody3D box = RigidBody3D::box(0.2, 0.3, 0.8);
    std::vector<double> a(1001, 0.0);
    for (std::size_t i = 0; i <= 200; ++i) {
      a[i] = 0.45 * kG * std::sin(2.0 * M_PI * static_cast<double>(i) * 0.002 / 0.4);
    }
    const GroundMotion mx = GroundMotion::uniform(a, 0.002);
    std::vector<double> b(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) b[i] = 0.6 * a[i];
    const GroundMotion my = GroundMotion::uniform(b, 0.002);
    Rigid3DOptions o = incline(6.0, 120.0);
    o.record_history = true;
    o.rel_tol = 1e-10;
    const Rigid3DResult r = rock3d(mx, &my, nullptr, box, o);
    EXPECT_GT(r.summary.impacts, 0U);
    EXPECT_GT(r.summary.max_tilt_rad, 0.01);
    double last = std::numeric_limits<double>::infinity();
    double scale = 0.0;
    for (const double e : r.history.energy_j_per_kg) scale = std::max(scale, std::abs(e));
    for (std::size_t i = 0; i < r.history.time_s.size(); ++i) {
      if (r.history.time_s[i] < 0.4 + 1e-9) continue;
      EXPECT_LE(r.history.energy_j_per_kg[i], last + 1e-8 * scale) << r.history.time_s[i];
      last = r.history.energy_j_per_kg[i];
    }
  }
  {
    const RigidBody3D box = RigidBody3D::box(1.0, 0.8, 0.4);
    Rigid3DOptions o = incline(25.0, 300.0);
    o.mu_s = 0.3;
    o.record_history = true;
    const Rigid3DResult r = rock3d(zeros(1.0, 0.01), nullptr, nullptr, box, o);
    const auto& E = r.history.energy_j_per_kg;
    ASSERT_GT(E.size(), 10U);
    for (std::size_t i = 1; i < E.size(); ++i) EXPECT_LE(E[i], E[i - 1] + 1e-12) << r.history.time_s[i];
    // the loss equals friction's work
    EXPECT_NEAR(E.front() - E.back(), r.summary.friction_energy_j_per_kg, 1e-6 * r.summary.friction_energy_j_per_kg);
  }
}

TEST(Rigid3DIncline, BadInclineIsAnInputErrorNamingTheField) {
  const RigidBody3D box = RigidBody3D::box(0.2, 0.3, 0.8);
  const GroundMotion still = zeros(0.1, 0.01);
  for (const double bad : {-1.0, 90.0, std::numeric_limits<double>::quiet_NaN()}) {
    try {
      (void)rock3d(still, nullptr, nullptr, box, incline(bad, 0.0));
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("base_incline_deg"), std::string::npos) << e.what();
    }
  }
  try {
    (void)rock3d(still, nullptr, nullptr, box, incline(5.0, std::numeric_limits<double>::infinity()));
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("base_incline_azimuth_deg"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace topple
