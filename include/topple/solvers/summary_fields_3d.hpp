#pragma once
// The field table of a three-dimensional rocking run's summary (rigid3d.hpp, topple/core/field.hpp): the result
// columns of a sweep's model = "3d" objects (ensemble/sweep.hpp), in one place. Its own header (not
// summary_fields.hpp) so that the widely included writers are not rebuilt for it.
#include <array>

#include "topple/core/field.hpp"
#include "topple/solvers/rigid3d.hpp"

namespace topple {

/// A three-dimensional run's summary.
struct Rigid3DOutcome {
  const Rigid3DSummary& summary;
};

/// Three-dimensional rocking (rigid3d.hpp), the names of `topple rock --model 3d --json` (io::rigid3d_summary_json):
/// overturned, overturn_time_s, overturn_azimuth_deg (null unless overturned: the direction the top fell toward,
/// degrees clockwise from north), max_tilt_rad, max_tilt_azimuth_deg, max_tilt_time_s, max_tilt_over_limit (the
/// tilt over the static limit of its direction, the planar theta / alpha about an edge), exceeded_limit_time_s,
/// impacts, uplifts, uplift_time_s, energy_lost_j_per_kg, flight_time_s, end_time_s, end_mode ("rest", "rocking",
/// "pivot", "fallen"). Every field is a sweep result column (sweep_column 0-14); a name a rocking column has
/// (overturned, overturn_time_s, impacts, uplifts, uplift_time_s, energy_lost_j_per_kg, end_time_s) is that column.
/// Not fields: modes (a list), steps, warnings.
extern const std::array<Field<Rigid3DOutcome>, 15> kRigid3DFields;

}  // namespace topple
