// The standard sweep: records and pulses against sliding blocks and rocking bodies, expanded into an ensemble plan
// whose run function calls the exact sliding solver and the rocking engine. See sweep.hpp (make_plan) for the
// columns.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "topple/solvers/summary_fields.hpp"
#include "topple/solvers/summary_fields_3d.hpp"
#include "topple/ensemble/sweep.hpp"
#include "topple/core/error.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/core/units.hpp"

namespace topple::ensemble {
namespace {

constexpr std::size_t kAbsent = std::numeric_limits<std::size_t>::max();

/// Column names in order, and where each one is.
class ColumnSet {
 public:
  void add(const std::string& name) {
    if (index_.count(name) == 0) {
      index_[name] = names_.size();
      names_.push_back(name);
    }
  }
  [[nodiscard]] std::size_t at(const std::string& name) const {
    const auto it = index_.find(name);
    return it == index_.end() ? kAbsent : it->second;
  }
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }

 private:
  std::vector<std::string> names_;
  std::map<std::string, std::size_t> index_;
};

/// The sweep's result columns of a result type: its table's fields that have a sweep position, in that order.
template <class Result, std::size_t N>
std::vector<const Field<Result>*> sweep_fields(const std::array<Field<Result>, N>& table) {
  std::vector<const Field<Result>*> fields;
  for (const auto& f : table) {
    if (f.sweep_column >= 0) fields.push_back(&f);
  }
  std::sort(fields.begin(), fields.end(), [](const auto* x, const auto* y) { return x->sweep_column < y->sweep_column; });
  return fields;
}

/// Where each sweep field of a table goes in a row of result columns.
template <class Result>
struct FieldSlots {
  std::vector<std::pair<const Field<Result>*, std::size_t>> slots;

  template <std::size_t N>
  FieldSlots(const std::array<Field<Result>, N>& table, const ColumnSet& columns) {
    for (const auto* f : sweep_fields(table)) {
      const std::size_t i = columns.at(f->name);
      if (i != kAbsent) slots.emplace_back(f, i);
    }
  }
  void fill(const Result& result, Value* row) const {
    for (const auto& [field, column] : slots) row[column] = field->get(result);
  }
};

/// The sliding result columns of model = "3d" objects with friction (Rigid3DSummary; the names of `topple rock --model
/// 3d --json`, io::rigid3d_summary_json), in this order. Only a sweep with such an object has them: others keep their
/// columns. The last five (issue 29: slide-rock and flight) were appended after the first eight.
constexpr std::array<const char*, 13> kSlide3DColumns{"residual_slide_east_m", "residual_slide_north_m",
                                                      "max_slide_speed_m_s",   "slide_path_length_m",
                                                      "friction_energy_j_per_kg", "slip_episodes",
                                                      "first_slip_time_s",    "slide_rock_time_s",
                                                      "slide_rock_duration_s", "flights",
                                                      "flight_duration_s",    "residual_yaw_deg",
                                                      "painleve_events"};

/// The coupled model's result columns: kSlideRockFields in order, less those that are object columns (sweep.hpp).
std::vector<const Field<SlideRockOutcome>*> coupled_fields() {
  std::vector<const Field<SlideRockOutcome>*> fields;
  for (const auto& f : kSlideRockFields) {
    const std::string_view n = f.name;
    if (n != "mu_static" && n != "mu_kinetic" && n != "g_m_s2" && n != "e_mode") fields.push_back(&f);
  }
  return fields;
}

/// Where each coupled field goes in a row.
struct CoupledSlots {
  std::vector<std::pair<const Field<SlideRockOutcome>*, std::size_t>> slots;
  explicit CoupledSlots(const ColumnSet& columns) {
    for (const auto* f : coupled_fields()) {
      const std::size_t i = columns.at(f->name);
      if (i != kAbsent) slots.emplace_back(f, i);
    }
  }
  void fill(const SlideRockOutcome& result, Value* row) const {
    for (const auto& [field, column] : slots) row[column] = field->get(result);
  }
};

/// The object's flexible support, if any.
const std::optional<SupportOscillator>& support_of(const ObjectSpec& o) {
  return std::visit([](const auto& x) -> const std::optional<SupportOscillator>& { return x.support; }, o);
}

bool same_support(const std::optional<SupportOscillator>& a, const std::optional<SupportOscillator>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->freq_hz == b->freq_hz && a->damping_ratio == b->damping_ratio);
}

/// The motion an object runs on: the ground's, or its flexible support's (support_motion), the last one kept so that
/// consecutive objects on the same support filter the motion once.
class OnSupport {
 public:
  explicit OnSupport(const GroundMotion& ground) : ground_(ground) {}
  const GroundMotion& operator()(const std::optional<SupportOscillator>& support) {
    if (!support) return ground_;
    if (!filtered_ || !same_support(support, last_)) {
      filtered_ = support_motion(ground_, *support);
      last_ = support;
    }
    return *filtered_;
  }

 private:
  const GroundMotion& ground_;
  std::optional<SupportOscillator> last_;
  std::optional<GroundMotion> filtered_;
};

/// A motion case made from a record set: the set (its first component is the case's base motion, which the engine
/// transforms), the transform to apply to its other components, and the objects' bearing.
struct SetCase {
  std::shared_ptr<const MotionSet> set;
  MotionTransform transform;
  double bearing_deg = 0.0;
};

/// The run function of the standard sweep. Consecutive level-or-inclined blocks with mu_kinetic = mu_static and the
/// same slope, mode and g go through slide_summaries, which shares the input scan across them and gives the same
/// numbers as slide_summary block by block.
class Runner {
 public:
  Runner(std::vector<ObjectSpec> objects, const ColumnSet& results, std::vector<std::optional<SetCase>> set_cases,
         OrientationOptions orientation)
      : objects_(std::move(objects)), slide_(kSlidingFields, results), slide_2d_(kSliding2dFields, results),
        rock_(kRockingFields, results),
        rock_sides_(kRockingSideFields, results), rock_3d_(kRigid3DFields, results), coupled_(results), stride_(results.names().size()), set_cases_(std::move(set_cases)),
        orientation_(orientation), governing_azimuth_(results.at("governing_azimuth_deg")),
        governing_axis_(results.at("governing_axis")) {
    for (std::size_t i = 0; i < kSlide3DColumns.size(); ++i) slide_3d_[i] = results.at(kSlide3DColumns[i]);
  }

  void operator()(const GroundMotion& ground, std::size_t motion_index, std::size_t begin, std::size_t end,
                  std::span<Value> out) const {
    if (motion_index < set_cases_.size() && set_cases_[motion_index]) {
      run_set(ground, *set_cases_[motion_index], begin, end, out);
      return;
    }
    std::size_t o = begin;
    std::vector<double> mus;
    OnSupport on_support(ground);
    while (o < end) {
      Value* row = out.data() + (o - begin) * stride_;
      const GroundMotion& motion = on_support(support_of(objects_[o]));
      if (const auto* s = std::get_if<SlideObject>(&objects_[o])) {
        std::size_t last = o + 1;
        while (last < end && batchable(*s, objects_[last])) ++last;
        if (last - o >= 2 && s->block.mu_kinetic == s->block.mu_static) {
          mus.clear();
          for (std::size_t k = o; k < last; ++k) mus.push_back(std::get<SlideObject>(objects_[k]).block.mu_static);
          const auto summaries = slide_summaries(motion, mus, s->block.slope_rad, s->block.mode, s->block.g_m_s2);
          for (std::size_t k = o; k < last; ++k) {
            slide_.fill(SlidingOutcome{summaries[k - o], std::get<SlideObject>(objects_[k]).block},
                        out.data() + (k - begin) * stride_);
          }
          o = last;
          continue;
        }
        slide_.fill(SlidingOutcome{slide_summary(motion, s->block), s->block}, row);
      } else {
        const auto& r = std::get<RockObject>(objects_[o]);
        if (r.coupled) {  // the coupled slide-rock model (checked by make_plan: options.mu is set)
          const SlideRockBody body = SlideRockBody::from_rocking(r.body, *r.options.mu, r.mu_kinetic);
          const SlideRockOptions options = slide_rock_options(r.options);
          const SlideRockSummary summary = slide_rock(motion, body, options).summary;
          coupled_.fill(SlideRockOutcome{summary, body, options}, row);
          ++o;
          continue;
        }
        const RockingSummary summary = rock_summary(motion, r.body, r.options);
        rock_.fill(RockingOutcome{summary, r.body, r.options}, row);
        rock_sides_.fill(RockingOutcome{summary, r.body, r.options}, row);  // no slots: no asymmetric body
      }
      ++o;
    }
  }

 private:
  /// Rocking objects as oriented objects: the governing direction's results, and which direction it was; sliding
  /// objects as bidirectional sliders (sliding2d.hpp: friction is isotropic, the bearing does not enter).
  void run_set(const GroundMotion& first, const SetCase& c, std::size_t begin, std::size_t end,
               std::span<Value> out) const {
    std::optional<MotionSet> transformed;
    if (!c.transform.is_identity()) transformed = transformed_set(*c.set, c.transform, first);
    const MotionSet& set = transformed ? *transformed : *c.set;
    // Three-dimensional objects: the pair along east and north (eq. M1), made once for the case's objects.
    std::optional<std::pair<GroundMotion, GroundMotion>> east_north;
    for (std::size_t o = begin; o < end; ++o) {
      Value* row = out.data() + (o - begin) * stride_;
      if (const auto* s = std::get_if<SlideObject>(&objects_[o])) {
        const Sliding2dSummary summary =
            slide_2d_summary(set.first(), set.second(), *set.azimuths(), s->block, set.vertical_ptr());
        slide_2d_.fill(Sliding2dOutcome{summary, s->block}, row);
        continue;
      }
      const auto& r = std::get<RockObject>(objects_[o]);
      if (r.three_d()) {
        if (!east_north) east_north.emplace(set.projected(90.0), set.projected(0.0));
        const Rigid3DSummary summary = run_3d(r, east_north->first, east_north->second, set.vertical_ptr(),
                                              c.bearing_deg);
        rock_3d_.fill(Rigid3DOutcome{summary}, row);
        if (r.options.mu) fill_slide_3d(summary, row);  // without friction the cells do not apply: empty
        continue;
      }
      const OrientedBody body = OrientedBody::make(r.body, r.depth_m);
      const OrientedRockingSummary s = rock_oriented_summary(set, body, c.bearing_deg, r.options, orientation_);
      const DirectionResponse& g = s.governing_response();
      const RockingOutcome outcome{g.summary, planar_body_of(body, g.axis), r.options};
      rock_.fill(outcome, row);
      rock_sides_.fill(outcome, row);  // no slots: no asymmetric body
      if (governing_azimuth_ != kAbsent) row[governing_azimuth_] = g.azimuth_deg;
      if (governing_axis_ != kAbsent) row[governing_axis_] = std::string(oriented_axis_name(g.axis));
    }
  }

  /// A three-dimensional object at `bearing_deg` (its +x axis; degrees clockwise from north) under the pair along east
  /// and north and the vertical: the body turned by 90 - bearing degrees counter-clockwise seen from above, as
  /// `topple rock --model 3d --h2 --bearing-deg` turns it (cli/rock_3d.cpp), so that its azimuths are the ground's.
  /// A cylinder (cylinder_3d) is axisymmetric: the pair along east and north as it is, whatever the bearing
  /// (cli/rock_3d.cpp likewise). Friction (options.mu, mu_kinetic) goes to Rigid3DOptions::mu_s, mu_k; absent: the
  /// no-slip engine, as before friction was taken.
  static Rigid3DSummary run_3d(const RockObject& r, const GroundMotion& east, const GroundMotion& north,
                               const GroundMotion* vertical, double bearing_deg) {
    Rigid3DOptions options = rigid3d_options(r.options);
    options.mu_s = r.options.mu;
    options.mu_k = r.mu_kinetic;
    if (r.cylinder_3d) return rock3d_cylinder(east, &north, vertical, *r.cylinder_3d, options).summary;
    const RigidBody3D turned = r.body_3d->rotated_about_vertical(deg_to_rad(90.0 - bearing_deg));
    return rock3d(east, &north, vertical, turned, options).summary;
  }

  /// The sliding columns of a model = "3d" run with friction (kSlide3DColumns).
  void fill_slide_3d(const Rigid3DSummary& s, Value* row) const {
    const auto put = [&](std::size_t i, Value v) {
      if (slide_3d_[i] != kAbsent) row[slide_3d_[i]] = std::move(v);
    };
    const auto opt = [](const std::optional<double>& x) { return x ? Value(*x) : Value(); };
    put(0, s.residual_slide_east_m);
    put(1, s.residual_slide_north_m);
    put(2, s.max_slide_speed_m_s);
    put(3, s.slide_path_length_m);
    put(4, s.friction_energy_j_per_kg);
    put(5, static_cast<std::int64_t>(s.slip_episodes));
    put(6, opt(s.first_slip_time_s));
    put(7, opt(s.slide_rock_time_s));
    put(8, s.slide_rock_duration_s);
    put(9, static_cast<std::int64_t>(s.flights));
    put(10, s.flight_duration_s);
    put(11, s.residual_yaw_deg);
    put(12, static_cast<std::int64_t>(s.painleve_events));
  }

  static bool batchable(const SlideObject& first, const ObjectSpec& next) {
    const auto* s = std::get_if<SlideObject>(&next);
    return s != nullptr && same_support(first.support, s->support) && first.block.mu_kinetic == first.block.mu_static &&
           s->block.mu_kinetic == s->block.mu_static && s->block.slope_rad == first.block.slope_rad &&
           s->block.mode == first.block.mode && s->block.g_m_s2 == first.block.g_m_s2;
  }

  std::vector<ObjectSpec> objects_;
  FieldSlots<SlidingOutcome> slide_;
  FieldSlots<Sliding2dOutcome> slide_2d_;
  FieldSlots<RockingOutcome> rock_;
  FieldSlots<RockingOutcome> rock_sides_;
  FieldSlots<Rigid3DOutcome> rock_3d_;
  CoupledSlots coupled_;
  std::size_t stride_ = 0;
  std::vector<std::optional<SetCase>> set_cases_;  ///< by motion index; empty for records and pulses
  OrientationOptions orientation_;
  std::size_t governing_azimuth_ = kAbsent;
  std::size_t governing_axis_ = kAbsent;
  std::array<std::size_t, kSlide3DColumns.size()> slide_3d_{};  ///< where kSlide3DColumns go (kAbsent: not a column)
};

std::string_view polarity_name(bool inverse) { return inverse ? "inverse" : "normal"; }

/// Values of a column set filled by name.
class RowValues {
 public:
  explicit RowValues(const ColumnSet& columns) : columns_(columns), values_(columns.names().size()) {}
  void set(const std::string& name, Value v) {
    const std::size_t i = columns_.at(name);
    if (i != kAbsent) values_[i] = std::move(v);
  }
  [[nodiscard]] std::vector<Value> take() { return std::move(values_); }

 private:
  const ColumnSet& columns_;
  std::vector<Value> values_;
};

}  // namespace

MotionSet transformed_set(const MotionSet& set, const MotionTransform& transform, const GroundMotion& first) {
  // The components share one grid, so the merge reproduces it.
  const GroundMotion second = transform.apply(set.second());
  MotionTransform up = transform;
  up.invert = false;
  const std::optional<GroundMotion> vertical = set.has_vertical() ? std::optional(up.apply(set.vertical())) : std::nullopt;
  return MotionSet::make(first, &second, set.azimuths(), vertical ? &*vertical : nullptr);
}

void check_housner_restitution(const RockingBody& body) {
  if (housner_restitution(body) < 0.0) {
    throw parameter_error("e", fmt::format("Housner's restitution 1 - 2a^2/D = {} is negative for this body (too squat "
                                           "to rock onto its other edge): {}", housner_restitution(body),
                                           kSquatBodyAdvice));
  }
}

namespace {

/// The spec's own consistency, checked first: something to run, and the constants that every case uses.
void check_spec(const SweepSpec& spec) {
  if (spec.records.empty() && spec.pulses.empty() && spec.record_sets.empty()) {
    throw parameter_error("motions", "the sweep has no motion");
  }
  if (spec.objects.empty()) throw parameter_error("object", "the sweep has no object");
  if (spec.inverse.empty()) throw parameter_error("polarity", "no polarity given");
  if ((!spec.records.empty() || !spec.record_sets.empty()) && (spec.time_scales.empty() || spec.scales.empty())) {
    throw parameter_error("scale", "no scale or time scale given");
  }
  if (!(spec.g_m_s2 > 0.0) || !std::isfinite(spec.g_m_s2)) {
    throw parameter_error("g", fmt::format("g must be positive and finite, got {}", spec.g_m_s2));
  }
}

/// Which kinds of motion and object the sweep holds: they decide its columns.
struct SweepKinds {
  bool any_slide = false;
  bool any_rock = false;
  bool any_rock_mu = false;
  bool any_block = false;
  bool any_cylinder = false;
  bool any_general = false;     // symmetric general: a, h, D
  bool any_asymmetric = false;  // asymmetric general: b1, b2, h, inertia
  bool any_mesh = false;
  bool any_support = false;
  bool any_box = false;     // a block with a depth (an oriented box)
  bool any_set = false;     // record sets (two horizontal components)
  bool any_single = false;  // single records or pulses
  bool any_rocking = false;  // rocking objects (Housner's model)
  bool any_coupled = false;  // coupled slide-rock objects
  bool any_3d = false;       // three-dimensional objects (model "3d")
  bool any_3d_mu = false;    // three-dimensional objects with friction (mu)
};

SweepKinds kinds_of(const SweepSpec& spec) {
  SweepKinds k;
  for (const auto& o : spec.objects) {
    k.any_support = k.any_support || support_of(o).has_value();
    if (const auto* r = std::get_if<RockObject>(&o)) {
      k.any_rock = true;
      k.any_coupled = k.any_coupled || r->coupled;
      k.any_3d = k.any_3d || r->three_d();
      k.any_3d_mu = k.any_3d_mu || (r->three_d() && r->options.mu.has_value());
      k.any_rocking = k.any_rocking || (!r->coupled && !r->three_d());
      k.any_rock_mu = k.any_rock_mu || r->options.mu.has_value();
      k.any_block = k.any_block || r->body.shape == RockingBody::Shape::block;
      k.any_cylinder = k.any_cylinder || r->body.shape == RockingBody::Shape::cylinder;
      k.any_general = k.any_general || (r->body.shape == RockingBody::Shape::general && r->body.symmetric());
      k.any_asymmetric = k.any_asymmetric || !r->body.symmetric();
      k.any_mesh = k.any_mesh || !r->mesh.empty();
      k.any_box = k.any_box || r->depth_m.has_value();
    } else {
      k.any_slide = true;
    }
  }
  k.any_set = !spec.record_sets.empty();
  k.any_single = !spec.records.empty() || !spec.pulses.empty();
  return k;
}

/// Each object against the kinds of motion it runs under, before any run.
void check_objects(const SweepSpec& spec, bool any_set) {
  for (std::size_t k = 0; k < spec.objects.size(); ++k) {
    const auto* r = std::get_if<RockObject>(&spec.objects[k]);
    const std::string name = fmt::format("object[{}]", k + 1);
    if (r != nullptr && r->coupled) {
      if (!r->options.mu) throw parameter_error(name + ".mu", "a coupled object needs its friction coefficient mu");
      if (any_set) {
        throw parameter_error(name + ".model", "coupled objects run under single records and pulses; under "
                                               "[[motions.set]] use model = \"rock\" (oriented rocking)");
      }
      // The body with its friction, valid before any run (from_rocking names "mu", "mu_k").
      try {
        (void)SlideRockBody::from_rocking(r->body, *r->options.mu, r->mu_kinetic);
      } catch (const InputError& e) {
        throw parameter_error(name + "." + (e.where().field == "mu_k" ? "mu_kinetic" : e.where().field), e.problem());
      }
    }
    if (r != nullptr && r->three_d()) {
      if (!spec.records.empty() || !spec.pulses.empty()) {
        throw parameter_error(name + ".model", "a three-dimensional object (model = \"3d\") runs under two horizontal "
                                               "components and a vertical: [[motions.set]] only, not single records "
                                               "or pulses");
      }
      if (r->mu_kinetic && !r->options.mu) {
        throw parameter_error(name + ".mu_kinetic", "a kinetic friction coefficient needs the static one (mu)");
      }
      if (r->options.mu) {  // the engine's own check (rigid3d.hpp: mu_s >= 0, 0 <= mu_k <= mu_s), before any run
        const double mu = *r->options.mu;
        if (!std::isfinite(mu) || mu < 0.0) {
          throw parameter_error(name + ".mu", fmt::format("static friction must be >= 0 and finite, got {}", mu));
        }
        if (r->mu_kinetic && (!std::isfinite(*r->mu_kinetic) || *r->mu_kinetic < 0.0 || *r->mu_kinetic > mu)) {
          throw parameter_error(name + ".mu_kinetic", fmt::format("kinetic friction must be in [0, mu = {}], got {}",
                                                                  mu, *r->mu_kinetic));
        }
      }
      if (r->coupled) throw parameter_error(name + ".model", "an object is coupled or three-dimensional, not both");
    }
    if (r != nullptr && r->depth_m) {
      if (!spec.records.empty() || !spec.pulses.empty()) {
        throw parameter_error(name + ".depth", "a box (a block with a depth) needs two horizontal components: run it "
                                               "under [[motions.set]] only, not under single records or pulses");
      }
      (void)OrientedBody::make(r->body, r->depth_m);  // a depth on another shape, or an invalid one: before any run
    }
    if (const auto* s = std::get_if<SlideObject>(&spec.objects[k]); any_set && s != nullptr) {
      // Under a set a sliding object is a bidirectional slider (sliding2d.hpp): two-way, on level ground (a slope
      // would need its fall line's azimuth, which a sweep object does not give).
      if (s->block.mode != SlidingMode::two_way) {
        throw parameter_error(name + ".mode", "under [[motions.set]] a sliding object slides in two dimensions and "
                                              "must be two-way (one-way sliding down the fall line has no meaning "
                                              "for a block free to move across it)");
      }
      if (s->block.slope_rad != 0.0) {
        throw parameter_error(name + ".slope_deg", "under [[motions.set]] sliding objects run on level ground (a "
                                                   "slope's fall-line azimuth is not a sweep field: use topple slide "
                                                   "H1 --h2 H2 --slope-deg B --slope-azimuth-deg Z)");
      }
    }
    if (any_set && support_of(spec.objects[k])) {
      throw parameter_error(name + ".support_freq", "flexible supports are not run under [[motions.set]] (the support "
                                                    "of an oriented object would filter each direction)");
    }
  }
}

/// The bearings and the record sets: bearings only under sets, and required there unless no object needs one.
void check_sets(const SweepSpec& spec, bool any_set) {
  bool all_cylinders_or_sliders = true;  // objects that need no bearing under a set
  for (const auto& o : spec.objects) {
    const auto* r = std::get_if<RockObject>(&o);
    all_cylinders_or_sliders =
        all_cylinders_or_sliders && (r == nullptr || r->body.shape == RockingBody::Shape::cylinder);
  }
  if (!any_set && !spec.bearings_deg.empty()) {
    throw parameter_error("bearing", "bearings apply to objects under [[motions.set]] (two horizontal components), "
                                     "and the sweep has none");
  }
  if (any_set && spec.bearings_deg.empty() && !all_cylinders_or_sliders) {
    throw parameter_error("bearing", "rocking objects under [[motions.set]] need their bearings (bearing_deg: the "
                                     "direction across the narrow side, degrees clockwise from north); only cylinders "
                                     "and sliding objects have none");
  }
  for (const double b : spec.bearings_deg) {
    if (!std::isfinite(b)) throw parameter_error("bearing", fmt::format("bearings must be finite, got {}", b));
  }
  if (any_set) {
    // The cylinder's direction grid, checked before any run.
    (void)oriented_directions(OrientedBody::planar(RockingBody::cylinder(1.0, 1.0)), 0.0, spec.orientation);
  }
  for (const auto& rs : spec.record_sets) {
    if (!rs.set || !rs.set->has_second() || !rs.set->azimuths()) {
      throw parameter_error("motions.set", fmt::format("record set '{}' needs two horizontal components with known "
                                                       "azimuths", rs.name));
    }
  }
}

/// Objects on a flexible support against the motions they would filter.
void check_supports(const SweepSpec& spec) {
  // The support's response is exact for uniformly sampled input (flexible.hpp); analytic pulses keep their jumps
  // on an irregular grid. Said before any run.
  for (const auto& rec : spec.records) {
    if (rec.motion && !rec.motion->is_uniform()) {
      throw parameter_error("support_freq", fmt::format("record '{}' is irregularly sampled: objects on a flexible "
                                                        "support need uniformly sampled records", rec.name));
    }
  }
  if (!spec.pulses.empty()) {
    throw parameter_error("support_freq", "objects on a flexible support run on records only (analytic pulses are "
                                          "irregularly sampled, at their jumps)");
  }
}

ColumnSet motion_columns(const SweepSpec& spec, const SweepKinds& k) {
  ColumnSet motion_cols;
  motion_cols.add("motion");
  if (!spec.pulses.empty()) {
    motion_cols.add("pulse_kind");
    motion_cols.add("pulse_amp_g");
    motion_cols.add("pulse_duration_s");
  }
  for (const char* c : {"time_scale", "scale_factor", "pga_g", "polarity"}) motion_cols.add(c);
  if (k.any_set) motion_cols.add("bearing_deg");
  return motion_cols;
}

ColumnSet object_columns(const SweepKinds& k) {
  ColumnSet object_cols;
  object_cols.add("model");
  object_cols.add("g_m_s2");
  if (k.any_slide || k.any_rock_mu) object_cols.add("mu");
  if (k.any_slide) {
    for (const char* c : {"mu_kinetic", "slope_deg", "mode"}) object_cols.add(c);
  }
  if (k.any_coupled || k.any_3d_mu) object_cols.add("mu_kinetic");
  if (k.any_rock) {
    object_cols.add("shape");
    if (k.any_block) object_cols.add("width_m");
    if (k.any_cylinder) object_cols.add("diameter_m");
    if (k.any_block || k.any_cylinder) object_cols.add("height_m");
    if (k.any_general) {
      for (const char* c : {"a_m", "h_m", "D_m2"}) object_cols.add(c);
    }
    if (k.any_asymmetric) {
      for (const char* c : {"b1_m", "b2_m", "h_m", "inertia_m2"}) object_cols.add(c);
    }
    if (k.any_mesh) {
      for (const char* c : {"mesh", "mesh_azimuth_deg", "mesh_pose"}) object_cols.add(c);
    }
    object_cols.add("restitution");
    if (k.any_box) object_cols.add("depth_m");
  }
  if (k.any_support) {
    object_cols.add("support_freq_hz");
    object_cols.add("support_damping");
  }
  return object_cols;
}

ColumnSet result_columns(const SweepKinds& k) {
  ColumnSet result_cols;
  // The result columns come from the field tables (summary_fields.hpp); a name both have (end_time_s) is one
  // column.
  // Sliding objects under single records and pulses (1-D); under sets (2-D) the bidirectional columns, those
  // that 1-D rows also have (max_abs_displacement_m ...) shared, the others (residual_azimuth_deg, residual_east_m,
  // residual_north_m, path_length_m) added: a sweep without sets keeps its columns.
  if (k.any_slide && k.any_single) {
    for (const auto* f : sweep_fields(kSlidingFields)) result_cols.add(f->name);
  }
  if (k.any_slide && k.any_set) {
    for (const auto* f : sweep_fields(kSliding2dFields)) result_cols.add(f->name);
  }
  if (k.any_rocking) {
    for (const auto* f : sweep_fields(kRockingFields)) result_cols.add(f->name);
  }
  if (k.any_set && k.any_rocking) {  // planar rocking objects (a 3-D object has no governing direction)
    result_cols.add("governing_azimuth_deg");
    result_cols.add("governing_axis");
  }
  if (k.any_asymmetric && k.any_rocking) {
    for (const auto* f : sweep_fields(kRockingSideFields)) result_cols.add(f->name);
  }
  if (k.any_coupled) {
    for (const auto* f : coupled_fields()) result_cols.add(f->name);
  }
  if (k.any_3d) {
    for (const auto* f : sweep_fields(kRigid3DFields)) result_cols.add(f->name);
  }
  if (k.any_3d_mu) {
    for (const char* c : kSlide3DColumns) result_cols.add(c);
  }
  return result_cols;
}

/// One scale of a record at one time scale: the transform, and the factor it multiplies the record by. A set's
/// transform carries the factor (its first component's to the target PGA), which the run function applies to its
/// other components too; a record's carries the target PGA.
std::pair<MotionTransform, double> scaled_transform(const ScaleSpec& sc, double ts, double peak,
                                                    const std::string& name, bool of_set) {
  double factor = 1.0;
  MotionTransform t;
  t.time_scale = ts;
  if (sc.kind == ScaleSpec::Kind::pga) {
    if (!(sc.value > 0.0) || !std::isfinite(sc.value)) {
      throw parameter_error("scale_pga", fmt::format("target PGA must be positive and finite, got {} m/s2",
                                                     sc.value));
    }
    if (peak == 0.0) {
      throw parameter_error("scale_pga", fmt::format("record '{}' is zero everywhere: it cannot be scaled to "
                                                     "a PGA", name));
    }
    factor = sc.value / peak;  // what GroundMotion::scaled_to_pga multiplies by
    if (of_set) {
      t.factor = factor;
    } else {
      t.target_pga_m_s2 = sc.value;
    }
  } else if (sc.kind == ScaleSpec::Kind::factor) {
    if (!std::isfinite(sc.value)) {
      throw parameter_error("scale", fmt::format("scale factors must be finite, got {}", sc.value));
    }
    t.factor = sc.value;
    factor = sc.value;
  }
  return {t, factor};
}

/// The plan's motion cases, in order: records, pulses, record sets (at each bearing); and the record sets' cases by
/// motion index (absent for records and pulses).
class MotionCases {
 public:
  MotionCases(const SweepSpec& spec, const ColumnSet& columns, Plan& plan)
      : spec_(spec), columns_(columns), plan_(plan), g_(spec.g_m_s2) {}

  void add_records() {
    for (const auto& rec : spec_.records) {
      if (!rec.motion) throw parameter_error("motions", fmt::format("record '{}' has no motion", rec.name));
      add_scaled(rec.name, rec.motion, nullptr);
    }
  }

  void add_pulses() {
    for (const auto& p : spec_.pulses) {
      const auto base = std::make_shared<const GroundMotion>(make_pulse(p.spec));
      for (const bool inv : spec_.inverse) {
        MotionCase mc;
        mc.base = base;
        mc.transform.invert = inv;
        RowValues v(columns_);
        v.set("motion", p.name);
        v.set("pulse_kind", std::string(pulse_kind_name(p.spec.kind)));
        v.set("pulse_amp_g", p.spec.amplitude_m_s2 / g_);
        v.set("pulse_duration_s", p.spec.duration_s);
        v.set("time_scale", 1.0);
        v.set("scale_factor", 1.0);
        v.set("pga_g", base->pga_m_s2() / g_);
        v.set("polarity", std::string(polarity_name(inv)));
        mc.values = v.take();
        plan_.motions.push_back(std::move(mc));
      }
    }
  }

  /// Record sets at each bearing (cylinders only: the bearing is not used, one case per set).
  void add_record_sets() {
    const std::vector<double> bearings = spec_.bearings_deg.empty() ? std::vector<double>{0.0} : spec_.bearings_deg;
    for (const auto& rs : spec_.record_sets) {
      // The first component is the case's base motion (aliasing the set, which owns it).
      const std::shared_ptr<const GroundMotion> first(rs.set, &rs.set->first());
      for (const double bearing : bearings) {
        const SetCase c{rs.set, {}, bearing};
        add_scaled(rs.name, first, &c);
      }
      // The fingerprint hashes the base motions; the other components and the azimuths enter through the identity.
      plan_.identity += fmt::format(";set {} az={},{} h2={} v={}", rs.name, rs.set->azimuths()->first_deg,
                                    rs.set->azimuths()->second_deg, motion_fingerprint(rs.set->second()),
                                    rs.set->has_vertical() ? motion_fingerprint(rs.set->vertical()) : "none");
    }
  }

  std::vector<std::optional<SetCase>> take_set_cases() {
    set_cases_.resize(plan_.motions.size());
    return std::move(set_cases_);
  }

 private:
  /// A record's (or a record set's, at one bearing) cases: time scales x scales x polarities of its base motion.
  void add_scaled(const std::string& name, const std::shared_ptr<const GroundMotion>& base, const SetCase* set_case) {
    const double peak = base->pga_m_s2();
    for (const double ts : spec_.time_scales) {
      if (!(ts > 0.0) || !std::isfinite(ts)) {
        throw parameter_error("time_scale", fmt::format("time scale factors must be positive and finite, got {}", ts));
      }
      for (const auto& sc : spec_.scales) {
        const auto [t, factor] = scaled_transform(sc, ts, peak, name, set_case != nullptr);
        // max |a f| = round(peak |f|): rounding is monotone, so this is the scaled record's PGA exactly.
        const double pga = peak * std::abs(factor);
        for (const bool inv : spec_.inverse) {
          MotionCase mc;
          mc.base = base;
          mc.transform = t;
          mc.transform.invert = inv;
          RowValues v(columns_);
          v.set("motion", name);
          v.set("time_scale", ts);
          v.set("scale_factor", factor);
          v.set("pga_g", pga / g_);
          v.set("polarity", std::string(polarity_name(inv)));
          if (set_case != nullptr) {
            if (!spec_.bearings_deg.empty()) v.set("bearing_deg", set_case->bearing_deg);  // cylinders: none
            set_cases_.resize(plan_.motions.size());
            set_cases_.emplace_back(SetCase{set_case->set, mc.transform, set_case->bearing_deg});
          }
          mc.values = v.take();
          plan_.motions.push_back(std::move(mc));
        }
      }
    }
  }

  const SweepSpec& spec_;
  const ColumnSet& columns_;
  Plan& plan_;
  double g_;
  std::vector<std::optional<SetCase>> set_cases_;
};

void set_rock_values(const RockObject& r, RowValues& v) {
  v.set("model", std::string(r.coupled ? "coupled" : r.three_d() ? "3d" : "rock"));
  v.set("g_m_s2", r.options.g_m_s2);
  if (r.coupled || (r.three_d() && r.options.mu)) {
    v.set("mu_kinetic", r.mu_kinetic.value_or(r.options.mu.value_or(0.0)));
  }
  if (r.options.mu) v.set("mu", *r.options.mu);
  v.set("shape", std::string(shape_name(r.body.shape)));
  if (r.width_m) v.set("width_m", *r.width_m);
  if (r.diameter_m) v.set("diameter_m", *r.diameter_m);
  if (r.height_m) v.set("height_m", *r.height_m);
  if (r.body.shape == RockingBody::Shape::general && r.body.symmetric()) {
    v.set("a_m", r.body.a_m);
    v.set("h_m", r.body.h_m);
    v.set("D_m2", r.body.D_m2);
  }
  if (!r.body.symmetric()) {
    v.set("b1_m", r.body.pivot_b_m(-1));
    v.set("b2_m", r.body.pivot_b_m(1));
    v.set("h_m", r.body.h_m);
    if (r.inertia_m2) v.set("inertia_m2", *r.inertia_m2);
  }
  if (!r.mesh.empty()) {
    v.set("mesh", r.mesh);
    if (r.mesh_azimuth_deg) v.set("mesh_azimuth_deg", *r.mesh_azimuth_deg);
    if (!r.mesh_pose.empty()) v.set("mesh_pose", r.mesh_pose);
  }
  v.set("restitution", std::string(restitution_mode_name(r.options.restitution)));
  if (r.depth_m) v.set("depth_m", *r.depth_m);
}

/// Settings of a rocking object that are not columns still decide the results: they enter the fingerprint.
std::string rock_identity(const RockObject& r) {
  const RockingOptions& x = r.options;
  std::string identity = fmt::format(";rock a={} h={} D={} e={} method={} rtol={} atol={} n={} rest={} runout={} "
                                     "theta0={} omega0={} stop={} steps={}",
                                     r.body.a_m, r.body.h_m, r.body.D_m2, x.e, static_cast<int>(x.method), x.rel_tol,
                                     x.abs_tol, x.rk4_substeps, x.rest_energy_fraction, x.max_run_out_s,
                                     x.initial_theta_rad, x.initial_theta_dot_rad_s, x.stop_when_alpha_exceeded,
                                     x.max_steps);
  // The other pivot of an asymmetric body (appended only for one, so that other sweeps keep their identity).
  if (!r.body.symmetric()) {
    identity += fmt::format(" b1={} D1={}", r.body.pivot_b_m(-1), r.body.pivot_D_m2(-1));
  }
  if (r.coupled) identity += " coupled";  // appended only for one: other sweeps keep their identity
  if (r.body_3d) {  // likewise: the three-dimensional body as run (a mesh's base, centre and inertia)
    identity += " 3d base=";
    for (const auto& v : r.body_3d->base_xy_m) identity += fmt::format("{},{};", v[0], v[1]);
    const Vec3& c = r.body_3d->centre_of_mass_m;
    identity += fmt::format(" c={},{},{} J=", c[0], c[1], c[2]);
    for (const Vec3& row : r.body_3d->inertia_cm_m2) identity += fmt::format("{},{},{};", row[0], row[1], row[2]);
  }
  if (r.cylinder_3d) {  // likewise: the cylinder's rim engine (rigid3d_disc.hpp)
    const CylinderBody3D& c = *r.cylinder_3d;
    identity += fmt::format(" 3d cylinder R={} h={} Ja={} Jt={}", c.radius_m, c.centre_height_m, c.inertia_axial_m2,
                            c.inertia_transverse_m2);
  }
  return identity;
}

/// An object's case: its column values; a rocking object's other settings appended to the identity.
ObjectCase object_case(const ObjectSpec& o, const ColumnSet& columns, std::string& identity) {
  RowValues v(columns);
  if (const auto& support = support_of(o)) {
    v.set("support_freq_hz", support->freq_hz);
    v.set("support_damping", support->damping_ratio);
  }
  if (const auto* s = std::get_if<SlideObject>(&o)) {
    v.set("model", std::string("slide"));
    v.set("g_m_s2", s->block.g_m_s2);
    v.set("mu", s->block.mu_static);
    v.set("mu_kinetic", s->block.mu_kinetic);
    v.set("slope_deg", s->slope_deg);
    v.set("mode", std::string(sliding_mode_name(s->block.mode)));
  } else {
    const auto& r = std::get<RockObject>(o);
    set_rock_values(r, v);
    identity += rock_identity(r);
  }
  return ObjectCase{v.take()};
}

}  // namespace

Plan make_plan(const SweepSpec& spec) {
  check_spec(spec);
  const SweepKinds kinds = kinds_of(spec);
  check_objects(spec, kinds.any_set);
  check_sets(spec, kinds.any_set);
  if (kinds.any_support) check_supports(spec);

  const ColumnSet motion_cols = motion_columns(spec, kinds);
  const ColumnSet object_cols = object_columns(kinds);
  const ColumnSet result_cols = result_columns(kinds);

  Plan plan;
  plan.motion_columns = motion_cols.names();
  plan.object_columns = object_cols.names();
  plan.result_columns = result_cols.names();
  plan.chunk_runs = spec.chunk_runs;
  plan.identity = "topple-sweep/1";

  MotionCases cases(spec, motion_cols, plan);
  cases.add_records();
  cases.add_pulses();
  cases.add_record_sets();
  if (kinds.any_set) plan.identity += fmt::format(";cylinder_step={}", spec.orientation.cylinder_step_deg);

  for (const auto& o : spec.objects) plan.objects.push_back(object_case(o, object_cols, plan.identity));

  plan.run = [runner = std::make_shared<const Runner>(spec.objects, result_cols, cases.take_set_cases(),
                                                      spec.orientation)](
                 const GroundMotion& motion, std::size_t m, std::size_t begin, std::size_t end, std::span<Value> out) {
    (*runner)(motion, m, begin, end, out);
  };
  return plan;
}

}  // namespace topple::ensemble
