// Slide-rock and flight of the three-dimensional body with Coulomb friction (rigid3d.hpp; rigid3d_contact.cpp;
// docs/method.md, "Slide-rock and flight in three dimensions").
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/slide_rock.hpp"

namespace topple {
namespace {

constexpr double kG = 9.80665;

GroundMotion sine(double amplitude, double period, double cycles, double dt, double tail, double t0 = 0.0) {
  const auto n = static_cast<std::size_t>(std::llround((t0 + cycles * period + tail) / dt)) + 1;
  std::vector<double> a(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt - t0;
    if (t >= 0.0 && t <= cycles * period) a[i] = amplitude * std::sin(2.0 * M_PI * t / period);
  }
  return GroundMotion::uniform(a, dt);
}

Rigid3DOptions friction(double mu_s, double mu_k) {
  Rigid3DOptions o;
  o.mu_s = mu_s;
  o.mu_k = mu_k;
  return o;
}

struct Case {
  double amp_g, period_s, mu, vert_g, vert_period_s;
};

// A box 0.4 wide (x), 0.3 deep, 0.8 tall under x alone (and the vertical), its plane of symmetry, equals the planar
// coupled model of the block 0.4 x 0.8 with the same friction and impact law (slide_rock.hpp): verdict, impacts, max
// theta, residual slide and the first slide-rock to 1e-6, the number of flights; cases chosen so that the planar model
// visits slide-rock (from rocking, at the stick limit and after impacts) and flight (a vertical above 1 g).
TEST(Rigid3DContact, BoxInItsPlaneOfSymmetrySlideRocksAndFliesAsThePlanarCoupledModel) {
  const RigidBody3D box = RigidBody3D::box(0.4, 0.3, 0.8);
  const std::vector<Case> cases{{0.9, 0.6, 0.55, 0.0, 1.0}, {0.8, 0.5, 0.52, 0.0, 1.0}, {0.6, 0.6, 0.6, 1.2, 0.2},
                                {0.4, 0.5, 0.4, 1.5, 0.25}};
  int slide_rocked = 0, flew = 0;
  for (const Case& c : cases) {
    const GroundMotion x = sine(c.amp_g * kG, c.period_s, 3.0, 0.005, 2.0);
    const GroundMotion z = sine(c.vert_g * kG, c.vert_period_s, 3.0 * c.period_s / c.vert_period_s, 0.005, 2.0);
    const bool vert = c.vert_g > 0.0;
    const SlideRockResult p = slide_rock(x, SlideRockBody::block(0.4, 0.8, c.mu), {}, vert ? &z : nullptr);
    const auto& s = p.summary;
    const Rigid3DResult r = rock3d(x, nullptr, vert ? &z : nullptr, box, friction(c.mu, c.mu));
    const std::size_t sr = s.mode_entries[static_cast<std::size_t>(SlideRockMode::slide_rock)];
    const std::size_t fl = s.mode_entries[static_cast<std::size_t>(SlideRockMode::flight)];
    if (sr > 0) ++slide_rocked;
    if (fl > 0) ++flew;
    EXPECT_EQ(r.summary.overturned, s.overturned) << c.amp_g << " " << c.mu;
    EXPECT_EQ(r.summary.impacts, s.impacts) << c.amp_g << " " << c.mu;
    EXPECT_EQ(r.summary.flights, fl) << c.amp_g << " " << c.mu;
    const double theta = std::max(s.max_rotation_positive_rad, s.max_rotation_negative_rad);
    EXPECT_NEAR(r.summary.max_tilt_rad, theta, 1e-6 * std::max(theta, 1e-3)) << c.amp_g << " " << c.mu;
    EXPECT_NEAR(r.summary.residual_slide_east_m, s.residual_slide_m,
                1e-6 * std::max(std::abs(s.residual_slide_m), 1e-3))
        << c.amp_g << " " << c.mu;
    EXPECT_NEAR(r.summary.residual_slide_north_m, 0.0, 1e-9);
    EXPECT_NEAR(r.summary.residual_yaw_deg, 0.0, 1e-6);
    const auto& first = s.mode_first_time_s[static_cast<std::size_t>(SlideRockMode::slide_rock)];
    ASSERT_EQ(r.summary.slide_rock_time_s.has_value(), first.has_value()) << c.amp_g << " " << c.mu;
    if (first) {
      EXPECT_NEAR(*r.summary.slide_rock_time_s, *first, 1e-6) << c.amp_g << " " << c.mu;
    }
    EXPECT_EQ(r.summary.painleve_events, s.tangential_impacts + s.painleve_holds);
    for (const auto& w : r.summary.warnings) EXPECT_EQ(w.find("not modelled"), std::string::npos) << w;
  }
  EXPECT_GE(slide_rocked, 3);
  EXPECT_GE(flew, 2);
}

/// An oblique load (x, and y at 0.8 of it a radian ahead, so that the load turns) on a box 0.6 x 0.4 x 0.8 (b/h =
/// 0.75 and 0.5) with mu_s = 0.6, mu_k = 0.55: it lifts about an edge and the contact slips while it rocks and pivots.
struct Oblique {
  GroundMotion x, y;
};
Oblique oblique(double amp_g, double cycles, double phi = 0.0) {
  const double dt = 0.004, period = 0.5;
  const auto n = static_cast<std::size_t>(std::llround((cycles * period) / dt)) + 1;
  std::vector<double> ax(n), ay(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    const double a = amp_g * kG * std::sin(2.0 * M_PI * t / period);
    const double b = 0.8 * amp_g * kG * std::sin(2.0 * M_PI * t / period + 1.0);
    ax[i] = std::cos(phi) * a - std::sin(phi) * b;
    ay[i] = std::sin(phi) * a + std::cos(phi) * b;
  }
  return {GroundMotion::uniform(ax, dt), GroundMotion::uniform(ay, dt)};
}

TEST(Rigid3DContact, ObliqueSlideRockTwists) {
  const RigidBody3D box = RigidBody3D::box(0.6, 0.4, 0.8);
  const Oblique m = oblique(0.7, 2.0);
  const Rigid3DResult r = rock3d(m.x, &m.y, nullptr, box, friction(0.6, 0.55));
  const auto& s = r.summary;
  ASSERT_TRUE(s.slide_rock_time_s.has_value());
  EXPECT_GT(s.slide_rock_duration_s, 0.0);
  EXPECT_GT(std::abs(s.residual_yaw_deg), 1e-3);  // twist: slipping corners turn the body about the vertical
  EXPECT_GT(std::hypot(s.residual_slide_east_m, s.residual_slide_north_m), 1e-4);
  bool slid_rocking = false;
  for (const auto& mc : s.modes) slid_rocking = slid_rocking || mc.mode == Rigid3DMode::slide_rock;
  EXPECT_TRUE(slid_rocking);
  EXPECT_GT(s.end_time_s, m.x.end_time_s());  // ran to rest after the record (no stop)
  EXPECT_EQ(s.end_mode, Rigid3DMode::rest);
}

// A turned body under the turned motion: the same motion turned (slide vector turned, same tilt, yaw and modes).
TEST(Rigid3DContact, TurnedBodyUnderTurnedMotionSlideRocksTheSame) {
  const RigidBody3D box = RigidBody3D::box(0.6, 0.4, 0.8);
  const double phi = 0.7;
  const Oblique m0 = oblique(0.7, 2.0);
  const Oblique m1 = oblique(0.7, 2.0, phi);
  const Rigid3DSummary r0 = rock3d(m0.x, &m0.y, nullptr, box, friction(0.6, 0.55)).summary;
  const Rigid3DSummary r1 = rock3d(m1.x, &m1.y, nullptr, box.rotated_about_vertical(phi), friction(0.6, 0.55)).summary;
  ASSERT_TRUE(r0.slide_rock_time_s.has_value());
  const double ue = std::cos(phi) * r0.residual_slide_east_m - std::sin(phi) * r0.residual_slide_north_m;
  const double un = std::sin(phi) * r0.residual_slide_east_m + std::cos(phi) * r0.residual_slide_north_m;
  const double scale = std::max(std::hypot(ue, un), 1e-6);
  // the turned body's origin is the box's centre (turned about it): the residual slides compare directly; the yaw
  // is the body frame's turn from its start, the same
  EXPECT_NEAR(r1.residual_slide_east_m, ue, 1e-5 * scale);
  EXPECT_NEAR(r1.residual_slide_north_m, un, 1e-5 * scale);
  EXPECT_NEAR(r1.max_tilt_rad, r0.max_tilt_rad, 1e-6 * r0.max_tilt_rad);
  EXPECT_NEAR(r1.residual_yaw_deg, r0.residual_yaw_deg, 1e-5 * std::max(1.0, std::abs(r0.residual_yaw_deg)));
  EXPECT_EQ(r1.impacts, r0.impacts);
  EXPECT_EQ(r1.overturned, r0.overturned);
  ASSERT_EQ(r1.modes.size(), r0.modes.size());
  for (std::size_t k = 0; k < r0.modes.size(); ++k) {
    EXPECT_EQ(r1.modes[k].mode, r0.modes[k].mode) << k;
    EXPECT_NEAR(r1.modes[k].time_s, r0.modes[k].time_s, 1e-6) << k;
  }
}

// On still ground (after the record) the energy, kinetic relative to the ground + g (z_c - h), never increases:
// Coulomb friction and the impacts dissipate; the history's rows, to the integration's tolerance.
TEST(Rigid3DContact, EnergyNeverIncreasesOnStillGround) {
  const RigidBody3D box = RigidBody3D::box(0.6, 0.4, 0.8);
  const Oblique m = oblique(0.7, 1.8);  // the record stops mid-motion
  Rigid3DOptions o = friction(0.6, 0.55);
  o.record_history = true;
  const Rigid3DResult r = rock3d(m.x, &m.y, nullptr, box, o);
  const auto& h = r.history;
  const double t_end = m.x.end_time_s();
  double last = std::numeric_limits<double>::infinity(), emax = 0.0;
  for (double e : h.energy_j_per_kg) emax = std::max(emax, e);
  int after = 0;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    if (h.time_s[i] < t_end) continue;
    EXPECT_LE(h.energy_j_per_kg[i], last + 1e-8 * emax) << h.time_s[i];
    last = h.energy_j_per_kg[i];
    ++after;
  }
  EXPECT_GE(after, 10);
  EXPECT_GT(r.summary.end_time_s, t_end);
  EXPECT_GT(r.summary.friction_energy_j_per_kg, 0.0);
}

// Free flight: a box rocking under x and y is thrown by a vertical pulse (g + a_z < 0). In flight no torque acts about
// c (the ground's inertial force is uniform, it acts at c): the angular momentum about c (ground frame, R J R^T w) and
// the rotational energy stay constant (Euler's torque-free motion).
TEST(Rigid3DContact, FreeFlightIsTorqueFree) {
  const RigidBody3D box = RigidBody3D::box(0.4, 0.3, 0.8);
  const double dt = 0.002;
  const std::size_t n = 1001;
  std::vector<double> ax(n, 0.0), ay(n, 0.0), az(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    if (t < 0.5) {
      ax[i] = 0.45 * kG * std::sin(2.0 * M_PI * t / 0.5);
      ay[i] = 0.3 * kG * std::sin(2.0 * M_PI * t / 0.5);
    }
    if (t > 0.3 && t < 0.5) az[i] = -1.6 * kG * std::sin(M_PI * (t - 0.3) / 0.2);
  }
  const GroundMotion x = GroundMotion::uniform(ax, dt), y = GroundMotion::uniform(ay, dt), z = GroundMotion::uniform(az, dt);
  Rigid3DOptions o = friction(0.8, 0.7);
  o.record_history = true;
  o.rel_tol = 1e-10;
  const Rigid3DResult r = rock3d(x, &y, &z, box, o);
  ASSERT_GE(r.summary.flights, 1U);
  ASSERT_TRUE(r.summary.flight_time_s.has_value());
  const auto& h = r.history;
  const auto& J = box.inertia_cm_m2;
  int rows = 0;
  std::optional<std::array<double, 3>> L0;
  double E0 = 0.0;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    if (h.mode[i] != Rigid3DMode::flight) {
      if (rows > 0) break;
      continue;
    }
    const Quaternion& q = h.orientation[i];
    const double w = q[0], qx = q[1], qy = q[2], qz = q[3];
    const std::array<std::array<double, 3>, 3> R{{{1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - w * qz), 2 * (qx * qz + w * qy)},
                                                 {2 * (qx * qy + w * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - w * qx)},
                                                 {2 * (qx * qz - w * qy), 2 * (qy * qz + w * qx), 1 - 2 * (qx * qx + qy * qy)}}};
    const auto& om = h.angular_velocity_rad_s[i];
    std::array<double, 3> wb{}, L{};  // w in the body frame, then L = R J w_b
    for (int a = 0; a < 3; ++a) wb[a] = R[0][a] * om[0] + R[1][a] * om[1] + R[2][a] * om[2];
    std::array<double, 3> Jw{};
    for (int a = 0; a < 3; ++a) Jw[a] = J[a][0] * wb[0] + J[a][1] * wb[1] + J[a][2] * wb[2];
    for (int a = 0; a < 3; ++a) L[a] = R[a][0] * Jw[0] + R[a][1] * Jw[1] + R[a][2] * Jw[2];
    const double E = 0.5 * (wb[0] * Jw[0] + wb[1] * Jw[1] + wb[2] * Jw[2]);
    if (!L0) {
      L0 = L;
      E0 = E;
    }
    const double Ln = std::hypot((*L0)[0], (*L0)[1], (*L0)[2]);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(L[a], (*L0)[a], 1e-7 * Ln) << h.time_s[i];
    EXPECT_NEAR(E, E0, 1e-7 * E0) << h.time_s[i];
    ++rows;
  }
  ASSERT_GE(rows, 3);
  ASSERT_GT(E0, 0.0);
}

// Order of convergence: the max tilt and residual slide of the oblique slide-rock against a tight run (1e-12) fall
// with the tolerance (measured: 3.7e-10, 1.2e-11, 1.4e-12 at 1e-6, 1e-8, 1e-10).
TEST(Rigid3DContact, ConvergesWithTheTolerance) {
  const RigidBody3D box = RigidBody3D::box(0.6, 0.4, 0.8);
  const Oblique m = oblique(0.7, 2.0);
  const auto run = [&](double tol) {
    Rigid3DOptions o = friction(0.6, 0.55);
    o.rel_tol = tol;
    const auto s = rock3d(m.x, &m.y, nullptr, box, o).summary;
    return std::array<double, 3>{s.max_tilt_rad, s.residual_slide_east_m, s.residual_slide_north_m};
  };
  const auto ref = run(1e-12);
  const auto err = [&](double tol) {
    const auto u = run(tol);
    return std::abs(u[0] - ref[0]) + std::hypot(u[1] - ref[1], u[2] - ref[2]);
  };
  const double e1 = err(1e-6), e2 = err(1e-8), e3 = err(1e-10);
  ASSERT_GT(e1, 0.0);
  EXPECT_LT(e2, e1 / 10.0);
  EXPECT_LT(e3, e2 / 5.0);
}

// Issue 29: with mu_k = mu_s (mu_k absent) the oblique slide-rock used to end in EventLimitError (stick-slip
// chattering: a slip started along the sticking force's opposite, not along its own acceleration) at mu = 0.6, 0.65,
// 0.7 and 0.75. Each now runs to its end: at rest (within the record or after it) or overturned.
TEST(Rigid3DContact, EqualStaticAndKineticFrictionRunsWithoutChattering) {
  const RigidBody3D box = RigidBody3D::box(0.6, 0.4, 0.8);
  const Oblique m = oblique(0.7, 2.0);
  int slide_rocked = 0;
  for (double mu : {0.55, 0.6, 0.65, 0.7, 0.75, 0.8}) {
    Rigid3DOptions o;
    o.mu_s = mu;  // mu_k absent: mu_s
    Rigid3DResult r;
    ASSERT_NO_THROW(r = rock3d(m.x, &m.y, nullptr, box, o)) << mu;
    const auto& s = r.summary;
    EXPECT_TRUE(s.end_mode == Rigid3DMode::rest || s.end_mode == Rigid3DMode::fallen) << mu;
    EXPECT_GE(s.end_time_s, s.overturned ? 0.0 : m.x.end_time_s() - 1e-12) << mu;
    if (s.slide_rock_duration_s > 0.0) ++slide_rocked;
  }
  EXPECT_GE(slide_rocked, 5);  // the runs do slide-rock (the case that chattered)
}

/// Oblique loads from the tests' own synthetic motions: the turning sine above (two phases), and a two-component
/// pulse train (x and y with different periods).
std::vector<Oblique> oblique_loads() {
  std::vector<Oblique> loads{oblique(0.7, 2.0), oblique(0.55, 3.0, 0.4)};
  const double dt = 0.004;
  const std::size_t n = 376;
  std::vector<double> ax(n), ay(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    ax[i] = 0.6 * kG * std::sin(2.0 * M_PI * t / 0.5) * std::exp(-t);
    ay[i] = 0.5 * kG * std::sin(2.0 * M_PI * t / 0.37 + 0.5) * std::exp(-t);
  }
  loads.push_back({GroundMotion::uniform(ax, dt), GroundMotion::uniform(ay, dt)});
  return loads;
}

// A sweep over mu_s in [0.3, 1.0] with mu_k = mu_s and mu_k = 0.8 mu_s on three oblique loads: every run ends
// without an error (no event or step limit), and on still ground (after the record) the energy never increases
// (Coulomb friction and the impacts dissipate; 1e-8 of the run's largest energy: the integration's tolerance).
TEST(Rigid3DContact, FrictionSweepRunsAndDissipatesOnStillGround) {
  const RigidBody3D box = RigidBody3D::box(0.6, 0.4, 0.8);
  int runs = 0, slide_rocked = 0;
  std::size_t held = 0;
  for (const Oblique& m : oblique_loads()) {
    const double t_end = m.x.end_time_s();
    for (int i = 0; i <= 14; ++i) {
      const double mu = 0.3 + 0.05 * i;
      for (double ratio : {1.0, 0.8}) {
        Rigid3DOptions o = friction(mu, ratio * mu);
        o.record_history = true;
        Rigid3DResult r;
        const int load = runs++ / 30;
        try {
          r = rock3d(m.x, &m.y, nullptr, box, o);
        } catch (const std::exception& e) {
          ADD_FAILURE() << "mu_s " << mu << " mu_k/mu_s " << ratio << " load " << load << ": " << e.what();
          continue;
        }
        if (r.summary.slide_rock_duration_s > 0.0) ++slide_rocked;
        held += r.summary.painleve_events;
        const auto& h = r.history;
        double emax = 0.0;
        for (double e : h.energy_j_per_kg) emax = std::max(emax, e);
        double last = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < h.time_s.size(); ++k) {
          if (h.time_s[k] < t_end) continue;
          EXPECT_LE(h.energy_j_per_kg[k], last + 1e-8 * emax) << mu << " " << ratio << " " << h.time_s[k];
          last = h.energy_j_per_kg[k];
        }
      }
    }
  }
  EXPECT_EQ(runs, 90);
  std::printf("sweep: %d runs, %d slide-rock, %zu held or Painleve events\n", runs, slide_rocked, held);
  EXPECT_GE(slide_rocked, 15) << slide_rocked;  // the sweep exercises slide-rock (measured: 18 of 90 runs)
}

}  // namespace
}  // namespace topple

namespace topple {
namespace {

/// One synthetic component as `topple synth --pga P --freq 3Hz --duration 20s --seed S` makes it.
GroundMotion synth(double pga_g, std::uint64_t seed) {
  SynthesisSpec spec;
  spec.pga_m_s2 = pga_g * kG;
  spec.predominant_frequency_hz = 3.0;
  spec.duration_s = 20.0;
  spec.dt_s = 0.01;
  spec.seed = seed;
  return synthesize(spec);
}

// Issue 29, robustness: runs with friction under two horizontal components and a vertical that used to stop with
// "more than 10000 events in one sample interval" (EventLimitError), each a mechanism of docs/method.md ("Held
// slips"): (a) the reproduction, a 40 x 30 x 80 cm box at bearing 30 with mu 0.45 under seeds 1, 2 (east, north)
// and 3 (vertical) at 0.5 g: a flat slip starting from rest at the stick limit (|v| ~ 1e-11 m/s, DP5 steps of
// 1e-11 s before the flat launch); (b) a 20 x 15 x 60 cm box, seeds 5, 6, 7: flat landings at 1e-15 J/kg under a
// load at the uplift limit (before the rest rule in the flat outcome). Each runs to its end (at rest at the record's
// end, or fallen) with the energy balance's signs: energy lost to impacts >= 0, friction work > 0, all finite.
// (a), which stays up and slips on its flat base (its slide-rock lasts < 0.02 s): friction's work within Coulomb's
// bounds mu_k (g - max |a_v|) path <= W_f <= mu_k (g + max |a_v|) path (W_f = mu_k int N |v| dt, N = g + a_z on the
// flat base), and the residual slide no longer than the path. (b) sits near its overturning limit (373 impacts; a
// record changed by 1e-16 of the other component, as the CLI's projection on east, decides whether it falls): only
// the completion and the signs are asserted there. Measured on the engine before the fix: (b) throws EventLimitError
// at 1.56 s; (a) (here without the CLI's projection, whose 1e-16 changes the path) ends with a residual slide longer
// than its slide path; the CLI's (a) throws at 3.37 s.
TEST(Rigid3DContact, SyntheticThreeComponentRunsWithFrictionRunToTheirEnd) {
  struct Box {
    double w, d, h;
    std::uint64_t seed;
  };
  for (const Box& c : {Box{0.4, 0.3, 0.8, 1}, Box{0.2, 0.15, 0.6, 5}}) {
    const GroundMotion east = synth(0.5, c.seed), north = synth(0.5, c.seed + 1), up = synth(0.5, c.seed + 2);
    const RigidBody3D box = RigidBody3D::box(c.w, c.d, c.h).rotated_about_vertical(M_PI / 3.0);  // bearing 30
    Rigid3DResult r;
    ASSERT_NO_THROW(r = rock3d(east, &north, &up, box, friction(0.45, 0.45))) << c.seed;
    const auto& s = r.summary;
    if (s.overturned) {
      EXPECT_EQ(s.end_mode, Rigid3DMode::fallen) << c.seed;
    } else {
      EXPECT_EQ(s.end_mode, Rigid3DMode::rest) << c.seed;
      EXPECT_NEAR(s.end_time_s, 20.0, 1e-9) << c.seed;
    }
    EXPECT_GT(s.uplifts, 0U) << c.seed;  // it rocks (0.5 g > the uplift threshold min(w, d) / h g)
    EXPECT_GT(s.slip_episodes, 0U) << c.seed;
    for (double v : {s.max_tilt_rad, s.energy_lost_j_per_kg, s.friction_energy_j_per_kg, s.slide_path_length_m,
                     s.residual_slide_east_m, s.residual_slide_north_m}) {
      EXPECT_TRUE(std::isfinite(v)) << c.seed;
    }
    EXPECT_GE(s.energy_lost_j_per_kg, 0.0) << c.seed;
    EXPECT_GT(s.friction_energy_j_per_kg, 0.0) << c.seed;
    if (c.seed != 1) continue;
    EXPECT_FALSE(s.overturned);
    EXPECT_LT(s.slide_rock_duration_s, 0.02);
    double av = 0.0;
    for (double a : up.accel_m_s2()) av = std::max(av, std::abs(a));
    const double path = s.slide_path_length_m;
    EXPECT_GE(s.friction_energy_j_per_kg, 0.45 * (kG - av) * path);
    EXPECT_LE(s.friction_energy_j_per_kg, 0.45 * (kG + av) * path);
    EXPECT_LE(std::hypot(s.residual_slide_east_m, s.residual_slide_north_m), path * (1.0 + 1e-9));
  }
}

// Issue 29, the ground's impenetrability: the lowest base vertex over a run's history (rows at the samples and the
// events) as a fraction of the body's size (the largest distance of c from a base vertex, the engine's size).
double lowest_vertex_over_size(const Rigid3DResult& r, const RigidBody3D& body) {
  double size = 0.0;
  for (const auto& p : body.base_xy_m) {
    size = std::max(size, std::hypot(p[0] - body.centre_of_mass_m[0], p[1] - body.centre_of_mass_m[1],
                                     body.centre_of_mass_m[2]));
  }
  double low = 0.0;
  const auto& h = r.history;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    const auto& q = h.orientation[i];  // (w, x, y, z), body -> ground: the rotation matrix's third row
    const double r20 = 2.0 * (q[1] * q[3] - q[0] * q[2]), r21 = 2.0 * (q[2] * q[3] + q[0] * q[1]);
    for (const auto& p : body.base_xy_m) low = std::min(low, h.position_m[i][2] + r20 * p[0] + r21 * p[1]);
  }
  return low / size;
}

// Issue 29, two defects of the contact engine found by the 540-run sweep of docs/method.md (a `topple synth` family:
// seeds s, s + 1, s + 2 as east, north and vertical, bearing 30):
// (1) a vertex on the ground at a phase's start moving down had no touch-down event (its function started at 0):
//     it went through the ground (0.4 x 0.3 x 0.8, mu 0.45, 0.5 g, seeds 7-9: a base vertex 0.30 m deep, then
//     "fallen" at 3.06 s with 13 impacts; now it stands, max tilt 1.4e-4 rad, 74 impacts);
// (2) a flight entered where g + a_z only touches 0 (the synthetic vertical's -1 g sample: seeds 4-6 with mu 0.2,
//     seeds 9-11 with mu 0.45, at 1.0 g) fell through the ground for the rest of the run (z = -29800 m, end mode
//     flight after the 60 s run-out); now the touch is one flight shorter than a sample, ended by a flat landing.
// Every run ends at rest at the record's end or fallen, and no base vertex is ever below the ground by more than
// 1e-6 of the size (the history's rows here; the engine's invariant, which throws a SolverError otherwise, at every
// step and event).
TEST(Rigid3DContact, NoBaseVertexPassesThroughTheGround) {
  struct Run {
    double w, d, h, mu, pga_g;
    std::uint64_t seed;
  };
  for (const Run& c : {Run{0.4, 0.3, 0.8, 0.45, 0.5, 7}, Run{0.2, 0.15, 0.6, 0.2, 1.0, 4},
                       Run{0.6, 0.5, 0.7, 0.45, 1.0, 9}}) {
    const GroundMotion east = synth(c.pga_g, c.seed), north = synth(c.pga_g, c.seed + 1),
                       up = synth(c.pga_g, c.seed + 2);
    const RigidBody3D box = RigidBody3D::box(c.w, c.d, c.h).rotated_about_vertical(M_PI / 3.0);  // bearing 30
    Rigid3DOptions o = friction(c.mu, c.mu);
    o.record_history = true;
    Rigid3DResult r;
    ASSERT_NO_THROW(r = rock3d(east, &north, &up, box, o)) << c.w << " " << c.seed;
    const auto& s = r.summary;
    EXPECT_GE(lowest_vertex_over_size(r, box), -1e-6) << c.w << " " << c.seed;
    if (s.overturned) {
      EXPECT_EQ(s.end_mode, Rigid3DMode::fallen) << c.w << " " << c.seed;
    } else {
      EXPECT_EQ(s.end_mode, Rigid3DMode::rest) << c.w << " " << c.seed;
      EXPECT_NEAR(s.end_time_s, 20.0, 1e-9) << c.w << " " << c.seed;
    }
    EXPECT_GE(s.energy_lost_j_per_kg, 0.0) << c.w << " " << c.seed;
    if (c.pga_g == 1.0) {
      // (2): g + a_z > 0 but at the one -1 g sample, so no flight can outlast a sample interval (0.01 s)
      EXPECT_LE(s.flights, 1U) << c.w << " " << c.seed;
      EXPECT_LT(s.flight_duration_s, 0.01) << c.w << " " << c.seed;
    }
    for (double e : r.history.energy_j_per_kg) EXPECT_TRUE(std::isfinite(e));
  }
}

// Issue 29, the Zeno limit of pivot swaps along an edge (docs/method.md, "The ground's impenetrability"): a slender
// box (0.2 x 0.15 x 0.6 m, mu 0.45, bearing 30, the synthetic family above) rocking about a base edge pivoted on one
// end, then the other, each landing of the other end a plastic strike that lifts the old pivot, the strike speeds
// falling by ~0.9 a swap and the gaps from 1e-3 s to 1e-6 s; the edge impact with friction needs a pulling impulse at
// the old pivot, so the edge was never reached and the runs stopped with "more than 10000 events in one sample
// interval" (EventLimitError: 0.5 g seed 4 at 3.33 s, 1.0 g seed 5 at 1.24 s). With the accumulation rule (after
// kZenoSwaps swaps with slower strikes, both ends down) they run to their end, no base vertex below the ground,
// no energy created at the impacts.
TEST(Rigid3DContact, PivotSwapsAlongAnEdgeReachTheEdge) {
  struct Run {
    double pga_g;
    std::uint64_t seed;
  };
  for (const Run& c : {Run{0.5, 4}, Run{1.0, 5}}) {
    const GroundMotion east = synth(c.pga_g, c.seed), north = synth(c.pga_g, c.seed + 1),
                       up = synth(c.pga_g, c.seed + 2);
    const RigidBody3D box = RigidBody3D::box(0.2, 0.15, 0.6).rotated_about_vertical(M_PI / 3.0);  // bearing 30
    Rigid3DOptions o = friction(0.45, 0.45);
    o.record_history = true;
    Rigid3DResult r;
    ASSERT_NO_THROW(r = rock3d(east, &north, &up, box, o)) << c.pga_g << " " << c.seed;
    const auto& s = r.summary;
    EXPECT_GE(lowest_vertex_over_size(r, box), -1e-6) << c.pga_g << " " << c.seed;
    EXPECT_GE(s.energy_lost_j_per_kg, 0.0) << c.pga_g << " " << c.seed;
    EXPECT_TRUE(std::isfinite(s.energy_lost_j_per_kg));
    if (s.overturned) {
      EXPECT_EQ(s.end_mode, Rigid3DMode::fallen) << c.pga_g << " " << c.seed;
      EXPECT_GT(s.end_time_s, 3.33) << c.pga_g << " " << c.seed;  // past where it used to stop
    } else {
      EXPECT_EQ(s.end_mode, Rigid3DMode::rest) << c.pga_g << " " << c.seed;
      EXPECT_NEAR(s.end_time_s, 20.0, 1e-9) << c.pga_g << " " << c.seed;
    }
    for (double e : r.history.energy_j_per_kg) EXPECT_TRUE(std::isfinite(e));
  }
}

}  // namespace
}  // namespace topple
