#pragma once
// The JSON of a three-dimensional rocking run (`topple rock --model 3d --json`, Python's rock3d): one table of the
// summary's fields and of the solver's settings for every front end, so that the two cannot drift.
#include <nlohmann/json.hpp>

#include "topple/solvers/rigid3d.hpp"

namespace topple::io {

/// {"model": "3d", overturned, overturn_time_s, overturn_azimuth_deg (null unless overturned), max_tilt_rad,
/// max_tilt_azimuth_deg, max_tilt_time_s, max_tilt_over_limit, exceeded_limit_time_s, impacts, uplifts,
/// uplift_time_s, energy_lost_j_per_kg, flight_time_s, end_time_s, end_mode, modes [{time_s, mode, vertex_a,
/// vertex_b}], steps, warnings}; absent times are null.
[[nodiscard]] nlohmann::ordered_json rigid3d_summary_json(const Rigid3DSummary& summary);

/// {"model": "3d", restitution, e (null unless given), impact_law, simultaneous_contact, rel_tol, g_m_s2}.
/// `circular_base`: the rim engine (rigid3d_disc.hpp), whose impact law is Housner's about the landing rim point and
/// which has no corners to join (simultaneous_contact null).
[[nodiscard]] nlohmann::ordered_json rigid3d_solver_json(const Rigid3DOptions& options, bool circular_base = false);

}  // namespace topple::io
