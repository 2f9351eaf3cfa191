#pragma once
// Shake-table campaigns: blind predictions of which objects overturned, scored against what the table tests observed
// (issue 29's target: accuracy, recall, and speed in times real time; docs/campaign.md).
//
// A campaign is a list of table tests, each a body (a block, a solid cylinder or a scanned mesh as posed) standing at
// a bearing on the table, the table's motion (x, optionally y and z components, in the table's frame: x and y
// horizontal and perpendicular, counter-clockwise seen from above, z up) and the outcome observed. Each test is run
// with each model asked for; the outcomes are read only to score (nothing is fitted to them: "blind").
//
// Frames. The table's x axis is taken as the engines' east and its y axis as their north; an azimuth in this file is
// an angle counter-clockwise from the table's x axis seen from above, degrees in [0, 360) (bearing_deg: from the
// table's x axis to the body's own x axis; a fall's azimuth: the direction the top fell toward).
//
// Models (run_campaign_test):
//   planar   the planar rocking model (rocking.hpp; Housner 1963) in the vertical planes of oriented.hpp's rule under
//            the table's horizontal acceleration projected on each (eq. M1): a block along its own x and y axes
//            (half-widths width / 2 and depth / 2); a cylinder along the table's x axis under one component, along
//            12 directions 15 degrees apart over 180 with two; a mesh in the plane of the table's x axis (the
//            scan's planar body there, bodies/body.hpp, with its two pivots b1, b2) under one component, along 12
//            directions over 180 with two. The most severe direction governs (oriented.hpp, "Severity").
//   coupled  the same planes with the coupled slide-rock model (slide_rock.hpp), Coulomb friction mu (mu_k).
//   3d       the three-dimensional engines: rigid3d.hpp for a block or a mesh (turned to its bearing; sliding flat
//            when mu is given), rigid3d_disc.hpp for a cylinder (rolls on its rim without slip, mu not used).
//
// Scoring (score_campaign): positive = overturned. With TP, FP, TN, FN the confusion counts and n their sum:
//   accuracy = (TP + TN) / n,  recall = TP / (TP + FN),  precision = TP / (TP + FP),
//   F1 = 2 TP / (2 TP + FP + FN)  (the harmonic mean of precision and recall);
// a ratio whose denominator is zero is undefined (absent, never 0 or NaN). The azimuth error of a fall predicted
// and observed with an observed azimuth is the angle between the two directions, in [0, 180] degrees; their median
// is reported. Speed: the CPU seconds of the model runs (the solver only: reading records and meshes is not timed)
// against the records' simulated duration: times real time = simulated seconds / CPU seconds.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "topple/bodies/body.hpp"
#include "topple/core/progress.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rocking.hpp"

namespace topple::ensemble {

enum class CampaignModel : std::uint8_t { planar, coupled, three_d };
/// "planar", "coupled", "3d"
[[nodiscard]] std::string_view campaign_model_name(CampaignModel model);
/// The model of a name ("planar", "coupled", "3d"); InputError naming `field` otherwise.
[[nodiscard]] CampaignModel parse_campaign_model(std::string_view name, const std::string& field = "models");

/// A rectangular block: width along its own x axis, depth along y, height (m).
struct CampaignBlock {
  double width_m = 0.0, depth_m = 0.0, height_m = 0.0;
};
/// A uniform solid cylinder standing on its end (m).
struct CampaignCylinder {
  double diameter_m = 0.0, height_m = 0.0;
};
/// A scanned body: the mesh file, read and posed by the caller's loader (CampaignInput::mesh).
struct CampaignMesh {
  std::string path;
};
using CampaignBody = std::variant<CampaignBlock, CampaignCylinder, CampaignMesh>;

/// One table test as the campaign file gives it (io/campaign_file.hpp reads it).
struct CampaignTest {
  std::string id;
  CampaignBody body;
  double bearing_deg = 0.0;        ///< from the table's x axis to the body's x axis, counter-clockwise, deg
  bool observed_overturned = false;
  std::optional<double> observed_azimuth_deg;  ///< of an observed fall, counter-clockwise from the table's x axis
};

/// What every test is run with.
struct CampaignSettings {
  std::string name;
  std::vector<CampaignModel> models{CampaignModel::planar, CampaignModel::three_d};
  std::optional<double> mu;    ///< static friction (coupled: required; 3d: sliding flat when given)
  std::optional<double> mu_k;  ///< kinetic friction (absent: mu)
  RestitutionMode restitution = RestitutionMode::housner;
  double e = 1.0;              ///< restitution given
  double g_m_s2 = kStandardGravity;
};

/// A test's inputs as loaded: the table's components (already scaled) and, for a mesh, its body as posed.
struct CampaignInput {
  GroundMotion x;
  std::optional<GroundMotion> y, z;
  std::optional<MeshBody> mesh;
};

/// One test under one model.
struct CampaignRow {
  std::string id;
  CampaignModel model = CampaignModel::planar;
  bool predicted_overturned = false;
  bool observed_overturned = false;
  double max_tilt_over_limit = 0.0;  ///< planar, coupled: max |theta| / alpha of the governing plane; 3d: rigid3d's
  std::optional<double> overturn_time_s;
  std::optional<double> overturn_azimuth_deg;  ///< counter-clockwise from the table's x axis, [0, 360)
  std::optional<double> observed_azimuth_deg;
  double cpu_s = 0.0;                ///< CPU time of the model's run(s) for this test
  double duration_s = 0.0;           ///< the record's duration (the longest component's), s
  std::vector<std::string> warnings;
};

/// Runs one test under one model (header). Throws InputError for a body or an option the model refuses (the field
/// as the library names it: "width", "mu", ...), SolverError at a solver's limits.
[[nodiscard]] CampaignRow run_campaign_test(const CampaignTest& test, const CampaignInput& input, CampaignModel model,
                                            const CampaignSettings& settings);

/// Runs every test under every model on all cores (oneTBB), `load(i)` giving test i's inputs (called once per test,
/// from any thread). Rows in a fixed order whatever the threads: by test, then by model in settings.models' order.
/// When tests fail, the error of the first failing test (in file order) is rethrown after all have ended; a model's
/// InputError or SolverError is rethrown with "test 'ID', model 'M': " before its problem (its location kept).
/// `threads` = 0: all cores. `progress` (optional) is called with (tests done, tests) after each test, from any thread.
[[nodiscard]] std::vector<CampaignRow> run_campaign(const std::vector<CampaignTest>& tests,
                                                    const CampaignSettings& settings,
                                                    const std::function<CampaignInput(std::size_t)>& load,
                                                    std::size_t threads = 0, const ProgressCallback& progress = {});

/// Confusion counts, positive = overturned.
struct Confusion {
  std::size_t tp = 0, fp = 0, tn = 0, fn = 0;
  [[nodiscard]] std::size_t total() const noexcept { return tp + fp + tn + fn; }
};

/// The metrics of a confusion (header); absent where the denominator is zero.
struct ClassificationMetrics {
  std::optional<double> accuracy, recall, precision, f1;
};
[[nodiscard]] ClassificationMetrics classification_metrics(const Confusion& c) noexcept;

/// The angle between two plan directions, degrees in [0, 180].
[[nodiscard]] double azimuth_difference_deg(double a_deg, double b_deg) noexcept;

/// One model's score over a campaign.
struct CampaignScore {
  CampaignModel model = CampaignModel::planar;
  Confusion confusion;
  ClassificationMetrics metrics;
  std::size_t azimuths_compared = 0;              ///< falls predicted and observed with an observed azimuth
  std::optional<double> median_azimuth_error_deg; ///< over those (absent when none)
  double cpu_s = 0.0;                             ///< sum over the tests
  double simulated_s = 0.0;                       ///< sum of the records' durations
  std::optional<double> times_real_time;          ///< simulated_s / cpu_s (absent when cpu_s is 0)
};

/// The score of `model` over the rows of that model (the others are skipped).
[[nodiscard]] CampaignScore score_campaign(const std::vector<CampaignRow>& rows, CampaignModel model);

/// Issue 29's target: accuracy >= 0.87 (the low end of a lab numerical model's 0.87-0.90), recall > 0.8, and at
/// least 1000 times a physics-engine digital twin's speed of about 60 times real time: >= 60000 times real time.
struct CampaignTarget {
  double accuracy_min = 0.87;
  double recall_above = 0.8;
  double times_real_time_min = 60000.0;
};
/// Which parts of the target a score meets (absent metrics do not meet it).
struct CampaignTargetCheck {
  bool accuracy = false, recall = false, speed = false;
  [[nodiscard]] bool all() const noexcept { return accuracy && recall && speed; }
};
[[nodiscard]] CampaignTargetCheck check_target(const CampaignScore& score, const CampaignTarget& target = {});

}  // namespace topple::ensemble
