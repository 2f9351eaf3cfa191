// The survey file's keys as one table (schema.hpp). The words of each refusal are the reader's (io/survey_file.cpp),
// held equal to them by tests/io/test_survey_schema.cpp; the friction table is docs/survey.md's, held equal to it by
// the same test.
#include "topple/survey/schema.hpp"

#include <fmt/format.h>

namespace topple {

std::string_view survey_key_kind_name(SurveyKeyKind kind) {
  switch (kind) {
    case SurveyKeyKind::text: return "text";
    case SurveyKeyKind::choice: return "choice";
    case SurveyKeyKind::number: return "number";
    case SurveyKeyKind::integer: return "integer";
    case SurveyKeyKind::value_or_range: return "value_or_range";
    case SurveyKeyKind::length: return "length";
    case SurveyKeyKind::area: return "area";
    case SurveyKeyKind::axis: return "axis";
    case SurveyKeyKind::lat_lon: return "lat_lon";
    case SurveyKeyKind::support: return "support";
    case SurveyKeyKind::path: return "path";
    case SurveyKeyKind::paths: return "paths";
    case SurveyKeyKind::numbers: return "numbers";
    case SurveyKeyKind::columns: return "columns";
    case SurveyKeyKind::tables: return "tables";
  }
  return "text";
}

namespace {

using K = SurveyKeyKind;

SurveyKeyBound incl(double v) { return {v, true}; }
SurveyKeyBound excl(double v) { return {v, false}; }

SurveyKey key(std::string table, std::string name, K kind, std::string help, std::string example) {
  SurveyKey k;
  k.table = std::move(table);
  k.key = std::move(name);
  k.kind = kind;
  k.help = std::move(help);
  k.example = std::move(example);
  return k;
}

SurveyKey& ranged(SurveyKey& k, std::optional<SurveyKeyBound> low, std::optional<SurveyKeyBound> high,
                  std::string problem) {
  k.low = low;
  k.high = high;
  k.range_problem = std::move(problem);
  return k;
}

const std::vector<std::string> kComponents3{"3"};
const char* kBearingProblem = "a bearing must lie in [0, 360) degrees clockwise from north, got {}";
const char* kDepthProblem = "depth must be positive and finite, got {}";  // survey_file.cpp, a box's depth
const char* kLengthProblem = "must be positive, got {} m";

std::vector<SurveyKey> make_schema() {
  std::vector<SurveyKey> s;
  const auto add = [&](SurveyKey k) -> SurveyKey& { return s.emplace_back(std::move(k)); };

  // ---- [site] (docs/survey.md, "[site]" and "Regional surveys") ----
  add(key("site", "name", K::text, "the site's name (default \"site N\")", "\"kitchen\""));
  {
    auto& k = add(key("site", "lat", K::number, "latitude, degrees (WGS84)", "35.0"));
    k.unit = "deg";
    ranged(k, incl(-90.0), incl(90.0), "latitude must lie in [-90, 90]");
  }
  {
    auto& k = add(key("site", "lon", K::number, "longitude, degrees (WGS84)", "139.0"));
    k.unit = "deg";
    ranged(k, incl(-180.0), incl(180.0), "longitude must lie in [-180, 180]");
  }
  add(key("site", "notes", K::text, "free text, echoed in the report", "\"ground floor\""));
  {
    auto& k = add(key("site", "support", K::support,
                      "the site's default flexible support {freq_hz = ..., damping = ...} for its objects",
                      "{freq_hz = [3, 5], damping = 0.05}"));
    k.in_form = false;  // a nested table: written in the file (docs/survey.md, "Flexible supports")
  }
  {
    auto& k = add(key("site", "vs30_m_s", K::number, "Vs30 (m/s), the earthquake prior's site term", "400"));
    k.unit = "m/s";
    ranged(k, incl(100.0), incl(3000.0), "must lie in [100, 3000] m/s, got {}");
  }
  {
    auto& k = add(key("site", "site_class", K::choice,
                      "instead of vs30_m_s: NEHRP class (A 1500, B 1070, C 525, D 255, E 150 m/s)", "\"C\""));
    k.choices = {"A", "B", "C", "D", "E"};
    k.conditions.push_back({"vs30_m_s", {"<absent>"}, "give either vs30_m_s or site_class, not both"});
  }
  {
    auto& k = add(key("site", "pga_g", K::number, "an instrument's measured PGA at the site (g)", "0.3"));
    k.unit = "g";
    ranged(k, excl(0.0), std::nullopt, "a measured PGA must be positive, got {} g");
  }
  {
    auto& k = add(key("site", "record", K::path, "an instrument's record file (instead of pga_g)", "\"station.csv\""));
    k.conditions.push_back({"pga_g", {"<absent>"}, "give either pga_g (measured) or record, not both"});
    k.in_form = false;  // names a file
  }
  // Macroseismic intensity (issue 30; survey_file.cpp's parse_intensity, docs/survey.md "Macroseismic intensity").
  {
    auto& k = add(key("site", "intensity", K::number, "macroseismic intensity at the site (MMI or EMS-98, 1-12)", "7"));
    ranged(k, incl(1.0), incl(12.0), "a macroseismic intensity lies in [1, 12], got {}");
  }
  {
    auto& k = add(key("site", "intensity_scale", K::choice, "the intensity's scale (EMS-98 is read as MMI)", "\"MMI\""));
    k.choices = {"MMI", "EMS-98"};
    k.default_text = "MMI";
    k.conditions.push_back({"intensity", {}, "an intensity_scale goes with an intensity = value"});
  }
  {
    auto& k = add(key("site", "intensity_reports", K::integer, "the number of felt reports behind the intensity", "12"));
    ranged(k, incl(1.0), incl(1e8), "the number of reports must lie in [1, 100000000], got {}");
    k.default_text = "1";
    k.conditions.push_back({"intensity", {}, "intensity_reports go with an intensity = value"});
  }

  // ---- [[object]] (docs/survey.md, "[[object]]") ----
  {
    auto& k = add(key("object", "id", K::text, "a short unique name (\"vase-1\")", "\"vase-1\""));
    k.required = true;
    k.missing_problem = "every object needs an id";
  }
  add(key("object", "description", K::text, "free text", "\"blue vase on the sideboard\""));
  {
    auto& k = add(key("object", "shape", K::choice,
                      "block (width, height), cylinder (diameter, height), general (a, h, D; or b1, b2, h, inertia)",
                      "\"block\""));
    k.choices = {"block", "cylinder", "general"};
    k.default_text = "block";
  }
  const auto dimension = [&](const char* name, std::vector<std::string> shapes, const char* help, const char* example) {
    auto& k = add(key("object", name, K::length, help, example));
    ranged(k, excl(0.0), std::nullopt, kLengthProblem);
    k.required_for_shapes = std::move(shapes);
    k.missing_problem = fmt::format("a {{shape}} needs its {} (a length with unit)", name);
    return &k;
  };
  dimension("width", {"block"}, "full base width across the narrow side it rocks over", "\"10cm\"");
  dimension("diameter", {"cylinder"}, "full base diameter", "\"10cm\"");
  dimension("height", {"block", "cylinder"}, "full height", "\"40cm\"");
  dimension("a", {"general"}, "centre of mass to the pivot edge, horizontally", "\"5cm\"");
  dimension("h", {"general", "general asymmetric"}, "height of the centre of mass", "\"20cm\"");
  {
    auto& k = add(key("object", "D", K::area, "I_pivot / m, an area with its unit (\"0.0123m2\")", "\"0.06m2\""));
    k.required_for_shapes = {"general"};
    k.missing_problem = "a general body needs D = I/m with its unit, e.g. \"0.01m2\"";
  }
  dimension("b1", {"general asymmetric"}, "asymmetric body: centre of mass to the -x pivot", "\"10cm\"");
  dimension("b2", {"general asymmetric"}, "asymmetric body: centre of mass to the +x pivot", "\"20cm\"");
  {
    auto& k = add(key("object", "inertia", K::area, "asymmetric body: I_cm / m, an area with its unit", "\"0.02m2\""));
    k.required_for_shapes = {"general asymmetric"};
    k.missing_problem = "an asymmetric general body needs inertia = I_cm/m with its unit, e.g. \"0.004m2\"";
  }
  // A body from a 3-D scan: the keys name a file, so the form leaves them to the file (docs/survey.md).
  {
    auto& k = add(key("object", "mesh", K::path, "a body from a 3-D scan: the mesh file", "\"scan.obj\""));
    k.in_form = false;
  }
  const std::string mesh_only = "goes with mesh = \"file\" (a body from a 3-D scan)";
  const auto mesh_key = [&](const char* name, K kind, const char* help, const char* example) -> SurveyKey& {
    auto& k = add(key("object", name, kind, help, example));
    k.conditions.push_back({"mesh", {}, mesh_only});
    k.in_form = false;
    return k;
  };
  mesh_key("mesh_azimuth_deg", K::number, "azimuth of the plane of shaking, degrees from the mesh's north", "30")
      .unit = "deg";
  mesh_key("mesh_unit", K::choice, "the unit of the mesh file's coordinates", "\"m\"").choices = {"m", "cm", "mm"};
  mesh_key("mesh_density_kg_m3", K::number, "uniform density (checked; it does not change a rocking body)", "2700")
      .unit = "kg/m3";
  mesh_key("mesh_pose", K::choice, "rest (default) or as-scanned", "\"rest\"").choices = {"rest", "as-scanned"};
  mesh_key("mesh_up", K::numbers, "[x, y, z]: the mesh's direction that becomes up", "[0, 0, 1]");
  mesh_key("mesh_rotation_wxyz", K::numbers, "[w, x, y, z]: a unit quaternion", "[1, 0, 0, 0]");
  mesh_key("mesh_axis_angle_deg", K::numbers, "[x, y, z, degrees]: an axis and an angle", "[0, 0, 1, 0]");
  {
    auto& k = mesh_key("mesh_face", K::integer, "a face number of topple body --list-faces", "1");
    ranged(k, incl(1.0), std::nullopt,
           "expected a face number (an integer from 1; see topple body --list-faces)");
  }
  mesh_key("mesh_contact_tolerance", K::length, "contact tolerance of the pose", "\"1mm\"");
  {
    auto& k = add(key("object", "outcome", K::choice, "what it did", "\"overturned\""));
    k.choices = {"overturned", "not_overturned", "rocked", "not_rocked", "slid", "not_slid",
                 "slid_stood", "slid_toppled", "walked", "toppled", "fell"};
    k.required = true;
    k.missing_problem = "every object needs its observed outcome";
  }
  {
    auto& k = add(key("object", "mu", K::value_or_range,
                      "static friction coefficient of the base on its support: a value or a range [low, high]",
                      "[0.4, 0.6]"));
    ranged(k, incl(0.0), std::nullopt, "must be >= 0");
    k.required = true;
    k.missing_problem = "the friction coefficient is required (a value or a range [low, high])";
  }
  {
    auto& k = add(key("object", "e", K::value_or_range,
                      "coefficient of restitution: \"housner\" (default), a value or a range", "0.8"));
    ranged(k, incl(0.0), incl(1.0), "restitution must lie in [0, 1]");
    k.choices = {"housner"};  // the one word it takes besides numbers
    k.default_text = "housner";
  }
  add(key("object", "support", K::support,
          "what it stood on: free text (\"ground\", \"furniture\") or a flexible support table", "\"furniture\""));
  {
    auto& k = add(key("object", "amplification", K::value_or_range,
                      "how much the support amplifies the ground motion: a value or a range (default 1)", "[1, 1.5]"));
    ranged(k, excl(0.0), std::nullopt, "must be positive");
    k.default_text = "1";
  }
  {
    auto& k = add(key("object", "orientation_deg", K::number,
                      "one component: angle between its rocking plane and the shaking (unknown: 0, the worst case)",
                      "30"));
    k.unit = "deg";
    ranged(k, incl(0.0), incl(90.0), "must lie in [0, 90] degrees");
    k.conditions.push_back({"inversion.components", {"1"},
                            "a three-component survey gives the object's bearing, azimuth_deg, instead"});
  }
  {
    auto& k = add(key("object", "azimuth_deg", K::number,
                      "three components: the bearing across its narrow side, degrees clockwise from north", "40"));
    k.unit = "deg";
    ranged(k, incl(0.0), excl(360.0), kBearingProblem);
    k.conditions.push_back({"inversion.components", kComponents3, "an object's bearing needs [inversion] components = 3"});
    k.conditions.push_back({"shape", {"block", "general"}, "a cylinder has no narrow side"});
  }
  {
    auto& k = add(key("object", "depth", K::length,
                      "three components, a block: its other horizontal dimension (the block is then a box)", "\"30cm\""));
    k.conditions.push_back({"inversion.components", kComponents3, "a box's depth needs [inversion] components = 3"});
    k.conditions.push_back({"shape", {"block"}, "a depth applies to a block (a box) only"});
    ranged(k, excl(0.0), std::nullopt, kDepthProblem);
  }
  {
    auto& k = add(key("object", "toppled_azimuth_deg", K::number,
                      "three components, a cylinder or a box that fell: the direction it fell, degrees from north",
                      "120"));
    k.unit = "deg";
    ranged(k, incl(0.0), excl(360.0), kBearingProblem);
    k.conditions.push_back({"inversion.components", kComponents3, "a fall direction needs [inversion] components = 3"});
    k.conditions.push_back({"outcome", {"overturned", "toppled", "fell"},
                            "a fall direction goes with outcome = \"overturned\""});
    // A block needs its depth as well (a box); the reader says so (survey.hpp, check_object_fall_direction).
    k.conditions.push_back({"shape", {"cylinder", "block"}, "only a cylinder or a box (a block with depth)"});
  }
  {
    auto& k = add(key("object", "slid_azimuth_deg", K::number,
                      "three components, outcome slid: the direction it moved, degrees from north", "200"));
    k.unit = "deg";
    ranged(k, incl(0.0), excl(360.0), kBearingProblem);
    k.conditions.push_back({"inversion.components", kComponents3, "a sliding direction needs [inversion] components = 3"});
    k.conditions.push_back({"outcome", {"slid"}, "a sliding direction goes with outcome = \"slid\""});
  }
  {
    auto& k = add(key("object", "model", K::choice,
                      "the model it is simulated with (absent: chosen by the rule of docs/survey.md)", "\"rock\""));
    k.choices = {"slide", "rock", "coupled", "3d"};  // "3d": three components, a box, a cylinder or a mesh (docs/survey.md)
  }
  {
    auto& k = add(key("object", "friction_3d", K::choice,
                      "model = \"3d\", a box or a mesh: \"mu\" lets its base slide with the object's mu (mu_s = mu_k), "
                      "which the outcomes slid, not_slid, slid_stood, slid_toppled and walked need; \"none\" (default) "
                      "does not",
                      "\"mu\""));
    k.choices = {"none", "mu"};
    k.default_text = "none";
    k.conditions.push_back({"model", {"3d"}, "friction_3d goes with model = \"3d\""});
  }
  {
    auto& k = add(key("object", "slid", K::length, "outcome slid or slid_stood: how far it slid", "\"3cm\""));
    ranged(k, excl(0.0), std::nullopt, "must be positive");
    k.conditions.push_back({"outcome", {"slid", "slid_stood"},
                            "a sliding distance goes with outcome = \"slid\" or \"slid_stood\""});
  }
  {
    auto& k = add(key("object", "slid_uncertainty", K::length,
                      "the sliding distance's uncertainty (floor: max(25 % of slid, 2 mm))", "\"1cm\""));
    ranged(k, incl(0.0), std::nullopt, "must be >= 0");
  }
  {
    auto& k = add(key("object", "slid_at_least", K::length, "instead of slid: it slid at least this far", "\"2cm\""));
    k.conditions.push_back({"outcome", {"slid", "slid_stood"},
                            "a sliding distance goes with outcome = \"slid\" or \"slid_stood\""});
    k.conditions.push_back({"slid", {"<absent>"}, "give either slid or slid_at_least"});
  }
  {
    auto& k = add(key("object", "evidence", K::choice,
                      "how sure: certain (2 % chance of a wrong observation), likely (10 %), reported (25 %)",
                      "\"likely\""));
    k.choices = {"certain", "likely", "reported"};
    k.default_text = "certain";
  }

  // ---- a flexible support's table (docs/survey.md, "Flexible supports"): written in the file ----
  {
    auto& k = add(key("support", "freq_hz", K::value_or_range, "the support's natural frequency (Hz)", "[3, 6]"));
    k.unit = "Hz";
    ranged(k, excl(0.0), std::nullopt, "must be positive, got {} Hz");
    k.required = true;
    k.missing_problem = "a flexible support needs its natural frequency freq_hz (Hz, a value or a range)";
    k.in_form = false;
  }
  {
    auto& k = add(key("support", "damping", K::value_or_range, "the support's damping ratio (0.05 is 5 %)", "0.05"));
    k.low = incl(0.0);
    k.high = excl(1.0);
    k.range_problem = "the damping ratio must lie in [0, 1)";
    k.required = true;
    k.missing_problem = "a flexible support needs its damping ratio (decimal: 0.05 is 5 %)";
    k.in_form = false;
  }
  add(key("support", "name", K::text, "a label for the report", "\"upper floor\"")).in_form = false;

  // ---- [[population]] (docs/survey.md, "Populations"; survey_file.cpp's parse_population; population.cpp's
  // check_population for the counts and sizes). Offered by the form (issue 30). The class' shared keys (mu, e,
  // support, amplification, orientation_deg, azimuth_deg, depth, evidence) are read as an object's (survey_file.cpp's
  // parse_object_placement), in the object's words: their rows are the object's, copied. ----
  const auto population = [&](const char* name, K kind, const char* help, const char* example) -> SurveyKey& {
    return add(key("population", name, kind, help, example));
  };
  const char* kCountProblem = "a count cannot be negative, got {}";
  {
    auto& k = population("id", K::text, "a short unique name of the class (\"stones-A\")", "\"stones\"");
    k.required = true;
    k.missing_problem = "every population needs an id";
  }
  population("description", K::text, "free text", "\"gravestones, row 3\"");
  {
    auto& k = population("shape", K::choice, "block (width, height) or cylinder (diameter, height)", "\"block\"");
    k.choices = {"block", "cylinder"};
    k.default_text = "block";
  }
  {
    // population_count refuses a negative count in its words first; check_population then asks for at least one.
    auto& k = population("count", K::integer, "how many objects of the class were there", "10");
    ranged(k, incl(1.0), std::nullopt, "must be at least 1, got {}");
    k.required = true;
    k.missing_problem = "a population needs its count (how many objects of the class were there)";
  }
  {
    auto& k = population("overturned", K::integer, "how many of them toppled (0 if none)", "2");
    k.required = true;
    k.missing_problem = "a population needs how many overturned (0 if none)";
    ranged(k, incl(0.0), std::nullopt, kCountProblem);
  }
  {
    auto& k = population("rocked", K::integer, "how many stood and visibly rocked (a category when given)", "1");
    ranged(k, incl(0.0), std::nullopt, kCountProblem);
    k.conditions.push_back({"inversion.components", {"1"}, "a population's rocked count needs [inversion] components = 1"});
  }
  {
    auto& k = population("slid", K::integer, "how many stood and visibly slid (a category when given)", "1");
    ranged(k, incl(0.0), std::nullopt, kCountProblem);
    k.conditions.push_back({"inversion.components", {"1"}, "a population's slid count needs [inversion] components = 1"});
  }
  // A size is a length or a range [low, high] of lengths; check_population's words for one not positive (of a range,
  // its low end), in metres.
  const char* kSizeProblem = "sizes must be positive, got {} m";
  {
    auto& k = population("width", K::length, "a block's width: a length or a range [low, high] of lengths", "\"10cm\"");
    ranged(k, excl(0.0), std::nullopt, kSizeProblem);
    k.conditions.push_back({"shape", {"block"}, "a population of cylinders has no width"});
  }
  ranged(population("height", K::length, "the height: a length or a range [low, high] of lengths", "\"40cm\""),
         excl(0.0), std::nullopt, kSizeProblem);
  {
    auto& k = population("diameter", K::length, "a cylinder's diameter: a length or a range [low, high]", "\"10cm\"");
    ranged(k, excl(0.0), std::nullopt, kSizeProblem);
    k.conditions.push_back({"shape", {"cylinder"}, "a population of blocks has no diameter"});
  }
  population("sample", K::tables, "the measured members, instead of ranges (or inside them): one per line, "
                                  "width and height (a cylinder: diameter and height)",
             "[{width = \"10cm\", height = \"40cm\"}]");
  {
    auto& k = population("members", K::integer, "K, the representative members simulated", "16");
    k.default_text = "16";
    ranged(k, incl(1.0), incl(200.0), "must be 1 to 200, got {}");  // population.hpp, kMaxPopulationMembers
  }
  {
    auto& k = population("fallen_azimuths_deg", K::numbers, "the directions the toppled ones fell, deg from north",
                         "[40.0]");
    k.unit = "deg";
    k.conditions.push_back({"inversion.components", kComponents3, "fall directions need [inversion] components = 3"});
    // A cylinder or a box (a block with depth): not one condition on one key, so the form says it itself, in the
    // reader's words (survey.cpp's check_object_fall_direction, held against the reader by the form's test).
  }
  for (const char* shared : {"mu", "e", "support", "amplification", "orientation_deg", "azimuth_deg", "depth",
                             "evidence"}) {
    const SurveyKey* object_row = nullptr;
    for (const SurveyKey& k : s) {
      if (k.table == "object" && k.key == shared) object_row = &k;
    }
    SurveyKey k = *object_row;  // copied before add() may move the rows
    k.table = "population";
    if (k.key == "azimuth_deg") k.conditions.back().values = {"block"};  // a population is of blocks or cylinders
    add(std::move(k));
  }

  // ---- [inversion] (docs/survey.md, "[inversion]") ----
  {
    auto& k = add(key("inversion", "family", K::choice,
                      "the motion family (records: written in the file with its record files)", "\"rezaeian2010\""));
    k.choices = {"synthetic", "records", "rezaeian2010", "boore2003", "mixture"};
    k.default_text = "synthetic";
  }
  {
    auto& k = add(key("inversion", "records", K::paths, "family = \"records\": the record files", "[\"r.csv\"]"));
    k.in_form = false;
  }
  const auto record_key = [&](const char* name, K kind, const char* help, const char* example) -> SurveyKey& {
    auto& k = add(key("inversion", name, kind, help, example));
    k.in_form = false;  // how record files are read: with the files, in the file
    return k;
  };
  record_key("record_format", K::choice, "the records' format", "\"plain\"").choices = {
      "auto", "peer-at2", "cosmos-v2", "csmip-v2", "knet", "usgs-smc", "esm", "plain"};
  record_key("record_units", K::text, "the records' acceleration unit (g, m/s2, cm/s2, gal, mm/s2)", "\"g\"");
  {
    auto& k = record_key("record_dt_s", K::number, "the records' time step (s)", "0.01");
    k.unit = "s";
    ranged(k, excl(0.0), std::nullopt, "must be positive, got {} s");
  }
  record_key("record_columns", K::columns, "the records' [time, acceleration] columns", "[1, 2]");
  record_key("record_separator", K::choice, "the records' column separator", "\"comma\"").choices = {
      "auto", "whitespace", "tab", "comma", "semicolon"};
  record_key("record_baseline", K::text, "the records' baseline correction (none, mean, ...)", "\"mean\"");
  const auto axis = [&](const char* name, const char* unit, const char* help, const char* example) {
    auto& k = add(key("inversion", name, K::axis, help, example));
    k.unit = unit;
  };
  axis("pga_g", "g", "the PGA axis [min, max, count], log-spaced", "[0.05, 2.0, 8]");
  axis("freq_hz", "Hz", "the predominant-frequency axis [min, max, count], log-spaced", "[0.5, 10.0, 6]");
  {
    auto& k = add(key("inversion", "motions_per_cell", K::integer, "motions per grid cell", "4"));
    ranged(k, incl(1.0), incl(100000.0), "must be a whole number >= 1");
  }
  {
    auto& k = add(key("inversion", "seed", K::integer, "the random seed", "7"));
    ranged(k, incl(0.0), std::nullopt, "must be a whole number >= 0");
  }
  {
    auto& k = add(key("inversion", "duration_s", K::number, "each synthetic motion's duration (s)", "10"));
    k.unit = "s";
    ranged(k, excl(0.0), std::nullopt, "must be positive");
  }
  {
    auto& k = add(key("inversion", "g_m_s2", K::number, "standard gravity (m/s2)", "9.81"));
    k.unit = "m/s2";
    ranged(k, excl(0.0), std::nullopt, "must be positive");
    k.in_form = false;
  }
  {
    auto& k = add(key("inversion", "components", K::choice, "1 (one horizontal component) or 3 (with bearings)", "3"));
    k.choices = {"1", "3"};
    k.default_text = "1";
  }
  {
    auto& k = add(key("inversion", "coherence", K::number, "components = 3: the horizontals' coherence", "0.3"));
    ranged(k, incl(0.0), incl(0.95), "must lie in [0, 0.95], got {}");
    k.conditions.push_back({"components", kComponents3, "coherence needs components = 3"});
  }
  {
    auto& k = add(key("inversion", "directions", K::integer, "components = 3: direction bins", "12"));
    ranged(k, incl(4.0), incl(72.0), "must be a whole number from 4 to 72, got {}");
    k.conditions.push_back({"components", kComponents3, "directions needs components = 3"});
  }
  {
    auto& k = add(key("inversion", "prior", K::choice, "the prior over PGA and frequency", "\"log-uniform\""));
    k.choices = {"log-uniform", "earthquake"};
    k.default_text = "log-uniform";
  }

  // ---- [event] (docs/survey.md, "[event]") ----
  add(key("event", "epicentre", K::lat_lon, "[lat, lon] of the epicentre, degrees", "[35.2, 139.1]"));
  {
    auto& k = add(key("event", "depth_km", K::number, "the hypocentre's depth (km)", "10"));
    k.unit = "km";
    ranged(k, incl(0.0), incl(700.0), "must lie in [0, 700] km, got {}");
    k.conditions.push_back({"epicentre", {}, "a depth goes with epicentre = [lat, lon]"});
  }
  {
    auto& k = add(key("event", "magnitude", K::number, "moment magnitude, for the earthquake prior", "6.5"));
    ranged(k, incl(3.0), incl(8.5), "must lie in [3, 8.5] (BSSA14's range), got {}");
  }
  // The axes' own words (Reader::axis), kept with their keys.
  for (SurveyKey& k : s) {
    if (k.kind == K::axis) {
      k.low = excl(0.0);
      k.range_problem = "need 0 < min < max, got [{}, {}]";
    }
  }
  return s;
}

}  // namespace

const std::vector<SurveyKey>& survey_schema() {
  static const std::vector<SurveyKey> schema = make_schema();
  return schema;
}

const SurveyKey* find_survey_key(std::string_view table, std::string_view key) {
  for (const SurveyKey& k : survey_schema()) {
    if (k.table == table && k.key == key) return &k;
  }
  return nullptr;
}

std::optional<std::string> survey_range_problem(const SurveyKey& key, double value) {
  const bool below = key.low && (key.low->inclusive ? value < key.low->value : !(value > key.low->value));
  const bool above = key.high && (key.high->inclusive ? value > key.high->value : !(value < key.high->value));
  if (!below && !above) return std::nullopt;
  std::string text = key.range_problem;
  if (const auto at = text.find("{}"); at != std::string::npos) text.replace(at, 2, fmt::format("{}", value));
  return text;
}

const std::vector<FrictionRow>& friction_table() {
  // docs/survey.md, "Friction coefficients" (its sources [1]-[3] are cited there); the test holds the two equal.
  static const std::vector<FrictionRow> table{
      {"glass on glass, clean", 0.9, 1.0, "[1] (glass–glass, clean and dry); [3] 0.9–1.0"},
      {"glass on glass, dusty or greasy", 0.1, 0.6, "[1] (glass–glass, lubricated and greasy)"},
      {"glass or glazed ceramic on metal", 0.5, 0.7, "[1] (glass–metal, clean and dry)"},
      {"glazed ceramic (vase, plate, mug) on wood or stone", 0.3, 0.7,
       "not tabulated: judgement between wood–stone 0.40 [3] and glass–metal 0.5–0.7 [1]; measure"},
      {"wood on wood", 0.25, 0.5, "[1] (wood–wood, clean); [3] 0.28; [2] oak on oak 0.54–0.62"},
      {"wood on stone, brick, concrete", 0.4, 0.62,
       "[3] wood–stone 0.40, wood–brick 0.6, wood–concrete 0.62; [1] wood–concrete 0.62"},
      {"metal on wood", 0.2, 0.6, "[1], [3] (wood–metals 0.2–0.6); [2] cast iron on oak 0.49"},
      {"felt pads on wood", 0.2, 0.3, "[3] wood–felt 0.29"},
      {"leather on wood", 0.27, 0.38, "[3] leather–wood"},
      {"rubber feet on wood, stone or tile", 0.6, 1.0,
       "[1] rubber–concrete 1.0 (dry); [3] rubber–concrete 1.02; wood and glazed tile are smoother: take the lower "
       "part of the range unless measured"},
      {"metal or wood on glazed ceramic tile", 0.3, 0.6,
       "not tabulated: judgement from glass–metal [1] and wood–stone [3]; measure"},
      {"metal or wood on laminate or vinyl flooring", 0.2, 0.5,
       "not tabulated: judgement from wood–wood and wood–metal [1]; measure"},
      {"anything on carpet", 0.5, 1.0,
       "not tabulated (legs sink into the pile, which resists more than surface friction); carpet is a poor sliding "
       "witness"},
      {"PTFE (Teflon) glides on a hard floor", 0.04, 0.2, "[1] steel–PTFE 0.04, PTFE–PTFE 0.05–0.2"},
  };
  return table;
}

}  // namespace topple
