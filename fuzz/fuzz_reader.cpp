// libFuzzer target for one reader: the format is fixed at compile time (TOPPLE_FUZZ_FORMAT, a topple::io::Format
// enumerator), so each target explores one parser deeply. Built once per format by fuzz/CMakeLists.txt.
//
// Contract checked (docs/fuzzing.md): parse_motion either throws topple::InputError or returns a record that is
// usable: at least one sample, a positive finite dt, finite accelerations and times, within GroundMotionLimits. On
// a record that reads, the whole `topple info` pipeline runs (every intensity measure must be finite or refused with
// an InputError, as `info` prints "undefined"), then one short sliding run and one short rocking run (their printed
// quantities finite; a SolverError, exit 3, is an allowed end). Any other exception, a crash, a sanitizer report, a
// non-finite number or a limit broken ends the run with a reproducer.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <optional>
#include <string_view>

#include "topple/core/error.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/baseline.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/motion/spectra.hpp"

namespace {

using topple::GroundMotion;
using Limits = topple::GroundMotionLimits;

void require_finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) std::abort();
  }
}

void check_record(const GroundMotion& m) {
  if (m.size() == 0 || m.size() > Limits::max_samples) std::abort();
  if (!(m.dt_s() > 0.0) || !std::isfinite(m.dt_s())) std::abort();
  for (double a : m.accel_m_s2()) {
    if (!std::isfinite(a) || std::abs(a) > Limits::max_abs_accel_m_s2) std::abort();
  }
  require_finite({m.start_time_s(), m.end_time_s(), m.pga_m_s2(), m.pga_time_s()});
  if (!(m.duration_s() <= Limits::max_duration_s)) std::abort();
}

/// Each exec stays fast: the pipeline sees at most this many samples (uniform, or of the irregular record's
/// finest step, which is what the spectra resample it to).
constexpr std::size_t kMaxPipelineSamples = 4096;

/// The part of the record the pipeline runs on: the whole record when small, else its beginning.
std::optional<GroundMotion> bounded(const GroundMotion& m) {
  double step = m.dt_s();
  if (!m.is_uniform()) {
    const auto t = m.times_s();
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (t[i] > t[i - 1]) step = std::min(step, t[i] - t[i - 1]);
    }
  }
  if (m.duration_s() / step < static_cast<double>(kMaxPipelineSamples) && m.size() <= kMaxPipelineSamples) return m;
  try {
    return m.trimmed(m.start_time_s(), m.start_time_s() + step * static_cast<double>(kMaxPipelineSamples - 1));
  } catch (const topple::InputError&) {
    return std::nullopt;  // a window of one jump: nothing left to run
  }
}

template <class F>
void allowing_input_errors(F f) {
  try {
    f();
  } catch (const topple::InputError&) {
    // `info` prints "undefined (reason)" for a measure that does not exist for this record.
  }
}

/// What `topple info`, `topple slide` and `topple rock` print, on a record that read.
void run_pipeline(const GroundMotion& full) {
  const auto m = bounded(full);
  if (!m) return;
  const auto im = topple::basic_intensity(*m);
  require_finite({im.pga_m_s2, im.pga_time_s, im.pgv_m_s, im.pgd_m, im.arias_m_s,
                  topple::cumulative_absolute_velocity_m_s(*m)});
  allowing_input_errors([&] {
    const auto d = topple::significant_duration(*m);
    require_finite({d.start_s, d.end_s, d.duration_s});
  });
  allowing_input_errors([&] { require_finite({topple::predominant_period_s(*m)}); });
  allowing_input_errors([&] { require_finite({topple::mean_period_s(*m)}); });
  allowing_input_errors([&] { require_finite({topple::predominant_frequency_hz(*m)}); });
  try {
    const auto s = topple::slide_summary(*m, topple::SlidingBlock::make(0.3));
    require_finite({s.max_abs_displacement_m, s.max_displacement_time_s, s.residual_displacement_m,
                    s.max_abs_velocity_m_s, s.total_slip_duration_s, s.end_time_s});
  } catch (const topple::SolverError&) {
  }
  try {
    topple::RockingOptions options;
    options.max_run_out_s = 2.0;           // short: the run-out on still ground is not what is fuzzed
    options.max_steps = 200'000;           // bounded exec time; past it a SolverError, an allowed end
    const auto s = topple::rock_summary(*m, topple::RockingBody::block(0.04, 0.2), options);
    require_finite({s.max_abs_rotation_rad, s.max_rotation_over_alpha, s.max_rotation_time_s,
                    s.max_abs_theta_dot_rad_s, s.energy_lost_j_per_kg, s.end_time_s});
  } catch (const topple::SolverError&) {
  }
}

void parse(std::string_view text, const topple::io::ReadOptions& options) {
  std::optional<GroundMotion> motion;
  try {
    motion = topple::io::parse_motion(text, "fuzz-input", options);
  } catch (const topple::InputError&) {
    return;  // refusing bad input is the expected outcome; anything else escapes and is reported by libFuzzer
  }
  check_record(*motion);
  run_pipeline(*motion);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  topple::io::ReadOptions options;
#ifdef TOPPLE_FUZZ_DETECT
  // Detection alone must not fail, then the automatic path as a user would call it.
  (void)topple::io::detect_format(text);
  options.format = topple::io::Format::automatic;
#else
  options.format = topple::io::Format::TOPPLE_FUZZ_FORMAT;
#endif
  parse(text, options);
  // The options that change what a reader does: a chosen channel (multi-channel formats), and for plain text a
  // unit and a time step (the one-column path; for the other formats a check against what the file states).
  options.channel = 2;
  parse(text, options);
  options.channel = std::nullopt;
  options.units = "g";
  options.dt_s = 0.01;
  parse(text, options);
  // Records as recorded (issue 28): a column choice by number and by name, with and without a time column, a forced
  // separator, and each baseline method (applied to whatever reads, in every format).
  options.dt_s = std::nullopt;
  options.units.clear();
  options.baseline = topple::parse_baseline("poly:3");
  parse(text, options);
  options.baseline = topple::parse_baseline("pre-event:0.05");
  parse(text, options);
  options.baseline = topple::Baseline{};
  if (options.format == topple::io::Format::plain || options.format == topple::io::Format::automatic) {
    options.columns = topple::io::parse_columns("1,3");
    parse(text, options);
    options.columns = topple::io::parse_columns("Time (s),Table Acc (g)");
    options.baseline = topple::parse_baseline("mean");
    parse(text, options);
    options.columns = topple::io::parse_columns(",2");
    options.separator = topple::io::Separator::tab;
    options.units = "g";
    options.dt_s = 0.01;
    parse(text, options);
  }
  return 0;
}
