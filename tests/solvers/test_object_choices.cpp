// The names of an object's choices (sliding mode, rocking method, restitution, shape) round-trip, unknown names are
// refused naming the field, and a body is built from the dimensions its shape needs, refusing the others.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

/// The InputError `f` throws, or a test failure.
template <class F>
InputError error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError(InputLocation{}, "none");
}

TEST(ObjectChoices, NamesRoundTrip) {
  for (SlidingMode m : {SlidingMode::two_way, SlidingMode::one_way}) EXPECT_EQ(parse_sliding_mode(sliding_mode_name(m)), m);
  for (RockingMethod m : {RockingMethod::adaptive, RockingMethod::rk4}) {
    EXPECT_EQ(parse_rocking_method(rocking_method_name(m)), m);
  }
  for (auto s : {RockingBody::Shape::block, RockingBody::Shape::cylinder, RockingBody::Shape::general}) {
    EXPECT_EQ(parse_shape(shape_name(s)), s);
  }
  EXPECT_EQ(sliding_mode_name(SlidingMode::one_way), "one-way");
  EXPECT_EQ(restitution_mode_name(RestitutionMode::housner), "housner");
  EXPECT_EQ(restitution_mode_name(RestitutionMode::given), "given");
}

TEST(ObjectChoices, UnknownNamesNameTheirField) {
  EXPECT_EQ(error_of([] { (void)parse_sliding_mode("sideways", "--mode"); }).where().field, "--mode");
  EXPECT_EQ(error_of([] { (void)parse_rocking_method("euler"); }).where().field, "method");
  EXPECT_EQ(error_of([] { (void)parse_shape("sphere"); }).where().field, "shape");
  EXPECT_EQ(error_of([] { (void)parse_shape(""); }).where().field, "shape");
  EXPECT_EQ(error_of([] { (void)parse_restitution("0.5x", "--e"); }).where().field, "--e");
  EXPECT_EQ(error_of([] { (void)parse_restitution(""); }).where().field, "e");
}

TEST(ObjectChoices, RestitutionIsHousnerOrANumber) {
  EXPECT_EQ(parse_restitution("housner").mode, RestitutionMode::housner);
  const RestitutionChoice given = parse_restitution("0.6");
  EXPECT_EQ(given.mode, RestitutionMode::given);
  EXPECT_EQ(given.e, 0.6);
}

TEST(ObjectChoices, BodyFromItsDimensions) {
  BodyDimensions d;
  d.width_m = 0.04;
  d.height_m = 0.20;
  const RockingBody b = make_rocking_body(RockingBody::Shape::block, d);
  const RockingBody expected = RockingBody::block(0.04, 0.20);
  EXPECT_EQ(b.a_m, expected.a_m);
  EXPECT_EQ(b.h_m, expected.h_m);
  EXPECT_EQ(b.D_m2, expected.D_m2);
  // A cylinder needs a diameter, not a width; a general body a, h, D.
  EXPECT_EQ(error_of([&] { (void)make_rocking_body(RockingBody::Shape::cylinder, d); }).where().field, "diameter");
  d.diameter_m = 0.04;
  EXPECT_EQ(error_of([&] { (void)make_rocking_body(RockingBody::Shape::cylinder, d); }).where().field, "width");
  BodyDimensions g;
  g.a_m = 0.02;
  g.h_m = 0.10;
  EXPECT_EQ(error_of([&] { (void)make_rocking_body(RockingBody::Shape::general, g); }).where().field, "D");
  g.D_m2 = parse_area_m2("140cm2", "--D");
  EXPECT_NEAR(make_rocking_body(RockingBody::Shape::general, g).D_m2, 0.014, 1e-17);  // one rounding of 140e-4
}

TEST(ObjectChoices, DimensionsBeyondTheLimitNameTheDimensionNotD) {
  // 1e308 m would make D = (4/3)(a^2 + h^2) infinite: the error is the width's, before D is formed.
  BodyDimensions d;
  d.width_m = 1e308;
  d.height_m = 0.2;
  const InputError e = error_of([&] { (void)make_rocking_body(RockingBody::Shape::block, d); });
  EXPECT_EQ(e.where().field, "width");
  EXPECT_NE(e.problem().find("1e+308"), std::string::npos) << e.problem();
  d.width_m = kMaxBodyDimension_m;  // the limit itself is a body
  EXPECT_NO_THROW((void)make_rocking_body(RockingBody::Shape::block, d));
}

TEST(ObjectChoices, AreaUnits) {
  EXPECT_DOUBLE_EQ(parse_area_m2("0.011m2", "--D"), 0.011);
  EXPECT_DOUBLE_EQ(parse_area_m2("110 cm^2", "--D"), 0.011);
  EXPECT_DOUBLE_EQ(parse_area_m2("11000mm2", "--D"), 0.011);
  EXPECT_EQ(error_of([] { (void)parse_area_m2("0.011", "--D"); }).where().field, "--D");  // a bare number
  EXPECT_EQ(error_of([] { (void)parse_area_m2("0.011 m", "--D"); }).where().field, "--D");
}

TEST(ObjectChoices, KineticFrictionIsOptionalNotASentinel) {
  EXPECT_EQ(SlidingBlock::make(0.4).mu_kinetic, 0.4);             // none: equal to the static coefficient
  EXPECT_EQ(SlidingBlock::make(0.4, 0.3).mu_kinetic, 0.3);
  EXPECT_EQ(error_of([] { (void)SlidingBlock::make(0.4, -0.1); }).where().field, "mu_kinetic");  // not "unset"
  EXPECT_EQ(error_of([] { (void)SlidingBlock::make(0.4, -1.0); }).where().field, "mu_kinetic");
}

}  // namespace
}  // namespace topple
