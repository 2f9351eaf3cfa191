#pragma once
// Observed objects for the inversion's tests (test_inversion.cpp, test_inversion_3c.cpp).
#include <string>

#include "topple/rocking.hpp"
#include "topple/survey.hpp"

namespace topple::testing {

/// A block of full width w and height h (m) with friction mu (a value or a range) and an observed outcome.
inline ObservedObject block(const std::string& id, double w, double h, Interval mu, Outcome outcome) {
  ObservedObject o;
  o.id = id;
  o.body = RockingBody::block(w, h);
  o.width_m = w;
  o.height_m = h;
  o.mu = mu;
  o.outcome = outcome;
  return o;
}

}  // namespace topple::testing
