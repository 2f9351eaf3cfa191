#include "topple/io/flexible_json.hpp"

#include "topple/io/write.hpp"

namespace topple::io {
namespace {

nlohmann::ordered_json with_mode(nlohmann::ordered_json support, const FlexibleSummary& s) {
  support["mode_freq_hz"] = s.mode.omega_rad_s / (2.0 * kPi);
  support["mode_damping_ratio"] = s.mode.damping_ratio;
  support["kmax"] = s.kmax;
  return support;
}

const char* analysis_name(FlexibleAnalysis a) { return a == FlexibleAnalysis::coupled ? "coupled" : "decoupled"; }

}  // namespace

nlohmann::ordered_json flexible_summary_json(const FlexibleSummary& summary, const SlidingBlock& block,
                                             const SupportOscillator& support, FlexibleAnalysis analysis) {
  nlohmann::ordered_json s;
  s["analysis"] = analysis_name(analysis);
  s["kind"] = "oscillator";
  s["freq_hz"] = support.freq_hz;
  s["damping_ratio"] = support.damping_ratio;
  s["mass_ratio"] = support.mass_ratio;
  nlohmann::ordered_json j = sliding_summary_json(summary.sliding, block);
  j["support"] = with_mode(std::move(s), summary);
  return j;
}

nlohmann::ordered_json flexible_summary_json(const FlexibleSummary& summary, const SlidingBlock& block,
                                             const SlidingMassColumn& column, FlexibleAnalysis analysis) {
  nlohmann::ordered_json s;
  s["analysis"] = analysis_name(analysis);
  s["kind"] = "sliding_mass";
  s["height_m"] = column.height_m;
  s["vs_slope_m_s"] = column.vs_slope_m_s;
  s["vs_base_m_s"] = column.vs_base_m_s;
  s["damping_ratio"] = column.damping_ratio;
  s["reference_strain"] =
      column.reference_strain ? nlohmann::ordered_json(*column.reference_strain) : nlohmann::ordered_json(nullptr);
  s["vs_final_m_s"] = summary.mode.vs_m_s;
  s["equivalent_linear_iterations"] = summary.mode.iterations;
  nlohmann::ordered_json j = sliding_summary_json(summary.sliding, block);
  j["support"] = with_mode(std::move(s), summary);
  return j;
}

}  // namespace topple::io
