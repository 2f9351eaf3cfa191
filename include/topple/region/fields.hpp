#pragma once
// The field tables of the regional fit (fit.hpp), as kSlidingFields is the sliding summary's (core/field.hpp): each
// reported quantity's name, with its unit, and how to read it, in the order of the JSON (region_output.hpp:
// region_json, the `region` key of `topple invert --json`, Python's topple.invert_region), which reads these tables.
// A value is a scalar (FieldValue), a posterior summary (Interval95: the JSON object {median, ci68: [low, high],
// ci95: [low, high]}) or a site's own estimate from its objects (Estimate: the same with an unconstrained end as
// null); an empty optional is null.
#include <array>
#include <optional>
#include <variant>

#include "topple/core/field.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/region/fit.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

using RegionalValue = std::variant<FieldValue, std::optional<Interval95>, std::optional<Estimate>>;

template <class Row>
struct RegionalField {
  const char* name;  ///< with its unit, as the JSON key
  RegionalValue (*get)(const Row& row);
};

/// The comparison's row: the frequency relation with the settings' threshold.
struct FrequencyComparisonRow {
  const FrequencyRelation& relation;
  const RegionalSettings& settings;
};

/// A fitted site's row: its pooled result, its survey site and its own inversion (nullptr: a station without objects).
struct RegionalSiteRow {
  const PooledSite& pooled;
  const Site& site;
  const InversionResult* own;
};

/// The tables, each in the order of its JSON object:
/// - kRelationFields, the PGA relation (R1): c0_ln_g, c1, c2_km, c2_fixed, tau_ln, reference_distance_km,
///   pga_at_reference_g;
/// - kFrequencyRelationFields, the frequency relation (F1): d0_ln_hz, d1, tau_f_ln, frequency_at_reference_hz;
/// - kConstantModelFields, the constant-frequency model it is compared with: f_c_hz, tau_f_ln;
/// - kFrequencyComparisonFields, the comparison (F3): ln_evidence_relation, ln_evidence_constant, ln_bayes_factor,
///   bayes_factor_threshold, supported, rule, sites_with_frequency;
/// - kRegionalSiteFields, a fitted site: site, survey_index, lat, lon, hypocentral_distance_km, instrument_pga_g,
///   objects, pooled_pga_g, relation_pga_g, independent_pga_g, independent_freq_hz, pooled_freq_hz,
///   relation_freq_hz.
extern const std::array<RegionalField<RegionalResult>, 7> kRelationFields;
extern const std::array<RegionalField<FrequencyRelation>, 4> kFrequencyRelationFields;
extern const std::array<RegionalField<FrequencyRelation>, 2> kConstantModelFields;
extern const std::array<RegionalField<FrequencyComparisonRow>, 7> kFrequencyComparisonFields;
extern const std::array<RegionalField<RegionalSiteRow>, 13> kRegionalSiteFields;

}  // namespace topple
