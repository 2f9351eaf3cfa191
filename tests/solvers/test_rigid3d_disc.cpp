// A cylinder in three dimensions (rigid3d_disc.hpp; docs/method.md, "A circular base: rolling on the rim"): under one
// horizontal component it is the planar engine's cylinder; a free cylinder spinning on its rim about the vertical
// through the contact keeps the closed-form steady precession; energy is conserved in free rolling and never
// increases with impacts; the error falls with the tolerance; a rotated ground motion gives the rotated motion.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "support/noise_record.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"

namespace topple {
namespace {

constexpr double kG = 9.80665;

GroundMotion noise(unsigned seed, double pga_m_s2, std::size_t n = 3000, double dt = 0.005) {
  return test::noise_record({.seed = seed, .samples = n, .dt_s = dt, .pga_m_s2 = pga_m_s2, .resonance_hz = 2.5,
                             .pole_radius = 0.97, .envelope_peak_s = 0.2 * static_cast<double>(n) * dt});
}

GroundMotion times(const GroundMotion& m, double k) {
  std::vector<double> a(m.accel_m_s2().begin(), m.accel_m_s2().end());
  for (double& x : a) x *= k;
  return GroundMotion::uniform(a, m.dt_s(), m.start_time_s());
}

GroundMotion still(double duration_s, double dt = 0.01) {
  return GroundMotion::uniform(std::vector<double>(static_cast<std::size_t>(std::llround(duration_s / dt)) + 1, 0.0),
                               dt);
}

/// Orientation tilting the axis by theta toward plan direction (cos phi, sin phi) (counter-clockwise from east).
Quaternion tilted(double theta, double phi) {
  // rotation by theta about the horizontal axis (-sin phi, cos phi, 0)
  const double s = std::sin(0.5 * theta);
  return {std::cos(0.5 * theta), -std::sin(phi) * s, std::cos(phi) * s, 0.0};
}

Vec3 axis_of(const Quaternion& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y)};
}

// A solid cylinder 0.3 m in diameter, 1.0 m tall (alpha = atan(0.15 / 0.5) = 16.7 deg) under x alone (and under y
// alone) rocks in the vertical plane of the input exactly as the planar cylinder 0.3 x 1.0 (rocking.hpp: D =
// (15 a^2 + 16 h^2) / 12, Housner's e = 1 - 24 a^2 / (15 a^2 + 16 h^2)): verdict, impacts, max tilt to 1e-6.
TEST(Rigid3DDisc, OneComponentEqualsThePlanarCylinder) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const RockingBody planar = RockingBody::cylinder(0.3, 1.0);
  int cases = 0, fell = 0;
  std::size_t impacts_total = 0;
  // 1e-6 asked (issue 29); measured (rel_tol 1e-12): worst 1.3e-7 rad, where seed 1 at 0.5 g chatters through 153
  // impacts of amplitude down to 1e-5 rad, whose timing amplifies the integrators' differences (1.9e-6 before the
  // landing was located on the continued rim equations, when the contact at a landing was the step's tilted one)
  constexpr double kTol = 1e-6;
  double worst = 0.0;
  for (const unsigned seed : {1U, 2U, 3U}) {
    for (const double pga_g : {0.3, 0.5, 0.8}) {
      const GroundMotion m = noise(seed, pga_g * kG);
      RockingOptions po;
      po.g_m_s2 = kG;
      po.rel_tol = 1e-12;
      const RockingSummary p = rock_summary(m, planar, po);
      for (const int axis : {0, 1}) {
        Rigid3DOptions o;
        o.g_m_s2 = kG;
        o.rel_tol = 1e-12;
        const Rigid3DSummary s = axis == 0 ? rock3d_cylinder(m, nullptr, nullptr, cyl, o).summary
                                           : rock3d_cylinder(times(m, 0.0), &m, nullptr, cyl, o).summary;
        SCOPED_TRACE(testing::Message() << "seed " << seed << " pga " << pga_g << " axis " << axis);
        EXPECT_EQ(s.overturned, p.overturned);
        EXPECT_EQ(s.impacts, p.impacts);
        EXPECT_EQ(s.uplifts, p.uplifts);
        EXPECT_NEAR(s.max_tilt_rad, p.max_abs_rotation_rad, kTol);
        EXPECT_NEAR(s.max_tilt_over_limit, p.max_rotation_over_alpha, kTol / planar.alpha_rad());
        EXPECT_NEAR(s.energy_lost_j_per_kg, p.energy_lost_j_per_kg, kTol * std::max(1.0, p.energy_lost_j_per_kg));
        worst = std::max(worst, std::abs(s.max_tilt_rad - p.max_abs_rotation_rad));
        if (p.overturned && s.overturned) {
          EXPECT_NEAR(*s.overturn_time_s, *p.overturn_time_s, kTol);
          // the fall along the input's axis: x east (azimuth 90 or 270), y north (0 or 180)
          const double az = s.overturn_azimuth_deg;
          const double off = axis == 0 ? std::min(std::abs(az - 90.0), std::abs(az - 270.0))
                                       : std::min({std::abs(az), std::abs(az - 180.0), std::abs(az - 360.0)});
          EXPECT_LT(off, 1e-6);
        }
        ++cases;
        fell += p.overturned ? 1 : 0;
        impacts_total += p.impacts;
      }
    }
  }
  EXPECT_EQ(cases, 18);
  EXPECT_GT(fell, 0);
  EXPECT_LT(fell, cases);
  EXPECT_GT(impacts_total, 20U);
  std::printf("cylinder 3-D vs planar: worst |max tilt difference| %.3g rad over %d cases\n", worst, cases);
}

// Steady motion with the contact point at rest: the body turns at Omega about the vertical through the contact, tilt
// theta constant. Angular momentum about the (fixed) contact, L = M_p Omega z, turns with the body: Omega z x L =
// r x (-g z), r = c - p = (h sin - R cos, 0, h cos + R sin) for the axis leaning toward +x, whose y component gives
// (the rolling disk's steady-motion condition, O'Reilly 1996, for a zero radius of the contact's path)
//   Omega^2 = g r_x / ((J_a - J_t) sin(theta) cos(theta) - r_z r_x).
TEST(Rigid3DDisc, SteadyPrecessionAboutTheContact) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const double R = 0.15, h = 0.5, Ja = 0.5 * R * R, Jt = (3.0 * R * R + 1.0) / 12.0;
  for (const double theta : {0.25, 0.27, 0.28}) {
    const double rx = h * std::sin(theta) - R * std::cos(theta);
    const double rz = h * std::cos(theta) + R * std::sin(theta);
    const double omega2 = kG * rx / ((Ja - Jt) * std::sin(theta) * std::cos(theta) - rz * rx);
    ASSERT_GT(omega2, 0.0);
    const double Omega = std::sqrt(omega2);
    Rigid3DOptions o;
    o.g_m_s2 = kG;
    o.rel_tol = 1e-11;
    o.abs_tol = 1e-14;
    o.max_run_out_s = 0.0;
    o.record_history = true;
    const CylinderInitialState init{tilted(theta, 0.0), {0.0, 0.0, Omega}};
    const Rigid3DResult r = rock3d_cylinder(still(2.0), nullptr, nullptr, cyl, o, init);
    SCOPED_TRACE(testing::Message() << "theta " << theta << " Omega " << Omega);
    EXPECT_EQ(r.summary.impacts, 0U);
    EXPECT_FALSE(r.summary.overturned);
    ASSERT_GT(r.history.time_s.size(), 100U);
    double worst_tilt = 0.0, worst_phase = 0.0;
    for (std::size_t i = 0; i < r.history.time_s.size(); ++i) {
      const Vec3 a = axis_of(r.history.orientation[i]);
      worst_tilt = std::max(worst_tilt, std::abs(std::acos(a[2]) - theta));
      const double phase = std::atan2(a[1], a[0]) - Omega * r.history.time_s[i];
      worst_phase = std::max(worst_phase, std::abs(std::remainder(phase, 2.0 * M_PI)));
    }
    EXPECT_LT(worst_tilt, 1e-6);
    EXPECT_LT(worst_phase, 1e-6);  // the precession rate Omega over 2 s
  }
}

double max_energy_drift(const Rigid3DResult& r) {
  double d = 0.0;
  for (const double e : r.history.energy_j_per_kg) d = std::max(d, std::abs(e - r.history.energy_j_per_kg.front()));
  return d;
}

// Free rolling on the rim (no impact): energy conserved to the tolerance; a wobbling motion (tilt, spin and a
// sideways rate) whose contact runs round the rim.
TEST(Rigid3DDisc, FreeRollingConservesEnergy) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.max_run_out_s = 0.0;
  o.record_history = true;
  const CylinderInitialState init{tilted(0.2, 0.3), {0.4, -0.3, 6.0}};
  const Rigid3DResult r = rock3d_cylinder(still(3.0), nullptr, nullptr, cyl, o, init);
  ASSERT_EQ(r.summary.impacts, 0U);
  ASSERT_FALSE(r.summary.overturned);
  // the contact went round the rim: the axis' azimuth swept more than a turn
  double swept = 0.0;
  for (std::size_t i = 1; i < r.history.time_s.size(); ++i) {
    const Vec3 a0 = axis_of(r.history.orientation[i - 1]), a1 = axis_of(r.history.orientation[i]);
    swept += std::remainder(std::atan2(a1[1], a1[0]) - std::atan2(a0[1], a0[0]), 2.0 * M_PI);
  }
  EXPECT_GT(std::abs(swept), 2.0 * M_PI);
  const double scale = kG * 0.5;  // g h: the potential energy's scale, J/kg
  EXPECT_LT(max_energy_drift(r), 1e-7 * scale);
  std::printf("free wobble: energy drift %.3g J/kg over 3 s (g h = %.3g), axis swept %.3g rad\n", max_energy_drift(r),
              scale, swept);
}

// With impacts (free, from a tilt coming back down, with no or a small sideways rate): the energy never increases.
// With a spin about the vertical the ideal rim does not land: the contact runs round the rim near the upright and
// the body rolls over onto the other side (the rolling disk; energy conserved, checked too).
TEST(Rigid3DDisc, EnergyNeverIncreasesWithImpacts) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const double phi = 1.0;
  const Vec3 u{std::cos(phi), std::sin(phi), 0.0}, t{-std::sin(phi), std::cos(phi), 0.0};
  for (const double side : {0.0, 1e-4, 1e-3}) {
    for (const double spin : {0.0, 0.3}) {
      Rigid3DOptions o;
      o.g_m_s2 = kG;
      o.max_run_out_s = 0.0;
      o.record_history = true;
      // tilted by 0.15 rad toward azimuth phi (from east), coming back down about the rocking axis t at 0.3 rad/s,
      // a sideways rate along u, a spin about the vertical
      const CylinderInitialState init{tilted(0.15, phi),
                                      {-0.3 * t[0] + side * u[0], -0.3 * t[1] + side * u[1], spin}};
      const Rigid3DResult r = rock3d_cylinder(still(4.0), nullptr, nullptr, cyl, o, init);
      SCOPED_TRACE(testing::Message() << "sideways " << side << " spin " << spin);
      const auto& e = r.history.energy_j_per_kg;
      ASSERT_GT(e.size(), 10U);
      for (std::size_t i = 1; i < e.size(); ++i) EXPECT_LE(e[i], e[i - 1] + 1e-9 * kG * 0.5) << "at " << i;
      if (spin == 0.0) {
        EXPECT_GT(r.summary.impacts, 5U);
        EXPECT_GT(r.summary.energy_lost_j_per_kg, 0.5 * e.front());
        EXPECT_NEAR(r.summary.energy_lost_j_per_kg + e.back(), e.front(), 1e-6 * e.front());
      } else {
        EXPECT_EQ(r.summary.impacts, 0U);
        EXPECT_NEAR(e.back(), e.front(), 1e-8 * kG * 0.5);
      }
    }
  }
}

// The integration error of a free wobbling motion falls in proportion to the tolerance (Dormand-Prince's error
// control: the global error is about proportional to the local tolerance).
TEST(Rigid3DDisc, ErrorFallsWithTheTolerance) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const CylinderInitialState init{tilted(0.2, 0.3), {0.4, -0.3, 6.0}};
  const auto end_axis = [&](double tol) {
    Rigid3DOptions o;
    o.g_m_s2 = kG;
    o.rel_tol = tol;
    o.abs_tol = tol * 1e-4;
    o.max_run_out_s = 0.0;
    o.record_history = true;
    const Rigid3DResult r = rock3d_cylinder(still(1.0), nullptr, nullptr, cyl, o, init);
    return axis_of(r.history.orientation.back());
  };
  const Vec3 ref = end_axis(1e-13);
  const auto err = [&](double tol) {
    const Vec3 a = end_axis(tol);
    return std::hypot(a[0] - ref[0], a[1] - ref[1], a[2] - ref[2]);
  };
  const double e6 = err(1e-6), e8 = err(1e-8), e10 = err(1e-10);
  EXPECT_LT(e8, e6 / 10.0);
  EXPECT_LT(e10, e8 / 10.0);
  EXPECT_LT(e10, 1e-8);
  const double order = std::log10(e6 / e10) / 4.0;  // error ~ tol^order
  std::printf("end-axis error at rel_tol 1e-6 / 1e-8 / 1e-10: %.3g / %.3g / %.3g, order %.3f\n", e6, e8, e10, order);
  EXPECT_GT(order, 0.7);
  EXPECT_LT(order, 1.3);
}

// Two horizontal components turned by phi about the vertical: the same tilt, impacts and verdict, the fall's azimuth
// turned by phi (azimuth clockwise from north: minus phi in degrees). The cylinder turned about its own axis is the
// same body (axisymmetric), so the rotated input covers it.
TEST(Rigid3DDisc, RotatedGroundMotionGivesTheRotatedMotion) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  int fell = 0;
  for (const double pga_g : {0.35, 0.6}) {
    const GroundMotion m1 = noise(7, pga_g * kG), m2 = noise(8, 0.8 * pga_g * kG);
    Rigid3DOptions o;
    o.g_m_s2 = kG;
    o.rel_tol = 1e-10;
    const Rigid3DSummary a = rock3d_cylinder(m1, &m2, nullptr, cyl, o).summary;
    for (const double phi : {0.7, 2.0}) {
      std::vector<double> x(m1.size()), y(m1.size());
      for (std::size_t i = 0; i < m1.size(); ++i) {
        x[i] = std::cos(phi) * m1.accel_m_s2()[i] - std::sin(phi) * m2.accel_m_s2()[i];
        y[i] = std::sin(phi) * m1.accel_m_s2()[i] + std::cos(phi) * m2.accel_m_s2()[i];
      }
      const GroundMotion rx = GroundMotion::uniform(x, m1.dt_s()), ry = GroundMotion::uniform(y, m1.dt_s());
      const Rigid3DSummary b = rock3d_cylinder(rx, &ry, nullptr, cyl, o).summary;
      SCOPED_TRACE(testing::Message() << "pga " << pga_g << " phi " << phi);
      EXPECT_EQ(a.overturned, b.overturned);
      EXPECT_EQ(a.impacts, b.impacts);
      EXPECT_NEAR(a.max_tilt_rad, b.max_tilt_rad, 1e-6);
      EXPECT_NEAR(std::remainder(b.max_tilt_azimuth_deg - (a.max_tilt_azimuth_deg - phi * 180.0 / M_PI), 360.0), 0.0,
                  1e-2);
      if (a.overturned && b.overturned) {
        EXPECT_NEAR(std::remainder(b.overturn_azimuth_deg - (a.overturn_azimuth_deg - phi * 180.0 / M_PI), 360.0),
                    0.0, 1e-2);
        ++fell;
      }
    }
    EXPECT_GT(a.uplifts, 0U);
  }
  (void)fell;
}

// Lifts shorter than a step: a record sampled coarsely (dt 0.02 s, the rocking chatters between samples, so steps that
// start flat end past the upright) and a single sample just over the uplift level (a lift of a few microseconds, or
// none): the runs end, impacts and max tilt as the planar engine's (its lift-off that did not happen is rest too).
TEST(Rigid3DDisc, LiftsShorterThanAStep) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const RockingBody planar = RockingBody::cylinder(0.3, 1.0);
  std::vector<double> spike(200, 0.0);
  spike[100] = 1.0001 * kG * 0.15 / 0.5;  // (g R / h) (1 + 1e-4)
  const std::vector<GroundMotion> motions{noise(4, 0.4 * kG, 750, 0.02), GroundMotion::uniform(spike, 0.01)};
  for (std::size_t k = 0; k < motions.size(); ++k) {
    RockingOptions po;
    po.g_m_s2 = kG;
    po.rel_tol = 1e-12;
    const RockingSummary p = rock_summary(motions[k], planar, po);
    Rigid3DOptions o;
    o.g_m_s2 = kG;
    o.rel_tol = 1e-12;
    const Rigid3DSummary s = rock3d_cylinder(motions[k], nullptr, nullptr, cyl, o).summary;
    SCOPED_TRACE(testing::Message() << "motion " << k);
    EXPECT_EQ(s.overturned, p.overturned);
    EXPECT_EQ(s.impacts, p.impacts);
    EXPECT_NEAR(s.max_tilt_rad, p.max_abs_rotation_rad, 1e-6);
    EXPECT_EQ(s.end_mode, Rigid3DMode::rest);
    if (k == 0) {
      EXPECT_GT(p.impacts, 20U);
    }
    std::printf("lifts shorter than a step, motion %zu: %zu impacts, %zu uplifts, max tilt %.3g rad\n", k, s.impacts,
                s.uplifts, s.max_tilt_rad);
  }
}

// The run-out after the record takes steps of any length (constant forcing); with a history its rows continue the
// record's spacing from the dense output, so the run takes the same steps: the same summary to the last bit.
TEST(Rigid3DDisc, RunOutHistoryTakesTheSameSteps) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  // a free wobble (FreeRollingConservesEnergy's) on 1 s of still ground, rolling on through a 2 s run-out
  const GroundMotion m1 = still(1.0, 0.005);
  const CylinderInitialState init{tilted(0.2, 0.3), {0.4, -0.3, 6.0}};
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.max_run_out_s = 2.0;
  const Rigid3DSummary a = rock3d_cylinder(m1, nullptr, nullptr, cyl, o, init).summary;
  o.record_history = true;
  const Rigid3DResult b = rock3d_cylinder(m1, nullptr, nullptr, cyl, o, init);
  ASSERT_NEAR(a.end_time_s, m1.end_time_s() + 2.0, 1e-12);  // rolling through the whole run-out
  ASSERT_FALSE(a.overturned);
  EXPECT_EQ(a.steps, b.summary.steps);
  EXPECT_EQ(a.impacts, b.summary.impacts);
  EXPECT_EQ(a.max_tilt_rad, b.summary.max_tilt_rad);
  EXPECT_EQ(a.end_time_s, b.summary.end_time_s);
  EXPECT_FALSE(a.overturned);
  // the run-out's rows: on the record's spacing after its end, and an event's own rows
  std::size_t on_grid = 0;
  for (const double t : b.history.time_s) {
    if (t <= m1.end_time_s()) continue;
    const double k = (t - m1.end_time_s()) / m1.dt_s();
    on_grid += std::abs(k - std::round(k)) < 1e-6 ? 1U : 0U;
  }
  EXPECT_GT(on_grid, static_cast<std::size_t>(0.9 * (a.end_time_s - m1.end_time_s()) / m1.dt_s()));
}

TEST(Rigid3DDisc, BadInputNamesTheField) {
  EXPECT_THROW((void)CylinderBody3D::solid(0.0, 1.0), InputError);
  EXPECT_THROW((void)CylinderBody3D::general(0.1, 0.5, 1.0, 0.1), InputError);
  const GroundMotion m = noise(1, 0.3 * kG);
  const GroundMotion v = times(m, -10.0);
  EXPECT_THROW((void)rock3d_cylinder(m, nullptr, &v, CylinderBody3D::solid(0.3, 1.0)), InputError);
}


// Friction given (Rigid3DOptions::mu_s; docs/method.md, "A circular base with friction"). With mu large the rolling
// contact never needs more than mu_s N: the answer is the no-slip rim engine's (the same steps: the check reads the
// contact force on the dense output and changes no state), for two components and a vertical.
TEST(Rigid3DDiscFriction, LargeMuIsTheNoSlipRimEngine) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  int rocked = 0, fell = 0;
  std::size_t contact_failed = 0;
  for (const unsigned seed : {1U, 2U, 3U}) {
    for (const double pga_g : {0.3, 0.6}) {
      const GroundMotion ex = noise(seed, pga_g * kG);
      const GroundMotion ny = noise(seed + 10, 0.7 * pga_g * kG);
      const GroundMotion up = noise(seed + 20, 0.3 * pga_g * kG);
      Rigid3DOptions o;
      o.g_m_s2 = kG;
      const Rigid3DSummary a = rock3d_cylinder(ex, &ny, &up, cyl, o).summary;
      o.mu_s = 10.0;
      o.mu_k = 8.0;
      const Rigid3DSummary b = rock3d_cylinder(ex, &ny, &up, cyl, o).summary;
      SCOPED_TRACE(testing::Message() << "seed " << seed << " pga " << pga_g);
      EXPECT_EQ(b.overturned, a.overturned);
      EXPECT_EQ(b.impacts, a.impacts);
      EXPECT_EQ(b.uplifts, a.uplifts);
      if (!a.overturned) {
        EXPECT_EQ(b.residual_slide_east_m, 0.0);
        EXPECT_TRUE(b.warnings.empty());
        EXPECT_FALSE(b.slide_rock_time_s);
        EXPECT_FALSE(b.flight_time_s);
        EXPECT_NEAR(b.max_tilt_rad, a.max_tilt_rad, 1e-6);
        EXPECT_NEAR(b.end_time_s, a.end_time_s, 1e-9);
      } else {
        // a toppling body's rolling contact fails near the end of its fall, where N -> 0 and |F_t| / N grows without
        // bound (even at mu = 10): it slips or flies for the last instants of the fall (measured: the fall at 90
        // degrees within 5e-3 s of the no-slip engine's, the same azimuth within 1 degree)
        ASSERT_TRUE(b.overturn_time_s);
        EXPECT_NEAR(*b.overturn_time_s, *a.overturn_time_s, 0.02);
        EXPECT_NEAR(std::remainder(b.overturn_azimuth_deg - a.overturn_azimuth_deg, 360.0), 0.0, 2.0);
        EXPECT_NEAR(b.max_tilt_rad, a.max_tilt_rad, 1e-6);  // 90 degrees
        if (b.slide_rock_time_s || b.flight_time_s) ++contact_failed;
      }
      rocked += a.uplifts > 0 ? 1 : 0;
      fell += a.overturned ? 1 : 0;
    }
  }
  EXPECT_GE(rocked, 4);
  EXPECT_GT(fell, 0);
  EXPECT_GT(contact_failed, 0U);
  std::printf("mu 10: %d of 6 runs rocked, %d fell, %zu falls ending in slip or flight\n", rocked, fell,
              contact_failed);
}

// mu_s h < R: the centre of pressure never reaches the rim (Shenton 1996), the cylinder is slide_2d's block: residual
// displacement, max speed, path and friction work to 1e-9 relative, never a tilt. Just above (mu_s h > R) a strong
// record lifts it.
TEST(Rigid3DDiscFriction, NoUpliftBelowShentonIsSlide2d) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.6, 1.0);  // R / h = 0.6
  const GroundMotion ex = noise(4, 1.5 * kG);
  const GroundMotion ny = noise(5, 1.0 * kG);
  const GroundMotion up = noise(6, 0.3 * kG);
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.mu_s = 0.55;
  o.mu_k = 0.45;
  o.record_history = true;
  const Rigid3DResult r = rock3d_cylinder(ex, &ny, &up, cyl, o);
  const Sliding2dSummary s =
      slide_2d_summary(ex, ny, ComponentAzimuths{90.0, 0.0}, SlidingBlock::make(0.55, 0.45, 0.0, SlidingMode::two_way, kG),
                       &up);
  const double d = std::hypot(s.residual_east_m, s.residual_north_m);
  ASSERT_GT(d, 0.05);  // it slid
  EXPECT_NEAR(r.summary.residual_slide_east_m, s.residual_east_m, 1e-9 * d);
  EXPECT_NEAR(r.summary.residual_slide_north_m, s.residual_north_m, 1e-9 * d);
  EXPECT_NEAR(r.summary.max_slide_speed_m_s, s.max_abs_velocity_m_s, 1e-9 * s.max_abs_velocity_m_s);
  EXPECT_NEAR(r.summary.slide_path_length_m, s.path_length_m, 1e-9 * s.path_length_m);
  EXPECT_NEAR(r.summary.friction_energy_j_per_kg, s.friction_work_J_kg, 1e-9 * s.friction_work_J_kg);
  EXPECT_EQ(r.summary.uplifts, 0U);
  EXPECT_EQ(r.summary.max_tilt_rad, 0.0);
  EXPECT_GT(r.summary.slip_episodes, 0);
  ASSERT_TRUE(r.summary.first_slip_time_s);
  for (const Rigid3DMode m : r.history.mode) EXPECT_TRUE(m == Rigid3DMode::rest || m == Rigid3DMode::sliding);
  o.mu_s = 0.65;
  o.mu_k = 0.65;
  EXPECT_GT(rock3d_cylinder(ex, &ny, &up, cyl, o).summary.uplifts, 0U);
}

// The contact force on the rim against its closed form. Released from rest at tilt theta0 in one vertical plane
// (w = 0), or with a rate w about the rocking axis, the body turns about the contact: with rho = |c - p|, beta = alpha
// - theta0 the angle of c - p from the vertical, D = J_t + rho^2 (rocking.hpp's cylinder), theta'' = g rho sin(beta) /
// D back toward the upright; c's acceleration is rho theta'' across c - p plus w^2 rho toward p, so (per unit mass)
//   F_t = g rho^2 sin(beta) cos(beta) / D - w^2 rho sin(beta),   N = g (1 - rho^2 sin^2(beta) / D) - w^2 rho cos(beta).
// A mu_s just below F_t / N stops the run at its start with a slip on the rim; just above, not there. A w^2 just above
// N's zero stops it at its start with flight; just below, not there.
TEST(Rigid3DDiscFriction, RimContactForceAgainstTheClosedForm) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const double R = 0.15, h = 0.5, rho2 = R * R + h * h, rho = std::sqrt(rho2);
  const double D = cyl.inertia_transverse_m2 + rho2;
  const double theta0 = 0.2, beta = std::atan2(R, h) - theta0;
  const auto run = [&](double mu, double w) {
    Rigid3DOptions o;
    o.g_m_s2 = kG;
    o.mu_s = mu;
    o.max_run_out_s = 0.0;
    // tilted toward +x (the contact on the +x rim); w about y: positive w raises the tilt (any sign: w^2)
    return rock3d_cylinder(still(1.0), nullptr, nullptr, cyl, o, CylinderInitialState{tilted(theta0, 0.0), {0.0, w, 0.0}})
        .summary;
  };
  const double ratio = rho2 * std::sin(beta) * std::cos(beta) / (D - rho2 * std::pow(std::sin(beta), 2));
  std::printf("cylinder 0.3 x 1.0 released at 0.2 rad: F_t / N = %.6f\n", ratio);
  const Rigid3DSummary below = run(ratio * (1.0 - 1e-6), 0.0);
  ASSERT_TRUE(below.slide_rock_time_s);
  EXPECT_EQ(*below.slide_rock_time_s, 0.0);
  EXPECT_FALSE(below.flight_time_s);
  EXPECT_GT(below.slide_path_length_m, 0.0);
  const Rigid3DSummary above = run(ratio * (1.0 + 1e-6), 0.0);
  ASSERT_TRUE(above.slide_rock_time_s);  // the ratio grows as the body falls back (beta grows): slips soon after
  EXPECT_GT(*above.slide_rock_time_s, 0.0);
  EXPECT_LT(*above.slide_rock_time_s, 0.1);
  // flight: N = 0 at w0^2 = g (1 - rho^2 sin^2(beta) / D) / (rho cos(beta)); mu_s = 100 keeps the slip test off
  const double w0 = std::sqrt(kG * (1.0 - rho2 * std::pow(std::sin(beta), 2) / D) / (rho * std::cos(beta)));
  const Rigid3DSummary fly = run(100.0, w0 * (1.0 + 1e-6));
  ASSERT_TRUE(fly.flight_time_s);
  EXPECT_EQ(*fly.flight_time_s, 0.0);
  EXPECT_TRUE(!fly.slide_rock_time_s || *fly.slide_rock_time_s > 0.0);  // after landing, if at all
  EXPECT_GE(fly.flights, 1U);
  const Rigid3DSummary stays = run(100.0, w0 * (1.0 - 1e-3));
  EXPECT_TRUE(!stays.flight_time_s || *stays.flight_time_s > 0.0);
}

// Under one component with no spin the cylinder stays in the vertical plane of the input, where the planar coupled
// model (slide_rock.hpp) with the cylinder's planar body (RockingBody::cylinder: b = d / 2, k2 = J_t) is the same
// mechanics: while its pivot sticks (rock) the rim engine rolls identically (verdict, impacts, max tilt to 1e-6); its
// first slip of a rocking pivot (slide-rock) or lift-off (flight), located there on its own dense output at |F| = mu_s
// N or N = 0, is where the rim engine's rolling contact fails (to 1e-6 s); after it the two engines slide-rock and fly
// with the same laws but impacts differ (the rim engine's flat landing, header), so the verdict and residual slide are
// compared within the numbers measured below.
TEST(Rigid3DDiscFriction, OneComponentAgreesWithThePlanarCoupledModel) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const RockingBody planar = RockingBody::cylinder(0.3, 1.0);
  int same = 0, coupled = 0, flights = 0, verdicts = 0;
  double worst_tilt = 0.0, worst_time = 0.0;
  for (const unsigned seed : {1U, 2U, 3U}) {
    for (const double pga_g : {0.3, 0.5}) {
      for (const double mu : {0.32, 0.5, 1.0}) {
        for (const bool vertical : {false, true}) {
          const GroundMotion m = noise(seed, pga_g * kG);
          const GroundMotion up = noise(seed + 30, 2.2 * pga_g * kG);
          SlideRockOptions po;
          po.g_m_s2 = kG;
          po.rel_tol = 1e-12;
          const SlideRockResult p =
              slide_rock(m, SlideRockBody::from_rocking(planar, mu, mu), po, vertical ? &up : nullptr);
          const auto& first = p.summary.mode_first_time_s;
          const auto sr = first[static_cast<std::size_t>(SlideRockMode::slide_rock)];
          const auto fl = first[static_cast<std::size_t>(SlideRockMode::flight)];
          Rigid3DOptions o;
          o.g_m_s2 = kG;
          o.rel_tol = 1e-12;
          o.mu_s = mu;
          const Rigid3DSummary s = rock3d_cylinder(m, nullptr, vertical ? &up : nullptr, cyl, o).summary;
          SCOPED_TRACE(testing::Message() << "seed " << seed << " pga " << pga_g << " mu " << mu << " vertical "
                                          << vertical);
          const double t1 = std::min(sr.value_or(1e300), fl.value_or(1e300));
          const double mine = std::min(s.slide_rock_time_s.value_or(1e300), s.flight_time_s.value_or(1e300));
          if (t1 > 1e299) {
            EXPECT_GT(mine, 1e299);
            EXPECT_EQ(s.overturned, p.summary.overturned);
            EXPECT_EQ(s.impacts, p.summary.impacts);
            EXPECT_NEAR(s.max_tilt_rad, p.summary.max_rotation_over_alpha * planar.alpha_rad(), 1e-6);
            worst_tilt = std::max(worst_tilt,
                                  std::abs(s.max_tilt_rad - p.summary.max_rotation_over_alpha * planar.alpha_rad()));
            ++same;
          } else {
            EXPECT_NEAR(mine, t1, 1e-6);
            worst_time = std::max(worst_time, std::abs(mine - t1));
            flights += fl ? 1 : 0;
            verdicts += s.overturned == p.summary.overturned ? 1 : 0;
            if (!s.overturned && !p.summary.overturned) {
              // both stand: the base's residual slide (the planar pivot's u) within 10 % + 0.1 mm (measured: to the
              // printed 0.1 mm)
              EXPECT_NEAR(std::hypot(s.residual_slide_east_m, s.residual_slide_north_m),
                          std::abs(p.summary.residual_slide_m), 0.1 * std::abs(p.summary.residual_slide_m) + 1e-4);
              EXPECT_NEAR(s.residual_slide_north_m, 0.0, 1e-9);  // in the plane of the input
            }
            std::printf("  seed %u pga %.1f mu %.2f v %d: first %.6f / %.6f, fell %d / %d, impacts %zu / %zu, slide "
                        "%.4f / %.4f m, flights %zu / %zu\n",
                        seed, pga_g, mu, vertical ? 1 : 0, mine, t1, s.overturned ? 1 : 0,
                        p.summary.overturned ? 1 : 0, s.impacts, p.summary.impacts,
                        std::hypot(s.residual_slide_east_m, s.residual_slide_north_m), p.summary.residual_slide_m,
                        s.flights, p.summary.mode_entries[static_cast<std::size_t>(SlideRockMode::flight)]);
            ++coupled;
          }
        }
      }
    }
  }
  std::printf("one component vs the coupled model: %d runs roll the same (worst max tilt %.3g rad); %d slip or fly "
              "(%d fly; first instant worst %.3g s; the same verdict in %d)\n",
              same, worst_tilt, coupled, flights, worst_time, verdicts);
  EXPECT_GE(same, 3);
  EXPECT_GE(coupled, 3);
  EXPECT_GE(flights, 1);
  // measured: 16 of 17 (one run, chattering through 131 impacts after two flights, stands where the coupled model's
  // falls: the flat landing's law differs from the planar corner impact, header)
  EXPECT_GE(verdicts, coupled - 1);
}

// Frictionless (mu_s = mu_k = 0) a cylinder released past its static limit slips on its rim: no horizontal force, so
// c falls straight down (its horizontal position fixed to rounding), and energy is conserved; with the contact on the
// ground (z_c = h cos(theta) + R sin(theta)) the energy gives the rate in closed form (planar, the "falling rod on a
// smooth floor"):  theta'^2 (J_t + (R cos(theta) - h sin(theta))^2) / 2 + g (h cos(theta) + R sin(theta) - h) = E_0.
TEST(Rigid3DDiscFriction, FrictionlessSlipIsTheFallingRodOnASmoothFloor) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const double R = 0.15, h = 0.5, Jt = cyl.inertia_transverse_m2, theta0 = 0.4;
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.mu_s = 0.0;
  o.max_run_out_s = 0.0;
  o.record_history = true;
  o.rel_tol = 1e-10;
  const Rigid3DResult r =
      rock3d_cylinder(still(2.0), nullptr, nullptr, cyl, o, CylinderInitialState{tilted(theta0, 0.0), {}});
  ASSERT_TRUE(r.summary.overturned);
  ASSERT_TRUE(r.summary.slide_rock_time_s);
  EXPECT_EQ(*r.summary.slide_rock_time_s, 0.0);
  const double E0 = kG * (h * std::cos(theta0) + R * std::sin(theta0) - h);
  const auto& H = r.history;
  ASSERT_GT(H.time_s.size(), 5U);
  double worst_rate = 0.0, worst_x = 0.0;
  const double cx0 = H.position_m.front()[0] + h * axis_of(H.orientation.front())[0];
  for (std::size_t i = 0; i < H.time_s.size(); ++i) {
    const Vec3 a = axis_of(H.orientation[i]);
    const double th = std::atan2(std::hypot(a[0], a[1]), a[2]);
    if (th > 1.5) break;  // up to the fall
    const double cx = H.position_m[i][0] + h * a[0];
    worst_x = std::max(worst_x, std::abs(cx - cx0));
    const double m = Jt + std::pow(R * std::cos(th) - h * std::sin(th), 2);
    const double rate = std::sqrt(2.0 * (E0 - kG * (h * std::cos(th) + R * std::sin(th) - h)) / m);
    worst_rate = std::max(worst_rate, std::abs(std::hypot(H.angular_velocity_rad_s[i][0],
                                                          H.angular_velocity_rad_s[i][1]) - rate));
    EXPECT_NEAR(H.energy_j_per_kg[i], E0, 1e-7) << "at " << H.time_s[i];  // conserved
  }
  std::printf("frictionless fall: |c_x drift| %.3g m, |theta' - closed form| %.3g rad/s\n", worst_x, worst_rate);
  EXPECT_LT(worst_x, 1e-9);
  EXPECT_LT(worst_rate, 1e-6);
  EXPECT_EQ(r.summary.friction_energy_j_per_kg, 0.0);
}

// On still ground, a cylinder released tilted with friction (rocking back onto its base, or wobbling with spin:
// slip, stick, flat landings, flat sliding): the energy never increases, and kinetic friction plus impacts account for
// what is lost (1e-6).
TEST(Rigid3DDiscFriction, EnergyNeverIncreasesOnStillGround) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  int slipped = 0;
  std::size_t impacts = 0;
  struct Start {
    double tilt, phi;
    Vec3 w;
  };
  for (const double mu : {0.05, 0.1, 0.2, 0.35}) {
    for (const Start& st : {Start{0.15, 1.0, {0.2530, -0.1613, 0.0}}, Start{0.2, 0.7, {-1.0, 0.6, 4.0}}}) {
      Rigid3DOptions o;
      o.g_m_s2 = kG;
      o.mu_s = mu;
      o.mu_k = 0.8 * mu;
      o.max_run_out_s = 0.0;
      o.record_history = true;
      const Rigid3DResult r =
          rock3d_cylinder(still(3.0), nullptr, nullptr, cyl, o, CylinderInitialState{tilted(st.tilt, st.phi), st.w});
      SCOPED_TRACE(testing::Message() << "mu " << mu << " spin " << st.w[2]);
      const auto& e = r.history.energy_j_per_kg;
      ASSERT_GT(e.size(), 10U);
      for (std::size_t i = 1; i < e.size(); ++i) EXPECT_LE(e[i], e[i - 1] + 1e-7) << "at " << r.history.time_s[i];
      const double lost = r.summary.energy_lost_j_per_kg + r.summary.friction_energy_j_per_kg;
      EXPECT_NEAR(e.front() - e.back(), lost, 1e-6 * e.front() + 1e-6);
      slipped += r.summary.slide_rock_time_s ? 1 : 0;
      impacts += r.summary.impacts;
    }
  }
  EXPECT_GE(slipped, 4);
  EXPECT_GE(impacts, 3U);
}

// The slipping rim's error falls with the tolerance (Dormand-Prince's error control): a spinning cylinder slipping
// on a frictionless floor for 0.3 s (no impact): the end axis against rel_tol 1e-12.
TEST(Rigid3DDiscFriction, SlipErrorFallsWithTheTolerance) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const auto end_axis = [&](double tol) {
    Rigid3DOptions o;
    o.g_m_s2 = kG;
    o.mu_s = 0.1;
    o.mu_k = 0.05;
    o.rel_tol = tol;
    o.abs_tol = tol * 1e-4;
    o.max_run_out_s = 0.0;
    o.record_history = true;
    const Rigid3DResult r =
        rock3d_cylinder(still(0.3), nullptr, nullptr, cyl, o, CylinderInitialState{tilted(0.25, 0.3), {0.5, -0.4, 6.0}});
    EXPECT_EQ(r.summary.impacts, 0U);
    EXPECT_TRUE(r.summary.slide_rock_time_s.has_value());
    return axis_of(r.history.orientation.back());
  };
  const Vec3 ref = end_axis(1e-12);
  const auto err = [&](double tol) {
    const Vec3 a = end_axis(tol);
    return std::hypot(a[0] - ref[0], a[1] - ref[1], a[2] - ref[2]);
  };
  const double e6 = err(1e-6), e8 = err(1e-8), e10 = err(1e-10);
  const double order = std::log10(e6 / e10) / 4.0;
  std::printf("slip: end-axis error at rel_tol 1e-6 / 1e-8 / 1e-10: %.3g / %.3g / %.3g, order %.3f\n", e6, e8, e10,
              order);
  EXPECT_LT(e8, e6 / 10.0);
  EXPECT_LT(e10, e8 / 10.0);
  EXPECT_GT(order, 0.7);
}

// An independent check: the cylinder as a 128-gon prism in the polygon engine with friction (rigid3d_slide.cpp,
// rigid3d_contact.cpp: vertex contacts, their own impact law), its vertices on the rim, an edge across the input
// (b = R cos(pi / 128): its static limit 1.2e-4 smaller in relative terms), the solid cylinder's inertia, under one
// component at 0.5 g, mu = 0.32. The first uplift agrees (the polygon's approximation), and where the first slip
// comes in the first rocking episode (seed 2) its instant agrees to 1e-3 s. After that the engines part (measured,
// printed: the prism now stands in all 3 runs with a max tilt near 0.02 rad and slides 3-13 mm, where the rim engine
// and the planar coupled model, test above, rock to about 0.23 rad and fall in 1 of 3; when this test was written the
// prism fell in all 3): a disagreement measured, not resolved, stated in docs/method.md.
TEST(Rigid3DDiscFriction, A128GonPrismInThePolygonEngineAgrees) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const double R = 0.15;
  std::vector<std::array<double, 2>> base;
  for (int k = 0; k < 128; ++k) {
    const double a = (2.0 * k + 1.0) * M_PI / 128.0;  // an edge's normal along +x and -x
    base.push_back({R * std::cos(a), R * std::sin(a)});
  }
  const RigidBody3D prism = RigidBody3D::polygon(
      base, {0.0, 0.0, 0.5},
      {Vec3{cyl.inertia_transverse_m2, 0.0, 0.0}, Vec3{0.0, cyl.inertia_transverse_m2, 0.0},
       Vec3{0.0, 0.0, cyl.inertia_axial_m2}});
  int cases = 0, same_verdict = 0;
  double worst_first = 0.0;
  for (const unsigned seed : {1U, 2U, 3U}) {
    const GroundMotion m = noise(seed, 0.5 * kG);
    Rigid3DOptions o;
    o.g_m_s2 = kG;
    o.mu_s = 0.32;
    const Rigid3DSummary c = rock3d_cylinder(m, nullptr, nullptr, cyl, o).summary;
    o.record_history = true;
    const Rigid3DResult pr = rock3d(m, nullptr, nullptr, prism, o);
    const Rigid3DSummary& p = pr.summary;
    // the prism's lowest base vertex over its history rows (issue 29: the polygon engine let vertices pass through
    // the ground; printed to tell whether that explains a differing verdict)
    double lowest = 0.0, lowest_t = 0.0;
    for (std::size_t i = 0; i < pr.history.time_s.size(); ++i) {
      const Quaternion& q = pr.history.orientation[i];
      const double w = q[0], x = q[1], y = q[2], z = q[3];
      for (const auto& v : base) {
        const double vz = pr.history.position_m[i][2] + 2.0 * (x * z - w * y) * v[0] + 2.0 * (y * z + w * x) * v[1];
        if (vz < lowest) {
          lowest = vz;
          lowest_t = pr.history.time_s[i];
        }
      }
    }
    std::printf("  128-gon seed %u: the prism's lowest base vertex %.3g m (%.3g of its size) at %.4f s\n", seed,
                lowest, lowest / std::hypot(R, 0.5), lowest_t);
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    ASSERT_TRUE(c.slide_rock_time_s.has_value());
    ASSERT_TRUE(p.slide_rock_time_s.has_value());
    std::printf("  128-gon seed %u: first slide-rock %.5f / %.5f s, fell %d / %d, max tilt %.4f / %.4f rad, impacts "
                "%zu / %zu, slide %.4f / %.4f m\n",
                seed, *c.slide_rock_time_s, *p.slide_rock_time_s, c.overturned ? 1 : 0, p.overturned ? 1 : 0,
                c.max_tilt_rad, p.max_tilt_rad, c.impacts, p.impacts,
                std::hypot(c.residual_slide_east_m, c.residual_slide_north_m),
                std::hypot(p.residual_slide_east_m, p.residual_slide_north_m));
    ASSERT_TRUE(c.uplift_time_s && p.uplift_time_s);
    EXPECT_NEAR(*c.uplift_time_s, *p.uplift_time_s, 1e-3);
    if (seed == 2) {
      EXPECT_NEAR(*c.slide_rock_time_s, *p.slide_rock_time_s, 1e-3);
    }
    worst_first = std::max(worst_first, std::abs(*c.slide_rock_time_s - *p.slide_rock_time_s));
    same_verdict += c.overturned == p.overturned ? 1 : 0;
    ++cases;
  }
  std::printf("128-gon prism vs the rim engine: the same verdict in %d of %d, first slide-rock within %.3g s\n",
              same_verdict, cases, worst_first);
}

// Issue 29's sweep (solid cylinders x mu x `topple synth` 3-component sets): a cylinder 0.3 x 0.9 m, mu 0.8, under the
// set of seed 4 at 0.5 g ended in EventLimitError at 5.57 s: a fresh slip running against its starting direction s_0
// sat at the regularised direction's singular point v_p,h = -e s_0 (|v_p,h| = 1.001 eps), stepping 1e-8 s. The slow-slip
// backstop holds slips up to 2 eps (docs/method.md); the run now ends (it overturns, as the CLI run does), and no
// rim point is ever below the ground (the engine's invariant, checked at every step's parts: it would throw).
TEST(Rigid3DDiscFriction, AFreshSlipAtItsDirectionsSingularPointEnds) {
  SynthesisSetSpec spec;
  spec.horizontal.pga_m_s2 = 0.5 * kG;
  spec.horizontal.predominant_frequency_hz = 3.0;
  spec.horizontal.duration_s = 20.0;
  spec.horizontal.dt_s = 0.01;
  spec.horizontal.seed = 4;
  const SynthesizedSet set = synthesize_set(spec);
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.mu_s = 0.8;
  Rigid3DResult r;
  ASSERT_NO_THROW(r = rock3d_cylinder(set.first, &set.second, &*set.vertical, CylinderBody3D::solid(0.3, 0.9), o));
  std::printf("  seed 4, 0.3 x 0.9, mu 0.8: fell %d at %.4f s, held or Painleve %zu, steps %zu\n",
              r.summary.overturned ? 1 : 0, r.summary.overturn_time_s.value_or(-1.0), r.summary.painleve_events,
              r.summary.steps);
  EXPECT_TRUE(r.summary.overturned);
  EXPECT_GE(r.summary.painleve_events, 1U);  // the hold acted (the slip stopped by the sticking impulse)
}

// A cylinder wobbling on its rim without a landing (the no-slip rim conserves energy) at the end of the run-out says
// so, as the contact engine does (the sweep's 0.3 x 0.9 m cylinder under seed 1 at 0.3 g ended "rocking" silently).
TEST(Rigid3DDisc, RunOutEndingOnTheRimWarns) {
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.max_run_out_s = 1.0;
  const CylinderInitialState start{tilted(0.2, 0.3), {0.4, -0.3, 6.0}};  // FreeRollingConservesEnergy's wobble
  const Rigid3DResult r = rock3d_cylinder(still(3.0), nullptr, nullptr, CylinderBody3D::solid(0.3, 1.0), o, start);
  EXPECT_EQ(r.summary.impacts, 0U);
  EXPECT_FALSE(r.summary.overturned);
  EXPECT_EQ(r.summary.end_mode, Rigid3DMode::rocking);
  ASSERT_EQ(r.summary.warnings.size(), 1U);
  EXPECT_NE(r.summary.warnings[0].find("still moving"), std::string::npos);
}

// Shenton's flat base (mu_s h < R: the base never lifts) under a vertical input that reaches g + a_z <= 0: the flat
// slide model excludes flight (an InputError before issue 29's sweep, 12 of 270 runs at 1 g); the contact engine's flat
// phases take it: the body leaves the ground flat and lands flat (no rotation acts in flight: the tilt stays 0), and the
// flat slide's near-threshold starts end (the backstop, docs/method.md).
TEST(Rigid3DDiscFriction, ShentonBaseWithFlightStaysFlat) {
  const GroundMotion m = noise(1, 0.5 * kG);
  const GroundMotion up = noise(31, 1.6 * kG);
  ASSERT_LT(*std::min_element(up.accel_m_s2().begin(), up.accel_m_s2().end()), -kG);  // the premise: a flight
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.mu_s = 0.2;  // 0.2 x 0.5 m < R = 0.15 m
  Rigid3DResult r;
  ASSERT_NO_THROW(r = rock3d_cylinder(m, nullptr, &up, CylinderBody3D::solid(0.3, 1.0), o));
  EXPECT_GE(r.summary.flights, 1U);
  EXPECT_FALSE(r.summary.overturned);
  EXPECT_EQ(r.summary.max_tilt_rad, 0.0);
  EXPECT_EQ(r.summary.uplifts, 0U);
  EXPECT_EQ(r.summary.end_mode, Rigid3DMode::rest);
  EXPECT_GT(r.summary.slide_path_length_m, 0.0);
  std::printf("  Shenton base with flight: flights %zu, slide %.4f m, held %zu\n", r.summary.flights,
              std::hypot(r.summary.residual_slide_east_m, r.summary.residual_slide_north_m),
              r.summary.painleve_events);
  // without the vertical the flat slide model runs, as before (no flight)
  const Rigid3DResult flat = rock3d_cylinder(m, nullptr, nullptr, CylinderBody3D::solid(0.3, 1.0), o);
  EXPECT_EQ(flat.summary.flights, 0U);
}

// Bad friction is refused as for a polygonal base (rigid3d_slide.cpp): mu_k without mu_s, mu_k > mu_s, mu_s < 0.
TEST(Rigid3DDiscFriction, BadFrictionNamesTheField) {
  const CylinderBody3D cyl = CylinderBody3D::solid(0.3, 1.0);
  const GroundMotion m = noise(1, 0.3 * kG);
  Rigid3DOptions o;
  o.mu_k = 0.3;
  EXPECT_THROW(static_cast<void>(rock3d_cylinder(m, nullptr, nullptr, cyl, o)), InputError);
  o.mu_s = 0.2;
  EXPECT_THROW(static_cast<void>(rock3d_cylinder(m, nullptr, nullptr, cyl, o)), InputError);
  o.mu_s = -1.0;
  o.mu_k.reset();
  EXPECT_THROW(static_cast<void>(rock3d_cylinder(m, nullptr, nullptr, cyl, o)), InputError);
}

}  // namespace
}  // namespace topple
