// The ensemble engine: plan expansion, chunked parallel execution, formatting and the resumable store. See
// ensemble.hpp for the model (runs, chunks, determinism, the store's layout and rules).
#include "topple/ensemble.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <utility>

#include <fmt/compile.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "topple/error.hpp"

namespace topple::ensemble {
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------------------------
// Plan
// ---------------------------------------------------------------------------------------------------------------

GroundMotion MotionTransform::apply(const GroundMotion& base) const {
  GroundMotion m = time_scale == 1.0 ? base : base.time_scaled(time_scale);
  if (target_pga_m_s2) m = m.scaled_to_pga(*target_pga_m_s2);
  if (factor) m = m.scaled(*factor);
  if (invert) m = m.inverted();
  return m;
}

std::size_t default_chunk_runs(std::size_t runs) noexcept {
  const std::size_t target = (runs + 4095) / 4096;
  return std::clamp<std::size_t>(target, 1024, 100'000);
}

std::size_t Plan::chunk_size() const noexcept { return chunk_runs > 0 ? chunk_runs : default_chunk_runs(runs()); }

std::size_t Plan::chunks() const noexcept {
  const std::size_t c = chunk_size();
  return (runs() + c - 1) / c;
}

std::vector<std::string> Plan::columns() const {
  std::vector<std::string> all{"run"};
  all.insert(all.end(), motion_columns.begin(), motion_columns.end());
  all.insert(all.end(), object_columns.begin(), object_columns.end());
  all.insert(all.end(), result_columns.begin(), result_columns.end());
  return all;
}

namespace {

bool has_line_break(const Value& v) {
  const auto* s = std::get_if<std::string>(&v);
  return s != nullptr && s->find_first_of("\r\n") != std::string::npos;
}

}  // namespace

void check_plan(const Plan& plan) {
  if (!plan.run) throw std::invalid_argument("ensemble plan: no run function");
  std::set<std::string> seen;
  for (const auto& c : plan.columns()) {
    if (c.empty()) throw std::invalid_argument("ensemble plan: empty column name");
    if (!seen.insert(c).second) throw std::invalid_argument("ensemble plan: duplicated column '" + c + "'");
  }
  for (std::size_t m = 0; m < plan.motions.size(); ++m) {
    const auto& mc = plan.motions[m];
    if (!mc.base) throw std::invalid_argument(fmt::format("ensemble plan: motion {} has no base motion", m));
    if (mc.values.size() != plan.motion_columns.size()) {
      throw std::invalid_argument(fmt::format("ensemble plan: motion {} has {} values for {} columns", m,
                                              mc.values.size(), plan.motion_columns.size()));
    }
    if (std::any_of(mc.values.begin(), mc.values.end(), has_line_break)) {
      throw std::invalid_argument(fmt::format("ensemble plan: motion {} has a line break in a value", m));
    }
  }
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    const auto& oc = plan.objects[o];
    if (oc.values.size() != plan.object_columns.size()) {
      throw std::invalid_argument(fmt::format("ensemble plan: object {} has {} values for {} columns", o,
                                              oc.values.size(), plan.object_columns.size()));
    }
    if (std::any_of(oc.values.begin(), oc.values.end(), has_line_break)) {
      throw std::invalid_argument(fmt::format("ensemble plan: object {} has a line break in a value", o));
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Formatting
// ---------------------------------------------------------------------------------------------------------------

namespace {

/// Shortest round-trip text of a number (fmt "{}", Dragonbox for doubles), appended without a format-string parse.
template <class T>
void append_number(std::string& out, T v) {
  char buf[40];
  char* end = fmt::format_to(buf, FMT_COMPILE("{}"), v);
  out.append(buf, end);
}

bool csv_needs_quotes(std::string_view s) {
  if (s.empty()) return false;
  if (s.front() == ' ' || s.back() == ' ') return true;
  return s.find_first_of(",\"\r\n") != std::string_view::npos;
}

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          fmt::format_to(std::back_inserter(out), "\\u{:04x}", static_cast<unsigned>(c));
        } else {
          out += ch;
        }
    }
  }
  out += '"';
}

}  // namespace

void append_csv_value(std::string& out, const Value& value) {
  std::visit(
      [&out](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          // empty cell
        } else if constexpr (std::is_same_v<T, bool>) {
          out += v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          append_number(out, v);
        } else if constexpr (std::is_same_v<T, double>) {
          if (std::isfinite(v)) append_number(out, v);
        } else {
          if (!csv_needs_quotes(v)) {
            out += v;
          } else {
            out += '"';
            for (const char c : v) {
              if (c == '"') out += '"';
              out += c;
            }
            out += '"';
          }
        }
      },
      value);
}

void append_json_value(std::string& out, const Value& value) {
  std::visit(
      [&out](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          out += "null";
        } else if constexpr (std::is_same_v<T, bool>) {
          out += v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          append_number(out, v);
        } else if constexpr (std::is_same_v<T, double>) {
          if (std::isfinite(v)) {
            append_number(out, v);
          } else {
            out += "null";
          }
        } else {
          append_json_string(out, v);
        }
      },
      value);
}

std::string csv_header(const Plan& plan) {
  std::string out;
  bool first = true;
  for (const auto& c : plan.columns()) {
    if (!first) out += ',';
    first = false;
    append_csv_value(out, Value{c});
  }
  out += '\n';
  return out;
}

namespace {

/// The parts of a row that depend on the motion or the object only, formatted once.
struct Layout {
  std::vector<std::string> motion_csv, object_csv;    // ",v1,v2..." (leading comma; empty without columns)
  std::vector<std::string> motion_json, object_json;  // ",\"k1\":v1,..."
  std::vector<std::string> result_json_keys;          // ",\"k\":"
  std::size_t result_count = 0;

  explicit Layout(const Plan& plan) : result_count(plan.result_columns.size()) {
    const auto csv_part = [](const std::vector<Value>& values) {
      std::string s;
      for (const auto& v : values) {
        s += ',';
        append_csv_value(s, v);
      }
      return s;
    };
    const auto json_part = [](const std::vector<std::string>& names, const std::vector<Value>& values) {
      std::string s;
      for (std::size_t i = 0; i < values.size(); ++i) {
        s += ',';
        append_json_string(s, names[i]);
        s += ':';
        append_json_value(s, values[i]);
      }
      return s;
    };
    for (const auto& m : plan.motions) {
      motion_csv.push_back(csv_part(m.values));
      motion_json.push_back(json_part(plan.motion_columns, m.values));
    }
    for (const auto& o : plan.objects) {
      object_csv.push_back(csv_part(o.values));
      object_json.push_back(json_part(plan.object_columns, o.values));
    }
    for (const auto& name : plan.result_columns) {
      std::string k = ",";
      append_json_string(k, name);
      k += ':';
      result_json_keys.push_back(std::move(k));
    }
  }
};

void check_result_text(const Value& v, std::size_t run) {
  if (has_line_break(v)) {
    throw std::logic_error(fmt::format("ensemble: run {} produced a text value with a line break", run));
  }
}

/// CSV and JSON-lines text of the runs [begin, end), whose results are `results` (row-major).
void format_rows(const Plan& plan, const Layout& layout, std::size_t begin, std::size_t end,
                 const std::vector<Value>& results, std::string* csv, std::string* jsonl) {
  const std::size_t n_obj = plan.objects.size();
  const std::size_t nres = layout.result_count;
  for (std::size_t run = begin; run < end; ++run) {
    const std::size_t m = run / n_obj;
    const std::size_t o = run % n_obj;
    const Value* r = results.data() + (run - begin) * nres;
    for (std::size_t k = 0; k < nres; ++k) check_result_text(r[k], run);
    if (csv != nullptr) {
      append_number(*csv, run);
      *csv += layout.motion_csv[m];
      *csv += layout.object_csv[o];
      for (std::size_t k = 0; k < nres; ++k) {
        *csv += ',';
        append_csv_value(*csv, r[k]);
      }
      *csv += '\n';
      if (run == begin) csv->reserve(csv->size() * (end - begin) * 9 / 8 + 64);  // rows are about as long as the first
    }
    if (jsonl != nullptr) {
      *jsonl += "{\"run\":";
      append_number(*jsonl, run);
      *jsonl += layout.motion_json[m];
      *jsonl += layout.object_json[o];
      for (std::size_t k = 0; k < nres; ++k) {
        *jsonl += layout.result_json_keys[k];
        append_json_value(*jsonl, r[k]);
      }
      *jsonl += "}\n";
      if (run == begin) jsonl->reserve(jsonl->size() * (end - begin) * 9 / 8 + 64);
    }
  }
}

}  // namespace

std::string to_csv(const ResultTable& table) {
  std::string out;
  bool first = true;
  for (const auto& c : table.columns) {
    if (!first) out += ',';
    first = false;
    append_csv_value(out, Value{c});
  }
  out += '\n';
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out += ',';
      append_csv_value(out, row[i]);
    }
    out += '\n';
  }
  return out;
}

std::string to_jsonl(const ResultTable& table) {
  std::string out;
  for (const auto& row : table.rows) {
    out += '{';
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out += ',';
      append_json_string(out, table.columns[i]);
      out += ':';
      append_json_value(out, row[i]);
    }
    out += "}\n";
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Fingerprint
// ---------------------------------------------------------------------------------------------------------------

namespace {

/// Two FNV-1a-style 64-bit hashes with different offset bases, fed the same data 8 bytes at a time (the samples of
/// long records are hashed on every run: a byte at a time would cost milliseconds).
struct Fingerprint {
  std::uint64_t a = 14695981039346656037ULL;
  std::uint64_t b = 0x9e3779b97f4a7c15ULL;
  static constexpr std::uint64_t kPrime = 1099511628211ULL;

  void word(std::uint64_t w) {
    a = (a ^ w) * kPrime;
    b = (b ^ (w >> 32 | w << 32)) * kPrime;
  }
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, p + i, 8);
      word(w);
    }
    for (; i < n; ++i) word(p[i]);
  }
  void text(std::string_view s) {
    const std::uint64_t n = s.size();
    bytes(&n, sizeof n);
    bytes(s.data(), s.size());
  }
  void number(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    bytes(&bits, sizeof bits);
  }
  void count(std::uint64_t n) { bytes(&n, sizeof n); }
  [[nodiscard]] std::string hex() const { return fmt::format("{:016x}{:016x}", a, b); }
};

void hash_motion(Fingerprint& f, const GroundMotion& g) {
  f.count(g.size());
  f.count(g.is_uniform() ? 1 : 0);
  f.number(g.dt_s());
  f.number(g.start_time_s());
  const auto a = g.accel_m_s2();
  f.bytes(a.data(), a.size_bytes());
  if (!g.is_uniform()) {
    for (std::size_t i = 0; i < g.size(); ++i) f.number(g.time_s(i));
  }
}

}  // namespace

std::string plan_fingerprint(const Plan& plan) {
  Fingerprint f;
  f.text("topple-ensemble/1");
  for (const auto& c : plan.columns()) f.text(c);
  f.count(plan.chunk_size());
  f.count(plan.motions.size());
  f.count(plan.objects.size());
  f.text(plan.identity);
  std::unordered_map<const GroundMotion*, std::string> base_hashes;
  const Layout layout(plan);
  for (std::size_t m = 0; m < plan.motions.size(); ++m) {
    const auto& mc = plan.motions[m];
    auto it = base_hashes.find(mc.base.get());
    if (it == base_hashes.end()) {
      Fingerprint fb;
      hash_motion(fb, *mc.base);
      it = base_hashes.emplace(mc.base.get(), fb.hex()).first;
    }
    f.text(it->second);
    f.number(mc.transform.time_scale);
    f.number(mc.transform.target_pga_m_s2.value_or(-1.0));
    f.number(mc.transform.factor.value_or(0.0));
    f.count(mc.transform.factor ? 1 : 0);
    f.count(mc.transform.invert ? 1 : 0);
    f.text(layout.motion_csv[m]);
  }
  for (const auto& s : layout.object_csv) f.text(s);
  return f.hex();
}

// ---------------------------------------------------------------------------------------------------------------
// Execution
// ---------------------------------------------------------------------------------------------------------------

namespace {

/// Shared by the tasks of one execution: the plan, its preformatted parts and the progress count.
struct Engine {
  const Plan& plan;
  Layout layout;
  const ExecuteOptions& options;
  std::atomic<std::size_t> done{0};
  std::size_t total = 0;

  Engine(const Plan& p, const ExecuteOptions& o) : plan(p), layout(p), options(o) {}

  /// Results of runs [begin, end) (one chunk), row-major. Runs of one motion are split over the threads.
  std::vector<Value> compute(std::size_t begin, std::size_t end) {
    const std::size_t n_obj = plan.objects.size();
    const std::size_t nres = layout.result_count;
    std::vector<Value> results((end - begin) * nres);
    const std::size_t m_first = begin / n_obj;
    const std::size_t m_last = (end - 1) / n_obj;
    for (std::size_t m = m_first; m <= m_last; ++m) {
      const std::size_t o_begin = m == m_first ? begin % n_obj : 0;
      const std::size_t o_end = m == m_last ? (end - 1) % n_obj + 1 : n_obj;
      const MotionCase& mc = plan.motions[m];
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
        plan.run(motion, m, r.begin(), r.end(),
                 std::span<Value>(results.data() + first_row * nres, r.size() * nres));
        const std::size_t now = done.fetch_add(r.size(), std::memory_order_relaxed) + r.size();
        if (options.progress) options.progress(now, total);
      });
    }
    return results;
  }

  [[nodiscard]] std::pair<std::size_t, std::size_t> chunk_range(std::size_t chunk) const {
    const std::size_t c = plan.chunk_size();
    return {chunk * c, std::min(plan.runs(), (chunk + 1) * c)};
  }
};

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

ResultTable run_in_memory(const Plan& plan, const ExecuteOptions& options) {
  check_plan(plan);
  ResultTable table;
  table.columns = plan.columns();
  const std::size_t runs = plan.runs();
  table.rows.resize(runs);
  if (runs == 0) return table;
  Engine engine(plan, options);
  engine.total = runs;
  const std::size_t chunks = plan.chunks();
  const std::size_t n_obj = plan.objects.size();
  const std::size_t nres = plan.result_columns.size();
  Workers workers(options.threads);
  workers.run([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const auto& r) {
      for (std::size_t chunk = r.begin(); chunk < r.end(); ++chunk) {
        const auto [begin, end] = engine.chunk_range(chunk);
        std::vector<Value> results = engine.compute(begin, end);
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
      }
    });
  });
  return table;
}

// ---------------------------------------------------------------------------------------------------------------
// The store
// ---------------------------------------------------------------------------------------------------------------

[[noreturn]] void SingleProcess::abort(int exit_code) { std::exit(exit_code); }

fs::path parts_directory(const fs::path& csv_path) {
  fs::path p = csv_path;
  p += ".parts";
  return p;
}

namespace {

constexpr std::string_view kStoreFormat = "topple-sweep-parts/1";

std::string chunk_name(std::size_t chunk, std::string_view ext) { return fmt::format("{:08}.{}", chunk, ext); }

std::string errno_text() { return std::strerror(errno); }

/// Writes `text` to `path` through a temporary file in the same directory and a rename.
void write_atomically(const fs::path& path, const std::string& text, const std::string& tmp_tag,
                      const InputLocation& where) {
  const fs::path tmp = path.parent_path() / fmt::format(".tmp-{}-{}", tmp_tag, path.filename().string());
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw InputError(where, fmt::format("cannot write '{}': {}", tmp.string(), errno_text()));
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const int close_status = std::fclose(f);
  if (!ok || close_status != 0) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(where, fmt::format("cannot write '{}': {}", tmp.string(), errno_text()));
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw InputError(where, fmt::format("cannot rename '{}' to '{}': {}", tmp.string(), path.string(), ec.message()));
}

std::size_t count_lines(const fs::path& path, std::vector<char>& buf, bool* ends_with_newline) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  *ends_with_newline = false;
  if (f == nullptr) return 0;
  std::size_t lines = 0;
  std::size_t n = 0;
  char last = '\n';
  bool any = false;
  while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) {
    lines += static_cast<std::size_t>(std::count(buf.data(), buf.data() + n, '\n'));
    last = buf[n - 1];
    any = true;
  }
  std::fclose(f);
  *ends_with_newline = !any || last == '\n';
  return lines;
}

/// flock on PARTS/lock for the lifetime of the object (released by the kernel if the process dies).
class StoreLock {
 public:
  StoreLock(const fs::path& dir, const InputLocation& where) {
    const fs::path p = dir / "lock";
    fd_ = ::open(p.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError(where, fmt::format("cannot open the lock file '{}': {}", p.string(), errno_text()));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw InputError(where, fmt::format("another topple sweep is writing to this output (its store '{}' is "
                                          "locked); wait for it or choose another output", dir.string()));
    }
  }
  StoreLock(const StoreLock&) = delete;
  StoreLock& operator=(const StoreLock&) = delete;
  ~StoreLock() {
    if (fd_ >= 0) ::close(fd_);
  }

 private:
  int fd_ = -1;
};

struct Manifest {
  std::string fingerprint;
  std::size_t runs = 0;
  std::size_t chunk_runs = 0;
  std::size_t chunks = 0;
  bool complete = false;
};

std::string manifest_text(const Plan& plan, const std::string& fingerprint, bool complete) {
  nlohmann::ordered_json j;
  j["format"] = kStoreFormat;
  j["fingerprint"] = fingerprint;
  j["runs"] = plan.runs();
  j["chunk_runs"] = plan.chunk_size();
  j["chunks"] = plan.chunks();
  j["complete"] = complete;
  j["columns"] = plan.columns();
  return j.dump(2) + "\n";
}

std::optional<Manifest> read_manifest(const fs::path& path, const InputLocation& where) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream s;
  s << in.rdbuf();
  try {
    const auto j = nlohmann::json::parse(s.str());
    if (j.at("format").get<std::string>() != kStoreFormat) throw std::runtime_error("format");
    Manifest m;
    m.fingerprint = j.at("fingerprint").get<std::string>();
    m.runs = j.at("runs").get<std::size_t>();
    m.chunk_runs = j.at("chunk_runs").get<std::size_t>();
    m.chunks = j.at("chunks").get<std::size_t>();
    m.complete = j.at("complete").get<bool>();
    return m;
  } catch (const std::exception&) {
    throw InputError(where, fmt::format("'{}' is not the manifest of a topple sweep store; remove the directory or "
                                        "rerun with --restart", path.string()));
  }
}

/// The chunk files, temporary files and manifest of a store (never anything else).
bool is_store_file(const std::string& name) {
  if (name == "manifest.json" || name == "lock") return true;
  if (name.rfind(".tmp-", 0) == 0) return true;
  const auto dot = name.find('.');
  if (dot != 8) return false;
  if (!std::all_of(name.begin(), name.begin() + 8, [](char c) { return c >= '0' && c <= '9'; })) return false;
  const std::string ext = name.substr(dot + 1);
  return ext == "csv" || ext == "jsonl";
}

void clear_store(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name != "lock" && is_store_file(name)) fs::remove(entry.path());
  }
}

void append_file(std::FILE* out, const fs::path& path, std::vector<char>& buf, const InputLocation& where) {
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (in == nullptr) throw InputError(where, fmt::format("cannot read '{}': {}", path.string(), errno_text()));
  std::size_t n = 0;
  bool ok = true;
  while ((n = std::fread(buf.data(), 1, buf.size(), in)) > 0) ok = ok && std::fwrite(buf.data(), 1, n, out) == n;
  std::fclose(in);
  if (!ok) throw InputError(where, fmt::format("write error while assembling the output: {}", errno_text()));
}

/// Header + every chunk's file, in order, to `target` (through a temporary file and a rename).
void assemble(const fs::path& dir, std::size_t chunks, std::string_view ext, const std::string& header,
              const fs::path& target, const InputLocation& where) {
  const fs::path tmp = target.parent_path() / (".tmp-" + target.filename().string());
  std::FILE* out = std::fopen(tmp.c_str(), "wb");
  if (out == nullptr) throw InputError(where, fmt::format("cannot write '{}': {}", tmp.string(), errno_text()));
  bool ok = std::fwrite(header.data(), 1, header.size(), out) == header.size();
  std::vector<char> buf(std::size_t{1} << 20);
  try {
    for (std::size_t c = 0; c < chunks; ++c) append_file(out, dir / chunk_name(c, ext), buf, where);
  } catch (...) {
    std::fclose(out);
    throw;
  }
  ok = std::fclose(out) == 0 && ok;
  if (!ok) throw InputError(where, fmt::format("cannot write '{}': {}", tmp.string(), errno_text()));
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) throw InputError(where, fmt::format("cannot rename '{}' to '{}': {}", tmp.string(), target.string(), ec.message()));
}

enum class StoreStatus : std::uint64_t { ready = 0, complete = 1, failed = 2 };

}  // namespace

SweepReport run_to_files(const Plan& plan, const StoreOptions& store, const ExecuteOptions& execute,
                         Cluster& cluster) {
  check_plan(plan);
  const InputLocation where{store.csv_path.string(), std::nullopt, store.field};
  const std::string fingerprint = plan_fingerprint(plan);
  SweepReport report;
  report.runs = plan.runs();
  report.chunks = plan.chunks();
  report.chunk_runs = plan.chunk_size();
  report.ranks = cluster.size();

  // Every rank must have expanded the same plan (they read the same sweep file and records).
  const std::uint64_t fp64 = std::stoull(fingerprint.substr(0, 16), nullptr, 16);
  const auto all_fp = cluster.all_gather(fp64);
  if (std::any_of(all_fp.begin(), all_fp.end(), [&](std::uint64_t x) { return x != fp64; })) {
    throw InputError(where, "the ranks of this MPI job expanded different sweeps: do they all see the same sweep "
                            "file and records?");
  }

  const fs::path dir = parts_directory(store.csv_path);
  const bool jsonl = store.jsonl_path.has_value();
  std::optional<StoreLock> lock;
  std::vector<std::uint64_t> message;  // [status, already done, pending chunk indices...]
  std::optional<InputError> failure;
  if (cluster.rank() == 0) {
    try {
      if (store.csv_path.has_parent_path()) fs::create_directories(store.csv_path.parent_path());
      fs::create_directories(dir);
      lock.emplace(dir, where);
      bool restart = store.restart;
      const fs::path manifest_path = dir / "manifest.json";
      if (!restart) {
        if (const auto m = read_manifest(manifest_path, where)) {
          if (m->fingerprint != fingerprint) {
            throw InputError(where, fmt::format(
                "the store '{}' holds results of a different sweep ({} runs in chunks of {}; the sweep file, a "
                "record or the chunk size has changed since). Rerun with --restart to discard them and start over, "
                "or write to another output", dir.string(), m->runs, m->chunk_runs));
          }
          if (m->complete) {
            const bool outputs_exist = fs::exists(store.csv_path) && (!jsonl || fs::exists(*store.jsonl_path));
            if (outputs_exist) {
              clear_store(dir);  // chunk files a killed assembly may have left
              write_atomically(manifest_path, manifest_text(plan, fingerprint, true), "manifest", where);
              message = {static_cast<std::uint64_t>(StoreStatus::complete), report.chunks};
            } else {
              restart = true;  // finished before, but its outputs are gone: compute them again
            }
          }
        }
      }
      if (message.empty()) {
        report.restarted = restart && fs::exists(manifest_path);
        if (restart) clear_store(dir);
        write_atomically(manifest_path, manifest_text(plan, fingerprint, false), "manifest", where);
        // Scan: temporary files are leftovers of a killed run; a chunk counts when every requested file of it
        // exists and holds one line per run.
        std::set<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir)) {
          const std::string name = entry.path().filename().string();
          if (name.rfind(".tmp-", 0) == 0) {
            fs::remove(entry.path());
          } else {
            names.insert(name);
          }
        }
        std::vector<std::uint64_t> pending;
        std::size_t already = 0;
        std::vector<char> buf(std::size_t{1} << 20);
        for (std::size_t c = 0; c < report.chunks; ++c) {
          const std::size_t begin = c * report.chunk_runs;
          const std::size_t end = std::min(report.runs, begin + report.chunk_runs);
          bool whole = true;
          for (const std::string_view ext : {std::string_view("csv"), std::string_view("jsonl")}) {
            if (ext == "jsonl" && !jsonl) continue;
            const std::string name = chunk_name(c, ext);
            if (names.count(name) == 0) {
              whole = false;
              continue;
            }
            bool newline_end = false;
            if (count_lines(dir / name, buf, &newline_end) != end - begin || !newline_end) {
              fs::remove(dir / name);  // cut short (a crash of the machine): compute it again
              whole = false;
            }
          }
          if (whole) {
            ++already;
          } else {
            pending.push_back(c);
          }
        }
        message = {static_cast<std::uint64_t>(StoreStatus::ready), already};
        message.insert(message.end(), pending.begin(), pending.end());
      }
    } catch (const InputError& e) {
      failure = e;
      message = {static_cast<std::uint64_t>(StoreStatus::failed), 0};
    } catch (const fs::filesystem_error& e) {
      failure = InputError(where, e.what());
      message = {static_cast<std::uint64_t>(StoreStatus::failed), 0};
    }
  }
  cluster.barrier();
  cluster.broadcast(message, 0);
  const auto status = static_cast<StoreStatus>(message.at(0));
  if (status == StoreStatus::failed) {
    if (failure) throw *failure;
    throw InputError(where, "rank 0 could not prepare the output (see its message)");
  }
  report.chunks_already_done = message.at(1);
  if (status == StoreStatus::complete) {
    report.was_complete = true;
    return report;
  }

  // This rank's share: static round-robin over the pending chunks.
  std::vector<std::size_t> mine;
  for (std::size_t i = 2 + static_cast<std::size_t>(cluster.rank()); i < message.size();
       i += static_cast<std::size_t>(cluster.size())) {
    mine.push_back(message[i]);
  }
  Engine engine(plan, execute);
  for (const std::size_t c : mine) {
    const auto [begin, end] = engine.chunk_range(c);
    engine.total += end - begin;
  }
  const std::string tag = fmt::format("{}-{}", cluster.rank(), ::getpid());
  const auto start = std::chrono::steady_clock::now();
  std::size_t my_runs = 0;
  try {
    Workers workers(execute.threads);
    report.threads = workers.count();
    workers.run([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mine.size(), 1), [&](const auto& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const std::size_t c = mine[i];
          const auto [begin, end] = engine.chunk_range(c);
          const std::vector<Value> results = engine.compute(begin, end);
          std::string csv;
          std::string lines;
          format_rows(plan, engine.layout, begin, end, results, &csv, jsonl ? &lines : nullptr);
          // The CSV file is renamed last: a chunk is done when it exists (and, if asked, its JSON lines).
          if (jsonl) write_atomically(dir / chunk_name(c, "jsonl"), lines, tag, where);
          write_atomically(dir / chunk_name(c, "csv"), csv, tag, where);
        }
      });
    });
    my_runs = engine.done.load();
  } catch (const std::exception& e) {
    if (cluster.size() == 1) throw;
    // The other ranks cannot learn about it and would wait forever: end the job. Finished chunks are kept.
    std::fprintf(stderr, "topple: rank %d: error: %s\n", cluster.rank(), e.what());
    std::fflush(stderr);
    cluster.abort(1);
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  cluster.barrier();
  const auto chunk_counts = cluster.all_gather(mine.size());
  const auto run_counts = cluster.all_gather(my_runs);
  for (const auto n : chunk_counts) report.chunks_computed += n;
  for (const auto n : run_counts) report.runs_computed += n;

  if (cluster.rank() == 0) {
    // Every chunk must now be in the store (the other ranks' too: the directory must be on a shared filesystem).
    for (std::size_t c = 0; c < report.chunks; ++c) {
      if (!fs::exists(dir / chunk_name(c, "csv"))) {
        throw InputError(where, fmt::format("chunk {} is missing from '{}' after every rank finished: with several "
                                            "machines the output must be on a filesystem they all share",
                                            c, dir.string()));
      }
    }
    assemble(dir, report.chunks, "csv", csv_header(plan), store.csv_path, where);
    if (jsonl) assemble(dir, report.chunks, "jsonl", std::string(), *store.jsonl_path, where);
    write_atomically(dir / "manifest.json", manifest_text(plan, fingerprint, true), "manifest", where);
    for (std::size_t c = 0; c < report.chunks; ++c) {
      std::error_code ec;
      fs::remove(dir / chunk_name(c, "csv"), ec);
      fs::remove(dir / chunk_name(c, "jsonl"), ec);
    }
  }
  return report;
}

}  // namespace topple::ensemble
