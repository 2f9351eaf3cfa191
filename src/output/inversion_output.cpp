#include "topple/output/inversion_output.hpp"

#include <cmath>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/inversion/inversion_3c.hpp"
#include "topple/core/output_file.hpp"
#include "topple/output/provenance.hpp"
#include "topple/region/region.hpp"
#include "topple/core/units.hpp"

namespace topple::io {
namespace {

nlohmann::ordered_json opt(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json estimate_json(const Estimate& e) {
  nlohmann::ordered_json j;
  j["best"] = e.best;
  j["median"] = e.median;
  j["ci68"] = {opt(e.ci68_low), opt(e.ci68_high)};
  j["ci95"] = {opt(e.ci95_low), opt(e.ci95_high)};
  // Added: where the median or the best cell lies in the grid's first or last cell, it is no estimate.
  const auto edge = [](int at) {
    return at == 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(at < 0 ? "below" : "above");
  };
  j["median_grid_edge"] = edge(e.median_edge);
  j["best_grid_edge"] = edge(e.best_edge);
  return j;
}

nlohmann::ordered_json threshold_json(const StaticBound& b, const char* side) {
  nlohmann::ordered_json t;
  t["object"] = b.object_id;
  t["side"] = side;
  t["pga_g"] = b.pga_g;
  t["kind"] = b.hard ? "hard" : "soft";
  t["reason"] = b.reason;
  return t;
}

nlohmann::ordered_json arc_json(const DirectionArc& a) {
  return {{"low_deg", a.low_deg}, {"high_deg", a.high_deg()}, {"width_deg", a.width_deg}};
}

/// Added (components = 3, inversion_3c.hpp): the PGA axis is RotD50; the larger component's; the direction.
nlohmann::ordered_json three_component_json(const ThreeComponentResult& tc, const InversionResult& r) {
  nlohmann::ordered_json j;
  j["pga_axis"] = "RotD50";
  // Added (inversion_3c.hpp, item 6): the static thresholds on RotD100, where they hold; the top-level
  // static_bounds_pga_g, static_bounds_hard_pga_g and static_thresholds are then their consequence on RotD50.
  j["static_bounds_pga_axis"] = "RotD50";
  if (r.rotd100_bounds) {
    const StaticBounds& b = *r.rotd100_bounds;
    j["static_bounds_rotd100_pga_g"] = {opt(b.lower_g), opt(b.upper_g)};
    j["static_bounds_hard_rotd100_pga_g"] = {opt(b.hard_lower_g), opt(b.hard_upper_g)};
    nlohmann::ordered_json thresholds = nlohmann::ordered_json::array();
    for (const auto& t : b.lower) thresholds.push_back(threshold_json(t, "lower"));
    for (const auto& t : b.upper) thresholds.push_back(threshold_json(t, "upper"));
    j["static_thresholds_rotd100"] = thresholds;
    j["static_thresholds_vertical_ratio"] = tc.threshold_vertical_ratio;
  }
  j["larger_component_ratio"] = tc.larger_component_ratio;
  j["rotd100_ratio"] = tc.rotd100_ratio;
  j["pga_larger_component_g"] = {{"median", tc.larger_component_median_g},
                                 {"ci95", {opt(tc.larger_component_ci95_low_g), opt(tc.larger_component_ci95_high_g)}}};
  const DirectionEstimate& d = tc.direction;
  nlohmann::ordered_json dj;
  dj["constrained"] = d.constrained;
  dj["unconstrained_rule"] = fmt::format("95 % arc wider than {:g} deg", kUnconstrainedArcDeg);
  dj["mode_deg"] = d.mode_deg;
  dj["mean_deg"] = d.mean_deg;
  dj["resultant_length"] = d.resultant_length;
  dj["ci68"] = arc_json(d.ci68);
  dj["ci95"] = arc_json(d.ci95);
  dj["bin_width_deg"] = d.bin_width_deg;
  dj["bins_deg"] = d.azimuth_deg;
  dj["posterior"] = d.posterior;
  j["direction_of_strongest_shaking"] = dj;
  j["family"] = {{"coherence", tc.coherence},
                 {"vertical_pga_ratio", tc.vertical_pga_ratio},
                 {"vertical_frequency_ratio", tc.vertical_frequency_ratio}};
  j["slid_direction_error"] = {{"model", "von Mises"}, {"kappa", tc.slid_direction_kappa}};
  return j;
}

}  // namespace

nlohmann::ordered_json inversion_json(const InversionResult& r, const Site& site, const Provenance& provenance) {
  nlohmann::ordered_json j = inversion_json(r, site);
  nlohmann::ordered_json p;
  for (const ProvenanceField& field : kProvenanceFields) p[field.key] = provenance.*field.member;
  j["provenance"] = p;
  return j;
}

nlohmann::ordered_json inversion_json(const InversionResult& r, const Site& site) {
  nlohmann::ordered_json j;
  j["site"] = site.name;
  j["lat"] = opt(site.lat_deg);
  j["lon"] = opt(site.lon_deg);
  j["summary"] = inversion_summary(r);
  j["pga_g"] = estimate_json(r.pga_estimate_g);
  j["freq_hz"] = estimate_json(r.freq_estimate_hz);
  j["static_bounds_pga_g"] = {opt(r.bounds.lower_g), opt(r.bounds.upper_g)};
  // Added (issue 18): the hard thresholds alone, and every threshold with its kind; static_bounds_pga_g keeps its
  // meaning (hard and soft together) for the old readers.
  j["static_bounds_hard_pga_g"] = {opt(r.bounds.hard_lower_g), opt(r.bounds.hard_upper_g)};
  nlohmann::ordered_json thresholds = nlohmann::ordered_json::array();
  for (const auto& b : r.bounds.lower) thresholds.push_back(threshold_json(b, "lower"));
  for (const auto& b : r.bounds.upper) thresholds.push_back(threshold_json(b, "upper"));
  j["static_thresholds"] = thresholds;
  j["contradictions"] = r.bounds.contradictions;
  j["notes"] = r.notes;
  j["prior"] = r.prior;  // added (issue 32): which prior made the posterior ("log-uniform", "earthquake")
  // Added (issue 32): the motion family when it is not the default (a default survey's JSON keeps its bytes), and for
  // family = "mixture" its members' posterior weights P(f | data) beside their prior weights (docs/method.md, "A
  // mixture of the two families").
  if (r.family != motion_family_name(MotionFamily::synthetic)) j["family"] = r.family;
  if (!r.family_weights.empty()) {
    nlohmann::ordered_json post = nlohmann::ordered_json::object();
    nlohmann::ordered_json prior = nlohmann::ordered_json::object();
    for (const FamilyWeight& w : r.family_weights) {
      post[w.family] = w.posterior_weight;
      prior[w.family] = w.prior_weight;
    }
    j["family_weights"] = post;
    j["family_prior_weights"] = prior;
  }
  j["misfit_level"] = kMisfitProbability;
  nlohmann::ordered_json constraining = nlohmann::ordered_json::array();
  for (std::size_t o : most_constraining_objects(r)) constraining.push_back(r.objects[o].id);
  j["constraining_objects"] = constraining;
  nlohmann::ordered_json objects = nlohmann::ordered_json::array();
  for (std::size_t o = 0; o < r.objects.size(); ++o) {
    const ObjectReport& rep = r.objects[o];
    nlohmann::ordered_json oj;
    oj["id"] = rep.id;
    oj["outcome"] = std::string(outcome_name(rep.outcome));
    // Added (issue 15) only for the coupled model, so that an older one-component survey's JSON keeps its bytes; with
    // components = 3 (added) for every object: "slide" for the two-dimensional sliding block, "rock" for the oriented
    // rocking body (a box, a cylinder, a block at its bearing).
    if (rep.model == ObjectModel::coupled || r.three_component) {
      oj["model"] = std::string(object_model_name(rep.model));
    }
    oj["probability_at_best"] = rep.probability_at_best;
    oj["max_probability"] = rep.max_probability;
    oj["reproduced_anywhere"] = rep.reproduced_anywhere;
    for (const auto& b : r.bounds.lower) {
      if (b.object_id == rep.id) oj["static_lower_bound_pga_g"] = b.pga_g;
    }
    for (const auto& b : r.bounds.upper) {
      if (b.object_id == rep.id) oj["static_upper_bound_pga_g"] = b.pga_g;
    }
    if (r.rotd100_bounds) {  // added (components = 3): the same thresholds on RotD100, where they hold
      for (const auto& b : r.rotd100_bounds->lower) {
        if (b.object_id == rep.id) oj["static_lower_bound_rotd100_pga_g"] = b.pga_g;
      }
      for (const auto& b : r.rotd100_bounds->upper) {
        if (b.object_id == rep.id) oj["static_upper_bound_rotd100_pga_g"] = b.pga_g;
      }
    }
    for (const auto& so : site.objects) {  // added (issue 28): a scanned body's pose, only for bodies from meshes
      if (so.id == rep.id && !so.mesh_pose.empty()) oj["mesh_pose"] = so.mesh_pose;
    }
    oj["posterior_predictive"] = rep.posterior_predictive;
    oj["misfit"] = rep.misfit;
    oj["constraint_bits"] = rep.constraint_bits;
    objects.push_back(oj);
  }
  j["objects"] = objects;
  j["grid"] = {{"pga_g", r.pga_g}, {"freq_hz", r.freq_hz}, {"measured_freq_hz", r.measured_freq_hz}};
  j["best_cell"] = {{"pga_g", r.pga_g[r.best_cell / r.freq_hz.size()]}, {"freq_hz", r.freq_hz[r.best_cell % r.freq_hz.size()]}};
  j["runs"] = r.runs;
  j["seconds"] = r.seconds;
  // Added (issue 32, evidence.hpp): the objects' own evidence (the likelihood normalised over the grid: the posterior
  // under the log-uniform prior), the ridge and what to look for next ("prior", above, names the prior used).
  if (!r.marginal_pga_likelihood.empty()) {
    j["likelihood"] = {{"pga_g", estimate_json(r.pga_likelihood_g)},
                       {"freq_hz", estimate_json(r.freq_likelihood_hz)},
                       {"marginal_pga", r.marginal_pga_likelihood},
                       {"marginal_freq", r.marginal_freq_likelihood}};
  }
  nlohmann::ordered_json ridge = nlohmann::ordered_json::array();
  for (const PgaGivenFreq& g : r.pga_given_freq) {
    nlohmann::ordered_json col;
    col["freq_hz"] = g.freq_hz;
    col["likelihood_share"] = g.likelihood_share;
    col["median_g"] = g.pga_g ? nlohmann::ordered_json(g.pga_g->median) : nlohmann::ordered_json(nullptr);
    col["ci68_g"] = g.pga_g ? nlohmann::ordered_json{opt(g.pga_g->ci68_low), opt(g.pga_g->ci68_high)}
                            : nlohmann::ordered_json(nullptr);
    col["ci95_g"] = g.pga_g ? nlohmann::ordered_json{opt(g.pga_g->ci95_low), opt(g.pga_g->ci95_high)}
                            : nlohmann::ordered_json(nullptr);
    ridge.push_back(col);
  }
  j["pga_given_freq"] = ridge;
  j["pga_given_freq_rule"] = fmt::format(
      "per frequency column, the likelihood of that column normalised over PGA (no prior): its median and 68 % / "
      "95 % intervals (null ends: the grid's edge cells); null where the column's likelihood mass is below {:g} of "
      "the largest column's",
      kRidgeNegligibleShare);
  nlohmann::ordered_json next = nlohmann::ordered_json::array();
  for (const NextObject& n : r.next_objects) {
    next.push_back({{"object", n.object}, {"description", n.description}, {"look_for", n.look_for},
                    {"bits_pga", n.bits_pga}, {"bits_freq", n.bits_freq}});
  }
  j["next_objects"] = next;
  if (!r.populations.empty()) j["populations"] = populations_json(r);  // added (issue 30), only with populations
  if (r.three_component) j["three_component"] = three_component_json(*r.three_component, r);
  return j;
}

nlohmann::ordered_json populations_json(const InversionResult& r) {
  const std::size_t nf = r.freq_hz.size();
  const PopulationSlices at = population_slices_at_estimate(r);
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const PopulationReport& p : r.populations) {
    nlohmann::ordered_json pj;
    pj["id"] = p.id;
    pj["count"] = p.count;
    pj["overturned"] = p.overturned;
    if (p.rocked) pj["rocked"] = *p.rocked;
    if (p.slid) pj["slid"] = *p.slid;
    pj["observed_fraction"] = p.observed_fraction;
    pj["model_fraction_at_estimate"] = p.model_fraction_at_estimate;
    pj["posterior_predictive_fraction"] = p.posterior_predictive_fraction;
    pj["members"] = p.members;
    pj["member_rule"] = p.member_rule;
    // The model's overturned fraction along the grid through the estimate: over PGA in the median frequency's
    // column, over frequency in the median PGA's row (the report's figure).
    std::vector<double> over_pga, over_freq;
    for (std::size_t i = 0; i < r.pga_g.size(); ++i) over_pga.push_back(p.model_fraction[i * nf + at.freq_column]);
    for (std::size_t j = 0; j < nf; ++j) over_freq.push_back(p.model_fraction[at.pga_row * nf + j]);
    pj["model_fraction_over_pga"] = {{"freq_hz", r.freq_hz[at.freq_column]}, {"pga_g", r.pga_g}, {"fraction", over_pga}};
    pj["model_fraction_over_freq"] = {{"pga_g", r.pga_g[at.pga_row]}, {"freq_hz", r.freq_hz}, {"fraction", over_freq}};
    out.push_back(pj);
  }
  return out;
}

PopulationSlices population_slices_at_estimate(const InversionResult& r) {
  const auto nearest = [](const std::vector<double>& axis, double x) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < axis.size(); ++i) {
      if (std::abs(std::log(axis[i] / x)) < std::abs(std::log(axis[best] / x))) best = i;
    }
    return best;
  };
  return {nearest(r.pga_g, r.pga_estimate_g.median), nearest(r.freq_hz, r.freq_estimate_hz.median)};
}

void write_inversion_grid_csv(const std::filesystem::path& path, const InversionResult& r) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "pga_g,freq_hz,log_likelihood,posterior";
  for (const auto& o : r.objects) out << ",p_" << o.id;
  out << "\n";
  const std::size_t nf = r.freq_hz.size();
  for (std::size_t c = 0; c < r.posterior.size(); ++c) {
    out << fmt::format("{},{},{},{}", r.pga_g[c / nf], r.freq_hz[c % nf], r.log_likelihood[c], r.posterior[c]);
    for (const auto& o : r.objects) out << fmt::format(",{}", o.probability[c]);
    out << "\n";
  }
  file.commit();
}

double epicentral_distance_km(double lat1, double lon1, double lat2, double lon2) {
  return geodesic_distance_km(lat1, lon1, lat2, lon2);  // WGS84 geodesic (region.hpp), no longer haversine
}

void write_sites_geojson(const std::filesystem::path& path, const std::vector<Site>& sites,
                         const std::vector<InversionResult>& results) {
  nlohmann::ordered_json fc;
  fc["type"] = "FeatureCollection";
  fc["features"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (!sites[i].lat_deg || !sites[i].lon_deg) continue;
    nlohmann::ordered_json f;
    f["type"] = "Feature";
    f["geometry"] = {{"type", "Point"}, {"coordinates", {*sites[i].lon_deg, *sites[i].lat_deg}}};
    const auto& r = results[i];
    f["properties"] = {{"site", sites[i].name},
                       {"pga_median_g", r.pga_estimate_g.median},
                       {"pga_best_g", r.pga_estimate_g.best},
                       {"pga_ci68_g", {opt(r.pga_estimate_g.ci68_low), opt(r.pga_estimate_g.ci68_high)}},
                       {"pga_ci95_g", {opt(r.pga_estimate_g.ci95_low), opt(r.pga_estimate_g.ci95_high)}},
                       {"static_bounds_pga_g", {opt(r.bounds.lower_g), opt(r.bounds.upper_g)}},
                       {"freq_median_hz", r.freq_estimate_hz.median}};
    if (r.three_component) {  // added (components = 3): the PGA axis and the direction of strongest shaking
      const DirectionEstimate& d = r.three_component->direction;
      f["properties"]["pga_axis"] = "RotD50";
      f["properties"]["direction_constrained"] = d.constrained;
      f["properties"]["direction_mode_deg"] = d.constrained ? nlohmann::ordered_json(d.mode_deg) : nlohmann::ordered_json(nullptr);
      f["properties"]["direction_ci95_deg"] = {d.ci95.low_deg, d.ci95.high_deg()};
      if (r.rotd100_bounds) {
        f["properties"]["static_bounds_rotd100_pga_g"] = {opt(r.rotd100_bounds->lower_g), opt(r.rotd100_bounds->upper_g)};
      }
    }
    fc["features"].push_back(f);
  }
  write_file_atomically(path, fc.dump(2) + "\n");
}

void write_distance_csv(const std::filesystem::path& path, const std::vector<Site>& sites,
                        const std::vector<InversionResult>& results, double lat, double lon) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  const auto cell = [](const std::optional<double>& v) { return v ? fmt::format("{}", *v) : std::string(); };
  out << "site,epicentral_distance_km,pga_median_g,pga_ci68_low_g,pga_ci68_high_g,pga_ci95_low_g,pga_ci95_high_g\n";
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (!sites[i].lat_deg || !sites[i].lon_deg) continue;
    const auto& r = results[i];
    std::string name = sites[i].name;
    if (name.find_first_of(",\"") != std::string::npos) {
      std::string q = "\"";
      for (char c : name) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
      name = q + "\"";
    }
    const Estimate& pga = r.pga_estimate_g;
    out << fmt::format("{},{},{},{},{},{},{}\n", name,
                       epicentral_distance_km(lat, lon, *sites[i].lat_deg, *sites[i].lon_deg), pga.median,
                       cell(pga.ci68_low), cell(pga.ci68_high), cell(pga.ci95_low), cell(pga.ci95_high));
  }
  file.commit();
}

}  // namespace topple::io
