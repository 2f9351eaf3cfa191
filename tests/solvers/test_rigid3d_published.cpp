// A cylinder in three dimensions against a published result (rigid3d_disc.hpp; docs/verification.md, "3-D rocking
// against published results"; issue 29: "a cylinder: rocking and wobbling against a published numerical or
// closed-form result").
//
// Srinivasan M. & Ruina A. (2008), "Rocking and rolling: a can that appears to rock might actually roll", Physical
// Review E 78, 066609 (arXiv:physics/0702028). A can tipped and released with a little sideways motion falls back
// toward the upright, does not slap flat, and rolls on its rim: the contact point runs quickly round the rim, and the
// can rises again leaning toward a direction turned by an "angle of turn". Their abstract states: (i) the angle is
// nearly independent of the initial conditions, (ii) it depends on the geometry and mass distribution but not on the
// moment of inertia about the symmetry axis, (iii) for tall containers it is just over pi. Their asymptotic formula
// (rolling, no slip, the tilt's minimum small against its maximum) is, with R the base radius, h the centre of mass
// above the base's centre and J_t the transverse inertia per unit mass about the centre of mass:
//
//   dpsi_inf = pi sqrt(1 + R^2 / (h^2 + J_t))                                                           (SR)
//
// Derivation (so that the test does not rest on a formula it cannot show; the stored copies of the paper this work
// could reach hold its abstract only): near the upright, with tilt theta, lean azimuth psi and no spin about the axis,
// the centre of mass moves as h times the axis' tilt vector horizontally and R theta vertically, so the kinetic energy
// per unit mass is  1/2 [(A + R^2) theta'^2 + A theta^2 psi'^2],  A = h^2 + J_t (the transverse inertia about the base's
// centre). This is the metric of a cone (rho = sqrt(A + R^2) theta, phi = k psi, k = sqrt(A / (A + R^2))); where the
// tilt is small the potential g (h cos theta + R sin theta) changes by O(g R theta) only, the motion is free, a straight
// line on the unrolled cone: phi turns by pi, psi by pi / k, (SR). It holds (i)-(iii) above.
//
// Finite tilt minimum: with the cone's potential g R theta (linear in rho) kept, the orbit's turn between two tilt
// maxima is a function of x = theta_min / theta_max only, Phi(x) / k with Phi(0) = pi (the apsidal angle of a central
// force of constant magnitude; quadrature below). The engine's turn must approach (SR) from above as x -> 0 and its
// excess must be Phi(x)/pi - 1 up to the terms this small-tilt model leaves out (the inverted pendulum's -g h theta^2/2
// against g R theta: h theta_max / (2 R) = 0.24-0.29 here).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "topple/solvers/rigid3d_disc.hpp"

namespace topple {
namespace {

constexpr double kG = 9.80665;

GroundMotion still(double duration_s, double dt) {
  return GroundMotion::uniform(std::vector<double>(static_cast<std::size_t>(std::llround(duration_s / dt)) + 1, 0.0),
                               dt);
}

Vec3 axis_of(const Quaternion& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y)};
}

/// (SR): the angle of turn in the limit theta_min / theta_max -> 0.
double turn_limit(const CylinderBody3D& b) {
  const double A = b.centre_height_m * b.centre_height_m + b.inertia_transverse_m2;
  return M_PI * std::sqrt(1.0 + b.radius_m * b.radius_m / A);
}

/// Phi(x): the angle swept between two apocentres of a planar orbit under a central force of constant magnitude
/// (potential c rho), with pericentre / apocentre = x. Units: rho_max = 1, c = 1; the turning points give
/// L^2 = 2 (E - 1) = 2 (E - x) x^2, so E = (1 - x^3) / (1 - x^2). Phi = 2 int_x^1 L / rho^2 / sqrt(2 (E - rho) -
/// L^2 / rho^2) drho, with rho = x + (1 - x) sin^2 u (the square-root ends become smooth); midpoint rule, 20,000 points
/// (converged to 1e-7 at the x used here).
double apsidal_turn(double x) {
  const double E = (1.0 - x * x * x) / (1.0 - x * x);
  const double L2 = 2.0 * (E - 1.0), L = std::sqrt(L2);
  constexpr int n = 20000;
  const double du = 0.5 * M_PI / n;
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) * du;
    const double r = x + (1.0 - x) * std::sin(u) * std::sin(u);
    const double d = 2.0 * (E - r) - L2 / (r * r);
    if (d > 0.0) s += L / (r * r) / std::sqrt(d) * 2.0 * (1.0 - x) * std::sin(u) * std::cos(u);
  }
  return 2.0 * s * du;
}

struct Turn {
  double angle_rad = 0.0;      ///< the lean's (the contact's) azimuth turned from the start to the next tilt maximum
  double theta_min_rad = 0.0;  ///< the least tilt on the way
  double theta_next_rad = 0.0; ///< the next tilt maximum
  std::size_t impacts = 0;
  bool found = false;
};

/// Released at rest in tilt at theta0 (leaning toward +x) with the axis' tip moving sideways (+y) at nu rad/s and no
/// spin about the axis (w = nu (a x e_y): w . a = 0, a' = nu e_y), on still ground; free rolling on the rim.
Turn angle_of_turn(const CylinderBody3D& cyl, double theta0, double nu) {
  Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.rel_tol = 1e-11;
  o.abs_tol = 1e-14;
  o.max_run_out_s = 0.0;
  o.record_history = true;
  const CylinderInitialState init{{std::cos(0.5 * theta0), 0.0, std::sin(0.5 * theta0), 0.0},
                                  {-nu * std::cos(theta0), 0.0, nu * std::sin(theta0)}};
  // rows every 0.1 ms: at the tilt's minimum theta' = 0, so a row misses it by theta'' dt^2 / 8 < 1e-3 of it here
  const Rigid3DResult r = rock3d_cylinder(still(1.2, 1e-4), nullptr, nullptr, cyl, o, init);
  Turn t;
  t.impacts = r.summary.impacts;
  t.theta_min_rad = theta0;
  double psi = 0.0, previous_psi = 0.0, previous_azimuth = 0.0, previous_tilt = theta0;
  bool near_upright = false;
  for (std::size_t i = 0; i < r.history.time_s.size(); ++i) {
    const Vec3 a = axis_of(r.history.orientation[i]);
    const double azimuth = std::atan2(a[1], a[0]);
    previous_psi = psi;
    if (i > 0) psi += std::remainder(azimuth - previous_azimuth, 2.0 * M_PI);
    previous_azimuth = azimuth;
    const double tilt = std::acos(std::min(1.0, a[2]));
    t.theta_min_rad = std::min(t.theta_min_rad, tilt);
    near_upright = near_upright || tilt < 0.5 * theta0;
    if (near_upright && tilt > 0.5 * theta0 && tilt < previous_tilt) {  // the previous row is the next maximum's
      // the true maximum is within a row (0.1 ms) of it, where the azimuth moves at nu / sin(theta0) <= 0.34 rad/s
      // here: < 3.4e-5 rad, 1e-5 of the angle
      t.angle_rad = previous_psi;
      t.theta_next_rad = previous_tilt;
      t.found = true;
      break;
    }
    previous_tilt = tilt;
  }
  return t;
}

/// A thin-walled closed can of uniform sheet, diameter 66 mm, height 122 mm (a 330 ml drinks can's size; the real can's
/// recessed base rolls on a smaller ring, not modelled): side 2 pi R H, two ends pi R^2 each; per unit mass about the
/// centre, side: J_a = R^2, J_t = R^2/2 + H^2/12; ends (each at H/2): J_a = R^2/2, J_t = R^2/4 + H^2/4.
CylinderBody3D closed_can() {
  const double R = 0.033, H = 0.122;
  const double ws = H / (H + R), we = R / (H + R);  // the side's and the two ends' shares of the mass
  return CylinderBody3D::general(R, 0.5 * H, ws * R * R + we * 0.5 * R * R,
                                 ws * (0.5 * R * R + H * H / 12.0) + we * 0.25 * (R * R + H * H));
}

// The angle of turn approaches (SR) as the sideways rate (and with it x = theta_min / theta0) falls, for a slender
// solid cylinder (tall: "just over pi"), a squat one and a thin-walled can; the excess is the finite-x correction of the
// small-tilt model, Phi(x)/pi - 1.
TEST(Rigid3DPublished, AngleOfTurnOfARockingCanSrinivasanRuina2008) {
  struct Case {
    const char* name;
    CylinderBody3D body;
    std::vector<double> rates;  // nu, chosen for x ~ 0.04, 0.012, 0.004
  };
  const std::vector<Case> cases{{"solid d 0.3 m, H 1.0 m", CylinderBody3D::solid(0.3, 1.0), {0.04, 0.012, 0.004}},
                                {"solid d 1.0 m, H 1.0 m", CylinderBody3D::solid(1.0, 1.0), {0.1, 0.03, 0.01}},
                                {"can d 66 mm, H 122 mm", closed_can(), {0.1, 0.03, 0.01}}};
  for (const Case& c : cases) {
    const double limit = turn_limit(c.body);
    const double theta0 = 0.6 * c.body.static_tilt_limit_rad();
    double previous_excess = 1.0;
    for (const double nu : c.rates) {
      const Turn t = angle_of_turn(c.body, theta0, nu);
      SCOPED_TRACE(testing::Message() << c.name << " nu " << nu);
      ASSERT_TRUE(t.found);
      EXPECT_EQ(t.impacts, 0U);  // it rolls round the rim: no slap
      EXPECT_NEAR(t.theta_next_rad, theta0, 1e-6 * theta0);  // free rolling conserves energy: back to the same tilt
      const double x = t.theta_min_rad / theta0;
      const double excess = t.angle_rad / limit - 1.0;
      const double model_excess = apsidal_turn(x) / M_PI - 1.0;
      std::printf("%s: nu %.3f rad/s, theta_min/theta0 %.4f: turn %.5f rad (SR limit %.5f, +%.2f %%; small-tilt model "
                  "+%.2f %%)\n",
                  c.name, nu, x, t.angle_rad, limit, 100.0 * excess, 100.0 * model_excess);
      EXPECT_GT(excess, 0.0);                // from above, as Phi(x) > pi
      EXPECT_LT(excess, previous_excess);    // closer as x falls
      // the excess falls with x as the small-tilt model's does, times a factor that depends on theta0 and the body
      // (measured 1.47-1.56 slender, 0.85-0.89 squat, 1.28-1.37 can: the model leaves out the inverted pendulum's
      // -g h theta^2 / 2, h theta0 / (2 R) = 0.29, 0.24, 0.28 here, and the spin the rolling constraint couples in)
      EXPECT_GT(excess / model_excess, 0.75);
      EXPECT_LT(excess / model_excess, 1.75);
      previous_excess = excess;
    }
    // x ~ 0.004 (0.0023 for the can): within 1.2 % of the limit (measured 1.04, 0.60, 0.57 %; the small-tilt model's
    // own excess there is 0.71, 0.71, 0.44 %)
    EXPECT_LT(previous_excess, 0.012);
  }
}

// (ii) not on the moment of inertia about the symmetry axis: J_a from 0.1 J_t to 2 J_t (the solid cylinder's is
// 0.126 J_t) with R, h, J_t fixed turns the lean by the same angle to 1e-3 (measured 8e-5: with no spin at the start
// the spin stays of the order of theta, and J_a enters through it only); (i) nearly independent of the initial
// conditions: released from 0.3 alpha instead of 0.6 alpha at the same x ~ 0.004, the same to 0.3 % (measured 0.20 %,
// a fifth of either's excess over the limit (SR), 1.04 and 0.84 %: the finite-tilt part of the correction).
TEST(Rigid3DPublished, AngleOfTurnIndependentOfAxialInertiaAndStart) {
  const double R = 0.15, h = 0.5, Jt = (3.0 * R * R + 1.0) / 12.0;
  const double alpha = std::atan2(R, h);
  std::vector<double> turns;
  for (const double ja : {0.1 * Jt, 0.5 * R * R, Jt, 2.0 * Jt}) {
    const Turn t = angle_of_turn(CylinderBody3D::general(R, h, ja, Jt), 0.6 * alpha, 0.012);
    ASSERT_TRUE(t.found);
    EXPECT_EQ(t.impacts, 0U);
    turns.push_back(t.angle_rad);
  }
  const auto [lo, hi] = std::minmax_element(turns.begin(), turns.end());
  EXPECT_LT((*hi - *lo) / *lo, 1e-3);
  const CylinderBody3D solid = CylinderBody3D::solid(0.3, 1.0);
  const Turn a = angle_of_turn(solid, 0.6 * alpha, 0.004);
  const Turn b = angle_of_turn(solid, 0.3 * alpha, 0.0032);  // the same x ~ 0.004 from half the tilt
  ASSERT_TRUE(a.found && b.found);
  EXPECT_NEAR(a.theta_min_rad / (0.6 * alpha), b.theta_min_rad / (0.3 * alpha), 0.002);
  EXPECT_LT(std::abs(a.angle_rad - b.angle_rad) / a.angle_rad, 3e-3);
  EXPECT_LT(b.angle_rad / turn_limit(solid) - 1.0, 0.012);
  std::printf("angle of turn over J_a in [0.1, 2] J_t: %.6f to %.6f rad; from 0.6 / 0.3 alpha: %.6f / %.6f rad\n", *lo,
              *hi, a.angle_rad, b.angle_rad);
}

}  // namespace
}  // namespace topple
