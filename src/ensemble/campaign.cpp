// Shake-table campaigns: the models run on each test and the scores (campaign.hpp, docs/campaign.md).
#include "topple/ensemble/campaign.hpp"

#include <time.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <numbers>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/slide_rock.hpp"

namespace topple::ensemble {
namespace {

/// CPU time of the calling thread, s (a test runs on one thread from start to end).
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// An angle in [0, 360).
double wrap_deg(double a) {
  double w = std::fmod(a, 360.0);
  if (w < 0.0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;
}

/// One vertical plane of a planar model: its direction (counter-clockwise from the table's x axis) and the planar
/// body whose +x points that way.
struct Plane {
  double direction_deg = 0.0;
  RockingBody body;
};

/// The planes of the planar models (campaign.hpp, "Models"). `two`: the table moved along both horizontal axes.
std::vector<Plane> planes_of(const CampaignTest& test, const CampaignInput& input, bool two, double g) {
  std::vector<Plane> planes;
  const auto grid = [&](const std::function<RockingBody(double)>& body_at) {
    if (!two) {
      planes.push_back({0.0, body_at(0.0)});
      return;
    }
    // Directions theta and theta + 180 give the mirror image of one response (oriented.hpp, "Cylinder"): half a
    // turn covers the circle.
    for (int k = 0; k < 12; ++k) planes.push_back({15.0 * k, body_at(15.0 * k)});
  };
  if (const auto* b = std::get_if<CampaignBlock>(&test.body)) {
    planes.push_back({wrap_deg(test.bearing_deg), RockingBody::block(b->width_m, b->height_m)});
    planes.push_back({wrap_deg(test.bearing_deg + 90.0), RockingBody::block(b->depth_m, b->height_m)});
  } else if (const auto* c = std::get_if<CampaignCylinder>(&test.body)) {
    const RockingBody body = RockingBody::cylinder(c->diameter_m, c->height_m);
    grid([&](double) { return body; });
  } else {
    if (!input.mesh) throw parameter_error("mesh", "the test's mesh body was not loaded");
    const MeshBody& mesh = *input.mesh;
    const std::string& file = std::get<CampaignMesh>(test.body).path;
    grid([&](double theta) {
      // The table's direction theta is theta - bearing from the body's x axis; in the mesh's frame (x east, y north)
      // that is the azimuth 90 - (theta - bearing) clockwise from north, whose +e the planar body's +x (b2) faces.
      const PlanarBody p = planar_body(mesh.mass, mesh.support, wrap_deg(90.0 - (theta - test.bearing_deg)), g, file);
      return RockingBody::general_asymmetric(p.b1_m, p.b2_m, p.h_m, p.inertia_cm_kg_m2 / mesh.mass.mass_kg);
    });
  }
  return planes;
}

/// The table's horizontal acceleration along `direction_deg` (counter-clockwise from x): eq. M1 with the table's x
/// as east (azimuth 90) and y as north (0); with one component, x cos(direction). None: no motion in that plane.
std::optional<GroundMotion> along(const CampaignInput& input, const std::optional<MotionSet>& set,
                                  double direction_deg) {
  if (set) return set->projected(wrap_deg(90.0 - direction_deg));
  const double c = std::cos(deg_to_rad(direction_deg));
  if (std::abs(c) < 1e-12) return std::nullopt;  // perpendicular to the only component: the plane does not move
  if (c == 1.0) return input.x;
  return input.x.scaled(c);
}

RockingOptions rocking_options(const CampaignSettings& s) {
  RockingOptions r;
  r.g_m_s2 = s.g_m_s2;
  r.restitution = s.restitution;
  r.e = s.e;
  return r;
}

/// The common part of a planar summary (rocking or coupled) that decides severity and the row.
struct PlaneOutcome {
  bool overturned = false;
  int side = 0;
  std::optional<double> overturn_time_s;
  double ratio = 0.0;
  std::vector<std::string> warnings;
};

/// oriented.hpp's "Severity": a fall beats none, an earlier fall a later one, else the larger max |theta| / alpha.
bool more_severe(const PlaneOutcome& x, const PlaneOutcome& y) {
  if (x.overturned != y.overturned) return x.overturned;
  if (x.overturned) return x.overturn_time_s.value_or(0.0) < y.overturn_time_s.value_or(0.0);
  return x.ratio > y.ratio;
}

void run_planar(const CampaignTest& test, const CampaignInput& input, bool coupled, const CampaignSettings& s,
                CampaignRow& row) {
  const bool two = input.y.has_value();
  std::optional<MotionSet> set;
  if (two) set = MotionSet::make(input.x, &*input.y, ComponentAzimuths{90.0, 0.0, 0.0});
  const GroundMotion* vertical = input.z ? &*input.z : nullptr;
  const RockingOptions options = rocking_options(s);
  std::optional<PlaneOutcome> best;
  double best_direction = 0.0;
  for (const Plane& plane : planes_of(test, input, two, s.g_m_s2)) {
    const std::optional<GroundMotion> h = along(input, set, plane.direction_deg);
    PlaneOutcome o;
    if (h) {
      if (coupled) {
        if (!s.mu) throw parameter_error("mu", "the coupled model needs the friction coefficient mu");
        const SlideRockBody body = SlideRockBody::from_rocking(plane.body, *s.mu, s.mu_k);
        SlideRockSummary r = slide_rock(*h, body, slide_rock_options(options), vertical).summary;
        o = {r.overturned, r.overturned_side, r.overturn_time_s, r.max_rotation_over_alpha, std::move(r.warnings)};
      } else {
        RockingSummary r = rock_summary(*h, plane.body, options, vertical);
        o = {r.overturned, r.overturned_side, r.overturn_time_s, r.max_rotation_over_alpha, std::move(r.warnings)};
      }
    }
    if (!best || more_severe(o, *best)) {
      best = std::move(o);
      best_direction = plane.direction_deg;
    }
  }
  row.predicted_overturned = best->overturned;
  row.max_tilt_over_limit = best->ratio;
  row.overturn_time_s = best->overturn_time_s;
  if (best->overturned) row.overturn_azimuth_deg = wrap_deg(best_direction + (best->side < 0 ? 180.0 : 0.0));
  row.warnings = std::move(best->warnings);
}

void run_3d(const CampaignTest& test, const CampaignInput& input, const CampaignSettings& s, CampaignRow& row) {
  Rigid3DOptions options = rigid3d_options(rocking_options(s));
  const GroundMotion* y = input.y ? &*input.y : nullptr;
  const GroundMotion* z = input.z ? &*input.z : nullptr;
  Rigid3DResult r;
  if (const auto* c = std::get_if<CampaignCylinder>(&test.body)) {
    // The rim engine rolls without slip (rigid3d_disc.hpp): mu is not used, and the bearing of an axisymmetric
    // body does not matter.
    r = rock3d_cylinder(input.x, y, z, CylinderBody3D::solid(c->diameter_m, c->height_m), options);
  } else {
    options.mu_s = s.mu;
    options.mu_k = s.mu ? s.mu_k : std::nullopt;
    RigidBody3D body;
    if (const auto* b = std::get_if<CampaignBlock>(&test.body)) {
      body = RigidBody3D::box(b->width_m, b->depth_m, b->height_m);
    } else {
      if (!input.mesh) throw parameter_error("mesh", "the test's mesh body was not loaded");
      body = RigidBody3D::from_mesh(*input.mesh);
    }
    // The engines' x is the table's x: the body turned counter-clockwise by its bearing (rotated_about_vertical).
    if (test.bearing_deg != 0.0) body = body.rotated_about_vertical(deg_to_rad(test.bearing_deg));
    r = rock3d(input.x, y, z, body, options);
  }
  const Rigid3DSummary& m = r.summary;
  row.predicted_overturned = m.overturned;
  row.max_tilt_over_limit = m.max_tilt_over_limit;
  row.overturn_time_s = m.overturn_time_s;
  // rigid3d's azimuths are clockwise from north with x east: counter-clockwise from x is 90 - azimuth.
  if (m.overturned) row.overturn_azimuth_deg = wrap_deg(90.0 - m.overturn_azimuth_deg);
  row.warnings = m.warnings;
}

}  // namespace

std::string_view campaign_model_name(CampaignModel model) {
  switch (model) {
    case CampaignModel::planar: return "planar";
    case CampaignModel::coupled: return "coupled";
    case CampaignModel::three_d: return "3d";
  }
  return "unknown";
}

CampaignModel parse_campaign_model(std::string_view name, const std::string& field) {
  for (const CampaignModel m : {CampaignModel::planar, CampaignModel::coupled, CampaignModel::three_d}) {
    if (name == campaign_model_name(m)) return m;
  }
  throw parameter_error(field, fmt::format("unknown model '{}' (known: planar, coupled, 3d)", name));
}

CampaignRow run_campaign_test(const CampaignTest& test, const CampaignInput& input, CampaignModel model,
                              const CampaignSettings& settings) {
  CampaignRow row;
  row.id = test.id;
  row.model = model;
  row.observed_overturned = test.observed_overturned;
  row.observed_azimuth_deg = test.observed_azimuth_deg;
  row.duration_s = input.x.duration_s();
  if (input.y) row.duration_s = std::max(row.duration_s, input.y->duration_s());
  if (input.z) row.duration_s = std::max(row.duration_s, input.z->duration_s());
  const double start = thread_cpu_s();
  switch (model) {
    case CampaignModel::planar: run_planar(test, input, false, settings, row); break;
    case CampaignModel::coupled: run_planar(test, input, true, settings, row); break;
    case CampaignModel::three_d: run_3d(test, input, settings, row); break;
  }
  row.cpu_s = thread_cpu_s() - start;
  return row;
}

std::vector<CampaignRow> run_campaign(const std::vector<CampaignTest>& tests, const CampaignSettings& settings,
                                      const std::function<CampaignInput(std::size_t)>& load, std::size_t threads,
                                      const ProgressCallback& progress) {
  const std::size_t n_models = settings.models.size();
  std::vector<CampaignRow> rows(tests.size() * n_models);
  std::vector<std::exception_ptr> errors(tests.size());
  std::atomic<std::size_t> done{0};
  const auto body = [&](std::size_t i) {
    try {
      const CampaignInput input = load(i);  // its errors name the test already (the loader's)
      for (std::size_t k = 0; k < n_models; ++k) {
        // A model's refusal or limit names the test and the model, so that one test among hundreds is found.
        const std::string who =
            fmt::format("test '{}', model '{}': ", tests[i].id, campaign_model_name(settings.models[k]));
        try {
          rows[i * n_models + k] = run_campaign_test(tests[i], input, settings.models[k], settings);
        } catch (const InputError& e) {
          throw InputError(e.where(), who + e.problem());
        } catch (const StepLimitError& e) {
          throw StepLimitError(who + e.what());
        } catch (const EventLimitError& e) {
          throw EventLimitError(who + e.what());
        } catch (const RootFindingError& e) {
          throw RootFindingError(who + e.what());
        } catch (const SolverError& e) {
          throw SolverError(who + e.what());
        }
      }
    } catch (...) {
      errors[i] = std::current_exception();
    }
    const std::size_t n = done.fetch_add(1) + 1;
    if (progress) progress(n, tests.size());
  };
  std::optional<tbb::global_control> limit;
  std::optional<tbb::task_arena> arena;
  if (threads > 0) {
    limit.emplace(tbb::global_control::max_allowed_parallelism, threads);
    arena.emplace(static_cast<int>(threads));
  } else {
    arena.emplace();
  }
  // One test per task (grain 1): tests differ in cost by orders of magnitude (a block at rest against a rock that
  // rocks for a minute).
  arena->execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tests.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
    });
  });
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  return rows;
}

ClassificationMetrics classification_metrics(const Confusion& c) noexcept {
  const auto ratio = [](std::size_t num, std::size_t den) -> std::optional<double> {
    if (den == 0) return std::nullopt;
    return static_cast<double>(num) / static_cast<double>(den);
  };
  ClassificationMetrics m;
  m.accuracy = ratio(c.tp + c.tn, c.total());
  m.recall = ratio(c.tp, c.tp + c.fn);
  m.precision = ratio(c.tp, c.tp + c.fp);
  m.f1 = ratio(2 * c.tp, 2 * c.tp + c.fp + c.fn);
  return m;
}

double azimuth_difference_deg(double a_deg, double b_deg) noexcept {
  const double d = wrap_deg(a_deg - b_deg);
  return d > 180.0 ? 360.0 - d : d;
}

CampaignScore score_campaign(const std::vector<CampaignRow>& rows, CampaignModel model) {
  CampaignScore s;
  s.model = model;
  std::vector<double> errors;
  for (const CampaignRow& r : rows) {
    if (r.model != model) continue;
    if (r.predicted_overturned) {
      (r.observed_overturned ? s.confusion.tp : s.confusion.fp) += 1;
    } else {
      (r.observed_overturned ? s.confusion.fn : s.confusion.tn) += 1;
    }
    if (r.predicted_overturned && r.observed_overturned && r.observed_azimuth_deg && r.overturn_azimuth_deg) {
      errors.push_back(azimuth_difference_deg(*r.overturn_azimuth_deg, *r.observed_azimuth_deg));
    }
    s.cpu_s += r.cpu_s;
    s.simulated_s += r.duration_s;
  }
  s.metrics = classification_metrics(s.confusion);
  s.azimuths_compared = errors.size();
  if (!errors.empty()) {
    std::sort(errors.begin(), errors.end());
    const std::size_t n = errors.size();
    s.median_azimuth_error_deg = n % 2 == 1 ? errors[n / 2] : 0.5 * (errors[n / 2 - 1] + errors[n / 2]);
  }
  if (s.cpu_s > 0.0) s.times_real_time = s.simulated_s / s.cpu_s;
  return s;
}

CampaignTargetCheck check_target(const CampaignScore& score, const CampaignTarget& target) {
  CampaignTargetCheck c;
  c.accuracy = score.metrics.accuracy && *score.metrics.accuracy >= target.accuracy_min;
  c.recall = score.metrics.recall && *score.metrics.recall > target.recall_above;
  c.speed = score.times_real_time && *score.times_real_time >= target.times_real_time_min;
  return c;
}

}  // namespace topple::ensemble
