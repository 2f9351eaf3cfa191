// Sites split across MPI ranks (inversion_distributed.hpp has the design).
#include "topple/region/inversion_distributed.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <exception>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "topple/core/error.hpp"

namespace topple {
namespace {

/// Words out: every value as one or more uint64 (doubles by bit pattern, strings as length + bytes).
class Packer {
 public:
  void operator()(const std::uint64_t& v) { words_.push_back(v); }
  void operator()(const double& v) { words_.push_back(std::bit_cast<std::uint64_t>(v)); }
  void operator()(const bool& v) { words_.push_back(v ? 1 : 0); }
  void operator()(const int& v) { words_.push_back(static_cast<std::uint64_t>(static_cast<std::int64_t>(v))); }
  template <class E>
    requires std::is_enum_v<E>
  void operator()(const E& v) {  // Outcome, ObjectModel
    words_.push_back(static_cast<std::uint64_t>(v));
  }
  void operator()(const std::string& s) {
    words_.push_back(s.size());
    for (std::size_t i = 0; i < s.size(); i += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
      words_.push_back(w);
    }
  }
  template <class T>
  void operator()(const std::optional<T>& v) {
    (*this)(v.has_value());
    if (v) (*this)(*v);
  }
  template <class T>
  void operator()(const std::vector<T>& v) {
    words_.push_back(v.size());
    for (const T& x : v) (*this)(x);
  }
  template <class T>
    requires std::is_class_v<T>
  void operator()(const T& v) {
    fields(*this, const_cast<T&>(v));  // fields() only reads through a Packer
  }
  std::vector<std::uint64_t>& words() { return words_; }

 private:
  std::vector<std::uint64_t> words_;
};

/// Words in, in the Packer's order; a payload that ends early is an internal error (the ranks run one build).
class Unpacker {
 public:
  explicit Unpacker(const std::vector<std::uint64_t>& w) : w_(w) {}
  std::uint64_t next() {
    if (at_ >= w_.size()) throw std::runtime_error("unpack_inversion_results: the payload ends early");
    return w_[at_++];
  }
  void operator()(std::uint64_t& v) { v = next(); }
  void operator()(double& v) { v = std::bit_cast<double>(next()); }
  void operator()(bool& v) { v = next() != 0; }
  void operator()(int& v) { v = static_cast<int>(static_cast<std::int64_t>(next())); }
  template <class E>
    requires std::is_enum_v<E>
  void operator()(E& v) {
    v = static_cast<E>(next());
  }
  void operator()(std::string& s) {
    const std::size_t n = next();
    if (n > 8 * (w_.size() - at_)) throw std::runtime_error("unpack_inversion_results: the payload ends early");
    s.assign(n, '\0');
    for (std::size_t i = 0; i < n; i += 8) {
      const std::uint64_t w = next();
      std::memcpy(s.data() + i, &w, std::min<std::size_t>(8, n - i));
    }
  }
  template <class T>
  void operator()(std::optional<T>& v) {
    bool has = false;
    (*this)(has);
    v.reset();
    if (has) (*this)(v.emplace());
  }
  template <class T>
  void operator()(std::vector<T>& v) {
    const std::size_t n = next();
    if (n > w_.size() - at_) throw std::runtime_error("unpack_inversion_results: the payload ends early");
    v.assign(n, T{});
    for (T& x : v) (*this)(x);
  }
  template <class T>
    requires std::is_class_v<T>
  void operator()(T& v) {
    fields(*this, v);
  }
  [[nodiscard]] bool done() const { return at_ == w_.size(); }

 private:
  const std::vector<std::uint64_t>& w_;
  std::size_t at_ = 0;
};

static_assert(std::is_same_v<std::size_t, std::uint64_t>, "counts travel as one 64-bit word");

// One list of fields per type, walked in the same order by the Packer and the Unpacker: every field of
// InversionResult (inversion.hpp), so a field added there must be added here (PackedResultsUnpackExactly compares the
// JSON of all of them).
template <class IO>
void fields(IO& io, Estimate& e) {
  io(e.best), io(e.median), io(e.ci68_low), io(e.ci68_high), io(e.ci95_low), io(e.ci95_high), io(e.median_edge),
      io(e.best_edge);
}
template <class IO>
void fields(IO& io, StaticBound& b) {
  io(b.pga_g), io(b.object_id), io(b.reason), io(b.hard);
}
template <class IO>
void fields(IO& io, StaticBounds& b) {
  io(b.lower_g), io(b.upper_g), io(b.hard_lower_g), io(b.hard_upper_g), io(b.lower), io(b.upper), io(b.contradictions);
}
template <class IO>
void fields(IO& io, ObjectReport& o) {
  io(o.id), io(o.outcome), io(o.model), io(o.probability), io(o.probability_at_best), io(o.max_probability),
      io(o.reproduced_anywhere), io(o.posterior_predictive), io(o.misfit), io(o.constraint_bits);
}
template <class IO>
void fields(IO& io, DirectionArc& a) {
  io(a.low_deg), io(a.width_deg);
}
template <class IO>
void fields(IO& io, DirectionEstimate& d) {
  io(d.azimuth_deg), io(d.bin_width_deg), io(d.posterior), io(d.mode_deg), io(d.mean_deg), io(d.resultant_length),
      io(d.ci68), io(d.ci95), io(d.constrained);
}
template <class IO>
void fields(IO& io, ThreeComponentResult& t) {
  io(t.direction), io(t.larger_component_ratio), io(t.rotd100_ratio), io(t.larger_component_median_g),
      io(t.larger_component_ci95_low_g), io(t.larger_component_ci95_high_g), io(t.coherence), io(t.vertical_pga_ratio),
      io(t.vertical_frequency_ratio), io(t.slid_direction_kappa), io(t.threshold_vertical_ratio);
}
template <class IO>
void fields(IO& io, PgaGivenFreq& g) {
  io(g.freq_hz), io(g.likelihood_share), io(g.pga_g);
}
template <class IO>
void fields(IO& io, NextObject& n) {
  io(n.object), io(n.description), io(n.look_for), io(n.bits_pga), io(n.bits_freq);
}
template <class IO>
void fields(IO& io, PopulationReport& p) {
  io(p.id), io(p.count), io(p.overturned), io(p.rocked), io(p.slid), io(p.members), io(p.member_rule),
      io(p.observed_fraction), io(p.model_fraction), io(p.model_fraction_at_estimate), io(p.posterior_predictive_fraction);
}
template <class IO>
void fields(IO& io, InversionResult& r) {
  io(r.site), io(r.pga_g), io(r.freq_hz), io(r.measured_freq_hz), io(r.log_likelihood), io(r.posterior),
      io(r.marginal_pga), io(r.marginal_freq);
  io(r.best_cell), io(r.runs), io(r.pga_estimate_g), io(r.freq_estimate_hz), io(r.bounds), io(r.objects), io(r.notes), io(r.seconds);
  io(r.three_component), io(r.rotd100_bounds);  // components = 3 (inversion_3c.hpp)
  io(r.log_prior), io(r.prior), io(r.marginal_pga_likelihood), io(r.marginal_freq_likelihood), io(r.pga_likelihood_g),
      io(r.freq_likelihood_hz), io(r.pga_given_freq), io(r.next_objects);
  io(r.populations);  // populations (docs/method.md, "Populations of objects")  // the prior (inversion/prior.hpp) and the
                                                                           // objects' own evidence (evidence.hpp)
}

// The first word of a rank's broadcast: ok, or how it failed (its exception's kind; the message follows).
enum class Status : std::uint64_t { ok = 0, solver_error = 1, other_error = 2 };

}  // namespace

std::vector<std::uint64_t> pack_inversion_results(const std::vector<InversionResult>& results) {
  Packer p;
  p(results);
  return std::move(p.words());
}

std::vector<InversionResult> unpack_inversion_results(const std::vector<std::uint64_t>& words) {
  Unpacker u(words);
  std::vector<InversionResult> out;
  u(out);
  if (!u.done()) throw std::runtime_error("unpack_inversion_results: words left over");
  return out;
}

std::vector<int> assign_sites_to_ranks(const std::vector<Site>& sites, int ranks) {
  if (ranks < 1) throw std::invalid_argument("assign_sites_to_ranks: ranks must be >= 1");
  std::vector<std::size_t> order(sites.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return sites[a].objects.size() > sites[b].objects.size(); });
  std::vector<std::size_t> load(static_cast<std::size_t>(ranks), 0);
  std::vector<int> rank_of(sites.size(), 0);
  for (const std::size_t s : order) {
    const auto least = std::min_element(load.begin(), load.end());  // the first of equals: the lower rank
    rank_of[s] = static_cast<int>(least - load.begin());
    *least += std::max<std::size_t>(sites[s].objects.size(), 1);
  }
  return rank_of;
}

std::vector<InversionResult> invert_sites_distributed(const std::vector<Site>& sites, const InversionSettings& settings,
                                                      const InversionOptions& options, ensemble::Cluster& cluster) {
  const int ranks = cluster.size();
  if (ranks == 1) return invert_sites(sites, settings, options);
  const std::vector<int> rank_of = assign_sites_to_ranks(sites, ranks);
  std::vector<Site> mine;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    if (rank_of[s] == cluster.rank()) mine.push_back(sites[s]);
  }
  std::vector<std::uint64_t> payload;
  std::exception_ptr failure;
  try {
    payload = pack_inversion_results(invert_sites(mine, settings, options));
    payload.insert(payload.begin(), static_cast<std::uint64_t>(Status::ok));
  } catch (...) {
    failure = std::current_exception();
    Packer p;
    Status status = Status::other_error;
    try {
      throw;
    } catch (const SolverError& e) {
      status = Status::solver_error;
      p(std::string(e.what()));
    } catch (const std::exception& e) {
      p(std::string(e.what()));
    } catch (...) {
      p(std::string("unknown error"));
    }
    payload = std::move(p.words());
    payload.insert(payload.begin(), static_cast<std::uint64_t>(status));
  }
  // Wait in the cluster's sleeping barrier (ensemble_mpi.cpp) rather than in a broadcast: a rank that has finished
  // its sites must not spin (Open MPI polls in a blocking broadcast) on a core that another rank's runs are using.
  cluster.barrier();
  // The gather: each rank in turn broadcasts its payload (rank order, so every rank sees the same sequence).
  std::vector<InversionResult> out(sites.size());
  std::optional<std::pair<int, std::string>> first_failure;
  Status first_status = Status::ok;
  for (int r = 0; r < ranks; ++r) {
    std::vector<std::uint64_t> words = r == cluster.rank() ? payload : std::vector<std::uint64_t>{};
    cluster.broadcast(words, r);
    const auto status = static_cast<Status>(words.at(0));
    words.erase(words.begin());
    if (status != Status::ok) {
      if (!first_failure) {
        Unpacker u(words);
        std::string message;
        u(message);
        first_failure = {r, message};
        first_status = status;
      }
      continue;
    }
    std::vector<InversionResult> part = unpack_inversion_results(words);
    std::size_t k = 0;
    for (std::size_t s = 0; s < sites.size(); ++s) {
      if (rank_of[s] == r) out[s] = std::move(part.at(k++));
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (first_failure) {
    const std::string what = fmt::format("rank {} failed: {}", first_failure->first, first_failure->second);
    if (first_status == Status::solver_error) throw SolverError(what);
    throw std::runtime_error(what);
  }
  return out;
}

}  // namespace topple
