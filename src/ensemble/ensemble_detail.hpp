#pragma once
// Private to the ensemble units (not installed): what the formatting, fingerprint, execution and store units share.
// Each job of the engine has its own unit:
//   ensemble_plan.cpp         plan checks, chunk sizes, motion transforms
//   ensemble_format.cpp       CSV / JSON-lines text of values and rows
//   ensemble_fingerprint.cpp  the plan's fingerprint
//   ensemble_execute.cpp      oneTBB execution of chunks (and run_in_memory)
//   ensemble_store.cpp        the POSIX store: lock, manifest, chunk files, checksums, assembly (run_to_files)
//   ensemble_mpi.cpp          the processes of a sweep (one, or the MPI world)
#include <atomic>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "topple/ensemble/ensemble.hpp"

namespace topple::ensemble::detail {

/// True for a text value holding '\r' or '\n' (which would break a CSV row).
[[nodiscard]] bool has_line_break(const Value& value);

/// A JSON string literal with its quotes.
void append_json_string(std::string& out, std::string_view s);

/// The parts of a row that depend on the motion or the object only, formatted once.
struct Layout {
  std::vector<std::string> motion_csv, object_csv;    // ",v1,v2..." (leading comma; empty without columns)
  std::vector<std::string> motion_json, object_json;  // ",\"k1\":v1,..."
  std::vector<std::string> result_json_keys;          // ",\"k\":"
  std::size_t result_count = 0;

  explicit Layout(const Plan& plan);
};

/// CSV and JSON-lines text of the runs [begin, end), whose results are `results` (row-major); either output may be
/// null. Throws std::logic_error when a run produced a text value with a line break.
void format_rows(const Plan& plan, const Layout& layout, std::size_t begin, std::size_t end,
                 const std::vector<Value>& results, std::string* csv, std::string* jsonl);

/// Computes chunks of a plan on worker threads.
class Engine {
 public:
  Engine(const Plan& plan, const ExecuteOptions& options) : plan_(plan), options_(options) {}

  /// Runs [begin, end) of a chunk.
  [[nodiscard]] std::pair<std::size_t, std::size_t> chunk_range(std::size_t chunk) const;

  /// Receives a computed chunk: its index, its runs [begin, end) and their results (row-major, may be moved from).
  /// Called concurrently from worker threads.
  using Commit =
      std::function<void(std::size_t chunk, std::size_t begin, std::size_t end, std::vector<Value>& results)>;

  /// Computes `chunks` on ExecuteOptions::threads workers (chunks in parallel, and the objects of one motion split
  /// over the threads) and hands each to `commit`. Returns the number of worker threads. Exceptions propagate.
  int run_chunks(std::span<const std::size_t> chunks, const Commit& commit);

  /// Runs finished so far.
  [[nodiscard]] std::size_t runs_done() const noexcept { return done_.load(); }

 private:
  std::vector<Value> compute(std::size_t begin, std::size_t end);

  const Plan& plan_;
  const ExecuteOptions& options_;
  std::atomic<std::size_t> done_{0};
  std::size_t total_ = 0;
};

}  // namespace topple::ensemble::detail
