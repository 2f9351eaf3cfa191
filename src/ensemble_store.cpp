// The resumable store of run_to_files (ensemble.hpp, "Store"): a POSIX directory beside the output holding a lock,
// a manifest and one file per finished chunk; assembled into the output when every chunk is there.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "ensemble_detail.hpp"
#include "topple/ensemble.hpp"
#include "topple/error.hpp"

namespace topple::ensemble {
namespace fs = std::filesystem;

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
  const detail::Layout layout(plan);
  detail::Engine engine(plan, execute);
  const std::string tag = fmt::format("{}-{}", cluster.rank(), ::getpid());
  const auto start = std::chrono::steady_clock::now();
  std::size_t my_runs = 0;
  try {
    report.threads = engine.run_chunks(mine, [&](std::size_t c, std::size_t begin, std::size_t end,
                                                 std::vector<Value>& results) {
      std::string csv;
      std::string lines;
      detail::format_rows(plan, layout, begin, end, results, &csv, jsonl ? &lines : nullptr);
      // The CSV file is renamed last: a chunk is done when it exists (and, if asked, its JSON lines).
      if (jsonl) write_atomically(dir / chunk_name(c, "jsonl"), lines, tag, where);
      write_atomically(dir / chunk_name(c, "csv"), csv, tag, where);
    });
    my_runs = engine.runs_done();
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
