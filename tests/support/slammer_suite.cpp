#include "support/slammer_suite.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "support/shared_data.hpp"
#include "topple/io/read.hpp"

namespace topple::test {
namespace {
struct Pclose {
  void operator()(std::FILE* f) const { pclose(f); }
};
}  // namespace

std::string gunzip(const std::filesystem::path& path) {
  std::unique_ptr<std::FILE, Pclose> pipe(popen(("gzip -dc '" + path.string() + "'").c_str(), "r"));
  std::string text;
  char buffer[65536];
  std::size_t got = 0;
  while (pipe && (got = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0) text.append(buffer, got);
  return text;
}

std::string slammer_event_key(std::string name) {
  const auto comma = name.find(',');
  if (comma != std::string::npos) {
    const auto year = name.rfind(' ');
    name = name.substr(0, comma) + name.substr(year);
  }
  return name;
}

std::map<std::string, SlammerRecordInfo> read_slammer_eq_sql(const std::filesystem::path& path) {
  std::map<std::string, SlammerRecordInfo> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cols;
    std::stringstream ss(line);
    std::string col;
    while (std::getline(ss, col, '\t')) cols.push_back(col);
    if (cols.size() < 7) continue;
    out[slammer_event_key(cols[0]) + "|" + cols[1]] = SlammerRecordInfo{std::stod(cols[2]), std::stod(cols[6])};
  }
  return out;
}

SlammerSuite::SlammerSuite()
    : dir_(shared_dir() / "verification" / "slammer"),
      results_(nlohmann::json::parse(gunzip(dir_ / "slammer_results.json.gz"))),
      records_(read_slammer_eq_sql(dir_ / "slammer_library" / "eq.sql")) {}

std::string SlammerSuite::record_file(const nlohmann::json& analysis) {
  std::string file = analysis.at("ground_motion_parameters").at("ground_motion_file").get<std::string>();
  return file.substr(0, file.rfind('.')) + ".txt";
}

GroundMotion SlammerSuite::scaled_record(const nlohmann::json& analysis) {
  const auto& gm = analysis.at("ground_motion_parameters");
  const std::string key =
      slammer_event_key(gm.at("earthquake").get<std::string>()) + "|" + gm.at("record_station").get<std::string>();
  const auto info = records_.find(key);
  if (info == records_.end()) throw std::runtime_error("record not in eq.sql: " + key);
  const std::string file = record_file(analysis);
  if (!cache_.contains(file)) {
    io::ReadOptions opt;
    opt.format = io::Format::plain;
    opt.dt_s = info->second.dt_s;
    opt.units = "g";
    cache_.emplace(file, io::read_motion(dir_ / "slammer_library" / file, opt));
  }
  return cache_.at(file).scaled(gm.at("target_pga_g").get<double>() / info->second.pga_g_rounded);
}

bool within_slammer_criterion(double ours_cm, double slammer_cm) {
  const double diff = std::abs(ours_cm - slammer_cm);
  if (slammer_cm < 0.5) return diff <= 0.05;
  return diff <= std::max(0.02 * slammer_cm, 1.0);
}

}  // namespace topple::test
