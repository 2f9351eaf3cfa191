#pragma once
// Onset of motion of a rigid body at rest on a level base: rest, rock, slide or slide-rock (Shenton 1996). The rocking
// engine (rocking.hpp) reports the mode at the first lift-off; the survey's physics checks call it too. Symbols as in
// rocking.hpp: a (CM to the pivot edge), h (CM height), D = I_O / m, g + a_v the effective gravity.
//
// Onset mode (Shenton 1996, J. Eng. Mech. 122(7), "Criteria for initiation of slide, rock, and slide-rock rigid-body
// modes"). At the instant theta = theta' = 0 that rocking starts, with A = |a_h| / (g + a_v):
//   theta'' = g (A h - a) / D,  friction needed H = m (A g - h theta''),  normal force N = m (g + a theta'').
// Pure rocking needs H <= mu N, i.e. mu >= mu_crit(A) = [A (D - h^2) + a h] / [(D - a^2) + A a h]; for a block this is
// [A (4 beta^2 + 1) + 3 beta] / [(beta^2 + 4) + 3 A beta], beta = a / h, the form attributed to Shenton (his printed
// equation was not retrieved; this one is derived from the three equations above and reduces to mu_crit(beta) = beta).
// If mu < a/h the body slides before it can rock: the rocking-only result is then not valid.
#include <cstdint>
#include <string_view>

#include "topple/bodies/rocking_body.hpp"

namespace topple {

enum class OnsetMode : std::uint8_t { unchecked, rest, rock, slide, slide_rock };
[[nodiscard]] std::string_view onset_mode_name(OnsetMode mode);  ///< "unchecked", "rest", "rock", "slide", "slide-rock"

/// mu_crit(A) = [A (D - h^2) + a h] / [(D - a^2) + A a h], A = |a_h| / (g + a_v) >= 0.
[[nodiscard]] double shenton_critical_mu(const RockingBody& body, double accel_ratio);

/// Mode the body starts in under A = |a_h| / (g + a_v) with friction mu: rest if A < min(mu, a/h); slide if
/// mu < a/h; otherwise rock if mu >= mu_crit(A), else slide-rock. Throws InputError for mu or A < 0 or not finite.
[[nodiscard]] OnsetMode shenton_onset_mode(const RockingBody& body, double accel_ratio, double mu);

}  // namespace topple
