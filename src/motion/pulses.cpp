#include "topple/motion/pulses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/enum_names.hpp"

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
  const double samples = std::ceil(t_end / dt - 1e-9);
  if (!(samples <= kMaxPulseSamples)) {
    throw parameter_error("dt", fmt::format("{} s sampled every {} s is more than {:.0e} samples", t_end, dt,
                                            kMaxPulseSamples));
  }
  const auto n = static_cast<std::size_t>(samples);
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
  if (name == "tri-train" || name == "triangular-train") return PulseKind::triangular_train;
  if (name == "trap-train" || name == "trapezoidal-train") return PulseKind::trapezoidal_train;
  throw parameter_error(field, fmt::format("unknown pulse '{}' (known: rect, tri, double-tri, sine, cosine, ricker, "
                                           "tri-train, trap-train)", name));
}

constexpr std::array<EnumName<PulseKind>, 8> kPulseKindNames{{
    {PulseKind::rectangular, "rect"},
    {PulseKind::triangular, "tri"},
    {PulseKind::double_triangular, "double-tri"},
    {PulseKind::sine, "sine"},
    {PulseKind::cosine, "cosine"},
    {PulseKind::ricker, "ricker"},
    {PulseKind::triangular_train, "tri-train"},
    {PulseKind::trapezoidal_train, "trap-train"},
}};

std::string_view pulse_kind_name(PulseKind kind) { return enum_name(kPulseKindNames, kind); }

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
  const bool train = spec.kind == PulseKind::triangular_train || spec.kind == PulseKind::trapezoidal_train;
  if (train && (spec.cycles < 1 || spec.cycles > kMaxPulseCycles)) {
    throw parameter_error("cycles", fmt::format("a pulse train needs 1 to {} cycles, got {}", kMaxPulseCycles,
                                                spec.cycles));
  }
  if (spec.kind == PulseKind::trapezoidal_train &&
      !(spec.trapezoid_ramp_fraction > 0.0 && spec.trapezoid_ramp_fraction <= 0.5)) {
    throw parameter_error("trapezoid_ramp_fraction", fmt::format("the ramp fraction must be in (0, 0.5], got {}",
                                                                 spec.trapezoid_ramp_fraction));
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
    case PulseKind::triangular_train:
    case PulseKind::trapezoidal_train: {
      // Corner times of one cycle as fractions of t0 (a triangle is a trapezoid with r = 1/2: no plateau).
      const double r = spec.kind == PulseKind::triangular_train ? 0.5 : spec.trapezoid_ramp_fraction;
      const double q = 0.5 * r;  // ramp length / t0
      p.add(0.0, 0.0);
      for (int c = 0; c < spec.cycles; ++c) {
        const double start = static_cast<double>(c) * t0;
        if (r < 0.5) {
          p.add(start + q * t0, amp);
          p.add(start + (0.5 - q) * t0, amp);
        } else {
          p.add(start + 0.25 * t0, amp);
        }
        p.add(start + 0.5 * t0, 0.0);
        if (r < 0.5) {
          p.add(start + (0.5 + q) * t0, -amp);
          p.add(start + (1.0 - q) * t0, -amp);
        } else {
          p.add(start + 0.75 * t0, -amp);
        }
        p.add(start + t0, 0.0);
      }
      end = static_cast<double>(spec.cycles) * t0;
      break;
    }
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

// ---- Mavroeidis & Papageorgiou (2003) ----
namespace topple {

void MavroeidisPapageorgiouPulse::validate() const {
  if (!std::isfinite(velocity_amplitude_m_s)) {
    throw parameter_error("velocity_amplitude_m_s", "the MP pulse's velocity amplitude A must be finite");
  }
  if (!(frequency_hz > 0.0) || !std::isfinite(frequency_hz)) {
    throw parameter_error("frequency_hz", fmt::format("the MP pulse's frequency f_p must be positive, got {} Hz",
                                                      frequency_hz));
  }
  if (!std::isfinite(phase_rad)) throw parameter_error("phase_rad", "the MP pulse's phase nu must be finite");
  if (!(gamma > 1.0) || !std::isfinite(gamma)) {
    throw parameter_error("gamma", fmt::format("the MP pulse needs gamma > 1 (MP 2003, eq. 1), got {}", gamma));
  }
}

double MavroeidisPapageorgiouPulse::velocity_m_s(double t) const {
  if (t < 0.0 || t > duration_s()) return 0.0;
  const double u = 2.0 * kPi * frequency_hz * (t - centre_time_s());
  return 0.5 * velocity_amplitude_m_s * (1.0 + std::cos(u / gamma)) * std::cos(u + phase_rad);  // MP 2003 eq. 1
}

double MavroeidisPapageorgiouPulse::acceleration_m_s2(double t) const {
  if (t < 0.0 || t > duration_s()) return 0.0;
  const double u = 2.0 * kPi * frequency_hz * (t - centre_time_s());
  return -(velocity_amplitude_m_s * kPi * frequency_hz / gamma) *
         (std::sin(u / gamma) * std::cos(u + phase_rad) +
          gamma * std::sin(u + phase_rad) * (1.0 + std::cos(u / gamma)));
}

double MavroeidisPapageorgiouPulse::displacement_m(double t) const {
  // v = A/2 [cos(u + nu) + cos(u p + nu) / 2 + cos(u m + nu) / 2], p = 1 + 1/gamma, m = 1 - 1/gamma (product to sum),
  // so D(u) = A / (2 w) [sin(u + nu) + sin(u p + nu) / (2 p) + sin(u m + nu) / (2 m)], w = 2 pi f_p, minus D(-pi gamma).
  const double w = 2.0 * kPi * frequency_hz;
  const double p = 1.0 + 1.0 / gamma;
  const double m = 1.0 - 1.0 / gamma;
  const auto antiderivative = [&](double u) {
    return 0.5 * velocity_amplitude_m_s / w *
           (std::sin(u + phase_rad) + std::sin(u * p + phase_rad) / (2.0 * p) + std::sin(u * m + phase_rad) / (2.0 * m));
  };
  const double tc = std::clamp(t, 0.0, duration_s());
  return antiderivative(w * (tc - centre_time_s())) - antiderivative(-kPi * gamma);
}

GroundMotion make_mavroeidis_papageorgiou_pulse(const MavroeidisPapageorgiouPulse& pulse, double dt_s, double tail_s) {
  pulse.validate();
  if (!(dt_s >= 0.0) || !std::isfinite(dt_s)) {
    throw parameter_error("dt", fmt::format("the sampling step must be non-negative and finite, got {} s", dt_s));
  }
  if (!(tail_s >= 0.0) || !std::isfinite(tail_s)) {
    throw parameter_error("tail", fmt::format("tail must be non-negative and finite, got {} s", tail_s));
  }
  const double end = pulse.duration_s();
  Points p;
  sample_smooth(p, end, dt_s > 0.0 ? dt_s : end / 2000.0, [&](double t) { return pulse.acceleration_m_s2(t); });
  p.a.front() = 0.0;  // exactly zero at both ends (eq. 1's envelope vanishes there)
  p.a.back() = 0.0;
  if (tail_s > 0.0) p.add(end + tail_s, 0.0);
  RecordMetadata meta;
  meta.format = "pulse";
  meta.event = fmt::format("Mavroeidis-Papageorgiou pulse, A {:.6g} m/s, f_p {:.6g} Hz, nu {:.6g} rad, gamma {:.6g}",
                           pulse.velocity_amplitude_m_s, pulse.frequency_hz, pulse.phase_rad, pulse.gamma);
  meta.units_as_read = "m/s2";
  return GroundMotion::irregular(std::move(p.t), std::move(p.a), std::move(meta));
}

}  // namespace topple
