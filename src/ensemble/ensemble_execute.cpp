// Execution of a plan on this process's cores with oneTBB: chunks in parallel, and the objects of one motion split
// over the threads so that a single large chunk still uses every core (ensemble.hpp, "Chunks").
#include <algorithm>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "ensemble/ensemble_detail.hpp"
#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"

namespace topple::ensemble {
namespace {

/// The worker threads of one execution: every core this process may use, or exactly `threads` (also more than
/// the cores: the global limit is raised for the duration, so that oneTBB does not cap the arena at the core count).
class Workers {
 public:
  explicit Workers(int threads) {
    if (threads < 0) throw parameter_error("--threads", fmt::format("must be >= 0 (0: all cores), got {}", threads));
    if (threads > 0) {
      limit_.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      arena_.emplace(threads);
    } else {
      arena_.emplace();
    }
  }
  template <class F>
  void run(F&& f) {
    arena_->execute(std::forward<F>(f));
  }
  [[nodiscard]] int count() { return arena_->max_concurrency(); }

 private:
  std::optional<tbb::global_control> limit_;
  std::optional<tbb::task_arena> arena_;
};

}  // namespace

namespace detail {

std::pair<std::size_t, std::size_t> Engine::chunk_range(std::size_t chunk) const {
  const std::size_t c = plan_.chunk_size();
  return {chunk * c, std::min(plan_.runs(), (chunk + 1) * c)};
}

/// Results of runs [begin, end) (one chunk), row-major. Runs of one motion are split over the threads.
std::vector<Value> Engine::compute(std::size_t begin, std::size_t end) {
  const std::size_t n_obj = plan_.objects.size();
  const std::size_t nres = plan_.result_columns.size();
  std::vector<Value> results((end - begin) * nres);
  const std::size_t m_first = begin / n_obj;
  const std::size_t m_last = (end - 1) / n_obj;
  for (std::size_t m = m_first; m <= m_last; ++m) {
    const std::size_t o_begin = m == m_first ? begin % n_obj : 0;
    const std::size_t o_end = m == m_last ? (end - 1) % n_obj + 1 : n_obj;
    const MotionCase& mc = plan_.motions[m];
    std::optional<GroundMotion> prepared;
    if (!mc.transform.is_identity()) prepared = mc.transform.apply(*mc.base);
    const GroundMotion& motion = prepared ? *prepared : *mc.base;
    const std::size_t row0 = m * n_obj + o_begin - begin;
    // At most about 8 pieces per thread: enough to balance, few enough that a run function with a per-call cost
    // (slide_summaries scans the record once per call) pays it rarely.
    const auto pieces = 8 * static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
    const std::size_t grain = std::max<std::size_t>(1, (o_end - o_begin + pieces - 1) / pieces);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(o_begin, o_end, grain), [&](const auto& r) {
      const std::size_t first_row = row0 + (r.begin() - o_begin);
      plan_.run(motion, m, r.begin(), r.end(), std::span<Value>(results.data() + first_row * nres, r.size() * nres));
      const std::size_t now = done_.fetch_add(r.size(), std::memory_order_relaxed) + r.size();
      if (options_.progress) options_.progress(now, total_);
    });
  }
  return results;
}

int Engine::run_chunks(std::span<const std::size_t> chunks, const Commit& commit) {
  for (const std::size_t c : chunks) {
    const auto [begin, end] = chunk_range(c);
    total_ += end - begin;
  }
  Workers workers(options_.threads);
  workers.run([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size(), 1), [&](const auto& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) {
        const std::size_t c = chunks[i];
        const auto [begin, end] = chunk_range(c);
        std::vector<Value> results = compute(begin, end);
        commit(c, begin, end, results);
      }
    });
  });
  return workers.count();
}

}  // namespace detail

ResultTable run_in_memory(const Plan& plan, const ExecuteOptions& options) {
  check_plan(plan);
  ResultTable table;
  table.columns = plan.columns();
  const std::size_t runs = plan.runs();
  table.rows.resize(runs);
  if (runs == 0) return table;
  const std::size_t n_obj = plan.objects.size();
  const std::size_t nres = plan.result_columns.size();
  std::vector<std::size_t> chunks(plan.chunks());
  for (std::size_t c = 0; c < chunks.size(); ++c) chunks[c] = c;
  detail::Engine engine(plan, options);
  engine.run_chunks(chunks, [&](std::size_t /*chunk*/, std::size_t begin, std::size_t end,
                                std::vector<Value>& results) {
    for (std::size_t run = begin; run < end; ++run) {
      auto& row = table.rows[run];
      const auto& mv = plan.motions[run / n_obj].values;
      const auto& ov = plan.objects[run % n_obj].values;
      row.reserve(1 + mv.size() + ov.size() + nres);
      row.emplace_back(static_cast<std::int64_t>(run));
      row.insert(row.end(), mv.begin(), mv.end());
      row.insert(row.end(), ov.begin(), ov.end());
      for (std::size_t k = 0; k < nres; ++k) row.push_back(std::move(results[(run - begin) * nres + k]));
    }
  });
  return table;
}

}  // namespace topple::ensemble
