// The recovery test on real records, full size (issue 18; tests/support/real_record_recovery.hpp has the method).
// Every record of shared/records worth scaling x the target PGAs, 12 objects each, 5 % of the observations
// misreported, inverted on the survey's default grid; prints one markdown row per survey and the summary against
// the targets. Figures: docs/verification.md, "Recovery on real records". Run: scripts/recovery-real-records.sh
//
//   recovery_real_records [--write DIR] [--threads N] [--misreport-rate R] [--inversion "TOML lines"]
//                         [--pga 0.1,0.2,...] [--records N] [--eps "c,l,r;c,l,r"]
//   With --eps: the evidence model's calibration: the same surveys (runs simulated once) with each set of error
//   rates for certain, likely, reported; one summary row per set.
//   recovery_real_records --pgv [--inversion "TOML lines"]
//     The hypothesis: PGV/PGA of each record against the mean over the family's motions (the [inversion]
//     table's family) at the record's own predominant frequency.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "support/real_record_recovery.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/io/read.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/motion/spectra.hpp"

namespace {

/// PGV / PGA (s) of each real record against the family's motions at the record's predominant frequency.
int pgv_table(const std::string& inversion_toml) {
  using namespace topple;
  const Survey survey = io::parse_survey(
      "[site]\nname = \"x\"\n[inversion]\n" + inversion_toml +
          "\n[[object]]\nid = \"a\"\nwidth = \"1cm\"\nheight = \"1cm\"\nmu = 0.5\noutcome = \"slid\"\n",
      "pgv.toml");
  // Two measures of the motion's shape, both dimensionless at a given predominant frequency f_p: PGV/PGA (the
  // velocity it carries per unit PGA, which sets how far a block slides) and f_p Tm (Tm: Rathje et al. 1998's mean
  // period, spectra.hpp), the predominant period over the mean one inverted: 1 for a motion whose energy sits at its
  // peak, below 1 for a broadband one whose mean frequency 1/Tm lies above its FAS peak.
  fmt::print("| record | f_p (Hz) | PGV/PGA record (s) | family mean (s) | family / record | rank in family | "
             "f_p Tm record | family mean | rank in family |\n"
             "|---|---|---|---|---|---|---|---|---|\n");
  std::vector<double> ratios;
  std::vector<double> tm_ratios;  // family mean f_p Tm / the record's
  std::vector<double> tm_ranks;
  std::vector<double> ranks;  // the share of the family's motions with a smaller PGV/PGA than the record's
  for (const recovery::RecordCase& rc : recovery::real_records(TOPPLE_SHARED_DIR)) {
    io::ReadOptions ro;
    ro.channel = rc.channel;
    const GroundMotion record = io::read_motion(rc.path, ro);
    const double fp = predominant_frequency_hz(record);
    const BasicIntensity bi = basic_intensity(record);
    const double rec_ratio = bi.pgv_m_s / bi.pga_m_s2;
    const double rec_tm = fp * mean_period_s(record);
    double sum = 0.0;
    double below = 0.0;
    double tm_sum = 0.0;
    double tm_below = 0.0;
    const std::vector<GroundMotion> family = family_motions(survey.inversion, fp);
    for (const GroundMotion& m : family) {
      const BasicIntensity fb = basic_intensity(m);
      sum += fb.pgv_m_s / fb.pga_m_s2;
      below += (fb.pgv_m_s / fb.pga_m_s2 < rec_ratio) ? 1.0 : 0.0;
      const double tm = fp * mean_period_s(m);
      tm_sum += tm;
      tm_below += (tm < rec_tm) ? 1.0 : 0.0;
    }
    const double nfam = static_cast<double>(family.size());
    const double rank = below / nfam;
    ranks.push_back(rank);
    tm_ranks.push_back(tm_below / nfam);
    const double fam_ratio = sum / nfam;
    ratios.push_back(fam_ratio / rec_ratio);
    tm_ratios.push_back(tm_sum / nfam / rec_tm);
    fmt::print("| {} | {:.2f} | {:.3f} | {:.3f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n", rc.label, fp,
               rec_ratio, fam_ratio, fam_ratio / rec_ratio, rank, rec_tm, tm_sum / nfam, tm_below / nfam);
  }
  std::sort(ratios.begin(), ratios.end());
  std::sort(ranks.begin(), ranks.end());
  const auto share = [&](double lo, double hi) {
    double c = 0.0;
    for (const double r : ranks) c += (r >= lo && r <= hi) ? 1.0 : 0.0;
    return 100.0 * c / static_cast<double>(ranks.size());
  };
  fmt::print("\nrank of the record's PGV/PGA among the family's (uniform if the family is like the records): median "
             "{:.2f}; below the family's 5 %: {:.0f} % of records, above its 95 %: {:.0f} %, in the middle 50 %: "
             "{:.0f} %",
             ranks[ranks.size() / 2], share(0.0, 0.05 - 1e-12), share(0.95 + 1e-12, 1.0), share(0.25, 0.75));
  fmt::print("\nfamily / record PGV/PGA: median {:.2f}, range {:.2f}-{:.2f} over {} records\n",
             ratios[ratios.size() / 2], ratios.front(), ratios.back(), ratios.size());
  std::sort(tm_ratios.begin(), tm_ratios.end());
  std::sort(tm_ranks.begin(), tm_ranks.end());
  double tm_low = 0.0;
  for (const double r : tm_ranks) tm_low += (r < 0.05) ? 1.0 : 0.0;
  fmt::print("family / record f_p Tm: median {:.2f}, range {:.2f}-{:.2f}; rank of the record's f_p Tm among the "
             "family's: median {:.2f}, below the family's 5 %: {:.0f} % of records\n",
             tm_ratios[tm_ratios.size() / 2], tm_ratios.front(), tm_ratios.back(), tm_ranks[tm_ranks.size() / 2],
             100.0 * tm_low / static_cast<double>(tm_ranks.size()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace topple;
  if (argc >= 2 && std::string(argv[1]) == "--pgv") {
    return pgv_table(argc >= 4 ? std::string(argv[3]) : std::string());
  }
  recovery::SurveyOptions options;
  InversionOptions inv;
  std::filesystem::path write_dir;
  std::vector<double> pga{0.1, 0.2, 0.35, 0.6};
  std::size_t max_records = 1000;
  std::vector<recovery::EvidenceRates> eps_sets;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const std::string value = argv[i + 1];
    if (key == "--write") {
      write_dir = value;
    } else if (key == "--threads") {
      inv.threads = std::stoi(value);
    } else if (key == "--misreport-rate") {
      options.misreport_rate = std::stod(value);
    } else if (key == "--inversion") {
      options.inversion_toml = value;
    } else if (key == "--eps") {
      // "c,l,r;c,l,r;...": error rates for certain, likely, reported, one set per variant
      std::stringstream sets(value);
      std::string set;
      while (std::getline(sets, set, ';')) {
        recovery::EvidenceRates r;
        if (std::sscanf(set.c_str(), "%lf,%lf,%lf", &r.certain, &r.likely, &r.reported) != 3) {
          fmt::print(stderr, "--eps: expected c,l,r;c,l,r..., got '{}'\n", set);
          return 2;
        }
        eps_sets.push_back(r);
      }
    } else if (key == "--records") {
      max_records = static_cast<std::size_t>(std::stoul(value));
    } else if (key == "--pga") {
      pga.clear();
      std::stringstream ss(value);
      std::string item;
      while (std::getline(ss, item, ',')) pga.push_back(std::stod(item));
    } else {
      fmt::print(stderr, "unknown option {}\n", key);
      return 2;
    }
  }
  if (!eps_sets.empty()) {
    std::vector<recovery::RecordCase> recs = recovery::real_records(TOPPLE_SHARED_DIR);
    if (recs.size() > max_records) recs.resize(max_records);
    const auto t0 = std::chrono::steady_clock::now();
    const auto scans = recovery::run_evidence_scan(recs, pga, options, inv, eps_sets);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fmt::print("{} records x {} PGAs, misreport rate {}, [inversion] \"{}\": {:.0f} s\n\n{}", recs.size(), pga.size(),
               options.misreport_rate, options.inversion_toml, seconds, recovery::summary_header());
    for (std::size_t v = 0; v < scans.size(); ++v) {
      fmt::print("{}", recovery::summary_row(fmt::format("eps certain {} / likely {} / reported {}", eps_sets[v].certain,
                                                         eps_sets[v].likely, eps_sets[v].reported),
                                             recovery::summarise(scans[v])));
      for (const double pv : pga) {
        std::vector<recovery::CaseScore> sub;
        for (const auto& sc : scans[v]) {
          if (sc.pga_g == pv) sub.push_back(sc);
        }
        fmt::print("{}", recovery::summary_row(fmt::format("  at {} g", pv), recovery::summarise(sub)));
      }
    }
    return 0;
  }
  std::vector<recovery::RecordCase> records = recovery::real_records(TOPPLE_SHARED_DIR);
  if (records.size() > max_records) records.resize(max_records);
  if (!write_dir.empty()) std::filesystem::create_directories(write_dir);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<recovery::CaseScore> scores = recovery::run(records, pga, options, inv, write_dir);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("{} records x {} PGAs, misreport rate {}, [inversion] \"{}\": {:.0f} s\n\n", records.size(), pga.size(),
             options.misreport_rate, options.inversion_toml, seconds);
  fmt::print("{}", recovery::markdown(scores, recovery::summarise(scores)));
  return 0;
}
