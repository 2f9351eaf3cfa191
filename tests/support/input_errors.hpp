#pragma once
// Test fixture: the assertion that a call throws topple::InputError naming a field, with a text in its message.
#include <string>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"

namespace topple::test {

/// `f()` throws InputError whose field is `field` and whose message holds `text` (gtest failures otherwise).
template <class F>
void expect_input_error(F&& f, const std::string& field, const std::string& text) {
  try {
    (void)f();
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, field) << e.what();
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

}  // namespace topple::test
