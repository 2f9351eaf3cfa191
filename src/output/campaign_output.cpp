// The outputs of `topple campaign`: campaign_output.hpp.
#include "topple/output/campaign_output.hpp"

#include <iterator>
#include <optional>

#include <fmt/format.h>

#include "topple/core/output_file.hpp"

namespace topple::io {
namespace {

nlohmann::ordered_json or_null(const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; }

std::string cell(const std::optional<double>& v) { return v ? fmt::format("{:.10g}", *v) : std::string(); }

const char* verdict(bool overturned) { return overturned ? "overturned" : "standing"; }

}  // namespace

void write_campaign_csv(const std::filesystem::path& path, const std::vector<ensemble::CampaignRow>& rows) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "id,model,predicted,observed,max_tilt_over_limit,overturn_time_s,overturn_azimuth_deg,observed_azimuth_deg,"
         "cpu_s,duration_s\n";
  fmt::memory_buffer line;
  for (const ensemble::CampaignRow& r : rows) {
    line.clear();
    // ids are refused with commas, quotes and line breaks by the reader: a plain field.
    fmt::format_to(std::back_inserter(line), "{},{},{},{},{:.10g},{},{},{},{:.6g},{:.10g}\n", r.id,
                   ensemble::campaign_model_name(r.model), verdict(r.predicted_overturned),
                   verdict(r.observed_overturned), r.max_tilt_over_limit, cell(r.overturn_time_s),
                   cell(r.overturn_azimuth_deg), cell(r.observed_azimuth_deg), r.cpu_s, r.duration_s);
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
  file.commit();
}

nlohmann::ordered_json campaign_summary_json(const ensemble::CampaignSettings& settings, const std::string& file,
                                             std::size_t tests, const std::vector<ensemble::CampaignRow>& rows) {
  const ensemble::CampaignTarget target;
  nlohmann::ordered_json j;
  j["campaign"] = settings.name;
  j["file"] = file;
  j["blind"] = true;  // the outcomes observed are read only to score: nothing is fitted to them
  j["tests"] = tests;
  j["positive"] = "overturned";
  j["azimuths"] = "degrees counter-clockwise from the table's x axis, seen from above";
  j["settings"] = {{"mu", or_null(settings.mu)},
                   {"mu_k", or_null(settings.mu ? std::optional(settings.mu_k.value_or(*settings.mu)) : std::nullopt)},
                   {"restitution", settings.restitution == RestitutionMode::given ? "given" : "housner"},
                   {"e", settings.restitution == RestitutionMode::given ? nlohmann::ordered_json(settings.e) : nullptr},
                   {"g_m_s2", settings.g_m_s2}};
  j["target"] = {{"accuracy_min", target.accuracy_min},
                 {"recall_above", target.recall_above},
                 {"times_real_time_min", target.times_real_time_min},
                 {"source", "issue 29: accuracy of a lab numerical model (0.87-0.90), recall above 0.8, 1000 times a "
                            "physics-engine digital twin's about 60 times real time"}};
  nlohmann::ordered_json models = nlohmann::ordered_json::array();
  nlohmann::ordered_json warnings = nlohmann::ordered_json::array();
  for (const ensemble::CampaignModel model : settings.models) {
    const ensemble::CampaignScore s = ensemble::score_campaign(rows, model);
    const ensemble::CampaignTargetCheck meets = ensemble::check_target(s, target);
    models.push_back({{"model", ensemble::campaign_model_name(model)},
                      {"tp", s.confusion.tp},
                      {"fp", s.confusion.fp},
                      {"tn", s.confusion.tn},
                      {"fn", s.confusion.fn},
                      {"accuracy", or_null(s.metrics.accuracy)},
                      {"recall", or_null(s.metrics.recall)},
                      {"precision", or_null(s.metrics.precision)},
                      {"f1", or_null(s.metrics.f1)},
                      {"azimuths_compared", s.azimuths_compared},
                      {"median_azimuth_error_deg", or_null(s.median_azimuth_error_deg)},
                      {"cpu_s", s.cpu_s},
                      {"simulated_s", s.simulated_s},
                      {"times_real_time", or_null(s.times_real_time)},
                      {"meets_target",
                       {{"accuracy", meets.accuracy}, {"recall", meets.recall}, {"speed", meets.speed},
                        {"all", meets.all()}}}});
  }
  for (const ensemble::CampaignRow& r : rows) {
    for (const std::string& w : r.warnings) {
      warnings.push_back(fmt::format("{} ({}): {}", r.id, ensemble::campaign_model_name(r.model), w));
    }
  }
  j["models"] = std::move(models);
  j["warnings"] = std::move(warnings);
  return j;
}

}  // namespace topple::io
