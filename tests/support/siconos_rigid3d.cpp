// The Siconos reference simulator of siconos_rigid3d.hpp (test code only).
#include "support/siconos_rigid3d.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include <SiconosKernel.hpp>
#include <SolverOptions.h>

namespace topple::test {
namespace {

using Vec3 = std::array<double, 3>;

/// Rotates v (body frame) by the unit quaternion (w, x, y, z): v' = q v q*.
Vec3 rotate(const std::array<double, 4>& q, const Vec3& v) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  // t = 2 (q_vec x v); v' = v + w t + q_vec x t (the usual expansion of q v q*).
  const Vec3 t{2.0 * (y * v[2] - z * v[1]), 2.0 * (z * v[0] - x * v[2]), 2.0 * (x * v[1] - y * v[0])};
  return {v[0] + w * t[0] + (y * t[2] - z * t[1]), v[1] + w * t[1] + (z * t[0] - x * t[2]),
          v[2] + w * t[2] + (x * t[1] - y * t[0])};
}

std::array<double, 4> quaternion_of(const SiconosVector& q) { return {q(3), q(4), q(5), q(6)}; }

/// Unilateral contact of one body-fixed point (the corner, body frame) with the plane z = 0. The gap is the corner's
/// height; the contact point on the body is the corner, its partner on the plane the corner's vertical projection,
/// the normal +z (from the plane toward the body, as Siconos' SphereNEDSPlanR sets it). NewtonEuler3DR builds the
/// Jacobians (normal and two tangential rows) from those three vectors.
class CornerPlaneR : public NewtonEuler3DR {
 public:
  explicit CornerPlaneR(const Vec3& corner_body) : corner_(corner_body) {}

  void computeh(double /*time*/, const BlockVector& q0, SiconosVector& y) override {
    const SiconosVector& q = *q0.getAllVect()[0];
    const Vec3 r = rotate(quaternion_of(q), corner_);
    const Vec3 p{q(0) + r[0], q(1) + r[1], q(2) + r[2]};
    y.setValue(0, p[2]);
    _Pc1->setValue(0, p[0]);
    _Pc1->setValue(1, p[1]);
    _Pc1->setValue(2, p[2]);
    _Pc2->setValue(0, p[0]);
    _Pc2->setValue(1, p[1]);
    _Pc2->setValue(2, 0.0);
    _Nc->setValue(0, 0.0);
    _Nc->setValue(1, 0.0);
    _Nc->setValue(2, 1.0);
  }

 private:
  Vec3 corner_;
};

/// Mean of the piecewise-linear component over [t0, t1] (zero before 0 and after the last sample), integrated exactly:
/// the interval is cut at the sample instants and each piece, linear, is integrated by the trapezoid rule.
double mean_over(const std::vector<double>& a, double dt, double t0, double t1) {
  if (a.size() < 2 || t1 <= t0) return 0.0;
  const double t_end = dt * static_cast<double>(a.size() - 1);
  double integral = 0.0;
  for (double ta = std::max(t0, 0.0); ta < std::min(t1, t_end);) {
    auto i = std::min(static_cast<std::size_t>(std::floor(ta / dt)), a.size() - 2);
    if (dt * static_cast<double>(i + 1) <= ta && i + 2 < a.size()) ++i;  // ta on a sample, floor rounded down
    const double tb = std::min({t1, t_end, dt * static_cast<double>(i + 1)});
    if (tb <= ta) break;
    auto on_piece = [&](double t) { return a[i] + (t / dt - static_cast<double>(i)) * (a[i + 1] - a[i]); };
    integral += 0.5 * (on_piece(ta) + on_piece(tb)) * (tb - ta);
    ta = tb;
  }
  return integral / (t1 - t0);
}

// Steps whose contact problem the solver left unconverged (its info != 0), counted instead of Siconos' default
// message on stderr. A plain function pointer is all TimeStepping takes, hence the thread-local counter.
thread_local std::vector<double>* unconverged_times = nullptr;
void count_unconverged(int info, Simulation* simulation) {
  if (info != 0 && unconverged_times != nullptr) unconverged_times->push_back(simulation->nextTime());
}

bool inside_footprint(const std::array<Vec3, 4>& c, double x, double y) {
  // Convex quadrilateral in order: the point is inside when all cross products have one sign.
  int sign = 0;
  for (int i = 0; i < 4; ++i) {
    const Vec3& p = c[static_cast<std::size_t>(i)];
    const Vec3& n = c[static_cast<std::size_t>((i + 1) % 4)];
    const double cross = (n[0] - p[0]) * (y - p[1]) - (n[1] - p[1]) * (x - p[0]);
    const int s = cross > 0.0 ? 1 : (cross < 0.0 ? -1 : 0);
    if (s == 0) continue;
    if (sign == 0) sign = s;
    else if (s != sign) return false;
  }
  return true;
}

}  // namespace

SiconosResult simulate_siconos_box(const SiconosBox& box, const SiconosGroundMotion& ground,
                                   const SiconosOptions& options) {
  const double a = box.half_x_m, b = box.half_y_m, c = box.half_z_m, m = box.mass_kg;
  if (!(a > 0 && b > 0 && c > 0 && m > 0 && options.step_s > 0 && ground.dt_s > 0))
    throw std::runtime_error("simulate_siconos_box: non-positive dimension, mass or step");

  auto q0 = std::make_shared<SiconosVector>(7);
  q0->zero();
  (*q0)(0) = options.initial_position_m[0];
  (*q0)(1) = options.initial_position_m[1];
  (*q0)(2) = c + options.initial_position_m[2];
  (*q0)(3) = 1.0;
  auto v0 = std::make_shared<SiconosVector>(6);
  v0->zero();
  auto inertia = std::make_shared<SimpleMatrix>(3, 3);
  inertia->zero();
  (*inertia)(0, 0) = m * (b * b + c * c) / 3.0;
  (*inertia)(1, 1) = m * (a * a + c * c) / 3.0;
  (*inertia)(2, 2) = m * (a * a + b * b) / 3.0;
  auto body = std::make_shared<NewtonEulerDS>(q0, v0, m, inertia);
  // The force vector is owned here and rewritten before each step (a constant vector to Siconos within the step).
  auto force = std::make_shared<SiconosVector>(3);
  force->zero();
  (*force)(2) = -m * options.g_m_s2;
  body->setFExtPtr(force);

  const double duration = options.duration_s;
  auto nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, duration);
  nsds->insertDynamicalSystem(body);

  const std::array<Vec3, 4> corners_body{Vec3{a, b, -c}, Vec3{-a, b, -c}, Vec3{-a, -b, -c}, Vec3{a, -b, -c}};
  auto law = std::make_shared<NewtonImpactFrictionNSL>(box.restitution, 0.0, box.mu, 3);
  for (const Vec3& corner : corners_body) {
    auto relation = std::make_shared<CornerPlaneR>(corner);
    auto interaction = std::make_shared<Interaction>(law, relation);
    nsds->link(interaction, body);
  }

  auto td = std::make_shared<TimeDiscretisation>(0.0, options.step_s);
  auto osi = std::make_shared<MoreauJeanOSI>(0.5);
  auto osnspb = std::make_shared<FrictionContact>(3);
  osnspb->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = options.solver_tolerance;
  osnspb->numericsSolverOptions()->iparam[SICONOS_IPARAM_MAX_ITER] = options.solver_max_iterations;
  auto simulation = std::make_shared<TimeStepping>(nsds, td, osi, osnspb);
  simulation->setNewtonTolerance(1e-10);
  simulation->setNewtonMaxIteration(20);
  simulation->setCheckSolverFunction(&count_unconverged);

  SiconosResult result;
  unconverged_times = &result.unconverged_step_times_s;
  SiconosHistory& h = result.history;
  auto record = [&](double t) {
    const SiconosVector& q = *body->q();
    const auto quat = quaternion_of(q);
    // Body z axis in the ground frame: its z component is cos(tilt) = 1 - 2 (x^2 + y^2).
    const Vec3 ez = rotate(quat, Vec3{0.0, 0.0, 1.0});
    const double tilt = std::acos(std::clamp(ez[2], -1.0, 1.0));
    std::array<Vec3, 4> world{};
    std::array<double, 4> cz{};
    for (std::size_t i = 0; i < 4; ++i) {
      const Vec3 r = rotate(quat, corners_body[i]);
      world[i] = Vec3{q(0) + r[0], q(1) + r[1], q(2) + r[2]};
      cz[i] = world[i][2];
      result.max_corner_z_m[i] = std::max(result.max_corner_z_m[i], cz[i]);
    }
    h.time_s.push_back(t);
    h.position_m.push_back({q(0), q(1), q(2)});
    h.quaternion.push_back(quat);
    h.tilt_rad.push_back(tilt);
    h.corner_z_m.push_back(cz);
    if (tilt > result.max_tilt_rad) {
      result.max_tilt_rad = tilt;
      result.max_tilt_time_s = t;
      const double n = std::hypot(ez[0], ez[1]);
      if (n > 0) result.max_tilt_axis = {ez[0] / n, ez[1] / n};
    }
    if (!result.cm_past_base_time_s && !inside_footprint(world, q(0), q(1))) result.cm_past_base_time_s = t;
    if (!result.overturned && tilt >= options.overturn_tilt_rad) {
      result.overturned = true;
      result.overturn_time_s = t;
    }
  };
  record(0.0);

  while (simulation->hasNextEvent() && !result.overturned) {
    const double t0 = simulation->startingTime();
    const double t1 = simulation->nextTime();
    (*force)(0) = -m * mean_over(ground.ax_m_s2, ground.dt_s, t0, t1);
    (*force)(1) = -m * mean_over(ground.ay_m_s2, ground.dt_s, t0, t1);
    (*force)(2) = -m * (options.g_m_s2 + mean_over(ground.az_m_s2, ground.dt_s, t0, t1));
    simulation->computeOneStep();
    simulation->nextStep();
    record(t1);
  }

  unconverged_times = nullptr;
  const auto& last = h.position_m.back();
  result.final_displacement_m = {last[0], last[1]};
  const auto& ql = h.quaternion.back();
  // Yaw: heading of the body x axis projected on the ground.
  const Vec3 ex = rotate(ql, Vec3{1.0, 0.0, 0.0});
  result.final_yaw_rad = std::atan2(ex[1], ex[0]);
  return result;
}

}  // namespace topple::test
