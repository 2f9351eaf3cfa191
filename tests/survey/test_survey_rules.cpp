// The survey's observation model (survey/survey.hpp): the rules the readers used to hold (names, the model rule,
// error rates, the physics checks of an object's model) now stand in the library, and are tested here directly; the
// readers' tests (tests/io, tests/cli) check that the same messages still come back located at the file's line.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <string>

#include "topple/bodies/rocking_body.hpp"
#include "topple/core/error.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/survey/survey.hpp"

namespace topple {
namespace {

ObservedObject block_object(double width_m, double height_m, double mu, Outcome outcome) {
  ObservedObject o;
  o.id = "x";
  o.body = RockingBody::block(width_m, height_m);
  o.mu = Interval{mu, mu};
  o.outcome = outcome;
  return o;
}

/// The field an InputError names, or "" when `f` does not throw.
template <class F>
std::string refused_field(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.where().field;
  }
  return "";
}

TEST(SurveyRules, NamesAreTheSurveyFilesWords) {
  EXPECT_EQ(outcome_name(Outcome::slid_toppled), "slid_toppled");
  EXPECT_EQ(outcome_name(Outcome::not_overturned), "not_overturned");
  EXPECT_EQ(object_model_name(ObjectModel::coupled), "coupled");
  EXPECT_EQ(evidence_name(Evidence::reported), "reported");
  EXPECT_EQ(motion_family_name(MotionFamily::rezaeian2010), "rezaeian2010");
}

TEST(SurveyRules, ErrorRatesAreTheStatedOnes) {
  // docs/survey.md ("evidence"): certain 2 %, likely 10 %, reported 25 %.
  EXPECT_EQ(evidence_error_rate(Evidence::certain), 0.02);
  EXPECT_EQ(evidence_error_rate(Evidence::likely), 0.10);
  EXPECT_EQ(evidence_error_rate(Evidence::reported), 0.25);
}

TEST(SurveyRules, TheModelRuleFollowsTheOutcomeUnlessTheSurveyForcesOne) {
  auto o = block_object(0.2, 0.6, 0.5, Outcome::slid);
  EXPECT_EQ(object_model(o), ObjectModel::slide);
  o.outcome = Outcome::rocked;
  EXPECT_EQ(object_model(o), ObjectModel::rock);
  o.outcome = Outcome::walked;
  EXPECT_EQ(object_model(o), ObjectModel::coupled);
  o.outcome = Outcome::rocked;
  o.model = ObjectModel::coupled;
  EXPECT_EQ(object_model(o), ObjectModel::coupled);
}

TEST(SurveyRules, CombinationsThatMakeNoSenseAreRefusedNamingTheField) {
  auto o = block_object(0.2, 0.6, 0.5, Outcome::slid_stood);
  o.model = ObjectModel::rock;  // a coupled observation on the rocking model
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 1); }), "model");
  o = block_object(0.2, 0.6, 0.5, Outcome::overturned);
  o.model = ObjectModel::slide;  // the sliding block cannot topple
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 1); }), "model");
  o = block_object(0.2, 0.6, 0.5, Outcome::not_slid);
  o.model = ObjectModel::rock;  // the rocking body's base does not slide
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 1); }), "model");
  o = block_object(0.2, 0.6, 0.5, Outcome::walked);  // the coupled model is planar
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 3); }), "outcome");
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 1); }), "");
}

TEST(SurveyRules, ABodyThatSlidesBeforeItCanLiftCannotTopple) {
  // Shenton (1996): b/h = 0.1 / 0.3 = 0.333; mu = 0.3 < b/h over the whole range: it never lifts, so slid_toppled
  // is refused; mu = 0.4 > b/h lets it lift, and the outcome stands.
  auto o = block_object(0.2, 0.6, 0.3, Outcome::slid_toppled);
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 1); }), "outcome");
  o.mu = Interval{0.4, 0.4};
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 1); }), "");
}

TEST(SurveyRules, MuAtThePainleveLimitIsKeptWithAWarning) {
  // A uniform rectangular block has mu_P = 4/3 (docs/method.md, "Painleve's paradox"): mu = 1.3 is below it, 1.34
  // above; the value is kept either way, the warning names mu.
  auto o = block_object(0.2, 0.6, 1.3, Outcome::slid_stood);
  EXPECT_TRUE(check_object_model(o, 1).empty());
  o.mu = Interval{1.34, 1.34};
  const auto warnings = check_object_model(o, 1);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_EQ(warnings[0].field, "mu");
  EXPECT_NE(warnings[0].problem.find("Painleve limit"), std::string::npos) << warnings[0].problem;
  // Objects on the sliding or rocking model are not checked for it.
  o.outcome = Outcome::slid;
  EXPECT_TRUE(check_object_model(o, 1).empty());
}


TEST(SurveyRules, AThreeDimensionalBodySlidesOnlyWithItsFriction) {
  // model = "3d": the sliding and coupled outcomes need friction_3d (field "model"); with it a body whose mu stays below
  // its least uplift ratio b_min / h cannot topple or walk (Shenton 1996, every direction; field "outcome"). A mesh's
  // support polygon, by hand: the triangle (0, 0), (0.3, 0), (0, 0.3) m with its centre of mass over (0.1, 0.1) at
  // h = 0.25 m is nearest its hypotenuse, (0.3 - 0.2) / sqrt(2) = 0.0707 m: b_min / h = 0.283.
  ObservedObject o = block_object(0.2, 0.6, 0.5, Outcome::walked);
  o.mesh_file = "rock.obj";
  o.model = ObjectModel::three_d;
  o.body_3d = std::make_shared<const RigidBody3D>(RigidBody3D::polygon(
      {{0.0, 0.0}, {0.3, 0.0}, {0.0, 0.3}}, Vec3{0.1, 0.1, 0.25},
      std::array<Vec3, 3>{Vec3{0.01, 0.0, 0.0}, Vec3{0.0, 0.01, 0.0}, Vec3{0.0, 0.0, 0.01}}));
  for (const Outcome outcome : {Outcome::slid, Outcome::not_slid, Outcome::slid_stood, Outcome::slid_toppled,
                                Outcome::walked}) {
    o.outcome = outcome;
    o.friction_3d = false;
    EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 3); }), "model") << outcome_name(outcome);
    o.friction_3d = true;
    EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 3); }), "") << outcome_name(outcome);
    EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 1); }), "model") << outcome_name(outcome);
  }
  o.mu = Interval{0.2, 0.28};  // below 0.283 over the whole range
  for (const Outcome outcome : {Outcome::slid_toppled, Outcome::walked}) {
    o.outcome = outcome;
    EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 3); }), "outcome") << outcome_name(outcome);
  }
  o.outcome = Outcome::slid_stood;  // sliding without lifting stands
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 3); }), "");
  o.mu = Interval{0.2, 0.29};  // may lift at its top
  o.outcome = Outcome::slid_toppled;
  EXPECT_EQ(refused_field([&] { (void)check_object_model(o, 3); }), "");
}

}  // namespace
}  // namespace topple
