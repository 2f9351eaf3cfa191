#pragma once
// Writers: solver results to the files and JSON objects users and scripts read. Column and key names carry units;
// the JSON keys are a stable interface shared by the CLI and the Python package.
#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "topple/core/field.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/solvers/summary_fields.hpp"

namespace topple::io {

/// A field's value as JSON: null for null, booleans, integers, numbers (a non-finite double dumps as null), text.
[[nodiscard]] nlohmann::ordered_json field_json(const FieldValue& value);

/// The fields of a result as a JSON object, keys in the table's order (topple/solvers/summary_fields.hpp): the one
/// mechanism behind the summary objects below.
template <class Result, std::size_t N>
[[nodiscard]] nlohmann::ordered_json fields_json(const std::array<Field<Result>, N>& table, const Result& result) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& field : table) j[field.name] = field_json(field.get(result));
  return j;
}

/// Summary of a sliding run as JSON: the fields of kSlidingFields (max_abs_displacement_m, residual_displacement_m,
/// slip_episodes, first_slip_time_s (null when none), ..., the block), then sign_convention. Never emits NaN: absent
/// values are null.
[[nodiscard]] nlohmann::ordered_json sliding_summary_json(const SlidingSummary& summary, const SlidingBlock& block);
/// The bidirectional sliding summary (kSliding2dFields) with the frame it is given in.
[[nodiscard]] nlohmann::ordered_json sliding_2d_summary_json(const Sliding2dSummary& summary, const SlidingBlock& block);
/// The bidirectional sliding spectrum (object_spectra.hpp) as `topple spectrum slide H1 --h2 H2 --json` prints it and
/// topple.slide_spectrum_2d returns it: motion and second (the components' names), vertical, azimuths_deg,
/// pga_axis, rotd50_pga_g, h1_pga_g, h2_pga_g, g_m_s2, mode, slope_deg, and points: per mu, mu, yield_accel_g,
/// ky_over_rotd50_pga, the 2-D run's sliding_2d_summary_json, and h1_alone / h2_alone (max_abs_displacement_m,
/// residual_displacement_m, slip_episodes of each component run alone by the 1-D solver).
[[nodiscard]] nlohmann::ordered_json sliding_spectrum_2d_json(const SlidingSpectrum2d& spectrum,
                                                              const std::string& first_name,
                                                              const std::string& second_name);

/// Summary of a rocking run as JSON, as `topple rock --json` prints it less its "input" object: the fields of
/// kRockingFields (max_abs_rotation_rad, max_rotation_over_alpha, overturned, overturn_time_s (null when none), ...),
/// then warnings, body {shape, dimensions in m, a_m, h_m, D_m2} and solver {method, rel_tol, ...}. Never emits NaN:
/// absent values are null.
[[nodiscard]] nlohmann::ordered_json rocking_summary_json(const RockingSummary& summary, const RockingBody& body,
                                                          const RockingOptions& options);

/// The "orientation" object of `topple rock --h2 --json` (oriented.hpp): model (the planar projection, in words),
/// bearing_deg (null for a cylinder), azimuths_deg [A1, A2], direction_step_deg (a cylinder), depth_m (a box),
/// governing_azimuth_deg, governing_axis, and directions [{azimuth_deg, axis, max_rotation_over_alpha, overturned,
/// overturn_time_s}] in the order they were run. The governing direction's own summary is rocking_summary_json's.
[[nodiscard]] nlohmann::ordered_json oriented_rocking_json(const OrientedRockingSummary& summary,
                                                           const OrientedBody& body, std::optional<double> bearing_deg,
                                                           const ComponentAzimuths& azimuths,
                                                           const OrientationOptions& orientation);

/// Summary of a coupled slide-rock run as JSON, as `topple rock --model coupled --json` prints it less its "input" object: the
/// fields of kSlideRockFields, then modes {rest|slide|rock|slide-rock|flight|fallen: {entries, first_time_s}},
/// warnings and body {b1_m, b2_m, h_m, inertia_m2}. Never emits NaN: absent values are null.
[[nodiscard]] nlohmann::ordered_json slide_rock_summary_json(const SlideRockSummary& summary,
                                                             const SlideRockBody& body,
                                                             const SlideRockOptions& options);

/// What a single run saw, for the "input" object of `topple slide|rock --json` and of the Python results' json().
struct RunInput {
  std::string motion;                   ///< the record's file name, or the pulse's description
  double scale_factor = 1.0;            ///< amplitude factor applied to the motion as read (GroundMotion::amplitude_factor)
  bool inverted = false;                ///< polarity flipped
  std::optional<std::string> vertical;  ///< the vertical record's name; none without one
  bool with_duration = false;           ///< add duration_s (the rocking object has it)
};

/// The "input" object: motion, pga_g, scale_factor, invert, vertical (null when none), npts, dt_s [, duration_s].
[[nodiscard]] nlohmann::ordered_json run_input_json(const RunInput& input, const GroundMotion& horizontal,
                                                    double g_m_s2);

/// The "input" object of `topple slide --h2 --json` and of the Python Sliding2dResult.json(): motion and h2 (the two
/// components' names), azimuths_deg, slope_deg and slope_azimuth_deg (on a slope only), scale_factor, vertical (true,
/// or null when none), pga_g of both components (in the block's g).
[[nodiscard]] nlohmann::ordered_json sliding_2d_input_json(const RunInput& input, const std::string& second_name,
                                                           const GroundMotion& first, const GroundMotion& second,
                                                           const ComponentAzimuths& azimuths,
                                                           const SlidingBlock& block);

/// History as CSV: time_s,ground_accel_m_s2,displacement_m,velocity_m_s,state (state: -1 slipping up-slope /
/// negative, 0 stuck, 1 slipping down-slope / positive). Written through OutputFile (temporary name, then rename);
/// throws OutputError naming the path when it cannot be written.
void write_sliding_history_csv(const std::filesystem::path& path, const SlidingHistory& history,
                               const GroundMotion& horizontal);

/// Bidirectional sliding history as CSV: time_s, the ground acceleration's east, north and up components
/// (ground_east_m_s2, ground_north_m_s2: the two horizontal components rotated from their azimuths; ground_up_m_s2:
/// the vertical, 0 without one), the block's displacement and velocity relative to the ground (displacement_east_m,
/// displacement_north_m, velocity_east_m_s, velocity_north_m_s) and slipping (1 slipping, 0 stuck). One row per
/// Sliding2dHistory row (merged grid points and events; at an event the state after it; on a slope the run-out
/// after the record, where the ground is still). Written through OutputFile; OutputError naming the path otherwise.
void write_sliding_2d_history_csv(const std::filesystem::path& path, const Sliding2dHistory& history,
                                  const GroundMotion& first, const GroundMotion& second,
                                  const ComponentAzimuths& azimuths, const GroundMotion* vertical);

/// Rocking history as CSV: time_s,theta_rad,theta_dot_rad_s,state (state: rocking-, rest, rocking+, fallen).
/// Written through OutputFile; throws OutputError naming the path when it cannot be written.
void write_rocking_history_csv(const std::filesystem::path& path, const RockingHistory& history);
/// Coupled slide-rock history: time_s,slide_m,slide_velocity_m_s,theta_rad,theta_dot_rad_s,cm_height_m,mode.
void write_slide_rock_history_csv(const std::filesystem::path& path, const SlideRockHistory& history);

}  // namespace topple::io
