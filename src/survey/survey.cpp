// The survey's observation model (topple/survey/survey.hpp): the names of outcomes, models, families and evidence,
// the model each object is simulated with, the error rate of each kind of evidence, and the physics checks of an
// object's model (Shenton 1996; Painleve's paradox), its restitution (Housner), bearing and fall direction. The
// readers (topple/io/survey_file.hpp) call these and locate what they throw at the file's line; the inversion and the
// report call the same functions.
#include "topple/survey/survey.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/core/enum_names.hpp"
#include "topple/survey/schema.hpp"

namespace topple {

constexpr std::array<EnumName<Outcome>, 9> kOutcomeNames{{
    {Outcome::overturned, "overturned"},
    {Outcome::not_overturned, "not_overturned"},
    {Outcome::rocked, "rocked"},
    {Outcome::not_rocked, "not_rocked"},
    {Outcome::slid, "slid"},
    {Outcome::not_slid, "not_slid"},
    {Outcome::slid_stood, "slid_stood"},
    {Outcome::slid_toppled, "slid_toppled"},
    {Outcome::walked, "walked"},
}};

std::string_view outcome_name(Outcome o) { return enum_name(kOutcomeNames, o); }

bool is_coupled_outcome(Outcome o) noexcept {
  return o == Outcome::slid_stood || o == Outcome::slid_toppled || o == Outcome::walked;
}

constexpr std::array<EnumName<ObjectModel>, 4> kObjectModelNames{{
    {ObjectModel::slide, "slide"},
    {ObjectModel::rock, "rock"},
    {ObjectModel::coupled, "coupled"},
    {ObjectModel::three_d, "3d"},
}};

std::string_view object_model_name(ObjectModel m) { return enum_name(kObjectModelNames, m); }

ObjectModel object_model(const ObservedObject& o) noexcept {
  if (o.model) return *o.model;
  if (is_coupled_outcome(o.outcome)) return ObjectModel::coupled;
  return o.outcome == Outcome::slid || o.outcome == Outcome::not_slid ? ObjectModel::slide : ObjectModel::rock;
}

constexpr std::array<EnumName<MotionFamily>, 5> kMotionFamilyNames{{
    {MotionFamily::synthetic, "synthetic"},
    {MotionFamily::records, "records"},
    {MotionFamily::rezaeian2010, "rezaeian2010"},
    {MotionFamily::boore2003, "boore2003"},
    {MotionFamily::mixture, "mixture"},
}};

std::string_view motion_family_name(MotionFamily f) { return enum_name(kMotionFamilyNames, f); }

constexpr std::array<EnumName<InversionPrior>, 2> kInversionPriorNames{{
    {InversionPrior::log_uniform, "log-uniform"},
    {InversionPrior::earthquake, "earthquake"},
}};

std::string_view inversion_prior_name(InversionPrior p) { return enum_name(kInversionPriorNames, p); }

constexpr std::array<EnumName<Evidence>, 3> kEvidenceNames{{
    {Evidence::certain, "certain"},
    {Evidence::likely, "likely"},
    {Evidence::reported, "reported"},
}};

std::string_view evidence_name(Evidence e) { return enum_name(kEvidenceNames, e); }

double evidence_error_rate(Evidence e) noexcept {
  switch (e) {
    case Evidence::certain: return 0.02;
    case Evidence::likely: return 0.10;
    case Evidence::reported: return 0.25;
  }
  return 0.02;
}

namespace {

/// A model = "3d" object's least uplift ratio b_min / h: the distance from its centre of mass' plan to the nearest
/// edge of its base (a mesh's support polygon; a box's min(width, depth) / 2), over the height of the centre of mass
/// (inversion_3c.cpp's polygon coefficients, the smaller). Below it in mu the base slides before it can lift and never
/// lifts while sliding (Shenton 1996, in every direction; rigid3d_slide.cpp).
double three_d_uplift_ratio(const ObservedObject& o) {
  if (o.body_3d) {  // a mesh's support polygon (a box's body_3d is made after the checks; the same number below)
    const auto& v = o.body_3d->base_xy_m;
    const Vec3& c = o.body_3d->centre_of_mass_m;
    double nearest = INFINITY;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const auto& a = v[i];
      const auto& b = v[(i + 1) % v.size()];
      const double ex = b[0] - a[0], ey = b[1] - a[1];
      nearest = std::min(nearest, (ex * (c[1] - a[1]) - ey * (c[0] - a[0])) / std::hypot(ex, ey));
    }
    return nearest / c[2];
  }
  // A box: half its smaller horizontal side over half its height (a cylinder: its radius, the planar body's a).
  const double half = o.depth_m ? std::min(o.body.a_m, 0.5 * *o.depth_m) : o.body.a_m;
  return half / o.body.h_m;
}

}  // namespace

std::vector<ObjectCheck> check_object_model(const ObservedObject& o, int components) {
  std::vector<ObjectCheck> warnings;
  const bool sliding = o.outcome == Outcome::slid || o.outcome == Outcome::not_slid;
  // model = "3d" makes the coupled outcomes too where its base may slide (friction_3d, checked below).
  if (o.model && *o.model != ObjectModel::coupled && *o.model != ObjectModel::three_d &&
      is_coupled_outcome(o.outcome)) {
    throw parameter_error("model", fmt::format("outcome \"{}\" is an observation of sliding and rocking together: only "
                                           "the coupled model makes it (leave model out or write \"coupled\"; in a "
                                           "three-component survey, model = \"3d\" with friction_3d = \"mu\")",
                                           outcome_name(o.outcome)));
  }
  if (o.model == ObjectModel::slide && !sliding) {
    throw parameter_error("model", fmt::format("the sliding block cannot rock or topple: outcome \"{}\" needs model "
                                           "\"rock\" or \"coupled\"", outcome_name(o.outcome)));
  }
  if (o.model == ObjectModel::rock && sliding) {
    throw parameter_error("model", fmt::format("the rocking body's base does not slide: outcome \"{}\" needs model "
                                           "\"slide\" or \"coupled\"", outcome_name(o.outcome)));
  }
  if (o.model == ObjectModel::three_d) {
    // The three-dimensional engine (rigid3d.hpp): two horizontal components and the vertical at a bearing, a
    // polygonal base (a box, or a mesh's support polygon), or a solid cylinder's circular base (rigid3d_disc.hpp, no
    // bearing needed); with friction_3d = "mu" a box's or a mesh's base slides, and the sliding and coupled outcomes
    // are scored on its runs (docs/survey.md, "Three-dimensional objects").
    if (components != 3) {
      throw parameter_error("model", "model = \"3d\" needs a three-component survey ([inversion] components = 3): "
                                     "the body responds to both horizontal components and the vertical");
    }
    if ((sliding || is_coupled_outcome(o.outcome)) && !o.friction_3d) {
      throw parameter_error("model", fmt::format("the three-dimensional engine does not slide without friction: "
                                                 "outcome \"{}\" needs friction_3d = \"mu\" (the base slides with "
                                                 "the object's mu){}",
                                                 outcome_name(o.outcome),
                                                 sliding ? ", or model \"slide\"" : ""));
    }
    if (o.mesh_file.empty()) {
      if (o.body.shape != RockingBody::Shape::block && o.body.shape != RockingBody::Shape::cylinder) {
        throw parameter_error("shape", "model = \"3d\": a general body is a section in one vertical plane, without a "
                                       "base in three dimensions; give a block with its depth, a cylinder, or a "
                                       "mesh");
      }
      if (!o.depth_m && o.body.shape == RockingBody::Shape::block) {
        throw parameter_error("depth", "model = \"3d\" needs the block's depth (its extent along bearing + 90 deg), "
                                       "a length with a unit");
      }
    }
    // Shenton (1996) in every direction (rigid3d_slide.cpp): a base with mu_s h < b_min, b_min the least distance
    // from the centre of mass' plan to an edge, slides before it can lift and never lifts while sliding, so it can
    // neither topple nor rock: refused when that holds over the whole mu range, as for the coupled model.
    if (o.outcome == Outcome::slid_toppled || o.outcome == Outcome::walked) {
      const double b_over_h = three_d_uplift_ratio(o);
      if (o.mu.high < b_over_h) {
        throw parameter_error("outcome", fmt::format("a body with mu <= {:.3g} < b/h = {:.3g} (its nearest base edge) "
                                                     "slides before it can lift and never lifts while sliding "
                                                     "(Shenton 1996): it cannot have {}; write \"slid\" or "
                                                     "\"slid_stood\", or check mu and the dimensions",
                                                     o.mu.high, b_over_h,
                                                     o.outcome == Outcome::walked ? "walked (rocked)" : "toppled"));
      }
    }
  }
  if (object_model(o) != ObjectModel::coupled) return warnings;
  if (components != 1) {
    throw parameter_error(o.model ? "model" : "outcome", "the coupled slide-rock model is planar: it needs a "
                                                     "one-component survey ([inversion] components = 1); in three "
                                                     "components a box or a mesh with model = \"3d\" and "
                                                     "friction_3d = \"mu\" makes this outcome");
  }
  // Shenton (1996): a body with mu_s < min(b1, b2) / h slides before it can lift and never lifts while sliding
  // (slide_rock.hpp, cannot_uplift), so it can neither topple nor rock; refused when that holds over the whole range.
  if ((o.outcome == Outcome::slid_toppled || o.outcome == Outcome::walked) &&
      SlideRockBody::from_rocking(o.body, o.mu.high).cannot_uplift()) {
    const RockingBody& b = o.body;
    const double b_over_h = std::min(std::tan(b.alpha_rad()), std::tan(b.side_body(-1).alpha_rad()));
    throw parameter_error("outcome", fmt::format("a body with mu <= {:.3g} < b/h = {:.3g} slides before it can lift and "
                                             "never lifts while sliding (Shenton 1996): it cannot have {}; "
                                             "write \"slid\" or \"slid_stood\", or check mu and the dimensions",
                                             o.mu.high, b_over_h,
                                             o.outcome == Outcome::walked ? "walked (rocked)" : "toppled"));
  }
  // Painleve's paradox (slide_rock.hpp, painleve_friction_limit; docs/method.md): with mu at or above mu_P the
  // coupled runs may meet a slipping corner that Coulomb friction cannot resolve; the solver resolves it (tangential
  // impacts, holds), which is a modelling choice the user should know of: said, the value kept.
  const SlideRockBody coupled = SlideRockBody::from_rocking(o.body, o.mu.high);
  const double mu_p = coupled.painleve_friction_limit();
  if (o.mu.high >= mu_p) {
    warnings.push_back(ObjectCheck{"mu", fmt::format("mu = {} reaches the Painleve limit of this body, mu_P = {:.4g} (b/h = {:.3g}, "
                                     "k2 = {:.3g} m2): its coupled runs may meet Painleve's paradox (Coulomb friction "
                                     "without a unique solution), which the solver resolves by tangential impacts "
                                     "(docs/method.md, \"Painleve's paradox\"); check mu",
                                     o.mu.is_value() ? fmt::format("{:g}", o.mu.low)
                                                     : fmt::format("[{:g}, {:g}]", o.mu.low, o.mu.high),
                                     mu_p, std::min(coupled.b1_m, coupled.b2_m) / coupled.h_m, coupled.inertia_m2)});
  }
  return warnings;
}

void check_object_restitution(const ObservedObject& o) {
  // A body that strikes needs Housner's e >= 0: the rocking model always, the coupled one when it can lift.
  const bool rocks = object_model(o) == ObjectModel::rock ||
                     (object_model(o) == ObjectModel::coupled &&
                      !SlideRockBody::from_rocking(o.body, o.mu.high).cannot_uplift());
  if (rocks && o.e_housner && housner_restitution(o.body) < 0.0) {
    throw parameter_error("e", fmt::format("Housner's restitution 1 - 2a^2/D = {:.3g} is negative for so squat a body "
                                           "(alpha = {:.3g} deg > 54.7 deg): {}",
                                           housner_restitution(o.body), rad_to_deg(o.body.alpha_rad()),
                                           kSquatBodyAdvice));
  }
  if (rocks && o.depth_m && o.e_housner) {  // the other axis is a block of width `depth` (oriented.hpp)
    const RockingBody across = *OrientedBody::make(o.body, o.depth_m).across;
    if (housner_restitution(across) < 0.0) {
      throw parameter_error("depth", fmt::format("Housner's restitution 1 - 2a^2/D = {:.3g} is negative across this "
                                                 "box (depth {:.3g} m, height {:.3g} m: alpha = {:.3g} deg > 54.7 "
                                                 "deg): give e = a value or a range, or leave depth out (the box then "
                                                 "rocks along its bearing only)",
                                                 housner_restitution(across), *o.depth_m, 2.0 * across.h_m,
                                                 rad_to_deg(across.alpha_rad())));
    }
  }
}

void check_object_bearing(const ObservedObject& o) {
  if (o.body.shape == RockingBody::Shape::cylinder) {
    throw parameter_error("azimuth_deg", "a cylinder has no narrow side: it rocks toward its worst direction "
                                         "(docs/method.md), so it takes no bearing");
  }
}

void check_object_fall_direction(const ObservedObject& o) {
  if (o.outcome != Outcome::overturned) {
    throw parameter_error("toppled_azimuth_deg", "a fall direction goes with outcome = \"overturned\"");
  }
  if (o.body.shape != RockingBody::Shape::cylinder && !o.depth_m && object_model(o) != ObjectModel::three_d) {
    throw parameter_error("toppled_azimuth_deg", kFallDirectionProblem);  // schema.hpp: the form says the same
  }
}

}  // namespace topple
