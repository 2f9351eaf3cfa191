// The field tables of the regional fit (fields.hpp).
#include "topple/region/fields.hpp"

#include <cmath>
#include <cstdint>
#include <string>

namespace topple {
namespace {

FieldValue optional_value(const std::optional<double>& v) { return v ? FieldValue{*v} : FieldValue{}; }

FieldValue count(std::size_t n) { return static_cast<std::int64_t>(n); }

Interval95 exp_of(const Interval95& v) {
  return {std::exp(v.median), std::exp(v.ci68_low), std::exp(v.ci68_high), std::exp(v.ci95_low), std::exp(v.ci95_high)};
}

std::optional<Estimate> own(const InversionResult* r, bool frequency) {
  if (r == nullptr) return std::nullopt;
  return frequency ? r->freq_estimate_hz : r->pga_estimate_g;
}

}  // namespace

const std::array<RegionalField<RegionalResult>, 7> kRelationFields{{
    {"c0_ln_g", [](const RegionalResult& r) -> RegionalValue { return std::optional(r.c0); }},
    {"c1", [](const RegionalResult& r) -> RegionalValue { return std::optional(r.c1); }},
    {"c2_km", [](const RegionalResult& r) -> RegionalValue { return FieldValue{r.c2_km}; }},
    // Fixed (fit.hpp: a dozen sites cannot resolve it).
    {"c2_fixed", [](const RegionalResult&) -> RegionalValue { return FieldValue{true}; }},
    {"tau_ln", [](const RegionalResult& r) -> RegionalValue { return std::optional(r.tau); }},
    {"reference_distance_km",
     [](const RegionalResult& r) -> RegionalValue { return FieldValue{r.reference_distance_km}; }},
    {"pga_at_reference_g", [](const RegionalResult& r) -> RegionalValue { return std::optional(exp_of(r.ln_a_ref)); }},
}};

const std::array<RegionalField<FrequencyRelation>, 4> kFrequencyRelationFields{{
    {"d0_ln_hz", [](const FrequencyRelation& f) -> RegionalValue { return std::optional(f.d0); }},
    {"d1", [](const FrequencyRelation& f) -> RegionalValue { return std::optional(f.d1); }},
    {"tau_f_ln", [](const FrequencyRelation& f) -> RegionalValue { return std::optional(f.tau); }},
    {"frequency_at_reference_hz",
     [](const FrequencyRelation& f) -> RegionalValue { return std::optional(exp_of(f.ln_f_ref)); }},
}};

const std::array<RegionalField<FrequencyRelation>, 2> kConstantModelFields{{
    {"f_c_hz", [](const FrequencyRelation& f) -> RegionalValue { return std::optional(f.constant_f_hz); }},
    {"tau_f_ln", [](const FrequencyRelation& f) -> RegionalValue { return std::optional(f.constant_tau); }},
}};

const std::array<RegionalField<FrequencyComparisonRow>, 7> kFrequencyComparisonFields{{
    {"ln_evidence_relation",
     [](const FrequencyComparisonRow& c) -> RegionalValue { return FieldValue{c.relation.log_evidence_relation}; }},
    {"ln_evidence_constant",
     [](const FrequencyComparisonRow& c) -> RegionalValue { return FieldValue{c.relation.log_evidence_constant}; }},
    {"ln_bayes_factor",
     [](const FrequencyComparisonRow& c) -> RegionalValue { return FieldValue{c.relation.ln_bayes_factor}; }},
    {"bayes_factor_threshold",
     [](const FrequencyComparisonRow& c) -> RegionalValue { return FieldValue{c.settings.frequency_bayes_factor}; }},
    {"supported", [](const FrequencyComparisonRow& c) -> RegionalValue { return FieldValue{c.relation.supported}; }},
    {"rule",
     [](const FrequencyComparisonRow&) -> RegionalValue {
       return FieldValue{
           std::string("supported when Z(relation) / Z(constant) >= the threshold (Kass & Raftery 1995: 3 "
                       "is the lower end of positive evidence); only then are the sites' frequencies "
                       "pooled")};
     }},
    {"sites_with_frequency",
     [](const FrequencyComparisonRow& c) -> RegionalValue { return count(c.relation.sites_with_frequency); }},
}};

const std::array<RegionalField<RegionalSiteRow>, 13> kRegionalSiteFields{{
    {"site", [](const RegionalSiteRow& s) -> RegionalValue { return FieldValue{s.pooled.name}; }},
    {"survey_index", [](const RegionalSiteRow& s) -> RegionalValue { return count(s.pooled.site_index); }},
    {"lat", [](const RegionalSiteRow& s) -> RegionalValue { return optional_value(s.site.lat_deg); }},
    {"lon", [](const RegionalSiteRow& s) -> RegionalValue { return optional_value(s.site.lon_deg); }},
    {"hypocentral_distance_km",
     [](const RegionalSiteRow& s) -> RegionalValue { return FieldValue{s.pooled.distance_km}; }},
    {"instrument_pga_g",
     [](const RegionalSiteRow& s) -> RegionalValue { return optional_value(s.pooled.instrument_pga_g); }},
    {"objects", [](const RegionalSiteRow& s) -> RegionalValue { return count(s.site.objects.size()); }},
    {"pooled_pga_g", [](const RegionalSiteRow& s) -> RegionalValue { return std::optional(s.pooled.pga_g); }},
    {"relation_pga_g",
     [](const RegionalSiteRow& s) -> RegionalValue { return std::optional(s.pooled.relation_pga_g); }},
    {"independent_pga_g", [](const RegionalSiteRow& s) -> RegionalValue { return own(s.own, false); }},
    {"independent_freq_hz", [](const RegionalSiteRow& s) -> RegionalValue { return own(s.own, true); }},
    {"pooled_freq_hz", [](const RegionalSiteRow& s) -> RegionalValue { return s.pooled.freq_hz; }},
    {"relation_freq_hz", [](const RegionalSiteRow& s) -> RegionalValue { return s.pooled.relation_freq_hz; }},
}};

}  // namespace topple
