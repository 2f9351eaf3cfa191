// topple campaign: blind predictions of a shake-table campaign's outcomes, scored (docs/campaign.md). Parsing and
// printing only: the reader is io::read_campaign_file, the runs and the scores ensemble::run_campaign and
// ensemble::score_campaign, the outputs io::write_campaign_csv and io::campaign_summary_json.
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "common.hpp"
#include "grids.hpp"
#include "progress.hpp"
#include "topple/core/output_file.hpp"
#include "topple/ensemble/campaign.hpp"
#include "topple/io/campaign_file.hpp"
#include "topple/output/campaign_output.hpp"

namespace topple::cli {
namespace {

struct CampaignOptions {
  std::string file;
  std::string csv;
  std::string json;
  int threads = 0;
  bool quiet = false;
};

std::string ratio_text(const nlohmann::ordered_json& v) {
  return v.is_null() ? std::string("-") : fmt::format("{:.4f}", v.get<double>());
}

void run_campaign_command(const CampaignOptions& o) {
  check_threads(o.threads);
  check_output_path(o.csv);  // before any work: a result that cannot be written is not computed
  check_output_path(o.json);
  const io::CampaignFile campaign = io::read_campaign_file(o.file);
  ProgressBar bar(progress_wanted(o.quiet), campaign.settings.name);
  const std::vector<ensemble::CampaignRow> rows = ensemble::run_campaign(
      campaign.tests, campaign.settings, [&](std::size_t i) { return io::load_campaign_input(campaign, i); },
      static_cast<std::size_t>(o.threads), bar.callback());
  bar.finish();
  for (const auto& r : rows) {
    require_finite({{"max tilt over limit", r.max_tilt_over_limit}, {"cpu seconds", r.cpu_s},
                    {"duration", r.duration_s}});
  }
  if (!o.csv.empty()) io::write_campaign_csv(o.csv, rows);
  const nlohmann::ordered_json summary =
      io::campaign_summary_json(campaign.settings, o.file, campaign.tests.size(), rows);
  if (!summary["warnings"].empty()) {
    fmt::print(stderr, "topple: warning: {} warning(s) from the runs (in the summary's \"warnings\")\n",
               summary["warnings"].size());
  }
  if (o.json.empty()) {
    fmt::print("{}\n", summary.dump(2));
    return;
  }
  io::OutputFile out(o.json);
  out.stream() << summary.dump(2) << '\n';
  out.commit();
  fmt::print("campaign {}: {} tests, blind (the outcomes observed are read only to score)\n",
             campaign.settings.name, campaign.tests.size());
  for (const auto& m : summary["models"]) {
    fmt::print("  {:<8} TP {} FP {} TN {} FN {}  accuracy {}  recall {}  precision {}  F1 {}  {} x real time{}\n",
               m["model"].get<std::string>(), m["tp"].get<std::size_t>(), m["fp"].get<std::size_t>(),
               m["tn"].get<std::size_t>(), m["fn"].get<std::size_t>(), ratio_text(m["accuracy"]),
               ratio_text(m["recall"]), ratio_text(m["precision"]), ratio_text(m["f1"]),
               m["times_real_time"].is_null() ? std::string("-")
                                              : fmt::format("{:.4g}", m["times_real_time"].get<double>()),
               m["meets_target"]["all"].get<bool>() ? "  (meets the target)" : "");
  }
  if (!o.csv.empty()) fmt::print("rows written to {}\n", o.csv);
  fmt::print("summary written to {}\n", o.json);
}

}  // namespace

void add_campaign_command(CLI::App& app) {
  auto o = std::make_shared<CampaignOptions>();
  CLI::App* cmd = app.add_subcommand(
      "campaign", "Blind predictions of a shake-table campaign (bodies, table records, outcomes observed) by the "
                  "planar, coupled and 3-D models, scored: accuracy, recall, precision, F1, azimuth error, speed");
  cmd->add_option("file", o->file, "Campaign file (TOML; see docs/campaign.md)")->required();
  cmd->add_option("--csv", o->csv, "Write one row per test and model to this CSV file");
  cmd->add_option("--json", o->json, "Write the summary (JSON) to this file and print a short table (default: the "
                                     "JSON on stdout)");
  cmd->add_option("--threads", o->threads, "Worker threads (default 0: every core)")->capture_default_str();
  add_quiet_flag(*cmd, o->quiet);
  cmd->callback([o] { run_campaign_command(*o); });
}

}  // namespace topple::cli
