// The field table of a three-dimensional rocking run (summary_fields_3d.hpp).
#include "topple/solvers/summary_fields_3d.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace topple {
namespace {

using R = Rigid3DOutcome;

FieldValue optional_value(const std::optional<double>& v) { return v ? FieldValue{*v} : FieldValue{}; }
FieldValue count(std::size_t n) { return static_cast<std::int64_t>(n); }

}  // namespace

const std::array<Field<Rigid3DOutcome>, 15> kRigid3DFields{{
    {"overturned", [](const R& r) -> FieldValue { return r.summary.overturned; }, 0},
    {"overturn_time_s", [](const R& r) { return optional_value(r.summary.overturn_time_s); }, 1},
    {"overturn_azimuth_deg",
     [](const R& r) {
       return r.summary.overturned ? FieldValue{r.summary.overturn_azimuth_deg} : FieldValue{};
     },
     2},
    {"max_tilt_rad", [](const R& r) -> FieldValue { return r.summary.max_tilt_rad; }, 3},
    {"max_tilt_azimuth_deg", [](const R& r) -> FieldValue { return r.summary.max_tilt_azimuth_deg; }, 4},
    {"max_tilt_time_s", [](const R& r) -> FieldValue { return r.summary.max_tilt_time_s; }, 5},
    {"max_tilt_over_limit", [](const R& r) -> FieldValue { return r.summary.max_tilt_over_limit; }, 6},
    {"exceeded_limit_time_s", [](const R& r) { return optional_value(r.summary.exceeded_limit_time_s); }, 7},
    {"impacts", [](const R& r) { return count(r.summary.impacts); }, 8},
    {"uplifts", [](const R& r) { return count(r.summary.uplifts); }, 9},
    {"uplift_time_s", [](const R& r) { return optional_value(r.summary.uplift_time_s); }, 10},
    {"energy_lost_j_per_kg", [](const R& r) -> FieldValue { return r.summary.energy_lost_j_per_kg; }, 11},
    {"flight_time_s", [](const R& r) { return optional_value(r.summary.flight_time_s); }, 12},
    {"end_time_s", [](const R& r) -> FieldValue { return r.summary.end_time_s; }, 13},
    {"end_mode", [](const R& r) -> FieldValue { return std::string(rigid3d_mode_name(r.summary.end_mode)); }, 14},
}};

}  // namespace topple
