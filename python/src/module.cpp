// topple._core: the Python binding of the topple library (nanobind). Bindings only: every computation, every
// validation and every JSON summary is the library's own, so that Python and the CLI give the same bits.
//
// Conventions of the Python API (python/topple/__init__.pyi documents them for users):
// - SI units, names carry them (accel_m_s2, dt_s, residual_displacement_m); lengths are plain floats in metres.
// - Arrays in: a numpy array must be float64 (TypeError otherwise: no silent cast of int or float32 data) and
//   1-D (ValueError); a strided (non-contiguous) float64 array is accepted and copied element by element; a Python
//   list or tuple of numbers is converted to float64. NaN, Inf, dt <= 0 and every other bad value raise
//   topple.InputError from the library's own validation, with the CLI's message.
// - Arrays out: GroundMotion.accel_m_s2 and the result histories are read-only views on the C++ data (no copy),
//   kept alive by the object they come from.
// - Computations release the GIL.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/variant.h>
#include <nanobind/stl/vector.h>
#include <nlohmann/json.hpp>

#include "docstrings.hpp"

#include "topple/ensemble/ensemble.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/core/error.hpp"
#include "topple/fragility/fragility.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/output/fragility_output.hpp"
#include "topple/output/record_fields.hpp"
#include "topple/region/survey_inversion.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/output/flexible_json.hpp"
#include "topple/output/inversion_output.hpp"
#include "topple/output/region_output.hpp"
#include "topple/output/rigid3d_json.hpp"
#include "topple/io/read.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/io/sweep_file.hpp"
#include "topple/output/write.hpp"
#include "topple/output/region_report.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/solvers/summary_fields.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace topple::python {
namespace {

using ReadOnlyArray = nb::ndarray<nb::numpy, const double, nb::ndim<1>>;
using OwnedArray = nb::ndarray<nb::numpy, double, nb::ndim<1>>;
using OwnedInt8Array = nb::ndarray<nb::numpy, std::int8_t, nb::ndim<1>>;

// ---- arrays ----

/// str(obj.dtype) for error messages.
std::string dtype_name(nb::handle obj) {
  if (!nb::hasattr(obj, "dtype")) return "unknown";
  nb::object dtype = obj.attr("dtype");
  nb::object text = nb::steal(PyObject_Str(dtype.ptr()));
  if (!text.is_valid()) {
    PyErr_Clear();
    return "unknown";
  }
  return nb::cast<std::string>(text);
}

/// The documented input rule (see the header): float64 numpy arrays (any stride) or Python sequences of numbers.
std::vector<double> to_vector(nb::handle obj, const char* name) {
  if (nb::ndarray_check(obj)) {
    nb::ndarray<nb::ro> array;
    if (!nb::try_cast(obj, array, /*convert=*/false)) {
      throw nb::type_error(fmt::format("{}: cannot read this array (expected a numpy float64 array)", name).c_str());
    }
    if (array.device_type() != nb::device::cpu::value) {
      throw nb::type_error(fmt::format("{}: the array must live in CPU memory", name).c_str());
    }
    if (array.dtype() != nb::dtype<double>()) {
      const std::string got = dtype_name(obj);
      throw nb::type_error(fmt::format("{} must be a float64 array, got dtype {}: convert it explicitly, e.g. "
                                       "numpy.asarray({}, dtype=numpy.float64)",
                                       name, got, name).c_str());
    }
    if (array.ndim() != 1) {
      throw nb::value_error(fmt::format("{} must be 1-D, got {} dimensions", name, array.ndim()).c_str());
    }
    const auto* data = static_cast<const double*>(array.data());
    const std::size_t n = array.shape(0);
    const std::int64_t stride = array.stride(0);  // in elements
    std::vector<double> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = data[static_cast<std::int64_t>(i) * stride];
    return out;
  }
  if (nb::isinstance<nb::list>(obj) || nb::isinstance<nb::tuple>(obj)) {
    std::vector<double> out;
    if (!nb::try_cast(obj, out, /*convert=*/true)) {
      throw nb::type_error(fmt::format("{}: every element of the sequence must be a number", name).c_str());
    }
    return out;
  }
  throw nb::type_error(fmt::format("{} must be a numpy float64 array or a list of numbers, got {}", name,
                                   nb::type_name(obj.type()).c_str()).c_str());
}

/// A numpy array owning `values` (moved to the heap; the capsule frees it with the array).
template <class T>
nb::ndarray<nb::numpy, T, nb::ndim<1>> to_numpy(std::vector<T> values) {
  auto owned = std::make_unique<std::vector<T>>(std::move(values));
  T* data = owned->data();
  const std::size_t n = owned->size();
  nb::capsule owner(owned.get(), [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  owned.release();  // now owned by the capsule
  return nb::ndarray<nb::numpy, T, nb::ndim<1>>(data, {n}, owner);
}

/// Read-only view on a vector that `self` (the Python object holding it) keeps alive (rv_policy reference_internal).
ReadOnlyArray view(const std::vector<double>& v) { return ReadOnlyArray(v.data(), {v.size()}, nb::handle()); }

template <class Enum>
std::vector<std::int8_t> state_codes(const std::vector<Enum>& states) {
  std::vector<std::int8_t> out(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) out[i] = static_cast<std::int8_t>(states[i]);
  return out;
}

/// nlohmann JSON -> Python objects through its own text (the CLI's bytes; doubles round-trip exactly).
nb::object to_python(const nlohmann::ordered_json& j) {
  // Imported on each call (sys.modules makes it cheap): a function-static Python object would be released after
  // the interpreter has finalised.
  return nb::module_::import_("json").attr("loads")(j.dump());
}

nb::object optional_float(const std::optional<double>& v) { return v ? nb::cast(*v) : nb::none(); }

/// A result field's value (topple/core/field.hpp): None, bool, int, float or str.
nb::object field_to_python(const FieldValue& value) {
  return std::visit(
      [](const auto& v) -> nb::object {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::monostate>) {
          return nb::none();
        } else {
          return nb::cast(v);
        }
      },
      value);
}

// ---- ground motions ----

std::string motion_name(const GroundMotion& m) {
  return m.metadata().source_file.empty() ? m.metadata().event : m.metadata().source_file;
}

GroundMotion make_motion(nb::handle accel, std::optional<double> dt_s, const std::string& units, nb::handle time,
                         double start_time_s, double g_m_s2) {
  std::vector<double> a = to_vector(accel, "accel");
  const double factor = acceleration_unit_factor(units, "units", g_m_s2);
  if (factor != 1.0) {
    for (double& v : a) v *= factor;
  }
  RecordMetadata meta;
  meta.format = "python";
  meta.units_as_read = units;
  meta.g_m_s2 = g_m_s2;
  if (!time.is_none()) {
    if (dt_s) throw parameter_error("dt", "give either dt (uniform samples) or time (irregular samples), not both");
    std::vector<double> t = to_vector(time, "time");
    return GroundMotion::irregular(std::move(t), std::move(a), std::move(meta));
  }
  if (!dt_s) throw parameter_error("dt", "give dt (uniform samples, s) or time (sample times, s)");
  return GroundMotion::uniform(std::move(a), *dt_s, start_time_s, std::move(meta));
}

// ---- sliding ----

/// The motions a run used, kept alive by their Python objects, for the "input" object of json() (built on demand:
/// it scans the record for its PGA, which would otherwise double the cost of a summary-only call). GroundMotion is
/// immutable from Python, so what json() reports is what the run saw.
struct RunInputs {
  nb::object horizontal;
  nb::object vertical;  // None when absent

  RunInputs() = default;
  RunInputs(const GroundMotion& h, const GroundMotion* v)
      : horizontal(nb::find(h)), vertical(v ? nb::find(*v) : nb::none()) {}
  bool with_duration = false;  // the rocking "input" object has duration_s
  [[nodiscard]] nlohmann::ordered_json json(double g_m_s2) const;
};

struct SlidingRun {
  SlidingSummary summary;
  SlidingHistory history;  // empty when run with history=False
  SlidingBlock block;
  RunInputs inputs;

  [[nodiscard]] nlohmann::ordered_json json() const {
    nlohmann::ordered_json j = io::sliding_summary_json(summary, block);
    j["input"] = inputs.json(block.g_m_s2);
    return j;
  }
};

/// The "input" object of the CLI's JSON for a motion used as given (no scaling or polarity flip in the call).
nlohmann::ordered_json RunInputs::json(double g_m_s2) const {
  const GroundMotion& h = nb::cast<const GroundMotion&>(horizontal);
  io::RunInput in;
  in.motion = motion_name(h);
  if (!vertical.is_none()) in.vertical = motion_name(nb::cast<const GroundMotion&>(vertical));
  in.with_duration = with_duration;
  return io::run_input_json(in, h, g_m_s2);
}

SlidingMode parse_mode(const std::string& mode) { return parse_sliding_mode(mode, "mode"); }

SlidingRun run_slide(const GroundMotion& motion, double mu, std::optional<double> mu_kinetic, const std::string& mode,
                     double slope_deg, const GroundMotion* vertical, double g_m_s2, bool history) {
  SlidingRun run;
  run.block = SlidingBlock::make(mu, mu_kinetic, deg_to_rad(slope_deg), parse_mode(mode), g_m_s2);
  {
    nb::gil_scoped_release release;
    if (history) {
      SlidingResult result = slide(motion, run.block, vertical);
      run.summary = result.summary;
      run.history = std::move(result.history);
    } else {
      run.summary = slide_summary(motion, run.block, vertical);
    }
  }
  run.inputs = RunInputs(motion, vertical);
  return run;
}

/// slide_2d: bidirectional sliding (sliding2d.hpp). The motions are kept alive by their Python objects for the
/// "input" object of json() (io::sliding_2d_input_json, the CLI's).
struct Sliding2dRun {
  Sliding2dSummary summary;
  Sliding2dHistory history;  // empty when run with history=False
  SlidingBlock block;
  ComponentAzimuths azimuths;
  nb::object first, second, vertical;  // vertical: None when absent

  [[nodiscard]] nlohmann::ordered_json json() const {
    nlohmann::ordered_json j = io::sliding_2d_summary_json(summary, block);
    io::RunInput in;
    in.motion = motion_name(nb::cast<const GroundMotion&>(first));
    if (!vertical.is_none()) in.vertical = motion_name(nb::cast<const GroundMotion&>(vertical));
    j["input"] = io::sliding_2d_input_json(in, motion_name(nb::cast<const GroundMotion&>(second)),
                                           nb::cast<const GroundMotion&>(first), nb::cast<const GroundMotion&>(second),
                                           azimuths, block);
    return j;
  }
};

/// azimuths_deg holds the two components' azimuths (InputError naming it otherwise).
void check_two_azimuths(const std::vector<double>& azimuths_deg) {
  if (azimuths_deg.size() != 2) {
    throw parameter_error("azimuths_deg", fmt::format("expected the two components' azimuths in degrees, e.g. (90, 0), "
                                                      "got {} values", azimuths_deg.size()));
  }
}

Sliding2dRun run_slide_2d(const GroundMotion& first, const GroundMotion& second, double mu,
                          std::optional<double> mu_kinetic, const std::vector<double>& azimuths_deg, double slope_deg,
                          std::optional<double> slope_azimuth_deg, const GroundMotion* vertical, double g_m_s2,
                          bool history) {
  check_two_azimuths(azimuths_deg);
  // As the CLI: the fall line's azimuth is required on a slope (no silent guess) and refused on level ground.
  if (slope_deg != 0.0 && !slope_azimuth_deg) {
    throw parameter_error("slope_azimuth_deg", "required with slope_deg: the azimuth of the downslope direction, "
                                               "degrees clockwise from north");
  }
  if (slope_deg == 0.0 && slope_azimuth_deg) {
    throw parameter_error("slope_azimuth_deg", "needs slope_deg (on level ground there is no fall line)");
  }
  Sliding2dRun run;
  run.azimuths = ComponentAzimuths{azimuths_deg[0], azimuths_deg[1], slope_azimuth_deg.value_or(0.0)};
  try {
    run.block = SlidingBlock::make(mu, mu_kinetic, deg_to_rad(slope_deg), SlidingMode::two_way, g_m_s2);
    nb::gil_scoped_release release;
    if (history) {
      Sliding2dResult result = slide_2d(first, second, run.azimuths, run.block, vertical);
      run.summary = result.summary;
      run.history = std::move(result.history);
    } else {
      run.summary = slide_2d_summary(first, second, run.azimuths, run.block, vertical);
    }
  } catch (const InputError& e) {
    // The library names its fields; the caller typed these parameters (as the CLI maps them to its options).
    if (!e.where().file.empty()) throw;
    const std::string& field = e.where().field;
    if (field == "slope") throw parameter_error("slope_deg", e.problem());
    if (field == "slope_azimuth") throw parameter_error("slope_azimuth_deg", e.problem());
    if (field == "first_azimuth" || field == "second_azimuth") throw parameter_error("azimuths_deg", e.problem());
    throw;
  }
  run.first = nb::find(first);
  run.second = nb::find(second);
  run.vertical = vertical != nullptr ? nb::find(*vertical) : nb::none();
  return run;
}

/// slide_flexible: an object on a shelf or floor (support_freq_hz) or SLAMMER's sliding mass (height_m); the dict is
/// `topple slide --support-freq|--height --json` (io::flexible_summary_json plus "input").
nb::dict run_slide_flexible(const GroundMotion& motion, double mu, const std::string& mode,
                            std::optional<double> support_freq_hz, double support_damping, double mass_ratio,
                            std::optional<double> height_m, std::optional<double> vs_slope_m_s,
                            std::optional<double> vs_base_m_s, std::optional<double> damping,
                            std::optional<double> reference_strain, bool coupled, const GroundMotion* vertical,
                            double g_m_s2) {
  if (support_freq_hz.has_value() == height_m.has_value()) {
    throw parameter_error("support_freq_hz", "give either support_freq_hz (shelf, floor) or height_m (sliding mass)");
  }
  const FlexibleAnalysis analysis = coupled ? FlexibleAnalysis::coupled : FlexibleAnalysis::decoupled;
  const SlidingBlock block = SlidingBlock::make(mu, std::nullopt, 0.0, parse_mode(mode), g_m_s2);
  nlohmann::ordered_json j;
  if (support_freq_hz) {
    const SupportOscillator s = SupportOscillator::make(*support_freq_hz, support_damping, mass_ratio);
    FlexibleSummary r;
    {
      nb::gil_scoped_release release;
      r = slide_flexible(motion, s, block, analysis, vertical);
    }
    j = io::flexible_summary_json(r, block, s, analysis);
  } else {
    if (!vs_slope_m_s || !vs_base_m_s || !damping) {
      throw parameter_error("height_m", "a sliding mass needs vs_slope_m_s, vs_base_m_s and damping");
    }
    const SlidingMassColumn c = SlidingMassColumn::make(*height_m, *vs_slope_m_s, *vs_base_m_s, *damping, reference_strain);
    FlexibleSummary r;
    {
      nb::gil_scoped_release release;
      r = slide_flexible(motion, c, mu, analysis, block.mode, g_m_s2, vertical);
    }
    j = io::flexible_summary_json(r, block, c, analysis);
  }
  j["input"] = RunInputs(motion, vertical).json(g_m_s2);
  return nb::cast<nb::dict>(to_python(j));
}

// ---- rocking ----

struct RockingRun {
  RockingResult result;  // history and events empty when run with history=False
  RockingBody body;
  RockingOptions options;
  RunInputs inputs;

  [[nodiscard]] nlohmann::ordered_json json() const {
    nlohmann::ordered_json j = io::rocking_summary_json(result.summary, body, options);
    j["input"] = inputs.json(options.g_m_s2);
    return j;
  }
};

RockingOptions make_rocking_options(const std::variant<double, std::string>& e, std::optional<double> mu,
                                    double g_m_s2, const std::string& method, double rel_tol, int rk4_substeps,
                                    double max_run_out_s);

RockingRun run_rock(const GroundMotion& motion, const RockingBody& body, const std::variant<double, std::string>& e,
                    std::optional<double> mu, double g_m_s2, const std::string& method, double rel_tol,
                    int rk4_substeps, double max_run_out_s, const GroundMotion* vertical, bool history) {
  RockingRun run;
  run.body = body;
  run.options = make_rocking_options(e, mu, g_m_s2, method, rel_tol, rk4_substeps, max_run_out_s);
  {
    nb::gil_scoped_release release;
    if (history) {
      run.result = rock(motion, body, run.options, vertical);
    } else {
      run.result.summary = rock_summary(motion, body, run.options, vertical);
    }
  }
  run.inputs = RunInputs(motion, vertical);
  run.inputs.with_duration = true;
  return run;
}

RockingOptions make_rocking_options(const std::variant<double, std::string>& e, std::optional<double> mu,
                                    double g_m_s2, const std::string& method, double rel_tol, int rk4_substeps,
                                    double max_run_out_s) {
  RockingOptions o;
  o.g_m_s2 = g_m_s2;
  if (const auto* name = std::get_if<std::string>(&e)) {
    const RestitutionChoice choice = parse_restitution(*name, "e");
    o.restitution = choice.mode;
    o.e = choice.e;
  } else {
    o.restitution = RestitutionMode::given;
    o.e = std::get<double>(e);
  }
  o.mu = mu;
  o.method = parse_rocking_method(method, "method");
  o.rel_tol = rel_tol;
  o.rk4_substeps = rk4_substeps;
  o.max_run_out_s = max_run_out_s;
  return o;
}

// ---- coupled slide-rock ----

/// slide_rock: the coupled model (slide_rock.hpp) of a rocking body with friction, as `topple rock --model coupled`.
struct SlideRockRun {
  SlideRockResult result;  // history and transitions empty when run with history=False
  RockingBody shape;       // the body as given (Python's RockingBody)
  SlideRockBody body;
  SlideRockOptions options;
  RunInputs inputs;

  [[nodiscard]] nlohmann::ordered_json json() const {
    nlohmann::ordered_json j = io::slide_rock_summary_json(result.summary, body, options);
    j["input"] = inputs.json(options.g_m_s2);
    return j;
  }
};

SlideRockRun run_slide_rock(const GroundMotion& motion, const RockingBody& shape, double mu,
                            std::optional<double> mu_k, const GroundMotion* vertical,
                            const std::variant<double, std::string>& e, double g_m_s2, double rel_tol,
                            double max_run_out_s, double slope_deg, bool history) {
  SlideRockRun run;
  run.shape = shape;
  run.body = SlideRockBody::from_rocking(shape, mu, mu_k);
  // The restitution, gravity and tolerances as `topple rock` reads them (make_rocking_options), then handed to the
  // coupled model as the CLI does (cli/cmd_rock.cpp).
  const RockingOptions rocking = make_rocking_options(e, std::nullopt, g_m_s2, "adaptive", rel_tol,
                                                      RockingOptions{}.rk4_substeps, max_run_out_s);
  run.options = slide_rock_options(rocking);
  run.options.slope_rad = deg_to_rad(slope_deg);  // validated by slide_rock (field "slope"), as --slope-deg
  run.options.record_history = history;
  {
    nb::gil_scoped_release release;
    run.result = slide_rock(motion, run.body, run.options, vertical);
  }
  run.inputs = RunInputs(motion, vertical);
  run.inputs.with_duration = true;
  return run;
}

/// rock3d: the three-dimensional engine (rigid3d.hpp) for a box, or the rim engine (rigid3d_disc.hpp) for a solid
/// cylinder (diameter_m instead of width_m and depth_m), as `topple rock --model 3d --json` less its "input" (the same
/// keys, in the same order; cli/rock_3d.cpp), plus "history" when asked.
nb::dict run_rock3d(const GroundMotion& first, const GroundMotion* second, std::optional<double> width_m,
                    std::optional<double> depth_m, double height_m, std::optional<double> diameter_m,
                    const std::vector<double>& azimuths_deg, std::optional<double> bearing_deg,
                    const GroundMotion* vertical, const std::variant<double, std::string>& e, double g_m_s2,
                    double rel_tol, std::optional<double> simultaneous_contact, double max_run_out_s, bool history,
                    std::optional<double> mu, std::optional<double> mu_k, double base_incline_deg,
                    double base_incline_azimuth_deg) {
  const auto naming = [](auto f) {
    return with_field_names({{"bearing", "bearing_deg"},
                             {"depth", "depth_m"},
                             {"width", "width_m"},
                             {"height", "height_m"},
                             {"diameter", "diameter_m"},
                             {"azimuths", "azimuths_deg"},
                             {"azimuth", "azimuths_deg"},
                             {"g", "g"},
                             {"rel_tol", "rel_tol"},
                             {"simultaneous_contact", "simultaneous_contact"},
                             {"max_run_out_s", "max_run_out_s"},
                             {"mu_s", "mu"},
                             {"mu_k", "mu_k"},
                             {"base_incline_deg", "base_incline_deg"},
                             {"base_incline_azimuth_deg", "base_incline_azimuth_deg"}},
                            f);
  };
  // The body: a box (width_m, depth_m, height_m) or a solid cylinder (diameter_m, height_m), as the CLI's --shape
  // block --width --depth --height or --shape cylinder --diameter --height.
  const bool cylinder = diameter_m.has_value();
  if (cylinder && (width_m || depth_m)) {
    throw parameter_error(width_m ? "width_m" : "depth_m",
                          "is a box's: a cylinder is given by diameter_m and height_m");
  }
  if (!cylinder && (!width_m || !depth_m)) {
    throw parameter_error(width_m ? "depth_m" : "width_m",
                          "required: a box is given by width_m, depth_m and height_m, a cylinder by diameter_m and "
                          "height_m");
  }
  if (cylinder && bearing_deg) {
    throw parameter_error("bearing_deg", "a cylinder is the same body turned about its axis: it has no bearing (the "
                                         "components act along their azimuths_deg)");
  }
  if (cylinder && simultaneous_contact) {
    throw parameter_error("simultaneous_contact", "is the polygon engine's (a box's corners landing together): a "
                                                  "cylinder's base lands flat on its rim");
  }
  std::optional<CylinderBody3D> disc;
  RigidBody3D box;
  if (cylinder) {
    disc = naming([&] { return CylinderBody3D::solid(*diameter_m, height_m); });
  } else {
    box = naming([&] { return RigidBody3D::box(*width_m, *depth_m, height_m); });
  }
  // The restitution as `rock` takes it ("housner" or a number in [0, 1]); the rocking options check it.
  const RockingOptions rocking = make_rocking_options(e, std::nullopt, g_m_s2, "adaptive", rel_tol,
                                                      RockingOptions{}.rk4_substeps, max_run_out_s);
  Rigid3DOptions options;
  options.g_m_s2 = rocking.g_m_s2;
  options.restitution = rocking.restitution;
  options.e = rocking.e;
  options.rel_tol = rocking.rel_tol;
  options.max_run_out_s = rocking.max_run_out_s;
  if (simultaneous_contact) options.simultaneous_contact = *simultaneous_contact;  // checked by rock3d, [0, 0.01]
  // Coulomb friction (rigid3d.hpp, Rigid3DOptions::mu_s, mu_k): absent, the no-slip engine; checked by rock3d
  // ("mu_s" named as mu, "mu_k" as mu_k).
  options.mu_s = mu;
  options.mu_k = mu_k;
  // An inclined base (rigid3d.hpp, "Inclined base"; the CLI's --base-incline-deg, --base-incline-azimuth-deg):
  // checked by rock3d; the cylinder's rim engine has a level base.
  if (cylinder && base_incline_deg != 0.0) {
    throw parameter_error("base_incline_deg", "the cylinder's rim engine (rigid3d_disc.hpp) has a level base: an "
                                              "inclined base is a box's");
  }
  options.base_incline_deg = base_incline_deg;
  options.base_incline_azimuth_deg = base_incline_azimuth_deg;
  options.record_history = history;
  Rigid3DResult r;
  if (second != nullptr) {
    // As the CLI: the pair along east and north (eq. M1); a box turned so that its +x axis points to the bearing, a
    // cylinder (axisymmetric) as it is.
    check_two_azimuths(azimuths_deg);
    if (!cylinder && !bearing_deg) {
      throw parameter_error("bearing_deg", "required with a second component: the azimuth of the box's +x axis "
                                           "(across its width), degrees clockwise from north");
    }
    if (bearing_deg && !std::isfinite(*bearing_deg)) {
      throw parameter_error("bearing_deg", fmt::format("must be finite, got {}", *bearing_deg));
    }
    const MotionSet set = naming([&] {
      return MotionSet::make(first, second, ComponentAzimuths{azimuths_deg[0], azimuths_deg[1]}, vertical);
    });
    const GroundMotion east = set.projected(90.0);
    const GroundMotion north = set.projected(0.0);
    if (cylinder) {
      r = naming([&] {
        nb::gil_scoped_release release;
        return rock3d_cylinder(east, &north, set.vertical_ptr(), *disc, options);
      });
    } else {
      const RigidBody3D turned = box.rotated_about_vertical(deg_to_rad(90.0 - *bearing_deg));
      r = naming([&] {
        nb::gil_scoped_release release;
        return rock3d(east, &north, set.vertical_ptr(), turned, options);
      });
    }
  } else {
    if (bearing_deg) throw parameter_error("bearing_deg", "applies with a second component (second=...)");
    r = naming([&] {
      nb::gil_scoped_release release;
      return cylinder ? rock3d_cylinder(first, nullptr, vertical, *disc, options)
                      : rock3d(first, nullptr, vertical, box, options);
    });
  }
  const Rigid3DSummary& s = r.summary;
  const auto opt = [](const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; };
  nlohmann::ordered_json j = io::rigid3d_summary_json(s);
  if (cylinder) {  // as cli/rock_3d.cpp
    j["body"] = {{"shape", "cylinder"}, {"diameter_m", *diameter_m}, {"height_m", height_m}, {"bearing_deg", nullptr}};
  } else {
    j["body"] = {{"shape", "block"}, {"width_m", *width_m}, {"depth_m", *depth_m}, {"height_m", height_m},
                 {"bearing_deg", opt(bearing_deg)}};
  }
  j["solver"] = io::rigid3d_solver_json(options, cylinder);
  if (history) {
    const Rigid3DHistory& h = r.history;
    nlohmann::ordered_json hj;
    hj["time_s"] = h.time_s;
    nlohmann::ordered_json pos = nlohmann::ordered_json::array(), q = nlohmann::ordered_json::array(),
                           w = nlohmann::ordered_json::array(), mode = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < h.time_s.size(); ++i) {
      pos.push_back(h.position_m[i]);
      q.push_back(h.orientation[i]);
      w.push_back(h.angular_velocity_rad_s[i]);
      mode.push_back(rigid3d_mode_name(h.mode[i]));
    }
    hj["position_m"] = pos;
    hj["orientation_wxyz"] = q;
    hj["angular_velocity_rad_s"] = w;
    hj["energy_j_per_kg"] = h.energy_j_per_kg;
    hj["mode"] = mode;
    j["history"] = hj;
  }
  return nb::cast<nb::dict>(to_python(j));
}

/// rock_oriented: an oriented object under two components (oriented.hpp), as `topple rock H1 --h2 H2 --json` less
/// its "input": the governing direction's summary and the "orientation" object.
nb::dict run_rock_oriented(const GroundMotion& first, const GroundMotion& second, const RockingBody& body,
                           const std::vector<double>& azimuths_deg, std::optional<double> bearing_deg,
                           std::optional<double> depth_m, std::optional<double> direction_step_deg,
                           const GroundMotion* vertical, const std::variant<double, std::string>& e,
                           std::optional<double> mu, double g_m_s2, const std::string& method, double rel_tol,
                           int rk4_substeps, double max_run_out_s) {
  check_two_azimuths(azimuths_deg);
  const ComponentAzimuths azimuths{azimuths_deg[0], azimuths_deg[1]};
  // The library names its fields; the caller typed these parameters.
  const auto naming = [](auto f) {
    return with_field_names({{"bearing", "bearing_deg"},
                             {"depth", "depth_m"},
                             {"cylinder_step", "direction_step_deg"},
                             {"azimuths", "azimuths_deg"},
                             {"azimuth", "azimuths_deg"}},
                            f);
  };
  const OrientedBody oriented = naming([&] { return OrientedBody::make(body, depth_m); });
  naming([&] { check_orientation(oriented, bearing_deg, direction_step_deg.has_value()); });
  OrientationOptions orientation;
  if (direction_step_deg) orientation.cylinder_step_deg = *direction_step_deg;
  const RockingOptions options = make_rocking_options(e, mu, g_m_s2, method, rel_tol, rk4_substeps, max_run_out_s);
  const MotionSet set = naming([&] { return MotionSet::make(first, &second, azimuths, vertical); });
  const OrientedRockingSummary summary = naming([&] {
    nb::gil_scoped_release release;
    return rock_oriented_summary(set, oriented, bearing_deg.value_or(0.0), options, orientation);
  });
  const DirectionResponse& governing = summary.governing_response();
  nlohmann::ordered_json j = io::rocking_summary_json(governing.summary, planar_body_of(oriented, governing.axis), options);
  j["orientation"] = io::oriented_rocking_json(summary, oriented, bearing_deg, azimuths, orientation);
  return nb::cast<nb::dict>(to_python(j));
}

// ---- intensity (the measures of `topple info`, undefined ones as None) ----

nb::dict intensity_dict(const GroundMotion& motion, double g_m_s2) {
  IntensityMeasures im;
  {
    nb::gil_scoped_release release;
    im = intensity_measures(motion, g_m_s2);
  }
  // The keys and values of `topple info --json` (its measures after the record's metadata): one field table.
  nb::dict d;
  for (const Field<IntensityOutcome>& field : kIntensityFields) {
    d[field.name] = field_to_python(field.get(IntensityOutcome{motion, im, g_m_s2}));
  }
  return d;
}

/// A 2-D numpy array (row-major, rows x cols) owning `values`.
template <class T>
nb::ndarray<nb::numpy, T, nb::ndim<2>> to_numpy_2d(std::vector<T> values, std::size_t rows, std::size_t cols) {
  auto owned = std::make_unique<std::vector<T>>(std::move(values));
  T* data = owned->data();
  nb::capsule owner(owned.get(), [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  owned.release();
  return nb::ndarray<nb::numpy, T, nb::ndim<2>>(data, {rows, cols}, owner);
}

// ---- motion sets and RotD ----

/// azimuths_deg = (first, second), degrees clockwise from north, or None (unknown).
std::optional<ComponentAzimuths> azimuths_arg(const std::optional<std::vector<double>>& azimuths_deg) {
  if (!azimuths_deg) return std::nullopt;
  if (azimuths_deg->size() != 2) {
    throw parameter_error("azimuths_deg", fmt::format("expected the two horizontal components' azimuths in degrees, "
                                                      "e.g. (90, 0), got {} values", azimuths_deg->size()));
  }
  return ComponentAzimuths{(*azimuths_deg)[0], (*azimuths_deg)[1]};
}

/// Runs `f` with a motion set's fields renamed to the Python parameters the caller typed: "azimuths" -> azimuths_deg,
/// "azimuth" -> azimuth_deg (with_field_names, error.hpp; errors located in a file are kept).
template <class F>
auto with_set_fields(F&& f) -> decltype(f()) {
  return with_field_names({{"azimuths", "azimuths_deg"}, {"azimuth", "azimuth_deg"}}, std::forward<F>(f));
}

MotionSet make_motion_set(const GroundMotion& first, const GroundMotion* second, const GroundMotion* vertical,
                          const std::optional<std::vector<double>>& azimuths_deg) {
  const std::optional<ComponentAzimuths> azimuths = azimuths_arg(azimuths_deg);
  return with_set_fields([&] { return MotionSet::make(first, second, azimuths, vertical); });
}

nb::object azimuths_to_python(const MotionSet& set) {
  const auto& az = set.azimuths();
  return az ? nb::object(nb::make_tuple(az->first_deg, az->second_deg)) : nb::none();
}

/// RotD50 / RotD100 of a set's pair (rotd.hpp, rotd_measures): the numbers `topple info H1 H2 --json` prints under
/// "rotd", in m/s^2 and in g, and the values at every angle.
nb::dict rotd_dict(const MotionSet& set, nb::handle periods, double damping, double g_m_s2) {
  if (!(g_m_s2 > 0.0) || !std::isfinite(g_m_s2)) throw parameter_error("g", "g must be a finite number > 0 (m/s^2)");
  const std::vector<double> p = periods.is_none() ? rotd_periods_s() : to_vector(periods, "periods_s");
  RotDMeasures r;
  {
    nb::gil_scoped_release release;
    r = with_set_fields([&] { return rotd_measures(set, p, damping); });
  }
  const std::size_t n_angles = r.pga_by_angle_m_s2.size();
  const std::size_t n_periods = r.psa_m_s2.size();
  std::vector<double> psa50(n_periods), psa100(n_periods), psa50_g(n_periods), psa100_g(n_periods),
      psa_angle(n_periods), psa_by_angle;
  nb::list psa_azimuth;
  psa_by_angle.reserve(n_periods * n_angles);
  for (std::size_t k = 0; k < n_periods; ++k) {
    const RotDValue& v = r.psa_m_s2[k];
    psa50[k] = v.rotd50;
    psa100[k] = v.rotd100;
    psa50_g[k] = v.rotd50 / g_m_s2;
    psa100_g[k] = v.rotd100 / g_m_s2;
    psa_angle[k] = v.rotd100_angle_deg;
    psa_azimuth.append(optional_float(rotd_azimuth_deg(set, v.rotd100_angle_deg)));
    psa_by_angle.insert(psa_by_angle.end(), r.psa_by_angle_m_s2[k].begin(), r.psa_by_angle_m_s2[k].end());
  }
  nb::dict d;
  d["angles_deg"] = to_numpy(rotd_angles_deg());
  d["pga_rotd50_m_s2"] = r.pga_m_s2.rotd50;
  d["pga_rotd100_m_s2"] = r.pga_m_s2.rotd100;
  d["pga_rotd50_g"] = r.pga_m_s2.rotd50 / g_m_s2;
  d["pga_rotd100_g"] = r.pga_m_s2.rotd100 / g_m_s2;
  d["pga_rotd100_angle_deg"] = r.pga_m_s2.rotd100_angle_deg;
  d["pga_rotd100_azimuth_deg"] = optional_float(rotd_azimuth_deg(set, r.pga_m_s2.rotd100_angle_deg));
  d["pga_by_angle_m_s2"] = to_numpy(std::move(r.pga_by_angle_m_s2));
  d["period_s"] = to_numpy(std::move(r.period_s));
  d["damping"] = r.damping;
  d["psa_rotd50_m_s2"] = to_numpy(std::move(psa50));
  d["psa_rotd100_m_s2"] = to_numpy(std::move(psa100));
  d["psa_rotd50_g"] = to_numpy(std::move(psa50_g));
  d["psa_rotd100_g"] = to_numpy(std::move(psa100_g));
  d["psa_rotd100_angle_deg"] = to_numpy(std::move(psa_angle));
  d["psa_rotd100_azimuth_deg"] = psa_azimuth;
  d["psa_by_angle_m_s2"] = to_numpy_2d(std::move(psa_by_angle), n_periods, n_angles);
  d["merged_npts"] = set.size();
  d["azimuths_deg"] = azimuths_to_python(set);
  d["g_m_s2"] = g_m_s2;
  return d;
}

/// synth: one motion (components=1, synthesize) or a horizontal pair and optionally a vertical (synthesize_set) as
/// a MotionSet. The set-only parameters are refused with components=1, the vertical's with components=2: a value
/// that would be ignored is a silent guess.
nb::object run_synth(double pga_g, double freq_hz, double duration_s, std::uint64_t seed, double dt_s,
                     const std::string& model, const std::string& envelope, double zeta_g, double g, int components,
                     std::optional<double> coherence, std::optional<std::vector<double>> azimuths_deg,
                     std::optional<double> vh_ratio, std::optional<double> vh_freq_ratio) {
  SynthesisSpec spec;
  spec.pga_m_s2 = pga_g * g;
  spec.predominant_frequency_hz = freq_hz;
  spec.duration_s = duration_s;
  spec.dt_s = dt_s;
  spec.seed = seed;
  spec.model = parse_filter_model(model, "model");
  spec.envelope = parse_envelope_kind(envelope, "envelope");
  spec.ground_damping = zeta_g;
  const auto in_g = [g](GroundMotion motion) {
    RecordMetadata meta = motion.metadata();
    meta.g_m_s2 = g;  // pga_g and accel_g are in the g it was asked in
    motion.set_metadata(std::move(meta));
    return motion;
  };
  if (components == 1) {
    for (const auto& [name, given] : {std::pair{"coherence", coherence.has_value()},
                                      std::pair{"azimuths_deg", azimuths_deg.has_value()},
                                      std::pair{"vh_ratio", vh_ratio.has_value()},
                                      std::pair{"vh_freq_ratio", vh_freq_ratio.has_value()}}) {
      if (given) throw parameter_error(name, "is for components=2 or 3 (a horizontal pair)");
    }
    GroundMotion motion = [&] {
      nb::gil_scoped_release release;
      return synthesize(spec);
    }();
    return nb::cast(in_g(std::move(motion)));
  }
  if (components != 2 && components != 3) {
    throw parameter_error("components", fmt::format("1, 2 (a horizontal pair) or 3 (and a vertical), got {}",
                                                    components));
  }
  if (components == 2) {
    if (vh_ratio) throw parameter_error("vh_ratio", "is for components=3 (with a vertical)");
    if (vh_freq_ratio) throw parameter_error("vh_freq_ratio", "is for components=3 (with a vertical)");
  }
  SynthesisSetSpec set_spec;  // its defaults are the library's (synthesis.hpp)
  set_spec.horizontal = spec;
  if (coherence) set_spec.coherence = *coherence;
  if (const auto az = azimuths_arg(azimuths_deg)) set_spec.azimuths = *az;
  set_spec.vertical = components == 3;
  if (vh_ratio) set_spec.vertical_pga_ratio = *vh_ratio;
  if (vh_freq_ratio) set_spec.vertical_frequency_ratio = *vh_freq_ratio;
  std::optional<SynthesizedSet> made;
  try {
    nb::gil_scoped_release release;
    made.emplace(synthesize_set(set_spec));
  } catch (const InputError& e) {
    // The library names its fields; the caller typed these parameters.
    const std::string& field = e.where().field;
    if (field == "azimuths") throw parameter_error("azimuths_deg", e.problem());
    if (field == "vertical_pga_ratio") throw parameter_error("vh_ratio", e.problem());
    if (field == "vertical_frequency_ratio" || field.starts_with("vertical ")) {
      throw parameter_error("vh_freq_ratio", e.problem());
    }
    throw;
  }
  const GroundMotion first = in_g(std::move(made->first));
  const GroundMotion second = in_g(std::move(made->second));
  const std::optional<GroundMotion> vertical =
      made->vertical ? std::optional(in_g(std::move(*made->vertical))) : std::nullopt;
  return nb::cast(MotionSet::make(first, &second, set_spec.azimuths, vertical ? &*vertical : nullptr));
}

// ---- inversion ----

/// The library's survey entry point as `topple invert` runs it (survey_inversion.hpp: invert_survey), in one process
/// and without the GIL: every site with objects inverted, then the regional fit of a multi-site survey.
SurveyInversion run_invert_survey(const Survey& survey, int threads, const RegionalSettings& settings) {
  nb::gil_scoped_release release;
  ensemble::SingleProcess one;
  return invert_survey(survey, InversionOptions{threads}, one, settings);
}

/// The inversion of a survey read by the library (io::read_survey or io::parse_survey: the same validation and
/// messages as the CLI), run and written by the library as `topple invert` does: the dict is its --json
/// (io::survey_inversion_json, without provenance); stations without objects get no result and no report. Optionally
/// with the HTML report written by write_survey_report as `topple invert --report` does (folders by
/// site_report_folder, the regional page; its warnings as RuntimeWarning).
nb::object invert_survey_dict(const Survey& survey, int threads, const std::optional<std::string>& report_dir) {
  const RegionalSettings region_settings;
  const SurveyInversion inv = run_invert_survey(survey, threads, region_settings);
  if (report_dir) {
    SurveyReport report;
    {
      nb::gil_scoped_release release;
      report = write_survey_report(*report_dir, survey, inv, std::nullopt, region_settings);
    }
    for (const std::string& w : report.warnings) {
      if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 1) != 0) throw nb::python_error();
    }
  }
  nb::dict all = nb::cast<nb::dict>(to_python(io::survey_inversion_json(survey, inv, std::nullopt, region_settings)));
  // Beyond the CLI's JSON: each site's grids, rows = PGA, columns = frequency (for topple.plot.inversion_map), in the
  // site's object (several sites: "sites"[k]; one site: the top).
  const bool multi = survey.sites.size() > 1;
  nb::list sites = multi ? nb::cast<nb::list>(all["sites"]) : nb::list();
  for (std::size_t k = 0; k < inv.results.size(); ++k) {
    const InversionResult& r = inv.results[k];
    nb::dict d = multi ? nb::cast<nb::dict>(sites[k]) : all;
    const std::size_t rows = r.pga_g.size();
    const std::size_t cols = r.freq_hz.size();
    d["posterior_grid"] = to_numpy_2d(r.posterior, rows, cols);
    d["log_likelihood_grid"] = to_numpy_2d(r.log_likelihood, rows, cols);
    // Each object's P(observation | cell), same layout: its 0.5 line is the map's per-object threshold line.
    nb::list objects = nb::cast<nb::list>(d["objects"]);
    for (std::size_t j = 0; j < r.objects.size() && j < objects.size(); ++j) {
      objects[j]["probability_grid"] = to_numpy_2d(r.objects[j].probability, rows, cols);
    }
  }
  return all;
}

/// A survey file read by the library (the options checked first, as the CLI does), without the GIL.
Survey survey_from_file(const std::string& path, int threads) {
  validate_inversion_options(InversionOptions{threads});
  nb::gil_scoped_release release;
  return io::read_survey(path);
}

/// A survey given as TOML text (name for messages, base_dir for records), likewise.
Survey survey_from_text(const std::string& text, const std::string& name, const std::string& base_dir, int threads) {
  validate_inversion_options(InversionOptions{threads});
  nb::gil_scoped_release release;
  Survey survey = io::parse_survey(text, name, base_dir);
  io::load_survey_records(survey);
  return survey;
}

nb::object invert_file(const std::string& path, int threads, const std::optional<std::string>& report_dir) {
  return invert_survey_dict(survey_from_file(path, threads), threads, report_dir);
}

nb::object invert_text(const std::string& text, const std::string& name, const std::string& base_dir, int threads,
                       const std::optional<std::string>& report_dir) {
  return invert_survey_dict(survey_from_text(text, name, base_dir, threads), threads, report_dir);
}

// ---- the regional inversion ----

/// A multi-site survey's inversion and regional fit as `topple invert --json` makes them (run_invert_survey,
/// one process): the `region` object (relation, frequency_relation, sites pooled beside their own estimates,
/// contour_levels_g, notes), plus region_notes and each site's own inversion (site_results, None for a station
/// without objects). A survey that gets no regional fit (no epicentre, fewer than 3 located sites) raises InputError
/// with the reason.
nb::object invert_region_survey(const Survey& survey, const std::string& where, int threads) {
  const RegionalSettings settings;
  const SurveyInversion inv = run_invert_survey(survey, threads, settings);
  if (!inv.region) {
    std::string why = inv.region_notes.empty() ? std::string("a regional fit needs a multi-site survey") : inv.region_notes.front();
    throw InputError(InputLocation{where, {}, "region"}, why);
  }
  const std::vector<const InversionResult*> per_site = inv.per_site(survey.sites.size());
  nb::dict d = nb::cast<nb::dict>(to_python(io::region_json(*inv.region, survey, per_site, settings)));
  nb::list notes;
  for (const std::string& n : inv.region_notes) notes.append(n);
  d["region_notes"] = notes;
  nb::list sites;
  for (std::size_t i = 0; i < survey.sites.size(); ++i) {
    if (per_site[i] == nullptr) {
      sites.append(nb::none());
    } else {
      sites.append(to_python(io::inversion_json(*per_site[i], survey.sites[i])));
    }
  }
  d["site_results"] = sites;
  return d;
}

nb::object invert_region_file(const std::string& path, int threads) {
  return invert_region_survey(survey_from_file(path, threads), path, threads);
}

nb::object invert_region_text(const std::string& text, const std::string& name, const std::string& base_dir,
                              int threads) {
  return invert_region_survey(survey_from_text(text, name, base_dir, threads), name, threads);
}

// ---- spectra of a motion ----


nb::dict response_spectrum_dict(const GroundMotion& motion, nb::handle periods, double damping, double g_m_s2) {
  const std::vector<double> p = periods.is_none() ? tp_periods_s() : to_vector(periods, "periods_s");
  if (!(g_m_s2 > 0.0) || !std::isfinite(g_m_s2)) throw parameter_error("g", "g must be a finite number > 0 (m/s^2)");
  ResponseSpectrum s;
  {
    nb::gil_scoped_release release;
    s = response_spectrum(motion, p, damping);
  }
  std::vector<double> psa_g(s.psa_m_s2);
  for (double& v : psa_g) v /= g_m_s2;
  nb::dict d;
  d["period_s"] = to_numpy(std::move(s.period_s));
  d["damping"] = s.damping;
  d["sd_m"] = to_numpy(std::move(s.sd_m));
  d["psv_m_s"] = to_numpy(std::move(s.psv_m_s));
  d["psa_m_s2"] = to_numpy(std::move(s.psa_m_s2));
  d["psa_g"] = to_numpy(std::move(psa_g));
  d["sv_m_s"] = to_numpy(std::move(s.sv_m_s));
  d["sa_m_s2"] = to_numpy(std::move(s.sa_m_s2));
  d["g_m_s2"] = g_m_s2;
  d["motion"] = motion_name(motion);
  return d;
}

nb::dict fourier_spectrum_dict(const GroundMotion& motion, std::optional<double> smoothing_b, nb::handle centre_hz,
                               std::optional<std::size_t> fft_length) {
  std::vector<double> centres;
  if (!centre_hz.is_none()) centres = to_vector(centre_hz, "centre_hz");
  if (smoothing_b && !(*smoothing_b > 0.0 && std::isfinite(*smoothing_b))) {
    throw parameter_error("smoothing_b", fmt::format("the Konno-Ohmachi bandwidth b must be a finite number > 0, got {}",
                                                     *smoothing_b));
  }
  FourierSpectrum fas;
  std::vector<double> smooth;
  std::optional<double> fp;
  {
    nb::gil_scoped_release release;
    const GroundMotion uniform = motion.to_uniform();
    fas = fourier_amplitude_spectrum(uniform,
                                     fft_length.value_or(predominant_frequency_fft_length(uniform.size())));
    if (smoothing_b) {
      if (centre_hz.is_none()) centres = predominant_frequency_centres_hz(uniform.dt_s());
      smooth = konno_ohmachi_smooth(fas, centres, *smoothing_b);
    }
    try {
      fp = predominant_frequency_hz(motion);
    } catch (const InputError&) {
      fp.reset();
    }
  }
  nb::dict d;
  d["freq_hz"] = to_numpy(std::move(fas.frequency_hz));
  d["amplitude_m_s"] = to_numpy(std::move(fas.amplitude_m_s));
  d["dt_s"] = fas.dt_s;
  d["fft_length"] = fas.fft_length;
  d["smoothing_b"] = smoothing_b ? nb::cast(*smoothing_b) : nb::none();
  if (smoothing_b) {
    d["smoothed_freq_hz"] = to_numpy(std::move(centres));
    d["smoothed_amplitude_m_s"] = to_numpy(std::move(smooth));
  } else {
    d["smoothed_freq_hz"] = nb::none();
    d["smoothed_amplitude_m_s"] = nb::none();
  }
  d["predominant_frequency_hz"] = optional_float(fp);
  d["motion"] = motion_name(motion);
  return d;
}

// ---- object spectra ----

nb::dict sliding_spectrum_dict(const GroundMotion& motion, nb::handle mu, double slope_deg, const std::string& mode,
                               double g_m_s2) {
  const std::vector<double> mus = to_vector(mu, "mu");
  const SlidingMode sliding_mode = parse_mode(mode);
  SlidingSpectrum s;
  {
    nb::gil_scoped_release release;
    s = sliding_spectrum(motion, mus, deg_to_rad(slope_deg), sliding_mode, g_m_s2);
  }
  const std::size_t n = s.points.size();
  std::vector<double> mu_out(n), yield_g(n), yield_over(n), max_abs(n), residual(n), slip_s(n);
  std::vector<std::int64_t> episodes(n);
  std::vector<bool> at_rest(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SlidingSpectrumPoint& p = s.points[i];
    mu_out[i] = p.mu;
    yield_g[i] = p.yield_accel_g;
    yield_over[i] = p.yield_over_pga;
    max_abs[i] = p.max_abs_displacement_m;
    residual[i] = p.residual_displacement_m;
    slip_s[i] = p.total_slip_duration_s;
    episodes[i] = p.slip_episodes;
    at_rest[i] = p.at_rest_at_end;
  }
  std::vector<std::uint8_t> rest_bytes(at_rest.begin(), at_rest.end());
  nb::dict d;
  d["mu"] = to_numpy(std::move(mu_out));
  d["max_abs_displacement_m"] = to_numpy(std::move(max_abs));
  d["residual_displacement_m"] = to_numpy(std::move(residual));
  d["yield_accel_g"] = to_numpy(std::move(yield_g));
  d["yield_over_pga"] = to_numpy(std::move(yield_over));
  d["slip_episodes"] = to_numpy(std::move(episodes));
  d["total_slip_duration_s"] = to_numpy(std::move(slip_s));
  d["at_rest_at_end"] = nb::module_::import_("numpy").attr("asarray")(to_numpy(std::move(rest_bytes)), "bool");
  d["pga_g"] = s.pga_m_s2 / s.g_m_s2;
  d["slope_deg"] = slope_deg;
  d["mode"] = mode;
  d["g_m_s2"] = s.g_m_s2;
  d["motion"] = motion_name(motion);  // for the figure's title (topple.plot.sliding_spectrum)
  return d;
}

/// slide_spectrum_2d: the bidirectional spectrum (object_spectra.hpp, sliding_spectrum_2d) of a pair, as the dict of
/// `topple spectrum slide H1 --h2 H2 --json` (io::sliding_spectrum_2d_json) with the main columns also as arrays.
nb::dict sliding_spectrum_2d_dict(const GroundMotion& first, const GroundMotion& second, nb::handle mu,
                                  const std::vector<double>& azimuths_deg, const GroundMotion* vertical, double g_m_s2) {
  const std::vector<double> mus = to_vector(mu, "mu");
  check_two_azimuths(azimuths_deg);
  const MotionSet set = make_motion_set(first, &second, vertical, azimuths_deg);
  SlidingSpectrum2d s;
  {
    nb::gil_scoped_release release;
    s = with_set_fields([&] { return sliding_spectrum_2d(set, mus, g_m_s2); });
  }
  nb::dict d = nb::cast<nb::dict>(to_python(io::sliding_spectrum_2d_json(s, motion_name(first), motion_name(second))));
  // Columns for plotting, one value per mu in the given order (the same numbers as "points").
  const auto column = [&s](auto get) {
    std::vector<double> v;
    v.reserve(s.points.size());
    for (const SlidingSpectrum2dPoint& p : s.points) v.push_back(get(p));
    return to_numpy(std::move(v));
  };
  using P = SlidingSpectrum2dPoint;
  d["mu"] = column([](const P& p) { return p.mu; });
  d["ky_over_rotd50_pga"] = column([](const P& p) { return p.yield_over_rotd50_pga; });
  d["max_abs_displacement_m"] = column([](const P& p) { return p.bidirectional.max_abs_displacement_m; });
  d["residual_displacement_m"] = column([](const P& p) { return p.bidirectional.residual_displacement_m; });
  d["h1_max_abs_displacement_m"] = column([](const P& p) { return p.first_alone.max_abs_displacement_m; });
  d["h2_max_abs_displacement_m"] = column([](const P& p) { return p.second_alone.max_abs_displacement_m; });
  return d;
}

RockingBody::Shape parse_family_shape(const std::string& shape) {
  if (shape != "general") return parse_shape(shape, "shape");
  throw parameter_error("shape", fmt::format("unknown shape '{}' for a body family (known: block, cylinder)", shape));
}

nb::dict overturning_map_dict(const GroundMotion& motion, double alpha_rad, nb::handle heights_m, nb::handle pga_g,
                              const std::string& shape, const std::variant<double, std::string>& e,
                              std::optional<double> mu, double g_m_s2, const std::string& method, double rel_tol,
                              int rk4_substeps, double max_run_out_s, int threads) {
  BodyFamily family;
  family.shape = parse_family_shape(shape);
  family.alpha_rad = alpha_rad;
  family.heights_m = to_vector(heights_m, "heights_m");
  std::vector<double> pga = to_vector(pga_g, "pga_g");
  for (double& v : pga) v *= g_m_s2;
  OverturningMapOptions options;
  options.rocking = make_rocking_options(e, mu, g_m_s2, method, rel_tol, rk4_substeps, max_run_out_s);
  options.threads = threads;
  OverturningMap map;
  {
    nb::gil_scoped_release release;
    map = overturning_map(motion, family, pga, options);
  }
  const std::size_t n_size = map.sizes.size();
  const std::size_t n_pga = map.pga_m_s2.size();
  std::vector<double> pga_out(map.pga_m_s2), height(n_size), width(n_size), R(n_size), p(n_size), first(n_size);
  for (double& v : pga_out) v /= map.g_m_s2;
  std::vector<std::uint8_t> standing(n_size);
  std::vector<std::int64_t> count(n_size);
  for (std::size_t i = 0; i < n_size; ++i) {
    const OverturningSize& s = map.sizes[i];
    height[i] = s.height_m;
    width[i] = s.width_m;
    R[i] = s.R_m;
    p[i] = s.p_rad_s;
    first[i] = s.first_overturn_pga_m_s2 ? *s.first_overturn_pga_m_s2 / map.g_m_s2 : std::nan("");
    standing[i] = s.standing_above_first ? 1 : 0;
    count[i] = static_cast<std::int64_t>(s.overturn_count);
  }
  nb::object as_bool = nb::module_::import_("numpy").attr("asarray");
  nb::dict d;
  d["pga_g"] = to_numpy(std::move(pga_out));
  d["pga_m_s2"] = to_numpy(std::vector<double>(map.pga_m_s2));
  d["height_m"] = to_numpy(std::move(height));
  d["width_m"] = to_numpy(std::move(width));
  d["R_m"] = to_numpy(std::move(R));
  d["p_rad_s"] = to_numpy(std::move(p));
  d["first_overturn_pga_g"] = to_numpy(std::move(first));
  d["standing_above_first"] = as_bool(to_numpy(std::move(standing)), "bool");
  d["overturn_count"] = to_numpy(std::move(count));
  d["overturned"] = as_bool(to_numpy_2d(std::vector<std::uint8_t>(map.overturned), n_size, n_pga), "bool");
  d["max_rotation_over_alpha"] = to_numpy_2d(std::vector<double>(map.max_rotation_over_alpha), n_size, n_pga);
  d["alpha_rad"] = map.alpha_rad;
  d["uplift_pga_g"] = std::tan(map.alpha_rad);
  d["shape"] = std::string(shape_name(map.shape));
  d["g_m_s2"] = map.g_m_s2;
  d["motion"] = motion_name(motion);
  return d;
}

// ---- fragility ----

/// Integers: a sequence (list, tuple, numpy integer array) whose items are Python or numpy integers (a float is
/// refused, not truncated).
std::vector<int> to_int_vector(nb::handle obj, const char* name) {
  if (nb::ndarray_check(obj) || nb::isinstance<nb::list>(obj) || nb::isinstance<nb::tuple>(obj)) {
    std::vector<int> out;
    for (nb::handle item : obj) {
      nb::object index = nb::steal(PyNumber_Index(item.ptr()));
      if (!index.is_valid()) {
        PyErr_Clear();
        throw nb::type_error(fmt::format("{}: every element must be an integer, got {}", name,
                                         nb::type_name(item.type()).c_str()).c_str());
      }
      const long long v = PyLong_AsLongLong(index.ptr());
      if (PyErr_Occurred() || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
        PyErr_Clear();
        throw nb::value_error(fmt::format("{}: an element is out of range", name).c_str());
      }
      out.push_back(static_cast<int>(v));
    }
    return out;
  }
  throw nb::type_error(fmt::format("{} must be a list or numpy array of integers, got {}", name,
                                   nb::type_name(obj.type()).c_str()).c_str());
}

/// A float for a Python number, else a float64 array of f applied to each element of the array-like.
template <class F>
nb::object map_im(nb::handle im, F f) {
  if (PyFloat_Check(im.ptr()) || PyLong_Check(im.ptr())) return nb::cast(f(nb::cast<double>(im)));
  std::vector<double> x = to_vector(im, "im");
  for (double& v : x) v = f(v);
  return nb::cast(to_numpy(std::move(x)));
}

/// The IM's display unit in SI: g for PGA, 1 otherwise (m/s, m, m/s).
double im_unit(IntensityMeasure im, double g_m_s2) { return 1.0 / intensity_measure_display_factor(im, g_m_s2); }

/// The fit with theta in the display unit (ln theta shifts by a constant: standard errors are unchanged).
LognormalFragilityFit fit_in_unit(LognormalFragilityFit fit, double unit) {
  fit.theta /= unit;
  return fit;
}

/// A fit at its beta bound is not an estimate of the dispersion (fragility.hpp: separated data): say so with the
/// numbers, as a RuntimeWarning (an error under `warnings.simplefilter("error")`).
void warn_if_beta_at_bound(const LognormalFragilityFit& fit, const std::string& what, const std::string& unit) {
  if (!fit.beta_at_bound) return;
  const std::string message = fmt::format(
      "{}: beta = {:g} is at its lower bound {:g} (theta = {:.4g}{}{}): the counts are separated (every level "
      "all-fail or none-fail), so beta and the band are not estimated; add levels between the last none-fail and "
      "the first all-fail level",
      what, fit.beta, kMinimumBeta, fit.theta, unit.empty() ? "" : " ", unit);
  if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw nb::python_error();
}

nb::dict fragility_dict(nb::handle motions, nb::handle levels, const std::string& im,
                        std::optional<double> mu, std::optional<double> threshold_m, std::optional<double> mu_kinetic,
                        const std::string& mode, double slope_deg, const std::optional<RockingBody>& body,
                        const std::variant<double, std::string>& e, std::optional<double> rock_mu, double g_m_s2,
                        const std::string& method, double rel_tol, int rk4_substeps, double max_run_out_s,
                        int threads, std::optional<double> bearing_deg, std::optional<std::uint64_t> bearing_seed) {
  FragilitySpec spec;
  spec.im = parse_intensity_measure(im, "im");
  const double unit = im_unit(spec.im, g_m_s2);
  spec.levels_si = to_vector(levels, "levels");
  for (double& v : spec.levels_si) v *= unit;
  if (nb::isinstance<GroundMotion>(motions) || nb::isinstance<MotionSet>(motions) ||
      !(nb::isinstance<nb::list>(motions) || nb::isinstance<nb::tuple>(motions))) {
    throw nb::type_error("motions must be a list of topple.GroundMotion, or of topple.MotionSet (pairs), the ensemble");
  }
  // One kind per ensemble: records (one component) or pairs (fragility.hpp, "Pairs"); the first element decides.
  const bool pairs = nb::len(motions) > 0 && nb::isinstance<MotionSet>(motions[0]);
  for (nb::handle item : motions) {
    if (pairs && nb::isinstance<MotionSet>(item)) {
      spec.motion_sets.push_back(std::make_shared<const MotionSet>(nb::cast<const MotionSet&>(item)));
    } else if (!pairs && nb::isinstance<GroundMotion>(item)) {
      spec.motions.push_back(std::make_shared<const GroundMotion>(nb::cast<const GroundMotion&>(item)));
    } else {
      throw nb::type_error(fmt::format("motions: every element must be a topple.{} (one kind per ensemble: the first "
                                       "is one), got {}", pairs ? "MotionSet" : "GroundMotion",
                                       nb::type_name(item.type()).c_str()).c_str());
    }
  }
  if (!pairs) {
    // A value that would be ignored is a silent guess (as `topple fragility` refuses --bearing-deg without pairs).
    for (const auto& [name, given] : {std::pair{"bearing_deg", bearing_deg.has_value()},
                                      std::pair{"bearing_seed", bearing_seed.has_value()}}) {
      if (given) throw parameter_error(name, "applies to an ensemble of pairs: motions as a list of topple.MotionSet");
    }
  }
  spec.bearing_deg = bearing_deg;
  if (bearing_seed) spec.bearing_seed = *bearing_seed;
  if (mu) {
    if (!threshold_m) throw parameter_error("threshold_m", "a sliding curve (mu given) needs threshold_m, m");
    spec.sliding = SlidingFailure{SlidingBlock::make(*mu, mu_kinetic, deg_to_rad(slope_deg),
                                                     parse_mode(mode), g_m_s2),
                                  *threshold_m};
  } else if (threshold_m) {
    throw parameter_error("mu", "threshold_m given without mu: give the block's friction coefficient mu");
  }
  if (body) {
    spec.overturning =
        OverturnFailure{*body, make_rocking_options(e, rock_mu, g_m_s2, method, rel_tol, rk4_substeps, max_run_out_s),
                        std::nullopt, std::nullopt, std::nullopt};  // Housner's rocking: no coupled or 3-D body (fragility.hpp)
  }
  spec.threads = threads;
  const FragilityResult result = with_field_names({{"bearing", "bearing_deg"}, {"slope", "slope_deg"}}, [&] {
    nb::gil_scoped_release release;
    return fragility_analysis(spec);
  });
  nb::list curves;
  for (const FragilityCurve& c : result.curves) {
    nb::dict cd;
    cd["name"] = c.name;
    std::vector<double> x(c.data.im);
    for (double& v : x) v /= unit;
    std::vector<double> fraction(x.size());
    for (std::size_t j = 0; j < x.size(); ++j) {
      fraction[j] = static_cast<double>(c.data.failures[j]) / static_cast<double>(c.data.trials[j]);
    }
    cd["im"] = to_numpy(std::move(x));
    cd["trials"] = to_numpy(std::vector<std::int64_t>(c.data.trials.begin(), c.data.trials.end()));
    cd["failures"] = to_numpy(std::vector<std::int64_t>(c.data.failures.begin(), c.data.failures.end()));
    cd["fraction"] = to_numpy(std::move(fraction));
    if (c.fit) warn_if_beta_at_bound(fit_in_unit(*c.fit, unit), "fragility curve '" + c.name + "'",
                                     std::string(intensity_measure_unit(result.im)));
    cd["fit"] = c.fit ? nb::cast(fit_in_unit(*c.fit, unit)) : nb::none();
    cd["fit_note"] = c.fit_note;
    curves.append(cd);
  }
  nb::dict d;
  d["im"] = std::string(intensity_measure_name(result.im));
  d["im_unit"] = std::string(intensity_measure_unit(result.im));
  // Pairs: the IM is each pair's RotD50 PGA, and each motion's rocking bearing (given or drawn) is reported.
  d["rotd50"] = result.rotd50;
  d["bearings_deg"] = result.rotd50 ? nb::cast(to_numpy(std::vector<double>(result.bearings_deg))) : nb::none();
  d["curves"] = curves;
  d["runs"] = result.runs;
  d["g_m_s2"] = g_m_s2;
  // What was analysed, for the figure's title (topple.plot.fragility).
  d["motions"] = pairs ? spec.motion_sets.size() : spec.motions.size();
  d["mu"] = mu;
  d["threshold_m"] = threshold_m;
  d["body"] = body;
  return d;
}

// ---- sweeps ----

nb::dict sweep_dict(const std::string& path, int threads) {
  ensemble::ResultTable table;
  {
    nb::gil_scoped_release release;
    const io::SweepFile file = io::read_sweep_file(path);
    const ensemble::Plan plan = ensemble::make_plan(file.spec);
    ensemble::ExecuteOptions options;
    options.threads = threads;
    table = ensemble::run_in_memory(plan, options);
  }
  nb::dict out;
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    bool text = false;
    for (const auto& row : table.rows) text = text || std::holds_alternative<std::string>(row[c]);
    if (text) {
      // Text columns: str, None where the value does not apply.
      nb::list values;
      for (const auto& row : table.rows) {
        const ensemble::Value& v = row[c];
        if (const auto* s = std::get_if<std::string>(&v)) {
          values.append(nb::str(s->data(), s->size()));
        } else if (std::holds_alternative<std::monostate>(v)) {
          values.append(nb::none());
        } else if (const auto* b = std::get_if<bool>(&v)) {
          values.append(nb::bool_(*b));
        } else if (const auto* i = std::get_if<std::int64_t>(&v)) {
          values.append(nb::int_(*i));
        } else {
          values.append(nb::float_(std::get<double>(v)));
        }
      }
      out[table.columns[c].c_str()] = values;
    } else {
      // Numeric columns (numbers, booleans as 0/1): float64, NaN where the value does not apply or is not finite
      // (the CSV's empty cell).
      std::vector<double> values(table.rows.size());
      for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const ensemble::Value& v = table.rows[r][c];
        if (const auto* d = std::get_if<double>(&v)) {
          values[r] = std::isfinite(*d) ? *d : std::nan("");
        } else if (const auto* i = std::get_if<std::int64_t>(&v)) {
          values[r] = static_cast<double>(*i);
        } else if (const auto* b = std::get_if<bool>(&v)) {
          values[r] = *b ? 1.0 : 0.0;
        } else {
          values[r] = std::nan("");
        }
      }
      out[table.columns[c].c_str()] = to_numpy(std::move(values));
    }
  }
  return out;
}

// ---- the exception ----

void translate_input_error(const std::exception_ptr& p, void* payload) {
  try {
    std::rethrow_exception(p);
  } catch (const InputError& e) {
    // A file that does not exist: topple.MissingFileError, both an InputError and a FileNotFoundError, so that
    // `except FileNotFoundError` works as for open(); its str() stays the CLI's message.
    auto* types = static_cast<std::pair<PyObject*, PyObject*>*>(payload);
    std::error_code ec;
    const bool missing = !e.where().file.empty() && !std::filesystem::exists(e.where().file, ec);
    nb::handle type(missing ? types->second : types->first);
    nb::object err = type(e.what());
    if (missing) {
      err.attr("errno") = ENOENT;
      err.attr("strerror") = e.problem();
      err.attr("filename") = e.where().file;
    }
    err.attr("file") = e.where().file.empty() ? nb::none() : nb::cast(e.where().file);
    err.attr("line") = e.where().line ? nb::cast(*e.where().line) : nb::none();
    err.attr("field") = e.where().field.empty() ? nb::none() : nb::cast(e.where().field);
    err.attr("problem") = e.problem();
    PyErr_SetObject(type.ptr(), err.ptr());
  }
}

/// The Python exception types of InputError and MissingFileError and their translator.
void bind_errors(nb::module_& m) {
  // The exception type lives as long as the module: it is an attribute of it.
  nb::object input_error =
      nb::steal(PyErr_NewExceptionWithDoc("topple.InputError", doc::input_error, PyExc_ValueError, nullptr));
  m.attr("InputError") = input_error;
  nb::object missing_file_bases = nb::make_tuple(input_error, nb::handle(PyExc_FileNotFoundError));
  // str() stays the CLI's message: BaseException's __str__, not OSError's "[Errno 2] ...: 'path'".
  nb::dict missing_file_dict;
  missing_file_dict["__str__"] = nb::handle(PyExc_BaseException).attr("__str__");
  nb::object missing_file_error = nb::steal(PyErr_NewExceptionWithDoc(
      "topple.MissingFileError", doc::missing_file_error, missing_file_bases.ptr(), missing_file_dict.ptr()));
  m.attr("MissingFileError") = missing_file_error;
  // The translator's payload: both types, alive as long as the module (they are its attributes).
  static std::pair<PyObject*, PyObject*> error_types{input_error.ptr(), missing_file_error.ptr()};
  nb::register_exception_translator(translate_input_error, &error_types);
}

/// GroundMotion, motion sets and RotD.
void bind_motion(nb::module_& m) {
  // ---- GroundMotion ----
  nb::class_<GroundMotion>(m, "GroundMotion", doc::ground_motion)
      .def("__init__",
           [](GroundMotion* self, nb::handle accel, std::optional<double> dt, const std::string& units,
              nb::handle time, double start_time_s, double g) {
             new (self) GroundMotion(make_motion(accel, dt, units, time, start_time_s, g));
           },
           "accel"_a, "dt"_a = nb::none(), "units"_a = "g", nb::kw_only(), "time"_a = nb::none(),
           "start_time_s"_a = 0.0, "g"_a = kStandardGravity)
      .def("__len__", &GroundMotion::size)
      .def_prop_ro("npts", &GroundMotion::size)
      .def_prop_ro("is_uniform", &GroundMotion::is_uniform)
      .def_prop_ro("dt_s", &GroundMotion::dt_s)
      .def_prop_ro("start_time_s", &GroundMotion::start_time_s)
      .def_prop_ro("end_time_s", &GroundMotion::end_time_s)
      .def_prop_ro("duration_s", &GroundMotion::duration_s)
      .def_prop_ro("accel_m_s2",
                   [](const GroundMotion& g) {
                     const auto a = g.accel_m_s2();
                     return ReadOnlyArray(a.data(), {a.size()}, nb::handle());
                   },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("accel_g", [](const GroundMotion& g) {
        std::vector<double> a(g.accel_m_s2().begin(), g.accel_m_s2().end());
        for (double& v : a) v /= g.metadata().g_m_s2;  // the motion's own g
        return to_numpy(std::move(a));
      }, nb::rv_policy::move)
      .def_prop_ro("time_s", [](const GroundMotion& g) { return to_numpy(g.times_s()); }, nb::rv_policy::move)
      .def_prop_ro("pga_m_s2", &GroundMotion::pga_m_s2)
      .def_prop_ro("pga_g", [](const GroundMotion& g) { return g.pga_m_s2() / g.metadata().g_m_s2; })
      .def_prop_ro("g_m_s2", [](const GroundMotion& g) { return g.metadata().g_m_s2; })
      .def_prop_ro("pga_time_s", &GroundMotion::pga_time_s)
      .def_prop_ro("metadata",
                   [](const GroundMotion& g) {
                     // The fields of `topple info --json`'s record metadata, one table (output/record_fields.hpp).
                     nb::dict d;
                     for (const Field<RecordMetadata>& field : kRecordMetadataFields) {
                       d[field.name] = field_to_python(field.get(g.metadata()));
                     }
                     return d;
                   })
      .def_prop_ro("name", [](const GroundMotion& g) { return motion_name(g); })
      .def("accel_at", &GroundMotion::accel_at, "t_s"_a, doc::accel_at)
      .def("scaled", &GroundMotion::scaled, "factor"_a, doc::scaled)
      .def("scaled_to_pga",
           [](const GroundMotion& g, double pga_g, std::optional<double> gravity) {
             return g.scaled_to_pga(pga_g * gravity.value_or(g.metadata().g_m_s2));
           },
           "pga_g"_a, "g"_a = nb::none(), doc::scaled_to_pga)
      .def("inverted", &GroundMotion::inverted, doc::inverted)
      .def("time_scaled", &GroundMotion::time_scaled, "factor"_a, doc::time_scaled)
      .def("trimmed", &GroundMotion::trimmed, "t_begin_s"_a, "t_end_s"_a, doc::trimmed)
      .def("resampled", &GroundMotion::resampled, "dt_s"_a, doc::resampled)
      .def("baseline_corrected", &GroundMotion::baseline_corrected, "order"_a, doc::baseline_corrected)
      .def("__repr__", [](const GroundMotion& g) {
        return fmt::format("GroundMotion({} samples, dt_s={:.6g}, duration_s={:.6g}, pga_g={:.5g}{})", g.size(),
                           g.dt_s(), g.duration_s(), g.pga_m_s2() / g.metadata().g_m_s2,
                           motion_name(g).empty() ? "" : ", name='" + motion_name(g) + "'");
      });

  using ColumnsArg = std::variant<std::string, std::vector<std::variant<long long, std::string>>>;
  m.def("read",
        [](const std::string& path, std::optional<std::string> format, std::optional<std::string> units,
           std::optional<double> dt, std::optional<int> channel, double g, std::optional<ColumnsArg> columns,
           const std::string& separator, const std::string& baseline) {
          io::ReadOptions o;
          o.format = io::parse_format_name(format.value_or("auto"), "format");
          o.channel = channel;
          o.units = units.value_or("");
          o.dt_s = dt;
          o.g_m_s2 = g;
          if (columns) {
            // "1,2" / "Time (s),Table Acc (g)" as --columns, or (time, accel) as a sweep file's columns ("" for no
            // time column).
            std::string text;
            if (const auto* str = std::get_if<std::string>(&*columns)) {
              text = *str;
            } else {
              const auto& parts = std::get<1>(*columns);
              if (parts.size() != 2) {
                throw parameter_error("columns", fmt::format("expected (time, acceleration), got {} items",
                                                             parts.size()));
              }
              for (std::size_t k = 0; k < 2; ++k) {
                std::string part;
                if (const auto* n = std::get_if<long long>(&parts[k])) {
                  if (*n < 1) throw parameter_error("columns", fmt::format("column numbers start at 1, got {}", *n));
                  part = std::to_string(*n);
                } else {
                  const std::string& name = std::get<std::string>(parts[k]);
                  if (name.find('"') != std::string::npos) {
                    throw parameter_error("columns", "a column name with a double quote");
                  }
                  if (!name.empty()) part = "\"" + name + "\"";
                }
                text += (k == 0 ? "" : ",") + part;
              }
            }
            o.columns = io::parse_columns(text, "columns");
          }
          o.separator = io::parse_separator(separator, "separator");
          o.baseline = parse_baseline(baseline, "baseline");
          nb::gil_scoped_release release;
          GroundMotion motion = io::read_motion(path, o);
          RecordMetadata meta = motion.metadata();
          meta.g_m_s2 = g;  // accel_g and pga_g are in the g the file was read with
          motion.set_metadata(std::move(meta));
          return motion;
        },
        "path"_a, "format"_a = nb::none(), "units"_a = nb::none(), "dt"_a = nb::none(), "channel"_a = nb::none(),
        "g"_a = kStandardGravity, "columns"_a = nb::none(), "separator"_a = "auto", "baseline"_a = "none", doc::read);

  // ---- motion sets (motion_set.hpp) and RotD (rotd.hpp) ----
  nb::class_<MotionSet>(m, "MotionSet", doc::motion_set)
      .def("__init__",
           [](MotionSet* self, const GroundMotion& first, const GroundMotion* second, const GroundMotion* vertical,
              std::optional<std::vector<double>> azimuths_deg) {
             new (self) MotionSet(make_motion_set(first, second, vertical, azimuths_deg));
           },
           "first"_a, "second"_a = nb::none(), nb::kw_only(), "vertical"_a = nb::none(),
           "azimuths_deg"_a = nb::none())
      .def("__len__", &MotionSet::size)
      .def_prop_ro("npts", &MotionSet::size)
      .def_prop_ro("first", &MotionSet::first, nb::rv_policy::reference_internal)
      .def_prop_ro("second", &MotionSet::second_ptr, nb::rv_policy::reference_internal)
      .def_prop_ro("vertical", &MotionSet::vertical_ptr, nb::rv_policy::reference_internal)
      .def_prop_ro("azimuths_deg", &azimuths_to_python)
      .def("projected",
           [](const MotionSet& s, double azimuth_deg) {
             return with_set_fields([&] { return s.projected(azimuth_deg); });
           },
           "azimuth_deg"_a, doc::projected)
      .def("rotated",
           [](const MotionSet& s, double azimuth_deg) {
             return with_set_fields([&] { return s.rotated(azimuth_deg); });
           },
           "azimuth_deg"_a, doc::rotated)
      .def("rotd", &rotd_dict, "periods_s"_a = nb::none(), "damping"_a = kDefaultDampingRatio, nb::kw_only(),
           "g"_a = kStandardGravity, doc::motion_set_rotd)
      .def("__repr__", [](const MotionSet& s) {
        const auto& az = s.azimuths();
        return fmt::format("MotionSet({} samples, components={}{}{})", s.size(),
                           1 + (s.has_second() ? 1 : 0) + (s.has_vertical() ? 1 : 0),
                           s.has_vertical() ? " (with vertical)" : "",
                           az ? fmt::format(", azimuths_deg=({:g}, {:g})", az->first_deg, az->second_deg) : "");
      });
  m.def("rotd",
        [](const GroundMotion& first, const GroundMotion& second, std::optional<std::vector<double>> azimuths_deg,
           nb::handle periods_s, double damping, double g) {
          return rotd_dict(make_motion_set(first, &second, nullptr, azimuths_deg), periods_s, damping, g);
        },
        "first"_a, "second"_a, nb::kw_only(), "azimuths_deg"_a = nb::none(), "periods_s"_a = nb::none(),
        "damping"_a = kDefaultDampingRatio, "g"_a = kStandardGravity, doc::rotd);
}

/// Sliding blocks: 1-D, 2-D, flexible supports.
void bind_sliding(nb::module_& m) {
  // ---- sliding ----
  // The summary attributes come from the field table (topple/solvers/summary_fields.hpp), as the JSON keys do.
  nb::class_<SlidingRun> sliding_result(m, "SlidingResult", doc::sliding_result);
  for (const Field<SlidingOutcome>& field : kSlidingFields) {
    sliding_result.def_prop_ro(field.name, [get = field.get](const SlidingRun& r) {
      return field_to_python(get(SlidingOutcome{r.summary, r.block}));
    });
  }
  sliding_result
      .def_prop_ro("time_s", [](const SlidingRun& r) { return view(r.history.time_s); }, nb::rv_policy::reference_internal)
      .def_prop_ro("displacement_m", [](const SlidingRun& r) { return view(r.history.displacement_m); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("velocity_m_s", [](const SlidingRun& r) { return view(r.history.velocity_m_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("state", [](const SlidingRun& r) { return to_numpy(state_codes(r.history.state)); },
                   nb::rv_policy::move)
      .def("json", [](const SlidingRun& r) { return to_python(r.json()); }, doc::sliding_json)
      .def("__repr__", [](const SlidingRun& r) {
        return fmt::format("SlidingResult(max_abs_displacement_m={:.6g}, residual_displacement_m={:.6g}, "
                           "slip_episodes={})",
                           r.summary.max_abs_displacement_m, r.summary.residual_displacement_m, r.summary.slip_episodes);
      });

  m.def("slide",
        [](const GroundMotion& motion, double mu, std::optional<double> mu_kinetic, const std::string& mode,
           double slope_deg, const GroundMotion* vertical, double g, bool history) {
          return run_slide(motion, mu, mu_kinetic, mode, slope_deg, vertical, g, history);
        },
        "motion"_a, nb::kw_only(), "mu"_a, "mu_kinetic"_a = nb::none(), "mode"_a = "two-way", "slope_deg"_a = 0.0,
        "vertical"_a = nb::none(), "g"_a = kStandardGravity, "history"_a = true, doc::slide);

  // Bidirectional sliding: the summary attributes from kSliding2dFields, as `topple slide --h2 --json` keys.
  nb::class_<Sliding2dRun> sliding_2d_result(m, "Sliding2dResult", doc::sliding_2d_result);
  for (const Field<Sliding2dOutcome>& field : kSliding2dFields) {
    sliding_2d_result.def_prop_ro(field.name, [get = field.get](const Sliding2dRun& r) {
      return field_to_python(get(Sliding2dOutcome{r.summary, r.block}));
    });
  }
  sliding_2d_result
      .def_prop_ro("time_s", [](const Sliding2dRun& r) { return view(r.history.time_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("east_m", [](const Sliding2dRun& r) { return view(r.history.east_m); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("north_m", [](const Sliding2dRun& r) { return view(r.history.north_m); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("east_m_s", [](const Sliding2dRun& r) { return view(r.history.east_m_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("north_m_s", [](const Sliding2dRun& r) { return view(r.history.north_m_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("slipping", [](const Sliding2dRun& r) { return to_numpy(r.history.slipping); }, nb::rv_policy::move)
      .def("json", [](const Sliding2dRun& r) { return to_python(r.json()); }, doc::sliding_2d_json)
      .def("__repr__", [](const Sliding2dRun& r) {
        return fmt::format("Sliding2dResult(residual_displacement_m={:.6g}, residual_azimuth_deg={}, "
                           "max_abs_displacement_m={:.6g}, slip_episodes={})",
                           r.summary.residual_displacement_m,
                           r.summary.residual_azimuth_deg ? fmt::format("{:.6g}", *r.summary.residual_azimuth_deg)
                                                          : std::string("None"),
                           r.summary.max_abs_displacement_m, r.summary.slip_episodes);
      });
  m.def("slide_2d", &run_slide_2d, "first"_a, "second"_a, nb::kw_only(),
        "mu"_a, "mu_kinetic"_a = nb::none(), "azimuths_deg"_a = std::vector<double>{90.0, 0.0}, "slope_deg"_a = 0.0,
        "slope_azimuth_deg"_a = nb::none(), "vertical"_a = nb::none(), "g"_a = kStandardGravity, "history"_a = false,
        doc::slide_2d);

  m.def("slide_spectrum", &sliding_spectrum_dict, "motion"_a, "mu"_a, nb::kw_only(), "slope_deg"_a = 0.0,
        "mode"_a = "two-way", "g"_a = kStandardGravity, doc::slide_spectrum);
  m.def("slide_spectrum_2d", &sliding_spectrum_2d_dict, "first"_a, "second"_a, "mu"_a, nb::kw_only(),
        "azimuths_deg"_a = std::vector<double>{90.0, 0.0}, "vertical"_a = nb::none(), "g"_a = kStandardGravity,
        doc::slide_spectrum_2d);
  m.def("slide_flexible", &run_slide_flexible, "motion"_a, nb::kw_only(), "mu"_a, "mode"_a = "two-way",
        "support_freq_hz"_a = nb::none(), "support_damping"_a = kDefaultDampingRatio, "mass_ratio"_a = 0.0, "height_m"_a = nb::none(),
        "vs_slope_m_s"_a = nb::none(), "vs_base_m_s"_a = nb::none(), "damping"_a = nb::none(),
        "reference_strain"_a = nb::none(), "coupled"_a = false, "vertical"_a = nb::none(), "g"_a = kStandardGravity,
        doc::slide_flexible);
}

/// Rocking bodies and rocking runs.
void bind_rocking(nb::module_& m) {
  const RockingOptions kRockingDefaults;  // the library's defaults are the Python defaults
  // ---- rocking ----
  nb::class_<RockingBody>(m, "RockingBody", doc::rocking_body)
      .def_prop_ro("shape", [](const RockingBody& b) { return std::string(shape_name(b.shape)); })
      .def_ro("a_m", &RockingBody::a_m)
      .def_ro("h_m", &RockingBody::h_m)
      .def_ro("D_m2", &RockingBody::D_m2)
      .def_prop_ro("symmetric", &RockingBody::symmetric)
      .def_prop_ro("b1_m", [](const RockingBody& b) { return b.pivot_b_m(-1); },
                   "CM to the pivot O- (theta < 0), m (a symmetric body: a_m)")
      .def_prop_ro("b2_m", [](const RockingBody& b) { return b.pivot_b_m(1); },
                   "CM to the pivot O+ (theta > 0), m (a_m)")
      .def_prop_ro("D1_m2", [](const RockingBody& b) { return b.pivot_D_m2(-1); }, "I_O / m about O-, m^2")
      .def_prop_ro("D2_m2", [](const RockingBody& b) { return b.pivot_D_m2(1); }, "I_O / m about O+, m^2 (D_m2)")
      .def_prop_ro("alpha_rad", &RockingBody::alpha_rad)
      .def_prop_ro("R_m", &RockingBody::R_m)
      .def("p_rad_s", &RockingBody::p_rad_s, "g"_a = kStandardGravity, doc::p_rad_s)
      .def_prop_ro("housner_e", [](const RockingBody& b) { return housner_restitution(b); })
      .def("__repr__", [](const RockingBody& b) {
        switch (b.shape) {
          case RockingBody::Shape::block:
            return fmt::format("Block(width={:.6g}, height={:.6g})", 2.0 * b.a_m, 2.0 * b.h_m);
          case RockingBody::Shape::cylinder:
            return fmt::format("Cylinder(diameter={:.6g}, height={:.6g})", 2.0 * b.a_m, 2.0 * b.h_m);
          case RockingBody::Shape::general: break;
        }
        if (b.negative_pivot) {
          return fmt::format("GeneralAsymmetric(b1={:.6g}, b2={:.6g}, h={:.6g}, inertia={:.6g})",
                             b.negative_pivot->b_m, b.a_m, b.h_m, b.D_m2 - b.a_m * b.a_m - b.h_m * b.h_m);
        }
        return fmt::format("General(a={:.6g}, h={:.6g}, D={:.6g})", b.a_m, b.h_m, b.D_m2);
      });
  m.def("Block", &RockingBody::block, "width"_a, "height"_a, doc::block);
  m.def("Cylinder", &RockingBody::cylinder, "diameter"_a, "height"_a, doc::cylinder);
  m.def("General", &RockingBody::general, "a"_a, "h"_a, "D"_a, doc::general);
  m.def("GeneralAsymmetric", &RockingBody::general_asymmetric, "b1"_a, "b2"_a, "h"_a, "inertia"_a,
        doc::general_asymmetric);

  nb::class_<RockingRun> rocking_result(m, "RockingResult", doc::rocking_result);
  for (const Field<RockingOutcome>& field : kRockingFields) {
    rocking_result.def_prop_ro(field.name, [get = field.get](const RockingRun& r) {
      return field_to_python(get(RockingOutcome{r.result.summary, r.body, r.options}));
    });
  }
  rocking_result
      .def_prop_ro("warnings", [](const RockingRun& r) { return r.result.summary.warnings; })
      .def_prop_ro("max_rotation_positive_rad",
                   [](const RockingRun& r) { return r.result.summary.max_rotation_positive_rad; })
      .def_prop_ro("max_rotation_negative_rad",
                   [](const RockingRun& r) { return r.result.summary.max_rotation_negative_rad; })
      .def_prop_ro("max_rotation_over_alpha_positive",
                   [](const RockingRun& r) { return r.result.summary.max_rotation_over_alpha_positive; })
      .def_prop_ro("max_rotation_over_alpha_negative",
                   [](const RockingRun& r) { return r.result.summary.max_rotation_over_alpha_negative; })
      .def_prop_ro("overturned_side", [](const RockingRun& r) { return r.result.summary.overturned_side; },
                   "+1: fell toward +x (about O+), -1: toward -x, 0: did not fall")
      .def_prop_ro("body", [](const RockingRun& r) { return r.body; })
      .def_prop_ro("time_s", [](const RockingRun& r) { return view(r.result.history.time_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("theta_rad", [](const RockingRun& r) { return view(r.result.history.theta_rad); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("theta_dot_rad_s", [](const RockingRun& r) { return view(r.result.history.theta_dot_rad_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("state", [](const RockingRun& r) { return to_numpy(state_codes(r.result.history.state)); },
                   nb::rv_policy::move)
      .def_prop_ro("events",
                   [](const RockingRun& r) {
                     nb::list out;
                     for (const RockingEvent& ev : r.result.events) {
                       nb::dict d;
                       d["kind"] = std::string(rocking_event_name(ev.kind));
                       d["time_s"] = ev.time_s;
                       d["theta_rad"] = ev.theta_rad;
                       d["theta_dot_before_rad_s"] = ev.theta_dot_before_rad_s;
                       d["theta_dot_after_rad_s"] = ev.theta_dot_after_rad_s;
                       out.append(d);
                     }
                     return out;
                   })
      .def("json", [](const RockingRun& r) { return to_python(r.json()); }, doc::rocking_json)
      .def("__repr__", [](const RockingRun& r) {
        return fmt::format("RockingResult(max_rotation_over_alpha={:.6g}, overturned={}, end_state='{}')",
                           r.result.summary.max_rotation_over_alpha, r.result.summary.overturned ? "True" : "False",
                           rocking_state_name(r.result.summary.end_state));
      });

  m.def("rock", &run_rock, "motion"_a, "shape"_a, nb::kw_only(), "e"_a = "housner", "mu"_a = nb::none(),
        "g"_a = kStandardGravity, "method"_a = std::string(rocking_method_name(kRockingDefaults.method)),
        "rel_tol"_a = kRockingDefaults.rel_tol, "rk4_substeps"_a = kRockingDefaults.rk4_substeps,
        "max_run_out_s"_a = kRockingDefaults.max_run_out_s, "vertical"_a = nb::none(), "history"_a = true, doc::rock);
}

/// The coupled slide-rock runs and oriented rocking objects.
void bind_slide_rock(nb::module_& m) {
  const RockingOptions kRockingDefaults;  // the library's defaults are the Python defaults
  nb::class_<SlideRockRun> slide_rock_result(m, "SlideRockResult", doc::slide_rock_result);
  for (const Field<SlideRockOutcome>& field : kSlideRockFields) {
    slide_rock_result.def_prop_ro(field.name, [get = field.get](const SlideRockRun& r) {
      return field_to_python(get(SlideRockOutcome{r.result.summary, r.body, r.options}));
    });
  }
  slide_rock_result
      .def_prop_ro("warnings", [](const SlideRockRun& r) { return r.result.summary.warnings; })
      .def_prop_ro("modes",
                   [](const SlideRockRun& r) {
                     nb::dict out;
                     for (std::size_t k = 0; k < kSlideRockModes; ++k) {
                       nb::dict d;
                       d["entries"] = r.result.summary.mode_entries[k];
                       d["first_time_s"] = r.result.summary.mode_first_time_s[k];
                       out[nb::str(std::string(slide_rock_mode_name(static_cast<SlideRockMode>(k))).c_str())] = d;
                     }
                     return out;
                   })
      .def_prop_ro("body", [](const SlideRockRun& r) { return r.shape; })
      .def_prop_ro("time_s", [](const SlideRockRun& r) { return view(r.result.history.time_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("slide_m", [](const SlideRockRun& r) { return view(r.result.history.slide_m); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("slide_velocity_m_s", [](const SlideRockRun& r) { return view(r.result.history.slide_velocity_m_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("theta_rad", [](const SlideRockRun& r) { return view(r.result.history.theta_rad); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("theta_dot_rad_s", [](const SlideRockRun& r) { return view(r.result.history.theta_dot_rad_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("cm_height_m", [](const SlideRockRun& r) { return view(r.result.history.cm_height_m); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("mode", [](const SlideRockRun& r) { return to_numpy(state_codes(r.result.history.mode)); },
                   nb::rv_policy::move)
      .def_prop_ro("transitions",
                   [](const SlideRockRun& r) {
                     nb::list out;
                     for (const SlideRockTransition& t : r.result.transitions) {
                       nb::dict d;
                       d["time_s"] = t.time_s;
                       d["mode"] = std::string(slide_rock_mode_name(t.mode));
                       out.append(d);
                     }
                     return out;
                   })
      .def("json", [](const SlideRockRun& r) { return to_python(r.json()); }, doc::slide_rock_json)
      .def("__repr__", [](const SlideRockRun& r) {
        return fmt::format("SlideRockResult(max_rotation_over_alpha={:.6g}, residual_slide_m={:.6g}, overturned={}, "
                           "end_mode='{}')",
                           r.result.summary.max_rotation_over_alpha, r.result.summary.residual_slide_m,
                           r.result.summary.overturned ? "True" : "False",
                           slide_rock_mode_name(r.result.summary.end_mode));
      });
  const SlideRockOptions kSlideRockDefaults;  // the library's defaults are the Python defaults
  m.def("slide_rock", &run_slide_rock, "motion"_a, "body"_a, "mu"_a, "mu_k"_a = nb::none(), nb::kw_only(),
        "vertical"_a = nb::none(), "e"_a = "housner", "g"_a = kStandardGravity,
        "rel_tol"_a = kSlideRockDefaults.rel_tol, "max_run_out_s"_a = kSlideRockDefaults.max_run_out_s,
        "slope_deg"_a = 0.0, "history"_a = true, doc::slide_rock);
  m.def("rock_oriented", &run_rock_oriented, "first"_a, "second"_a, "shape"_a, nb::kw_only(),
        "azimuths_deg"_a = std::vector<double>{90.0, 0.0}, "bearing_deg"_a = nb::none(), "depth_m"_a = nb::none(),
        "direction_step_deg"_a = nb::none(), "vertical"_a = nb::none(), "e"_a = "housner", "mu"_a = nb::none(),
        "g"_a = kStandardGravity, "method"_a = std::string(rocking_method_name(kRockingDefaults.method)),
        "rel_tol"_a = kRockingDefaults.rel_tol, "rk4_substeps"_a = kRockingDefaults.rk4_substeps,
        "max_run_out_s"_a = kRockingDefaults.max_run_out_s, doc::rock_oriented);
  const Rigid3DOptions kRigid3DDefaults;  // the library's defaults are the Python defaults
  m.def("rock3d", &run_rock3d, "first"_a, "second"_a = nb::none(), nb::kw_only(), "width_m"_a = nb::none(),
        "depth_m"_a = nb::none(), "height_m"_a, "diameter_m"_a = nb::none(),
        "azimuths_deg"_a = std::vector<double>{90.0, 0.0}, "bearing_deg"_a = nb::none(), "vertical"_a = nb::none(),
        "e"_a = "housner", "g"_a = kStandardGravity, "rel_tol"_a = kRigid3DDefaults.rel_tol,
        "simultaneous_contact"_a = nb::none(), "max_run_out_s"_a = kRigid3DDefaults.max_run_out_s,
        "history"_a = false, "mu"_a = nb::none(), "mu_k"_a = nb::none(), "base_incline_deg"_a = 0.0,
        "base_incline_azimuth_deg"_a = 0.0, doc::rock3d);
}

/// Synthetic motions, intensity measures, the survey and regional inversions.
void bind_synthesis_and_inversion(nb::module_& m) {
  // ---- synthesis, intensity, inversion ----
  m.def("synth", &run_synth, nb::kw_only(), "pga_g"_a, "freq_hz"_a, "duration_s"_a, "seed"_a = 0, "dt_s"_a = 0.01,
        "model"_a = "clough-penzien", "envelope"_a = "saragoni-hart", "zeta_g"_a = 0.3, "g"_a = kStandardGravity,
        "components"_a = 1, "coherence"_a = nb::none(), "azimuths_deg"_a = nb::none(), "vh_ratio"_a = nb::none(),
        "vh_freq_ratio"_a = nb::none(), doc::synth);

  m.def("intensity", &intensity_dict, "motion"_a, "g"_a = kStandardGravity, doc::intensity);
  // topple.invert (python/topple/__init__.py) takes a path or a dict and calls one of these.
  m.def("_invert_file", &invert_file, "path"_a, nb::kw_only(), "threads"_a = 0, "report_dir"_a = nb::none(),
        doc::invert_file);
  m.def("_invert_text", &invert_text, "text"_a, nb::kw_only(), "name"_a, "base_dir"_a, "threads"_a = 0,
        "report_dir"_a = nb::none(), doc::invert_text);
  // topple.invert_region (python/topple/__init__.py) likewise.
  m.def("_invert_region_file", &invert_region_file, "path"_a, nb::kw_only(), "threads"_a = 0, doc::invert_region_file);
  m.def("_invert_region_text", &invert_region_text, "text"_a, nb::kw_only(), "name"_a, "base_dir"_a, "threads"_a = 0,
        doc::invert_region_text);
}

/// Spectra, object spectra, fragility, sweeps.
void bind_spectra_and_fragility(nb::module_& m) {
  const RockingOptions kRockingDefaults;  // the library's defaults are the Python defaults
  // ---- spectra, object spectra, fragility, sweeps ----
  m.def("response_spectrum", &response_spectrum_dict, "motion"_a, "periods_s"_a = nb::none(), "damping"_a = kDefaultDampingRatio,
        nb::kw_only(), "g"_a = kStandardGravity, doc::response_spectrum);
  m.def("fourier_spectrum", &fourier_spectrum_dict, "motion"_a, "smoothing_b"_a = 40.0, nb::kw_only(),
        "centre_hz"_a = nb::none(), "fft_length"_a = nb::none(), doc::fourier_spectrum);
  m.def("overturning_map", &overturning_map_dict, "motion"_a, nb::kw_only(), "alpha_rad"_a, "heights_m"_a, "pga_g"_a,
        "shape"_a = "block", "e"_a = "housner", "mu"_a = nb::none(), "g"_a = kStandardGravity,
        "method"_a = std::string(rocking_method_name(kRockingDefaults.method)), "rel_tol"_a = kRockingDefaults.rel_tol,
        "rk4_substeps"_a = kRockingDefaults.rk4_substeps, "max_run_out_s"_a = kRockingDefaults.max_run_out_s,
        "threads"_a = 0, doc::overturning_map);

  // The fit's attributes come from the field table of `topple fragility --json`'s "fit" (output/fragility_output.hpp).
  // The fit here is already in the IM's display unit (fit_in_unit), hence the factor 1; a bare fit (fragility_fit)
  // has no unit, so theta_unit is the dict's im_unit instead of an attribute.
  nb::class_<LognormalFragilityFit> fragility_fit(m, "FragilityFit", doc::fragility_fit_class);
  for (const Field<FragilityFitShown>& field : kFragilityFitFields) {
    if (std::string_view(field.name) == "theta_unit") continue;
    fragility_fit.def_prop_ro(field.name, [get = field.get](const LognormalFragilityFit& f) {
      return field_to_python(get(FragilityFitShown{f, 1.0, ""}));
    });
  }
  fragility_fit
      .def_ro("iterations", &LognormalFragilityFit::iterations)
      .def("probability",
           [](const LognormalFragilityFit& f, nb::handle im) {
             return map_im(im, [&](double x) { return f.probability(x); });
           },
           "im"_a, doc::fragility_probability)
      .def("band",
           [](const LognormalFragilityFit& f, nb::handle im, double level) {
             return nb::make_tuple(map_im(im, [&](double x) { return f.band(x, level).first; }),
                                   map_im(im, [&](double x) { return f.band(x, level).second; }));
           },
           "im"_a, "level"_a = 0.95, doc::fragility_band)
      .def("__repr__", [](const LognormalFragilityFit& f) {
        return fmt::format("FragilityFit(theta={:.6g}, beta={:.6g}{})", f.theta, f.beta,
                           f.beta_at_bound ? ", beta_at_bound=True" : "");
      });
  m.def("fragility_fit",
        [](nb::handle im, nb::handle trials, nb::handle failures) {
          FragilityData data;
          data.im = to_vector(im, "im");
          data.trials = to_int_vector(trials, "trials");
          data.failures = to_int_vector(failures, "failures");
          LognormalFragilityFit fit;
          {
            nb::gil_scoped_release release;
            fit = fit_lognormal_fragility(data);
          }
          warn_if_beta_at_bound(fit, "fragility_fit", "");
          return fit;
        },
        "im"_a, "trials"_a, "failures"_a, doc::fragility_fit);
  m.def("fragility", &fragility_dict, "motions"_a, "levels"_a, nb::kw_only(), "im"_a = "pga", "mu"_a = nb::none(),
        "threshold_m"_a = nb::none(), "mu_kinetic"_a = nb::none(), "mode"_a = "two-way", "slope_deg"_a = 0.0,
        "body"_a = nb::none(), "e"_a = "housner", "rock_mu"_a = nb::none(), "g"_a = kStandardGravity,
        "method"_a = std::string(rocking_method_name(kRockingDefaults.method)), "rel_tol"_a = kRockingDefaults.rel_tol,
        "rk4_substeps"_a = kRockingDefaults.rk4_substeps, "max_run_out_s"_a = kRockingDefaults.max_run_out_s,
        "threads"_a = 0, "bearing_deg"_a = nb::none(), "bearing_seed"_a = nb::none(), doc::fragility);
  m.def("_sweep", &sweep_dict, "path"_a, nb::kw_only(), "threads"_a = 0, doc::sweep);
}

/// The names of the library's field tables by the Python object they become (`_core._field_tables()`): a class
/// whose attributes are a table's fields, or a dict whose keys are ("intensity": topple.intensity,
/// "GroundMotion.metadata"). python/tests/test_docstrings.py checks each against the classes, their docstrings and
/// the stubs, so that neither can drift from the tables.
template <class Result, std::size_t N>
nb::list field_names(const std::array<Field<Result>, N>& table) {
  nb::list names;
  for (const Field<Result>& field : table) names.append(field.name);
  return names;
}

void bind_field_tables(nb::module_& m) {
  m.def("_field_tables", [] {
    nb::dict d;
    d["SlidingResult"] = field_names(kSlidingFields);
    d["Sliding2dResult"] = field_names(kSliding2dFields);
    d["RockingResult"] = field_names(kRockingFields);
    d["SlideRockResult"] = field_names(kSlideRockFields);
    d["FragilityFit"] = field_names(kFragilityFitFields);
    d["intensity"] = field_names(kIntensityFields);
    d["GroundMotion.metadata"] = field_names(kRecordMetadataFields);
    return d;
  });
}

}  // namespace
}  // namespace topple::python

NB_MODULE(_core, m) {
  using namespace topple;
  using namespace topple::python;
  m.doc() = "topple's C++ library (see the topple package for the documented API)";
  m.attr("STANDARD_GRAVITY") = kStandardGravity;
  bind_errors(m);
  bind_motion(m);
  bind_sliding(m);
  bind_rocking(m);
  bind_slide_rock(m);
  bind_synthesis_and_inversion(m);
  bind_spectra_and_fragility(m);
  bind_field_tables(m);
}
