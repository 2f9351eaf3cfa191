#pragma once
// SLAMMER 1.1's published verification suite (../shared/verification/slammer, its README): the results file, the
// records as SLAMMER read them (slammer_library/*.txt with dt from eq.sql) and SLAMMER's scaling rule.
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "topple/motion/ground_motion.hpp"

namespace topple::test {

struct SlammerRecordInfo {
  double dt_s = 0.0;
  double pga_g_rounded = 0.0;  ///< eq.sql's PGA, rounded to 3 decimals: SLAMMER scaled by target / this
};

/// The whole text of a gzip file (through `gzip -dc`); empty when it cannot be read.
[[nodiscard]] std::string gunzip(const std::filesystem::path& path);

/// "Chi-Chi, Taiwan 1999" (eq.sql) and "Chi-Chi 1999" (results) name the same event: drop ", country".
[[nodiscard]] std::string slammer_event_key(std::string name);

/// eq.sql keyed by slammer_event_key(event) + "|" + station.
[[nodiscard]] std::map<std::string, SlammerRecordInfo> read_slammer_eq_sql(const std::filesystem::path& path);

/// The suite's folder and its content, records loaded once.
class SlammerSuite {
 public:
  SlammerSuite();
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }
  [[nodiscard]] const nlohmann::json& results() const { return results_; }
  /// The record of an analysis scaled as SLAMMER did (target PGA / the rounded eq.sql PGA), normal polarity.
  [[nodiscard]] GroundMotion scaled_record(const nlohmann::json& analysis);
  /// The record's file name in slammer_library (".txt").
  [[nodiscard]] static std::string record_file(const nlohmann::json& analysis);

 private:
  std::filesystem::path dir_;
  nlohmann::json results_;
  std::map<std::string, SlammerRecordInfo> records_;
  std::map<std::string, GroundMotion> cache_;
};

/// pySLAMMER's criterion (verification_config.toml): within 2 % or 1 cm, and within 0.05 cm below 0.5 cm.
[[nodiscard]] bool within_slammer_criterion(double ours_cm, double slammer_cm);

}  // namespace topple::test
