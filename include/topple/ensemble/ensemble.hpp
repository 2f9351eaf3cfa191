#pragma once
// The ensemble engine: many (ground motion x object x parameters) simulations, reduced to a table.
//
// Spectra, fragility curves and the inversion of field observations all run the same thing. This header is the one
// engine for it; features build a Plan in code (the standard sweep of records and pulses against blocks and bodies
// is topple/ensemble/sweep.hpp, read from a sweep file by topple/io/sweep_file.hpp) and call it rather than loop on their
// own. The engine knows runs, chunks and stores, never the physics: it includes no solver header.
//
// Plan. A list of motion cases (a base record or pulse, loaded once and shared read-only, plus a transform: time
// scale, scale to a PGA or by a factor, polarity) and a list of object variants (a friction block with its mu,
// a rocking body with its size...). Run r pairs motion m = r / |objects| with object o = r % |objects|: all the
// objects of one motion are consecutive, so a transformed motion is prepared once and reused across them. A run
// function maps (motion, objects [o0, o1)) to the values of the result columns.
//
// Chunks. Run indices are cut into chunks of Plan::chunk_runs consecutive runs (the last may be shorter). A chunk
// is the unit of distribution (oneTBB tasks on one machine, static round-robin over MPI ranks across machines) and
// of commit (a finished chunk is one file that is never recomputed). The chunk size depends on the plan only, never
// on the number of threads or ranks, so a sweep may be resumed with other resources.
//
// Determinism. A run is a pure function of its inputs; rows are written in run order and every double in the
// shortest form that reads back to the same value (fmt "{}", Dragonbox), so the output files are byte-identical
// whatever the number of threads or ranks, and whether the sweep was interrupted and resumed.
//
// Rows. Columns: "run" (0-based index), then the plan's motion columns, object columns and result columns. A value
// that does not apply to a row (a rocking column on a sliding row, a first slip that never happened) is an empty CSV
// cell and a JSON null. Non-finite doubles are written the same way (they never carry a measurement).
//
// Store (run_to_files; docs/sweeps.md, "The result store"). Results of a sweep writing PATH (CSV) live, until it
// ends, in the directory PATH.parts/:
//   manifest.json       format "topple-sweep-parts/2", the plan fingerprint (hash of the expanded plan, the record
//                       samples and the chunk size), counts, the XXH3-64 checksum of every chunk file verified so far,
//                       and, once complete, the size and checksum of each output
//   00000042.csv        chunk 42: a header line (its format, the plan fingerprint, its index, its row count, the
//                       checksum of its JSON lines, and a checksum of the whole file but that checksum), then its
//                       CSV rows; 00000042.jsonl holds its JSON lines when they are asked for. Written under a
//                       temporary name and renamed when complete (the .jsonl first)
//   lock                held (flock) by the process that owns the store, so that two sweeps cannot share it
// Rerunning the same sweep reads every chunk back and keeps those that check out (header, checksum, index, rows,
// and the manifest's record); a damaged one is computed again (SweepReport::chunks_failed_verification). A chunk
// that checks out but carries another plan's fingerprint, or a manifest of another plan, is refused with InputError
// (the sweep file, a record or the chunk size changed) unless StoreOptions::restart discards the store; so is a store
// of the earlier format topple-sweep-parts/1, which has no checksums. When every chunk is there, rank 0 reads each
// back once more (recomputing any that fails), writes PATH (header + chunks in order) through io::OutputFile, records
// the outputs' sizes and checksums in the manifest, marks it complete and deletes the chunk files. A rerun of a
// complete sweep verifies its outputs: intact, it does nothing; missing, it computes them again; changed or
// truncated, it is refused with InputError (--restart computes it again). A file that cannot be written throws
// OutputError, and no temporary file stays behind.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "topple/core/field.hpp"
#include "topple/core/progress.hpp"
#include "topple/motion/ground_motion.hpp"

namespace topple::ensemble {

/// One cell of a result row: null (does not apply), boolean, integer, double or text (the value of a result field,
/// topple/core/field.hpp).
using Value = FieldValue;

// ---------------------------------------------------------------------------------------------------------------
// The generic engine
// ---------------------------------------------------------------------------------------------------------------

/// How a motion case is made from its base motion, in this order (the order of `topple slide` options, so that a
/// sweep row and the single-run CLI see the same samples): time scaling, scaling to a PGA, scaling by a factor,
/// polarity flip.
struct MotionTransform {
  double time_scale = 1.0;                ///< t -> t0 + time_scale (t - t0); > 0, 1 = unchanged
  std::optional<double> target_pga_m_s2;  ///< scale so that max |a| is this (m/s^2, > 0)
  std::optional<double> factor;           ///< then multiply by this factor (dimensionless)
  bool invert = false;                    ///< then a -> -a ("inverse" polarity)

  [[nodiscard]] bool is_identity() const noexcept {
    return time_scale == 1.0 && !target_pga_m_s2 && !factor && !invert;
  }
  /// The transformed motion. Throws InputError for an invalid factor (see GroundMotion).
  [[nodiscard]] GroundMotion apply(const GroundMotion& base) const;
};

/// One motion of a plan.
struct MotionCase {
  std::shared_ptr<const GroundMotion> base;  ///< loaded once, shared read-only by every case and thread
  MotionTransform transform;
  std::vector<Value> values;                 ///< one per Plan::motion_columns
};

/// One object variant of a plan: only its column values; what it means is the run function's business.
struct ObjectCase {
  std::vector<Value> values;  ///< one per Plan::object_columns
};

/// Computes the runs of objects [object_begin, object_end) on one prepared motion (case `motion_index`). Row k of
/// `results` (row-major, stride = number of result columns) receives object object_begin + k; every cell starts
/// null. Called concurrently from several threads: it must only read shared state.
using RunFunction = std::function<void(const GroundMotion& motion, std::size_t motion_index,
                                       std::size_t object_begin, std::size_t object_end, std::span<Value> results)>;

struct Plan {
  std::vector<std::string> motion_columns;  ///< names with units, e.g. "pga_g"
  std::vector<std::string> object_columns;
  std::vector<std::string> result_columns;
  std::vector<MotionCase> motions;
  std::vector<ObjectCase> objects;
  RunFunction run;
  std::size_t chunk_runs = 0;  ///< runs per chunk; 0 = default_chunk_runs(runs())
  std::string identity;        ///< extra text mixed into the fingerprint (e.g. a model or format version)

  [[nodiscard]] std::size_t runs() const noexcept { return motions.size() * objects.size(); }
  [[nodiscard]] std::size_t chunk_size() const noexcept;
  [[nodiscard]] std::size_t chunks() const noexcept;
  /// "run", then motion, object and result columns.
  [[nodiscard]] std::vector<std::string> columns() const;
};

/// Default chunk size: about runs / 4096 (so that a large cluster still gets several chunks per core), at least 1024
/// runs (a chunk costs a file creation and a rename, 0.05-0.5 ms on a local ext4 disk and more on a network
/// filesystem, against ~10 us for a sliding run on a 4000-sample record) and at most 100,000.
[[nodiscard]] std::size_t default_chunk_runs(std::size_t runs) noexcept;

/// Checks the plan's internal consistency (value counts match the columns, a run function is set, no duplicated
/// column, no line break in a text value). Throws std::invalid_argument: a malformed plan is a programming error.
void check_plan(const Plan& plan);

/// 32 hex digits identifying the expanded plan: columns, every motion's and object's values, the samples of every
/// base motion, the transforms, the chunk size and Plan::identity (two 64-bit FNV-1a-style hashes).
[[nodiscard]] std::string plan_fingerprint(const Plan& plan);

/// 32 hex digits identifying one motion's samples (grid and values), hashed as plan_fingerprint hashes a base
/// motion: for a run function's inputs that are not base motions (a record set's other components), which a plan
/// mixes into Plan::identity.
[[nodiscard]] std::string motion_fingerprint(const GroundMotion& motion);

struct ExecuteOptions {
  int threads = 0;  ///< worker threads; 0 = every core this process may use (its CPU affinity mask)
  /// Called from worker threads (concurrently; keep it cheap and thread-safe) after each batch of runs with the
  /// number of runs this process has finished and the number it has to do.
  ProgressCallback progress;
};

/// Every row, in run order (no files).
struct ResultTable {
  std::vector<std::string> columns;        ///< Plan::columns()
  std::vector<std::vector<Value>> rows;    ///< one per run; row[0] is the run index
};

/// Runs the whole plan in this process (all its threads) and keeps the rows in memory: for features that reduce
/// the table further (spectra, inversion). Exceptions of the run function propagate.
[[nodiscard]] ResultTable run_in_memory(const Plan& plan, const ExecuteOptions& options = {});

// ---- Formatting (what the files hold) ----

/// The CSV header line (with '\n').
[[nodiscard]] std::string csv_header(const Plan& plan);
/// A cell: shortest round-trip doubles, true/false, text quoted when it holds a comma, quote or leading/trailing
/// space; null and non-finite numbers as an empty cell.
void append_csv_value(std::string& out, const Value& value);
/// A JSON value: null for null and non-finite numbers, escaped strings.
void append_json_value(std::string& out, const Value& value);
/// A table as CSV / JSON lines text (the same bytes run_to_files writes).
[[nodiscard]] std::string to_csv(const ResultTable& table);
[[nodiscard]] std::string to_jsonl(const ResultTable& table);

// ---- Processes taking part in one sweep ----

/// The processes that share a sweep's chunks. One process: SingleProcess. Several machines: the MPI world
/// (join_cluster). Only the main thread calls these.
class Cluster {
 public:
  Cluster() = default;
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;
  virtual ~Cluster() = default;
  [[nodiscard]] virtual int rank() const noexcept = 0;
  [[nodiscard]] virtual int size() const noexcept = 0;
  virtual void barrier() = 0;
  /// `values` of rank `root` replace those of every other rank (which are resized).
  virtual void broadcast(std::vector<std::uint64_t>& values, int root) = 0;
  /// Every rank's value, in rank order, on every rank.
  [[nodiscard]] virtual std::vector<std::uint64_t> all_gather(std::uint64_t value) = 0;
  /// Ends every process of the sweep (after an error on one rank that the others cannot learn about).
  [[noreturn]] virtual void abort(int exit_code) = 0;
};

class SingleProcess final : public Cluster {
 public:
  [[nodiscard]] int rank() const noexcept override { return 0; }
  [[nodiscard]] int size() const noexcept override { return 1; }
  void barrier() override {}
  void broadcast(std::vector<std::uint64_t>& /*values*/, int /*root*/) override {}
  [[nodiscard]] std::vector<std::uint64_t> all_gather(std::uint64_t value) override { return {value}; }
  [[noreturn]] void abort(int exit_code) override;
};

/// True when topple was built with MPI (CMake option TOPPLE_WITH_MPI).
[[nodiscard]] bool built_with_mpi() noexcept;

/// True when this process was started by an MPI launcher (mpirun/mpiexec of Open MPI, or srun/Hydra through PMI or
/// PMIx), judged from the environment variables they set.
[[nodiscard]] bool launched_by_mpi() noexcept;

/// The MPI world (MPI_COMM_WORLD; MPI is initialised here with MPI_THREAD_FUNNELED and finalised when the object
/// dies) when built with MPI and launched by an MPI launcher; a SingleProcess otherwise. At most one at a time.
[[nodiscard]] std::unique_ptr<Cluster> join_cluster();

// ---- Sweeps to files, resumable ----

struct StoreOptions {
  std::filesystem::path csv_path;                  ///< the final CSV; chunks live in csv_path + ".parts"
  std::optional<std::filesystem::path> jsonl_path; ///< also JSON lines here
  bool restart = false;  ///< discard an existing store (of this or another plan) and compute everything again
  std::string field = "--out";  ///< how the caller names the output in error messages
};

struct SweepReport {
  std::size_t runs = 0;
  std::size_t chunks = 0;
  std::size_t chunk_runs = 0;
  std::size_t chunks_already_done = 0;  ///< found complete (and verified) in the store when the sweep started
  std::size_t chunks_failed_verification = 0;  ///< found in the store but damaged (checksum, length, position) or
                                                ///< failing at assembly: computed again (rank 0)
  std::size_t chunks_computed = 0;      ///< computed now, all ranks together
  std::size_t runs_computed = 0;        ///< all ranks together
  bool was_complete = false;            ///< the sweep had finished before: nothing was done
  bool restarted = false;               ///< an existing store was discarded (StoreOptions::restart, or outputs
                                        ///< of a complete sweep had been removed)
  int ranks = 1;
  int threads = 1;                      ///< worker threads of rank 0
  double seconds = 0.0;                 ///< wall time of the computation (rank 0)
};

/// Runs the plan on every rank of `cluster` (each with its threads) into the store beside options.csv_path and
/// writes the final files on rank 0. Every rank must call it with the same plan (checked: the fingerprints must
/// agree). Throws InputError when the store belongs to another plan or an earlier store format (without restart),
/// is locked by another sweep, or its finished outputs have changed; OutputError when a file cannot be written
/// (disk full, permission), leaving no temporary file.
SweepReport run_to_files(const Plan& plan, const StoreOptions& options, const ExecuteOptions& execute,
                         Cluster& cluster);

/// The store directory of a CSV output: "results.csv" -> "results.csv.parts".
[[nodiscard]] std::filesystem::path parts_directory(const std::filesystem::path& csv_path);

}  // namespace topple::ensemble
