// Sites split across MPI ranks (inversion_distributed.hpp has the design).
#include "topple/inversion_distributed.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <exception>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "topple/error.hpp"

namespace topple {
namespace {

/// Words out: every value as one or more uint64 (doubles by bit pattern, strings as length + bytes).
class Packer {
 public:
  void u(std::uint64_t v) { words_.push_back(v); }
  void d(double v) { words_.push_back(std::bit_cast<std::uint64_t>(v)); }
  void b(bool v) { u(v ? 1 : 0); }
  void opt(const std::optional<double>& v) {
    b(v.has_value());
    if (v) d(*v);
  }
  void str(const std::string& s) {
    u(s.size());
    for (std::size_t i = 0; i < s.size(); i += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
      u(w);
    }
  }
  void vec(const std::vector<double>& v) {
    u(v.size());
    for (double x : v) d(x);
  }
  void strs(const std::vector<std::string>& v) {
    u(v.size());
    for (const std::string& s : v) str(s);
  }
  void estimate(const Estimate& e) {
    d(e.best);
    d(e.median);
    opt(e.ci68_low);
    opt(e.ci68_high);
    opt(e.ci95_low);
    opt(e.ci95_high);
    u(static_cast<std::uint64_t>(static_cast<std::int64_t>(e.median_edge)));
    u(static_cast<std::uint64_t>(static_cast<std::int64_t>(e.best_edge)));
  }
  void bound(const StaticBound& s) {
    d(s.pga_g);
    str(s.object_id);
    str(s.reason);
    b(s.hard);
  }
  std::vector<std::uint64_t>& words() { return words_; }

 private:
  std::vector<std::uint64_t> words_;
};

/// Words in, in the Packer's order; a payload that ends early is an internal error (the ranks run one build).
class Unpacker {
 public:
  explicit Unpacker(const std::vector<std::uint64_t>& w) : w_(w) {}
  std::uint64_t u() {
    if (at_ >= w_.size()) throw std::runtime_error("unpack_inversion_results: the payload ends early");
    return w_[at_++];
  }
  double d() { return std::bit_cast<double>(u()); }
  bool b() { return u() != 0; }
  std::optional<double> opt() { return b() ? std::optional<double>(d()) : std::nullopt; }
  std::string str() {
    const std::size_t n = u();
    std::string s(n, '\0');
    for (std::size_t i = 0; i < n; i += 8) {
      const std::uint64_t w = u();
      std::memcpy(s.data() + i, &w, std::min<std::size_t>(8, n - i));
    }
    return s;
  }
  std::vector<double> vec() {
    std::vector<double> v(u());
    for (double& x : v) x = d();
    return v;
  }
  std::vector<std::string> strs() {
    std::vector<std::string> v(u());
    for (std::string& s : v) s = str();
    return v;
  }
  Estimate estimate() {
    Estimate e;
    e.best = d();
    e.median = d();
    e.ci68_low = opt();
    e.ci68_high = opt();
    e.ci95_low = opt();
    e.ci95_high = opt();
    e.median_edge = static_cast<int>(static_cast<std::int64_t>(u()));
    e.best_edge = static_cast<int>(static_cast<std::int64_t>(u()));
    return e;
  }
  StaticBound bound() {
    StaticBound s;
    s.pga_g = d();
    s.object_id = str();
    s.reason = str();
    s.hard = b();
    return s;
  }
  [[nodiscard]] bool done() const { return at_ == w_.size(); }

 private:
  const std::vector<std::uint64_t>& w_;
  std::size_t at_ = 0;
};

void pack_one(Packer& p, const InversionResult& r) {
  p.str(r.site);
  for (const auto* v : {&r.pga_g, &r.freq_hz, &r.measured_freq_hz, &r.log_likelihood, &r.posterior, &r.marginal_pga,
                        &r.marginal_freq}) {
    p.vec(*v);
  }
  p.u(r.best_cell);
  p.estimate(r.pga_estimate_g);
  p.estimate(r.freq_estimate_hz);
  const StaticBounds& sb = r.bounds;
  for (const auto* o : {&sb.lower_g, &sb.upper_g, &sb.hard_lower_g, &sb.hard_upper_g}) p.opt(*o);
  for (const auto* list : {&sb.lower, &sb.upper}) {
    p.u(list->size());
    for (const StaticBound& s : *list) p.bound(s);
  }
  p.strs(sb.contradictions);
  p.u(r.objects.size());
  for (const ObjectReport& o : r.objects) {
    p.str(o.id);
    p.u(static_cast<std::uint64_t>(o.outcome));
    p.vec(o.probability);
    p.d(o.probability_at_best);
    p.d(o.max_probability);
    p.b(o.reproduced_anywhere);
    p.d(o.posterior_predictive);
    p.b(o.misfit);
    p.d(o.constraint_bits);
  }
  p.strs(r.notes);
  p.u(r.runs);
  p.d(r.seconds);
}

InversionResult unpack_one(Unpacker& u) {
  InversionResult r;
  r.site = u.str();
  for (auto* v : {&r.pga_g, &r.freq_hz, &r.measured_freq_hz, &r.log_likelihood, &r.posterior, &r.marginal_pga,
                  &r.marginal_freq}) {
    *v = u.vec();
  }
  r.best_cell = u.u();
  r.pga_estimate_g = u.estimate();
  r.freq_estimate_hz = u.estimate();
  StaticBounds& sb = r.bounds;
  for (auto* o : {&sb.lower_g, &sb.upper_g, &sb.hard_lower_g, &sb.hard_upper_g}) *o = u.opt();
  for (auto* list : {&sb.lower, &sb.upper}) {
    list->resize(u.u());
    for (StaticBound& s : *list) s = u.bound();
  }
  sb.contradictions = u.strs();
  r.objects.resize(u.u());
  for (ObjectReport& o : r.objects) {
    o.id = u.str();
    o.outcome = static_cast<Outcome>(u.u());
    o.probability = u.vec();
    o.probability_at_best = u.d();
    o.max_probability = u.d();
    o.reproduced_anywhere = u.b();
    o.posterior_predictive = u.d();
    o.misfit = u.b();
    o.constraint_bits = u.d();
  }
  r.notes = u.strs();
  r.runs = u.u();
  r.seconds = u.d();
  return r;
}

// The first word of a rank's broadcast: ok, or how it failed (its exception's kind; the message follows).
enum class Status : std::uint64_t { ok = 0, solver_error = 1, other_error = 2 };

}  // namespace

std::vector<std::uint64_t> pack_inversion_results(const std::vector<InversionResult>& results) {
  Packer p;
  p.u(results.size());
  for (const InversionResult& r : results) pack_one(p, r);
  return std::move(p.words());
}

std::vector<InversionResult> unpack_inversion_results(const std::vector<std::uint64_t>& words) {
  Unpacker u(words);
  std::vector<InversionResult> out(u.u());
  for (InversionResult& r : out) r = unpack_one(u);
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
      p.str(e.what());
    } catch (const std::exception& e) {
      p.str(e.what());
    } catch (...) {
      p.str("unknown error");
    }
    payload = std::move(p.words());
    payload.insert(payload.begin(), static_cast<std::uint64_t>(status));
  }
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
        first_failure = {r, u.str()};
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
