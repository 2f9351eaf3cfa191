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
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/variant.h>
#include <nanobind/stl/vector.h>
#include <nlohmann/json.hpp>

#include "topple/error.hpp"
#include "topple/ground_motion.hpp"
#include "topple/intensity.hpp"
#include "topple/inversion.hpp"
#include "topple/io/inversion_output.hpp"
#include "topple/io/read.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/io/write.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"
#include "topple/spectra.hpp"
#include "topple/synthesis.hpp"
#include "topple/units.hpp"

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
  const GroundMotion* v = vertical.is_none() ? nullptr : &nb::cast<const GroundMotion&>(vertical);
  nlohmann::ordered_json in;
  in["motion"] = motion_name(h);
  in["pga_g"] = h.pga_m_s2() / g_m_s2;
  in["scale_factor"] = 1.0;
  in["invert"] = false;
  in["vertical"] = v ? nlohmann::ordered_json(motion_name(*v)) : nlohmann::ordered_json(nullptr);
  in["npts"] = h.size();
  in["dt_s"] = h.dt_s();
  return in;
}

SlidingMode parse_mode(const std::string& mode) {
  if (mode == "two-way") return SlidingMode::two_way;
  if (mode == "one-way") return SlidingMode::one_way;
  throw parameter_error("mode", fmt::format("unknown mode '{}' (known: two-way, one-way)", mode));
}

SlidingRun run_slide(const GroundMotion& motion, double mu, std::optional<double> mu_kinetic, const std::string& mode,
                     double slope_deg, const GroundMotion* vertical, double g_m_s2, bool history) {
  SlidingRun run;
  run.block = SlidingBlock::make(mu, mu_kinetic.value_or(-1.0), slope_deg * kPi / 180.0, parse_mode(mode), g_m_s2);
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

// ---- rocking ----

struct RockingRun {
  RockingResult result;  // history and events empty when run with history=False
  RockingBody body;
  RockingOptions options;
  RunInputs inputs;

  [[nodiscard]] nlohmann::ordered_json json() const {
    nlohmann::ordered_json j = io::rocking_summary_json(result.summary, body, options);
    j["input"] = inputs.json(options.g_m_s2);
    j["input"]["duration_s"] = nb::cast<const GroundMotion&>(inputs.horizontal).duration_s();
    return j;
  }
};

RockingRun run_rock(const GroundMotion& motion, const RockingBody& body, const std::variant<double, std::string>& e,
                    std::optional<double> mu, double g_m_s2, const std::string& method, double rel_tol,
                    int rk4_substeps, double max_run_out_s, const GroundMotion* vertical, bool history) {
  RockingRun run;
  run.body = body;
  RockingOptions& o = run.options;
  o.g_m_s2 = g_m_s2;
  if (const auto* name = std::get_if<std::string>(&e)) {
    if (*name != "housner") throw parameter_error("e", fmt::format("'{}' is neither a number in [0, 1] nor 'housner'", *name));
    o.restitution = RestitutionMode::housner;
  } else {
    o.restitution = RestitutionMode::given;
    o.e = std::get<double>(e);
  }
  o.mu = mu;
  if (method == "adaptive") {
    o.method = RockingMethod::adaptive;
  } else if (method == "rk4") {
    o.method = RockingMethod::rk4;
  } else {
    throw parameter_error("method", fmt::format("unknown method '{}' (known: adaptive, rk4)", method));
  }
  o.rel_tol = rel_tol;
  o.rk4_substeps = rk4_substeps;
  o.max_run_out_s = max_run_out_s;
  {
    nb::gil_scoped_release release;
    if (history) {
      run.result = rock(motion, body, o, vertical);
    } else {
      run.result.summary = rock_summary(motion, body, o, vertical);
    }
  }
  run.inputs = RunInputs(motion, vertical);
  return run;
}

// ---- intensity (the measures of `topple info`, undefined ones as None) ----

template <class F>
nb::object measure_or_none(F f) {
  try {
    return nb::cast(f());
  } catch (const InputError&) {
    return nb::none();
  }
}

nb::dict intensity_dict(const GroundMotion& motion, double g_m_s2) {
  BasicIntensity im;
  std::optional<SignificantDuration> duration;
  double cav = 0.0;
  std::optional<double> tp, tm, fp;
  {
    nb::gil_scoped_release release;
    im = basic_intensity(motion, g_m_s2);
    try {
      duration = significant_duration(motion);
    } catch (const InputError&) {
      duration.reset();  // identically zero record
    }
    cav = cumulative_absolute_velocity_m_s(motion);
    const auto attempt = [](auto f) -> std::optional<double> {
      try {
        return f();
      } catch (const InputError&) {
        return std::nullopt;
      }
    };
    tp = attempt([&] { return predominant_period_s(motion); });
    tm = attempt([&] { return mean_period_s(motion); });
    fp = attempt([&] { return predominant_frequency_hz(motion); });
  }
  nb::dict d;
  d["npts"] = motion.size();
  d["dt_s"] = motion.dt_s();
  d["duration_s"] = motion.duration_s();
  d["pga_g"] = im.pga_m_s2 / g_m_s2;
  d["pga_m_s2"] = im.pga_m_s2;
  d["pga_time_s"] = im.pga_time_s;
  d["pgv_m_s"] = im.pgv_m_s;
  d["pgd_m"] = im.pgd_m;
  d["arias_m_s"] = im.arias_m_s;
  d["d5_95_s"] = duration ? nb::cast(duration->duration_s) : nb::none();
  d["d5_time_s"] = duration ? nb::cast(duration->start_s) : nb::none();
  d["d95_time_s"] = duration ? nb::cast(duration->end_s) : nb::none();
  d["cav_m_s"] = cav;
  d["tp_s"] = optional_float(tp);
  d["tm_s"] = optional_float(tm);
  d["predominant_frequency_hz"] = optional_float(fp);
  d["g_m_s2"] = g_m_s2;
  return d;
}

// ---- inversion ----

nb::object invert_survey(const std::string& path, int threads) {
  const Survey survey = io::read_survey(path);
  std::vector<InversionResult> results;
  {
    nb::gil_scoped_release release;
    for (const Site& site : survey.sites) results.push_back(invert_site(site, survey.inversion, InversionOptions{threads}));
  }
  const auto site_dict = [&](std::size_t i) {
    const InversionResult& r = results[i];
    nb::dict d = nb::cast<nb::dict>(to_python(io::inversion_json(r, survey.sites[i])));
    // Beyond the CLI's JSON: the grids, rows = PGA, columns = frequency (for topple.plot.inversion_map).
    const std::size_t rows = r.pga_g.size();
    const std::size_t cols = r.freq_hz.size();
    const auto grid = [&](const std::vector<double>& v) {
      auto owned = std::make_unique<std::vector<double>>(v);
      double* data = owned->data();
      nb::capsule owner(owned.get(), [](void* p) noexcept { delete static_cast<std::vector<double>*>(p); });
      owned.release();
      return nb::ndarray<nb::numpy, double, nb::ndim<2>>(data, {rows, cols}, owner);
    };
    d["posterior_grid"] = grid(r.posterior);
    d["log_likelihood_grid"] = grid(r.log_likelihood);
    return d;
  };
  if (results.size() == 1) return site_dict(0);
  nb::dict all;
  nb::list sites;
  for (std::size_t i = 0; i < results.size(); ++i) sites.append(site_dict(i));
  all["sites"] = sites;
  return all;
}

// ---- the exception ----

void translate_input_error(const std::exception_ptr& p, void* payload) {
  try {
    std::rethrow_exception(p);
  } catch (const InputError& e) {
    nb::handle type(static_cast<PyObject*>(payload));
    nb::object err = type(e.what());
    err.attr("file") = e.where().file.empty() ? nb::none() : nb::cast(e.where().file);
    err.attr("line") = e.where().line ? nb::cast(*e.where().line) : nb::none();
    err.attr("field") = e.where().field.empty() ? nb::none() : nb::cast(e.where().field);
    err.attr("problem") = e.problem();
    PyErr_SetObject(type.ptr(), err.ptr());
  }
}

}  // namespace
}  // namespace topple::python

NB_MODULE(_core, m) {
  using namespace topple;
  using namespace topple::python;
  m.doc() = "topple's C++ library (see the topple package for the documented API)";
  m.attr("STANDARD_GRAVITY") = kStandardGravity;

  // The exception type lives as long as the module: it is an attribute of it.
  nb::object input_error = nb::steal(PyErr_NewExceptionWithDoc(
      "topple.InputError",
      "Bad caller input (file, parameter, array): the message is the CLI's; attributes file, line, field, problem.",
      PyExc_ValueError, nullptr));
  m.attr("InputError") = input_error;
  nb::register_exception_translator(translate_input_error, input_error.ptr());

  // ---- GroundMotion ----
  nb::class_<GroundMotion>(m, "GroundMotion", "One component of ground acceleration, piecewise linear in time (SI).")
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
        for (double& v : a) v /= kStandardGravity;
        return to_numpy(std::move(a));
      }, nb::rv_policy::move)
      .def_prop_ro("time_s", [](const GroundMotion& g) { return to_numpy(g.times_s()); }, nb::rv_policy::move)
      .def_prop_ro("pga_m_s2", &GroundMotion::pga_m_s2)
      .def_prop_ro("pga_g", [](const GroundMotion& g) { return g.pga_m_s2() / kStandardGravity; })
      .def_prop_ro("pga_time_s", &GroundMotion::pga_time_s)
      .def_prop_ro("metadata",
                   [](const GroundMotion& g) {
                     const RecordMetadata& md = g.metadata();
                     nb::dict d;
                     d["format"] = md.format;
                     d["source_file"] = md.source_file;
                     d["event"] = md.event;
                     d["station"] = md.station;
                     d["component"] = md.component;
                     d["units_as_read"] = md.units_as_read;
                     return d;
                   })
      .def_prop_ro("name", [](const GroundMotion& g) { return motion_name(g); })
      .def("accel_at", &GroundMotion::accel_at, "t_s"_a)
      .def("scaled", &GroundMotion::scaled, "factor"_a)
      .def("scaled_to_pga",
           [](const GroundMotion& g, double pga_g, double gravity) { return g.scaled_to_pga(pga_g * gravity); },
           "pga_g"_a, "g"_a = kStandardGravity)
      .def("inverted", &GroundMotion::inverted)
      .def("time_scaled", &GroundMotion::time_scaled, "factor"_a)
      .def("trimmed", &GroundMotion::trimmed, "t_begin_s"_a, "t_end_s"_a)
      .def("resampled", &GroundMotion::resampled, "dt_s"_a)
      .def("baseline_corrected", &GroundMotion::baseline_corrected, "order"_a)
      .def("__repr__", [](const GroundMotion& g) {
        return fmt::format("GroundMotion({} samples, dt_s={:.6g}, duration_s={:.6g}, pga_g={:.5g}{})", g.size(),
                           g.dt_s(), g.duration_s(), g.pga_m_s2() / kStandardGravity,
                           motion_name(g).empty() ? "" : ", name='" + motion_name(g) + "'");
      });

  m.def("read",
        [](const std::string& path, std::optional<std::string> format, std::optional<std::string> units,
           std::optional<double> dt, std::optional<int> channel, double g) {
          io::ReadOptions o;
          o.format = io::parse_format_name(format.value_or("auto"), "format");
          o.channel = channel;
          o.units = units.value_or("");
          o.dt_s = dt;
          o.g_m_s2 = g;
          nb::gil_scoped_release release;
          return io::read_motion(path, o);
        },
        "path"_a, "format"_a = nb::none(), "units"_a = nb::none(), "dt"_a = nb::none(), "channel"_a = nb::none(),
        "g"_a = kStandardGravity);

  // ---- sliding ----
  nb::class_<SlidingRun>(m, "SlidingResult", "Sliding response: summary attributes as in `topple slide --json`.")
      .def_prop_ro("max_abs_displacement_m", [](const SlidingRun& r) { return r.summary.max_abs_displacement_m; })
      .def_prop_ro("max_displacement_time_s", [](const SlidingRun& r) { return r.summary.max_displacement_time_s; })
      .def_prop_ro("residual_displacement_m", [](const SlidingRun& r) { return r.summary.residual_displacement_m; })
      .def_prop_ro("max_abs_velocity_m_s", [](const SlidingRun& r) { return r.summary.max_abs_velocity_m_s; })
      .def_prop_ro("slip_episodes", [](const SlidingRun& r) { return r.summary.slip_episodes; })
      .def_prop_ro("first_slip_time_s", [](const SlidingRun& r) { return r.summary.first_slip_time_s; })
      .def_prop_ro("total_slip_duration_s", [](const SlidingRun& r) { return r.summary.total_slip_duration_s; })
      .def_prop_ro("end_time_s", [](const SlidingRun& r) { return r.summary.end_time_s; })
      .def_prop_ro("at_rest_at_end", [](const SlidingRun& r) { return r.summary.at_rest_at_end; })
      .def_prop_ro("contact_lost_time_s", [](const SlidingRun& r) { return r.summary.contact_lost_time_s; })
      .def_prop_ro("yield_down_g", [](const SlidingRun& r) { return r.block.yield_down_m_s2() / r.block.g_m_s2; })
      .def_prop_ro("yield_up_g",
                   [](const SlidingRun& r) {
                     const double up = r.block.yield_up_m_s2();
                     return std::isfinite(up) ? std::optional<double>(up / r.block.g_m_s2) : std::nullopt;
                   })
      .def_prop_ro("mu_static", [](const SlidingRun& r) { return r.block.mu_static; })
      .def_prop_ro("mu_kinetic", [](const SlidingRun& r) { return r.block.mu_kinetic; })
      .def_prop_ro("slope_deg", [](const SlidingRun& r) { return r.block.slope_rad * 180.0 / kPi; })
      .def_prop_ro("mode", [](const SlidingRun& r) {
        return std::string(r.block.mode == SlidingMode::one_way ? "one-way" : "two-way");
      })
      .def_prop_ro("g_m_s2", [](const SlidingRun& r) { return r.block.g_m_s2; })
      .def_prop_ro("time_s", [](const SlidingRun& r) { return view(r.history.time_s); }, nb::rv_policy::reference_internal)
      .def_prop_ro("displacement_m", [](const SlidingRun& r) { return view(r.history.displacement_m); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("velocity_m_s", [](const SlidingRun& r) { return view(r.history.velocity_m_s); },
                   nb::rv_policy::reference_internal)
      .def_prop_ro("state", [](const SlidingRun& r) { return to_numpy(state_codes(r.history.state)); },
                   nb::rv_policy::move)
      .def("json", [](const SlidingRun& r) { return to_python(r.json()); })
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
        "vertical"_a = nb::none(), "g"_a = kStandardGravity, "history"_a = true);

  m.def("slide_spectrum",
        [](const GroundMotion& motion, nb::handle mu, double slope_deg, const std::string& mode, double g) {
          const std::vector<double> mus = to_vector(mu, "mu");
          const SlidingMode sliding_mode = parse_mode(mode);
          std::vector<SlidingSummary> s;
          {
            nb::gil_scoped_release release;
            s = slide_summaries(motion, mus, slope_deg * kPi / 180.0, sliding_mode, g);
          }
          std::vector<double> max_abs(s.size()), residual(s.size());
          for (std::size_t i = 0; i < s.size(); ++i) {
            max_abs[i] = s[i].max_abs_displacement_m;
            residual[i] = s[i].residual_displacement_m;
          }
          nb::dict d;
          d["mu"] = to_numpy(std::vector<double>(mus));
          d["max_abs_displacement_m"] = to_numpy(std::move(max_abs));
          d["residual_displacement_m"] = to_numpy(std::move(residual));
          return d;
        },
        "motion"_a, "mu"_a, nb::kw_only(), "slope_deg"_a = 0.0, "mode"_a = "two-way", "g"_a = kStandardGravity);

  // ---- rocking ----
  nb::class_<RockingBody>(m, "RockingBody", "A rigid body that rocks: made by Block, Cylinder or General (metres).")
      .def_prop_ro("shape", [](const RockingBody& b) { return std::string(shape_name(b.shape)); })
      .def_ro("a_m", &RockingBody::a_m)
      .def_ro("h_m", &RockingBody::h_m)
      .def_ro("D_m2", &RockingBody::D_m2)
      .def_prop_ro("alpha_rad", &RockingBody::alpha_rad)
      .def_prop_ro("R_m", &RockingBody::R_m)
      .def("p_rad_s", &RockingBody::p_rad_s, "g"_a = kStandardGravity)
      .def_prop_ro("housner_e", [](const RockingBody& b) { return housner_restitution(b); })
      .def("__repr__", [](const RockingBody& b) {
        switch (b.shape) {
          case RockingBody::Shape::block:
            return fmt::format("Block(width={:.6g}, height={:.6g})", 2.0 * b.a_m, 2.0 * b.h_m);
          case RockingBody::Shape::cylinder:
            return fmt::format("Cylinder(diameter={:.6g}, height={:.6g})", 2.0 * b.a_m, 2.0 * b.h_m);
          case RockingBody::Shape::general: break;
        }
        return fmt::format("General(a={:.6g}, h={:.6g}, D={:.6g})", b.a_m, b.h_m, b.D_m2);
      });
  m.def("Block", &RockingBody::block, "width"_a, "height"_a);
  m.def("Cylinder", &RockingBody::cylinder, "diameter"_a, "height"_a);
  m.def("General", &RockingBody::general, "a"_a, "h"_a, "D"_a);

  nb::class_<RockingRun>(m, "RockingResult", "Rocking response: summary attributes as in `topple rock --json`.")
      .def_prop_ro("max_abs_rotation_rad", [](const RockingRun& r) { return r.result.summary.max_abs_rotation_rad; })
      .def_prop_ro("max_rotation_over_alpha",
                   [](const RockingRun& r) { return r.result.summary.max_rotation_over_alpha; })
      .def_prop_ro("max_rotation_time_s", [](const RockingRun& r) { return r.result.summary.max_rotation_time_s; })
      .def_prop_ro("max_abs_theta_dot_rad_s",
                   [](const RockingRun& r) { return r.result.summary.max_abs_theta_dot_rad_s; })
      .def_prop_ro("impacts", [](const RockingRun& r) { return r.result.summary.impacts; })
      .def_prop_ro("uplifts", [](const RockingRun& r) { return r.result.summary.uplifts; })
      .def_prop_ro("uplift_time_s", [](const RockingRun& r) { return r.result.summary.uplift_time_s; })
      .def_prop_ro("exceeded_alpha_time_s", [](const RockingRun& r) { return r.result.summary.exceeded_alpha_time_s; })
      .def_prop_ro("overturned", [](const RockingRun& r) { return r.result.summary.overturned; })
      .def_prop_ro("overturn_time_s", [](const RockingRun& r) { return r.result.summary.overturn_time_s; })
      .def_prop_ro("end_state",
                   [](const RockingRun& r) { return std::string(rocking_state_name(r.result.summary.end_state)); })
      .def_prop_ro("end_time_s", [](const RockingRun& r) { return r.result.summary.end_time_s; })
      .def_prop_ro("still_rocking_at_end", [](const RockingRun& r) { return r.result.summary.still_rocking_at_end; })
      .def_prop_ro("energy_lost_j_per_kg", [](const RockingRun& r) { return r.result.summary.energy_lost_j_per_kg; })
      .def_prop_ro("alpha_rad", [](const RockingRun& r) { return r.result.summary.alpha_rad; })
      .def_prop_ro("alpha_deg", [](const RockingRun& r) { return r.result.summary.alpha_rad * 180.0 / kPi; })
      .def_prop_ro("R_m", [](const RockingRun& r) { return r.result.summary.R_m; })
      .def_prop_ro("p_rad_s", [](const RockingRun& r) { return r.result.summary.p_rad_s; })
      .def_prop_ro("e", [](const RockingRun& r) { return r.result.summary.e; })
      .def_prop_ro("e_mode", [](const RockingRun& r) {
        return std::string(r.options.restitution == RestitutionMode::housner ? "housner" : "given");
      })
      .def_prop_ro("onset_mode",
                   [](const RockingRun& r) { return std::string(onset_mode_name(r.result.summary.onset_mode)); })
      .def_prop_ro("onset_accel_ratio", [](const RockingRun& r) { return r.result.summary.onset_accel_ratio; })
      .def_prop_ro("critical_mu", [](const RockingRun& r) { return r.result.summary.critical_mu; })
      .def_prop_ro("mu", [](const RockingRun& r) { return r.options.mu; })
      .def_prop_ro("g_m_s2", [](const RockingRun& r) { return r.options.g_m_s2; })
      .def_prop_ro("warnings", [](const RockingRun& r) { return r.result.summary.warnings; })
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
      .def("json", [](const RockingRun& r) { return to_python(r.json()); })
      .def("__repr__", [](const RockingRun& r) {
        return fmt::format("RockingResult(max_rotation_over_alpha={:.6g}, overturned={}, end_state='{}')",
                           r.result.summary.max_rotation_over_alpha, r.result.summary.overturned ? "True" : "False",
                           rocking_state_name(r.result.summary.end_state));
      });

  m.def("rock", &run_rock, "motion"_a, "shape"_a, nb::kw_only(), "e"_a = "housner", "mu"_a = nb::none(),
        "g"_a = kStandardGravity, "method"_a = "adaptive", "rel_tol"_a = 1e-8, "rk4_substeps"_a = 10,
        "max_run_out_s"_a = 60.0, "vertical"_a = nb::none(), "history"_a = true);

  // ---- synthesis, intensity, inversion ----
  m.def("synth",
        [](double pga_g, double freq_hz, double duration_s, std::uint64_t seed, double dt_s, const std::string& model,
           const std::string& envelope, double zeta_g, double g) {
          SynthesisSpec spec;
          spec.pga_m_s2 = pga_g * g;
          spec.predominant_frequency_hz = freq_hz;
          spec.duration_s = duration_s;
          spec.dt_s = dt_s;
          spec.seed = seed;
          spec.model = parse_filter_model(model, "model");
          spec.envelope = parse_envelope_kind(envelope, "envelope");
          spec.ground_damping = zeta_g;
          nb::gil_scoped_release release;
          return synthesize(spec);
        },
        nb::kw_only(), "pga_g"_a, "freq_hz"_a, "duration_s"_a, "seed"_a = 0, "dt_s"_a = 0.01,
        "model"_a = "clough-penzien", "envelope"_a = "saragoni-hart", "zeta_g"_a = 0.3, "g"_a = kStandardGravity);

  m.def("intensity", &intensity_dict, "motion"_a, "g"_a = kStandardGravity);
  m.def("invert", &invert_survey, "survey_path"_a, nb::kw_only(), "threads"_a = 0);
}
