#pragma once
// The recovery test on real records (issue 18): surveys made from real accelerograms, inverted, and scored.
//
// For a record scaled to a target PGA, a fixed set of household objects (sliding objects with various mu, rocking
// objects of various sizes and slenderness) is simulated with the solvers themselves (slide_summary, rock_summary:
// never the inversion's observation_match or likelihood code), a few observations are deliberately misreported
// (each one independently with probability misreport_rate, from a seeded PortableRandom), and the survey is written
// as TOML text (the format of examples/survey.toml) that io::parse_survey reads back. The truth is the scaled
// record's PGA and its predominant frequency measured exactly as the inversion's frequency axis measures its motions
// (spectra.hpp: predominant_frequency_hz). Score: coverage of both truths by the marginal 68 % / 95 % intervals
// (an open end is unconstrained: it covers everything on its side), median / truth, widths (open end: infinite).
//
// Used by tests/inversion/test_inversion_real_records.cpp (a few surveys on a small grid) and bench/recovery_real_records.cpp
// (the full set on the survey's own grid; figures in docs/verification.md).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/inversion/inversion.hpp"

namespace topple::recovery {

struct RecordCase {
  std::string label;             ///< short name for the tables ("Kobe TAK-090")
  std::filesystem::path path;    ///< the file under shared/records
  std::optional<int> channel;    ///< 1-based channel of a multi-channel file
};

/// The real records of shared/records with a PGA worth scaling (the readers-only files of a few cm/s^2 are left
/// out): the 18 SLAMMER records and the agency files beside them that are not copies of one of those.
[[nodiscard]] std::vector<RecordCase> real_records(const std::filesystem::path& shared_dir);

struct SurveyOptions {
  double misreport_rate = 0.05;  ///< chance that each observation is flipped to a wrong one (dimensionless)
  std::uint64_t seed = 1;        ///< the survey's own draws (true mu of each object, misreports)
  std::string inversion_toml;    ///< the [inversion] table's body, written as given ("pga_g = [...]\n...")
};

struct SurveyCase {
  std::string name;         ///< "<record> @ 0.30 g"
  std::string record;       ///< RecordCase::label
  double pga_g = 0.0;       ///< truth, g
  double freq_hz = 0.0;     ///< truth: predominant_frequency_hz of the scaled record, Hz
  std::string toml;         ///< the survey file
  int objects = 0;
  int misreports = 0;       ///< how many observations were flipped
  bool moved = false;       ///< some *reported* outcome says an object moved (slid, rocked, overturned)
};

/// Score of one survey against its truths; `site` gives the hard static threshold (static_bounds).
/// One survey: `record` scaled to `pga_g`, the objects' outcomes from the solvers, misreports, the TOML text.
[[nodiscard]] SurveyCase make_survey(const GroundMotion& record, const std::string& label, double pga_g,
                                     const SurveyOptions& options);

struct CaseScore {
  std::string name;
  double pga_g = 0.0, freq_hz = 0.0;   ///< truths
  int misreports = 0;
  bool moved = false;
  Estimate pga, freq;                  ///< the inversion's marginal estimates
  bool pga_in68 = false, pga_in95 = false, freq_in68 = false, freq_in95 = false;
  double median_ratio = 0.0;           ///< median PGA / truth
  double pga_width95 = 0.0;            ///< ci95 high / low (infinity when an end is open)
  double freq_width95 = 0.0;           ///< likewise
  bool freq_closed95 = false;          ///< both ends of the frequency 95 % interval exist
  std::optional<double> hard_lower_g;  ///< the survey's largest hard static lower threshold (g), if any
  bool leaks = false;                  ///< the PGA 95 % interval reaches more than a grid cell below it, or is open
};

[[nodiscard]] CaseScore score(const SurveyCase& survey, const InversionResult& result, const Site& site);

struct Summary {
  int surveys = 0;
  double pga_cov68 = 0.0, pga_cov95 = 0.0;      ///< fractions
  double median_within = 0.0;                   ///< fraction with median / truth in [0.8, 1.25]
  double median_width95_moved = 0.0;            ///< median over surveys where something moved (infinite if open)
  int moved = 0;
  double top95_quiet_max_g = 0.0;               ///< largest 95 % top where nothing moved (infinite if open); 0: none
  int quiet = 0;
  double freq_cov68 = 0.0, freq_cov95 = 0.0;    ///< fractions
  double freq_closed95 = 0.0;                   ///< fraction closed at both ends
  double median_ratio_median = 0.0;             ///< median of median/truth
  int hard = 0;                                 ///< surveys with a hard lower threshold
  double leak = 0.0;                            ///< fraction of those whose 95 % interval leaks (CaseScore::leaks)
};

[[nodiscard]] Summary summarise(const std::vector<CaseScore>& scores);

/// A markdown table with one row per survey, then the summary against the targets.
[[nodiscard]] std::string markdown(const std::vector<CaseScore>& scores, const Summary& summary);

/// Makes the surveys of every (record, pga) pair, parses them, inverts them all with one shared family
/// (invert_sites) and scores them. `write_dir`, when not empty, receives each survey's TOML file.
[[nodiscard]] std::vector<CaseScore> run(const std::vector<RecordCase>& records, const std::vector<double>& pga_g,
                                         const SurveyOptions& options, const InversionOptions& inversion_options,
                                         const std::filesystem::path& write_dir = {});

/// The error rates eps (dimensionless) that the likelihood gives each evidence level (survey.hpp:
/// evidence_error_rate gives the library's 0.02 / 0.10 / 0.25).
struct EvidenceRates {
  double certain = 0.02, likely = 0.10, reported = 0.25;
};

/// The same surveys inverted with each set of error rates: the runs are simulated once per survey (the matches do not
/// depend on eps) and the likelihood is reduced once per set (inversion.hpp's steps: build_family, simulate_matches,
/// reduce_likelihood, fill_posterior_and_estimates). Scores per set, in the order of `rates`.
[[nodiscard]] std::vector<std::vector<CaseScore>> run_evidence_scan(const std::vector<RecordCase>& records,
                                                                   const std::vector<double>& pga_g,
                                                                   const SurveyOptions& options,
                                                                   const InversionOptions& inversion_options,
                                                                   const std::vector<EvidenceRates>& rates);

/// One markdown row of a summary: label, then the figures of `markdown`'s summary table in its order.
[[nodiscard]] std::string summary_row(const std::string& label, const Summary& summary);
[[nodiscard]] std::string summary_header();

}  // namespace topple::recovery
