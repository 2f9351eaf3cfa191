#include "topple/pulses.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "topple/error.hpp"

namespace topple {
namespace {

struct Points {
  std::vector<double> t;
  std::vector<double> a;
  void add(double time, double accel) {
    t.push_back(time);
    a.push_back(accel);
  }
};

template <class F>
void sample_smooth(Points& p, double t_end, double dt, F f) {
  const auto n = static_cast<std::size_t>(std::ceil(t_end / dt - 1e-9));
  for (std::size_t i = 0; i <= n; ++i) {
    const double t = std::min(static_cast<double>(i) * dt, t_end);
    p.add(t, f(t));
  }
}

}  // namespace

PulseKind parse_pulse_kind(std::string_view name, const std::string& field) {
  if (name == "rect" || name == "rectangular") return PulseKind::rectangular;
  if (name == "tri" || name == "triangular") return PulseKind::triangular;
  if (name == "double-tri" || name == "double-triangular") return PulseKind::double_triangular;
  if (name == "sine") return PulseKind::sine;
  if (name == "cosine") return PulseKind::cosine;
  if (name == "ricker") return PulseKind::ricker;
  throw parameter_error(field, fmt::format("unknown pulse '{}' (known: rect, tri, double-tri, sine, cosine, ricker)",
                                           name));
}

std::string_view pulse_kind_name(PulseKind kind) {
  switch (kind) {
    case PulseKind::rectangular: return "rect";
    case PulseKind::triangular: return "tri";
    case PulseKind::double_triangular: return "double-tri";
    case PulseKind::sine: return "sine";
    case PulseKind::cosine: return "cosine";
    case PulseKind::ricker: return "ricker";
  }
  return "unknown";
}

GroundMotion make_pulse(const PulseSpec& spec) {
  const double amp = spec.amplitude_m_s2;
  const double t0 = spec.duration_s;
  if (!std::isfinite(amp)) throw parameter_error("amplitude", "pulse amplitude must be finite");
  if (!(t0 > 0.0) || !std::isfinite(t0)) {
    throw parameter_error("duration", fmt::format("pulse duration must be positive and finite, got {} s", t0));
  }
  if (!(spec.tail_s >= 0.0) || !std::isfinite(spec.tail_s)) {
    throw parameter_error("tail", fmt::format("tail must be non-negative and finite, got {} s", spec.tail_s));
  }
  const double dt = spec.dt_s > 0.0 ? spec.dt_s : t0 / 2000.0;
  if (!std::isfinite(dt)) throw parameter_error("dt", "pulse sampling step must be finite");
  Points p;
  double end = t0;
  switch (spec.kind) {
    case PulseKind::rectangular:
      p.add(0.0, 0.0);
      p.add(0.0, amp);
      p.add(t0, amp);
      p.add(t0, 0.0);
      break;
    case PulseKind::triangular:
      p.add(0.0, 0.0);
      p.add(0.5 * t0, amp);
      p.add(t0, 0.0);
      break;
    case PulseKind::double_triangular:
      p.add(0.0, 0.0);
      p.add(0.5 * t0, amp);
      p.add(t0, 0.0);
      p.add(1.5 * t0, -amp);
      p.add(2.0 * t0, 0.0);
      end = 2.0 * t0;
      break;
    case PulseKind::sine:
      sample_smooth(p, t0, dt, [&](double t) { return amp * std::sin(2.0 * kPi * t / t0); });
      p.a.back() = 0.0;  // one full cycle ends at zero; keep the jump out
      break;
    case PulseKind::cosine:
      // A cosine cycle starts and ends at A: the ground jumps to A at t = 0 and back to 0 at t0.
      p.add(0.0, 0.0);
      sample_smooth(p, t0, dt, [&](double t) { return amp * std::cos(2.0 * kPi * t / t0); });
      p.add(t0, 0.0);
      break;
    case PulseKind::ricker: {
      const double f = 1.0 / t0;
      end = 3.0 * t0;
      sample_smooth(p, end, dt, [&](double t) {
        const double x = kPi * f * (t - 1.5 * t0);
        return amp * (1.0 - 2.0 * x * x) * std::exp(-x * x);
      });
      break;
    }
  }
  if (spec.tail_s > 0.0) p.add(end + spec.tail_s, 0.0);
  RecordMetadata meta;
  meta.format = "pulse";
  meta.event = fmt::format("{} pulse, amplitude {:.6g} m/s2, duration {:.6g} s", pulse_kind_name(spec.kind), amp, t0);
  meta.units_as_read = "m/s2";
  return GroundMotion::irregular(std::move(p.t), std::move(p.a), std::move(meta));
}

}  // namespace topple
