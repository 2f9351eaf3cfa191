// The resumable store of run_to_files (ensemble.hpp, "Store"; docs/sweeps.md, "The result store"): a POSIX directory
// beside the output holding a lock, a manifest and one self-checking file per finished chunk; assembled into the
// output when every chunk is there and verified.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <xxhash.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "ensemble/ensemble_detail.hpp"
#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"

namespace topple::ensemble {
namespace fs = std::filesystem;

fs::path parts_directory(const fs::path& csv_path) {
  fs::path p = csv_path;
  p += ".parts";
  return p;
}

namespace {

constexpr std::string_view kStoreFormat = "topple-sweep-parts/2";
constexpr std::string_view kOldStoreFormat = "topple-sweep-parts/1";  // no checksums: refused (docs/sweeps.md)
constexpr std::string_view kChunkFormat = "topple-sweep-chunk/2";
constexpr std::string_view kChecksumName = "xxh3-64";

std::string chunk_name(std::size_t chunk, std::string_view ext) { return fmt::format("{:08}.{}", chunk, ext); }

std::string errno_text() { return std::strerror(errno); }

std::string hex64(XXH64_hash_t h) { return fmt::format("{:016x}", static_cast<unsigned long long>(h)); }

/// XXH3 (64 bits) over data given in pieces.
class Checksum {
 public:
  Checksum() : state_(XXH3_createState()) {
    if (state_ == nullptr) throw std::bad_alloc();
    XXH3_64bits_reset(state_.get());
  }
  void add(std::string_view bytes) { XXH3_64bits_update(state_.get(), bytes.data(), bytes.size()); }
  [[nodiscard]] std::string hex() const { return hex64(XXH3_64bits_digest(state_.get())); }

 private:
  struct Free {
    void operator()(XXH3_state_t* s) const { XXH3_freeState(s); }
  };
  std::unique_ptr<XXH3_state_t, Free> state_;
};

std::string checksum_of(std::string_view bytes) { return hex64(XXH3_64bits(bytes.data(), bytes.size())); }

/// The whole file, or nullopt when it cannot be opened (absent).
std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return std::nullopt;
  const std::streamoff size = in.tellg();
  if (size < 0) return std::nullopt;
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(text.data(), size);
  text.resize(static_cast<std::size_t>(in.gcount()));  // a file cut while it is read is damaged, not an error here
  return text;
}

// ---- Chunk files ----
//
// NNNNNNNN.csv holds one header line, then the chunk's CSV rows:
//   # topple-sweep-chunk/2 fingerprint=<32 hex> chunk=<N> rows=<R> jsonl_xxh3=<16 hex or -> xxh3=<16 hex>
// where xxh3 is the XXH3-64 of the header line up to (not including) " xxh3=", a '\n', and the rows: it covers the
// whole file but itself, so a damaged fingerprint reads as damage, not as another sweep. NNNNNNNN.jsonl (when JSON
// lines are asked for) holds the rows as JSON lines only; its checksum is the csv header's jsonl_xxh3. The jsonl file
// is renamed into place before the csv file: a chunk is there when its csv file is.

struct ChunkHeader {
  std::string fingerprint;
  std::size_t chunk = 0;
  std::size_t rows = 0;
  std::string jsonl_hash;  ///< "-" without JSON lines
  std::string hash;
};

std::string header_prefix(const std::string& fingerprint, std::size_t chunk, std::size_t rows,
                          const std::string& jsonl_hash) {
  return fmt::format("# {} fingerprint={} chunk={} rows={} jsonl_xxh3={}", kChunkFormat, fingerprint, chunk, rows,
                     jsonl_hash);
}

std::optional<ChunkHeader> parse_header(std::string_view line) {
  std::istringstream in{std::string(line)};
  std::string hash_mark;
  std::string format;
  in >> hash_mark >> format;
  if (hash_mark != "#" || format != kChunkFormat) return std::nullopt;
  std::map<std::string, std::string> kv;
  std::string token;
  while (in >> token) {
    const auto eq = token.find('=');
    if (eq == std::string::npos) return std::nullopt;
    kv[token.substr(0, eq)] = token.substr(eq + 1);
  }
  for (const char* key : {"fingerprint", "chunk", "rows", "jsonl_xxh3", "xxh3"}) {
    if (kv.count(key) == 0) return std::nullopt;
  }
  ChunkHeader h;
  h.fingerprint = kv["fingerprint"];
  h.jsonl_hash = kv["jsonl_xxh3"];
  h.hash = kv["xxh3"];
  const auto number = [](const std::string& s, std::size_t* out) {
    if (s.empty() || s.size() > 18 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      return false;
    }
    *out = std::stoull(s);
    return true;
  };
  if (!number(kv["chunk"], &h.chunk) || !number(kv["rows"], &h.rows)) return std::nullopt;
  return h;
}

/// Writes chunk `c` (its JSON lines first, then its CSV file with the header) through temporary names. Returns the
/// checksums (csv, jsonl or "-"). Throws OutputError when a file cannot be written.
std::pair<std::string, std::string> write_chunk(const fs::path& dir, std::size_t c, std::size_t rows,
                                                const std::string& fingerprint, const std::string& csv,
                                                const std::string* jsonl) {
  std::string jsonl_hash = "-";
  if (jsonl != nullptr) {
    jsonl_hash = checksum_of(*jsonl);
    io::write_file_atomically(dir / chunk_name(c, "jsonl"), *jsonl);
  }
  const std::string prefix = header_prefix(fingerprint, c, rows, jsonl_hash);
  Checksum sum;
  sum.add(prefix);
  sum.add("\n");
  sum.add(csv);
  const std::string hash = sum.hex();
  io::OutputFile out(dir / chunk_name(c, "csv"));
  out.stream() << prefix << " xxh3=" << hash << '\n';
  out.stream().write(csv.data(), static_cast<std::streamsize>(csv.size()));
  out.commit();
  return {hash, jsonl_hash};
}

enum class ChunkState { ok, missing, foreign, damaged };

/// A chunk as read back: its rows and checksums.
struct ChunkText {
  std::string csv_file;     ///< the whole CSV file; the rows start at rows_at
  std::size_t rows_at = 0;
  std::string jsonl;
  std::string csv_hash;
  std::string jsonl_hash;
  std::string fingerprint;  ///< the chunk's own, when it is foreign
};

/// Checksums the manifest records for a chunk ("" when it records none).
struct ChunkRecord {
  std::string csv;
  std::string jsonl;
};

/// Reads chunk c back and checks it: its header parses, its checksum matches its bytes, it is chunk c with `rows`
/// rows of the plan with `fingerprint`, its JSON lines (if asked) match their checksum, and both checksums equal
/// what the manifest recorded (if it recorded them). A chunk that checks out but carries another fingerprint is
/// `foreign`: it belongs to another sweep.
ChunkState read_chunk(const fs::path& dir, std::size_t c, std::size_t rows, const std::string& fingerprint,
                      bool jsonl, const ChunkRecord* recorded, ChunkText* text) {
  auto csv = read_file(dir / chunk_name(c, "csv"));
  if (!csv) return ChunkState::missing;
  const auto eol = csv->find('\n');
  if (eol == std::string::npos) return ChunkState::damaged;
  const std::string_view line(csv->data(), eol);
  const auto header = parse_header(line);
  if (!header) return ChunkState::damaged;
  const auto mark = line.rfind(" xxh3=");
  if (mark == std::string_view::npos) return ChunkState::damaged;
  Checksum sum;
  sum.add(line.substr(0, mark));
  sum.add("\n");
  sum.add(std::string_view(*csv).substr(eol + 1));
  if (sum.hex() != header->hash) return ChunkState::damaged;
  if (header->fingerprint != fingerprint) {
    text->fingerprint = header->fingerprint;
    return ChunkState::foreign;
  }
  if (header->chunk != c || header->rows != rows) return ChunkState::damaged;
  if (recorded != nullptr && !recorded->csv.empty() && recorded->csv != header->hash) return ChunkState::damaged;
  std::string lines;
  if (jsonl) {
    if (header->jsonl_hash == "-") return ChunkState::damaged;  // made without JSON lines: make it again
    auto j = read_file(dir / chunk_name(c, "jsonl"));
    if (!j || checksum_of(*j) != header->jsonl_hash) return ChunkState::damaged;
    if (recorded != nullptr && !recorded->jsonl.empty() && recorded->jsonl != header->jsonl_hash) {
      return ChunkState::damaged;
    }
    lines = std::move(*j);
  }
  text->csv_file = std::move(*csv);
  text->rows_at = eol + 1;
  text->jsonl = std::move(lines);
  text->csv_hash = header->hash;
  text->jsonl_hash = header->jsonl_hash;
  return ChunkState::ok;
}

// ---- Lock ----

/// flock on PARTS/lock for the lifetime of the object (released by the kernel if the process dies).
class StoreLock {
 public:
  StoreLock(const fs::path& dir, const InputLocation& where) {
    const fs::path p = dir / "lock";
    fd_ = ::open(p.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw OutputError(fmt::format("cannot open the lock file '{}': {}", p.string(), errno_text()));
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

// ---- Manifest ----

/// A finished output as recorded: its size and checksum.
struct OutputRecord {
  std::uint64_t bytes = 0;
  std::string hash;
};

struct Manifest {
  std::string fingerprint;
  std::size_t runs = 0;
  std::size_t chunk_runs = 0;
  std::size_t chunks = 0;
  bool complete = false;
  std::map<std::string, std::string> chunk_hashes;  ///< chunk file name -> checksum (verified, or assembled)
  std::optional<OutputRecord> csv, jsonl;           ///< the outputs (when complete)
};

std::string manifest_text(const Plan& plan, const Manifest& m) {
  nlohmann::ordered_json j;
  j["format"] = kStoreFormat;
  j["fingerprint"] = m.fingerprint;
  j["runs"] = plan.runs();
  j["chunk_runs"] = plan.chunk_size();
  j["chunks"] = plan.chunks();
  j["complete"] = m.complete;
  j["columns"] = plan.columns();
  j["checksum"] = kChecksumName;
  j["chunk_checksums"] = nlohmann::ordered_json::object();
  for (const auto& [name, hash] : m.chunk_hashes) j["chunk_checksums"][name] = hash;
  if (m.complete) {
    nlohmann::ordered_json outputs = nlohmann::ordered_json::object();
    for (const auto& [key, record] : {std::pair{"csv", &m.csv}, std::pair{"jsonl", &m.jsonl}}) {
      if (*record) outputs[key] = {{"bytes", (*record)->bytes}, {"xxh3", (*record)->hash}};
    }
    j["outputs"] = outputs;
  }
  return j.dump(2) + "\n";
}

std::optional<Manifest> read_manifest(const fs::path& path, const InputLocation& where) {
  const auto text = read_file(path);
  if (!text) return std::nullopt;
  nlohmann::json j;
  std::string format;
  try {
    j = nlohmann::json::parse(*text);
    format = j.at("format").get<std::string>();
  } catch (const std::exception&) {
    format.clear();
  }
  if (format == kOldStoreFormat) {
    throw InputError(where, fmt::format(
        "the store '{}' was written by an earlier topple (store format {}, without checksums), which this version "
        "does not resume or trust as complete: rerun with --restart to compute the sweep again (or finish it with "
        "the version that started it)", path.parent_path().string(), kOldStoreFormat));
  }
  try {
    if (format != kStoreFormat) throw std::runtime_error("format");
    Manifest m;
    m.fingerprint = j.at("fingerprint").get<std::string>();
    m.runs = j.at("runs").get<std::size_t>();
    m.chunk_runs = j.at("chunk_runs").get<std::size_t>();
    m.chunks = j.at("chunks").get<std::size_t>();
    m.complete = j.at("complete").get<bool>();
    if (j.contains("chunk_checksums")) {
      for (const auto& [name, hash] : j.at("chunk_checksums").items()) m.chunk_hashes[name] = hash.get<std::string>();
    }
    if (j.contains("outputs")) {
      const auto& o = j.at("outputs");
      for (const auto& [key, record] : {std::pair{"csv", &m.csv}, std::pair{"jsonl", &m.jsonl}}) {
        if (o.contains(key)) {
          *record = OutputRecord{o.at(key).at("bytes").get<std::uint64_t>(), o.at(key).at("xxh3").get<std::string>()};
        }
      }
    }
    return m;
  } catch (const std::exception&) {
    throw InputError(where, fmt::format("'{}' is not the manifest of a topple sweep store; remove the directory or "
                                        "rerun with --restart", path.string()));
  }
}

// ---- Housekeeping ----

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

/// Removes what a killed assembly left beside an output: io::OutputFile's temporary ".tmp-<pid>-<name>" (the store's
/// lock is held, so no other sweep is writing this output).
void remove_stale_temporaries(const fs::path& target) {
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string suffix = "-";  // (not "-" + name: GCC 12 warns falsely on that, -Wrestrict)
  suffix += target.filename().string();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= 5 + suffix.size() || name.rfind(".tmp-", 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
      continue;
    }
    const std::string pid = name.substr(5, name.size() - 5 - suffix.size());
    if (std::all_of(pid.begin(), pid.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      fs::remove(entry.path(), ec);
    }
  }
}

/// Checks a finished output against its record. Returns an empty string when it matches, else what differs.
std::string output_difference(const fs::path& path, const OutputRecord& record) {
  const auto text = read_file(path);
  if (!text) return "it cannot be read";
  if (text->size() != record.bytes) {
    return fmt::format("it holds {} bytes, {} when the sweep finished", text->size(), record.bytes);
  }
  const std::string hash = checksum_of(*text);
  if (hash != record.hash) return fmt::format("its checksum is {}, {} when the sweep finished", hash, record.hash);
  return {};
}

enum class StoreStatus : std::uint64_t { ready = 0, complete = 1, failed = 2 };

}  // namespace

namespace {

/// What the phases of run_to_files share: the plan and its fingerprint, the store and the outputs.
struct StoreRun {
  const Plan& plan;
  const StoreOptions& store;
  InputLocation where;
  std::string fingerprint;
  fs::path dir;
  fs::path manifest_path;
  bool jsonl = false;
  std::size_t runs = 0;
  std::size_t chunks = 0;
  std::size_t chunk_runs = 0;

  [[nodiscard]] std::size_t rows_of(std::size_t c) const {
    return std::min(runs, (c + 1) * chunk_runs) - c * chunk_runs;
  }
};

/// A sweep finished before: its outputs verified against their recorded checksums. A missing output (or one never
/// recorded, such as JSON lines asked for only now) is computed again (false); a changed one is refused.
bool outputs_verified(const StoreRun& s, const Manifest& manifest) {
  bool outputs_there = true;
  for (const auto& [path, record] :
       {std::pair{std::optional<fs::path>(s.store.csv_path), &manifest.csv},
        std::pair{s.store.jsonl_path, &manifest.jsonl}}) {
    if (!path) continue;
    if (!*record || !fs::exists(*path)) {
      outputs_there = false;
      continue;
    }
    const std::string difference = output_difference(*path, **record);
    if (!difference.empty()) {
      throw InputError(s.where, fmt::format(
          "'{}' has changed since this sweep finished ({}): it is not reported complete. Rerun with "
          "--restart to compute it again, or write to another output", path->string(), difference));
    }
  }
  return outputs_there;
}

/// The checksums the manifest recorded for a chunk's files, if any.
ChunkRecord recorded_chunk(const std::optional<Manifest>& manifest, std::size_t c) {
  ChunkRecord recorded;
  if (manifest) {
    const auto csv_it = manifest->chunk_hashes.find(chunk_name(c, "csv"));
    const auto jsonl_it = manifest->chunk_hashes.find(chunk_name(c, "jsonl"));
    if (csv_it != manifest->chunk_hashes.end()) recorded.csv = csv_it->second;
    if (jsonl_it != manifest->chunk_hashes.end()) recorded.jsonl = jsonl_it->second;
  }
  return recorded;
}

/// The chunks of the store read back and checked: those done kept in a fresh manifest, the others pending. The
/// message to the ranks: [ready, already done, pending chunk indices...].
std::vector<std::uint64_t> scan_chunks(const StoreRun& s, const std::optional<Manifest>& manifest,
                                       SweepReport& report) {
  // Temporary files are leftovers of a killed run. Every chunk file is read back and checked (ChunkState).
  for (const auto& entry : fs::directory_iterator(s.dir)) {
    if (entry.path().filename().string().rfind(".tmp-", 0) == 0) fs::remove(entry.path());
  }
  Manifest fresh;
  fresh.fingerprint = s.fingerprint;
  std::vector<std::uint64_t> pending;
  std::size_t already = 0;
  for (std::size_t c = 0; c < s.chunks; ++c) {
    ChunkRecord recorded = recorded_chunk(manifest, c);
    ChunkText text;
    const ChunkState state = read_chunk(s.dir, c, s.rows_of(c), s.fingerprint, s.jsonl, &recorded, &text);
    if (state == ChunkState::foreign) {
      throw InputError(s.where, fmt::format(
          "the store '{}' holds chunks of a different sweep ({} carries the fingerprint {}, this sweep's is "
          "{}{}). Rerun with --restart to discard them and start over, or write to another output",
          s.dir.string(), chunk_name(c, "csv"), text.fingerprint, s.fingerprint,
          manifest ? "" : "; the store has no manifest"));
    }
    if (state == ChunkState::ok) {
      ++already;
      fresh.chunk_hashes[chunk_name(c, "csv")] = text.csv_hash;
      if (s.jsonl) fresh.chunk_hashes[chunk_name(c, "jsonl")] = text.jsonl_hash;
      continue;
    }
    if (state == ChunkState::damaged) {
      ++report.chunks_failed_verification;
      std::error_code ec;
      fs::remove(s.dir / chunk_name(c, "csv"), ec);
      fs::remove(s.dir / chunk_name(c, "jsonl"), ec);
    }
    pending.push_back(c);
  }
  io::write_file_atomically(s.manifest_path, manifest_text(s.plan, fresh));
  std::vector<std::uint64_t> message = {static_cast<std::uint64_t>(StoreStatus::ready), already};
  message.insert(message.end(), pending.begin(), pending.end());
  return message;
}

/// Rank 0 prepares the store: created and locked, its manifest read, a complete sweep's outputs verified, the chunks
/// checked. The message to the ranks: [status, already done, pending chunk indices...].
std::vector<std::uint64_t> prepare_store(const StoreRun& s, std::optional<StoreLock>& lock, SweepReport& report) {
  try {
    if (s.store.csv_path.has_parent_path()) fs::create_directories(s.store.csv_path.parent_path());
    fs::create_directories(s.dir);
  } catch (const fs::filesystem_error& e) {
    throw OutputError(fmt::format("cannot create the store '{}': {}", s.dir.string(), e.code().message()));
  }
  lock.emplace(s.dir, s.where);
  remove_stale_temporaries(s.store.csv_path);
  if (s.jsonl) remove_stale_temporaries(*s.store.jsonl_path);
  bool restart = s.store.restart;
  std::optional<Manifest> manifest;
  if (!restart) manifest = read_manifest(s.manifest_path, s.where);
  if (manifest && manifest->fingerprint != s.fingerprint) {
    throw InputError(s.where, fmt::format(
        "the store '{}' holds results of a different sweep ({} runs in chunks of {}; the sweep file, a "
        "record or the chunk size has changed since). Rerun with --restart to discard them and start over, "
        "or write to another output", s.dir.string(), manifest->runs, manifest->chunk_runs));
  }
  if (manifest && manifest->complete) {
    if (outputs_verified(s, *manifest)) {
      clear_store(s.dir);  // chunk files a killed cleanup may have left (the manifest is rewritten below)
      io::write_file_atomically(s.manifest_path, manifest_text(s.plan, *manifest));
      return {static_cast<std::uint64_t>(StoreStatus::complete), s.chunks};
    }
    restart = true;
  }
  report.restarted = restart && fs::exists(s.manifest_path);
  if (restart) {
    clear_store(s.dir);
    manifest.reset();
  }
  return scan_chunks(s, manifest, report);
}

/// Assembly on rank 0: every chunk is read back and checked once more (the other ranks' too: with several machines
/// the directory must be on a filesystem they all share); one that fails is computed again here. Then the header
/// and the chunks in order go to each output through a temporary file, and the outputs' checksums to the manifest.
void assemble_outputs(const StoreRun& s, detail::Engine& engine, const detail::Engine::Commit& commit,
                      const Cluster& cluster, SweepReport& report) {
  io::OutputFile csv_out(s.store.csv_path);
  std::optional<io::OutputFile> jsonl_out;
  if (s.jsonl) jsonl_out.emplace(*s.store.jsonl_path);
  Checksum csv_sum;
  Checksum jsonl_sum;
  std::uint64_t csv_bytes = 0;
  std::uint64_t jsonl_bytes = 0;
  const auto put = [](io::OutputFile& f, Checksum& sum, std::uint64_t& bytes, std::string_view text) {
    f.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!f.stream()) {
      f.commit();  // a failed stream: throws OutputError with the system's reason and removes the temporary file
      throw OutputError(fmt::format("cannot write '{}'", f.final_path().string()));  // (not reached)
    }
    sum.add(text);
    bytes += text.size();
  };
  put(csv_out, csv_sum, csv_bytes, csv_header(s.plan));
  Manifest done;
  done.fingerprint = s.fingerprint;
  for (std::size_t c = 0; c < s.chunks; ++c) {
    ChunkText text;
    ChunkState state = read_chunk(s.dir, c, s.rows_of(c), s.fingerprint, s.jsonl, nullptr, &text);
    if (state == ChunkState::missing && cluster.size() > 1) {
      throw InputError(s.where, fmt::format("chunk {} is missing from '{}' after every rank finished: with several "
                                            "machines the output must be on a filesystem they all share",
                                            c, s.dir.string()));
    }
    if (state != ChunkState::ok) {
      ++report.chunks_failed_verification;
      const std::size_t again[] = {c};
      const std::size_t before = engine.runs_done();
      engine.run_chunks(again, commit);
      report.chunks_computed += 1;
      report.runs_computed += engine.runs_done() - before;
      state = read_chunk(s.dir, c, s.rows_of(c), s.fingerprint, s.jsonl, nullptr, &text);
      if (state != ChunkState::ok) {
        throw OutputError(fmt::format("chunk {} of '{}' does not read back as it was just written: the disk or "
                                      "filesystem returns other bytes", c, s.dir.string()));
      }
    }
    put(csv_out, csv_sum, csv_bytes, std::string_view(text.csv_file).substr(text.rows_at));
    if (jsonl_out) put(*jsonl_out, jsonl_sum, jsonl_bytes, text.jsonl);
    done.chunk_hashes[chunk_name(c, "csv")] = text.csv_hash;
    if (s.jsonl) done.chunk_hashes[chunk_name(c, "jsonl")] = text.jsonl_hash;
  }
  csv_out.commit();
  if (jsonl_out) jsonl_out->commit();
  done.complete = true;  // with every chunk's checksum as assembled, and the outputs'
  done.csv = OutputRecord{csv_bytes, csv_sum.hex()};
  if (s.jsonl) done.jsonl = OutputRecord{jsonl_bytes, jsonl_sum.hex()};
  io::write_file_atomically(s.manifest_path, manifest_text(s.plan, done));
  for (std::size_t c = 0; c < s.chunks; ++c) {
    std::error_code ec;
    fs::remove(s.dir / chunk_name(c, "csv"), ec);
    fs::remove(s.dir / chunk_name(c, "jsonl"), ec);
  }
}

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
  const StoreRun s{plan, store, where, fingerprint, dir, dir / "manifest.json", store.jsonl_path.has_value(),
                   report.runs, report.chunks, report.chunk_runs};
  std::optional<StoreLock> lock;
  std::vector<std::uint64_t> message;  // [status, already done, pending chunk indices...]
  std::exception_ptr failure;
  if (cluster.rank() == 0) {
    try {
      message = prepare_store(s, lock, report);
    } catch (const fs::filesystem_error& e) {
      failure = std::make_exception_ptr(OutputError(fmt::format("store '{}': {}", dir.string(), e.what())));
      message = {static_cast<std::uint64_t>(StoreStatus::failed), 0};
    } catch (const std::exception&) {
      failure = std::current_exception();
      message = {static_cast<std::uint64_t>(StoreStatus::failed), 0};
    }
  }
  cluster.barrier();
  cluster.broadcast(message, 0);
  const auto status = static_cast<StoreStatus>(message.at(0));
  if (status == StoreStatus::failed) {
    if (failure) std::rethrow_exception(failure);
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
  const detail::Engine::Commit commit = [&](std::size_t c, std::size_t begin, std::size_t end,
                                            std::vector<Value>& results) {
    std::string csv;
    std::string lines;
    detail::format_rows(plan, layout, begin, end, results, &csv, s.jsonl ? &lines : nullptr);
    static_cast<void>(write_chunk(dir, c, end - begin, fingerprint, csv, s.jsonl ? &lines : nullptr));
  };
  const auto start = std::chrono::steady_clock::now();
  std::size_t my_runs = 0;
  try {
    report.threads = engine.run_chunks(mine, commit);
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
  if (cluster.rank() != 0) return report;
  assemble_outputs(s, engine, commit, cluster, report);
  return report;
}

}  // namespace topple::ensemble
