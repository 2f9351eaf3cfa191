#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

TEST(Units, LengthsConvertToMetres) {
  EXPECT_DOUBLE_EQ(parse_length_m("4cm", "--width"), 0.04);
  EXPECT_DOUBLE_EQ(parse_length_m(" 0.2 m ", "--height"), 0.2);
  EXPECT_DOUBLE_EQ(parse_length_m("40mm", "--width"), 0.04);
  EXPECT_DOUBLE_EQ(parse_length_m("2in", "--width"), 0.0508);
}

TEST(Units, AccelerationInGUsesTheGivenG) {
  EXPECT_DOUBLE_EQ(parse_acceleration_m_s2("0.5g", "--scale-pga"), 0.5 * kStandardGravity);
  EXPECT_DOUBLE_EQ(parse_acceleration_m_s2("1g", "--scale-pga", 9.81), 9.81);
  EXPECT_DOUBLE_EQ(parse_acceleration_m_s2("490gal", "--scale-pga"), 4.9);
  EXPECT_DOUBLE_EQ(parse_acceleration_m_s2("3m/s2", "--scale-pga"), 3.0);
}

TEST(Units, MissingOrUnknownUnitIsAnErrorNamingTheField) {
  try {
    (void)parse_length_m("0.3", "--width");
    FAIL() << "a bare number must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--width"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("no unit"), std::string::npos);
  }
  EXPECT_THROW((void)parse_length_m("3 parsecs", "--width"), InputError);
  EXPECT_THROW((void)parse_length_m("cm", "--width"), InputError);
  EXPECT_THROW((void)parse_length_m("nan m", "--width"), InputError);
  EXPECT_THROW((void)parse_acceleration_m_s2("inf g", "--pga"), InputError);
}

TEST(Units, OtherQuantities) {
  EXPECT_DOUBLE_EQ(parse_duration_s("150ms", "--duration"), 0.15);
  EXPECT_DOUBLE_EQ(parse_frequency_hz("3Hz", "--freq"), 3.0);
  EXPECT_NEAR(parse_angle_rad("180deg", "--slope"), kPi, 1e-15);
  EXPECT_DOUBLE_EQ(acceleration_unit_factor("cm/s2", "units"), 0.01);
  EXPECT_DOUBLE_EQ(acceleration_unit_factor("G", "units", 9.81), 9.81);
  EXPECT_THROW((void)acceleration_unit_factor("furlongs", "units"), InputError);
}

}  // namespace
}  // namespace topple
