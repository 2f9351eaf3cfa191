// topple sweep: an ensemble of runs (motions x objects x parameters) from a sweep file, on every core, across
// machines under mpirun, resumable. Parsing and printing only: the work is topple::ensemble::run_to_files.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "grids.hpp"
#include "progress.hpp"
#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"
#include "topple/io/sweep_file.hpp"
#include "topple/ensemble/sweep.hpp"

namespace topple::cli {
namespace {

struct SweepOptions {
  std::string file;
  int threads = 0;
  std::string out;
  bool jsonl = false;
  bool quiet = false;
  bool verbose = false;
  bool restart = false;
};

/// Ends a rank other than 0 without printing (rank 0 reports), after MPI is finalised.
[[noreturn]] void quiet_exit(std::unique_ptr<ensemble::Cluster>& cluster, int code) {
  cluster.reset();
  std::fflush(stdout);
  std::exit(code);
}

void run_sweep(const SweepOptions& o) {
  check_threads(o.threads);  // before any work; oneTBB aborts on absurd counts (100000)
  std::unique_ptr<ensemble::Cluster> cluster = ensemble::join_cluster();
  const int rank = cluster->rank();

  // Every rank reads the sweep file and its records (the plan is identical everywhere; run_to_files checks).
  std::optional<io::SweepFile> sweep;
  std::optional<ensemble::Plan> plan;
  std::optional<InputError> failure;
  try {
    sweep = io::read_sweep_file(o.file);
    plan = ensemble::make_plan(sweep->spec);
  } catch (const InputError& e) {
    failure = e;
  }
  const auto failed = cluster->all_gather(failure ? 1 : 0);
  if (failure) {
    if (rank == 0) throw *failure;
    if (failed[0] == 0) fmt::print(stderr, "topple: rank {}: error: {}\n", rank, failure->what());
    quiet_exit(cluster, 2);
  }
  for (std::size_t r = 0; r < failed.size(); ++r) {
    if (failed[r] != 0) {
      if (rank == 0) throw InputError(InputLocation{o.file, std::nullopt, ""}, fmt::format("rank {} could not read the sweep (see its message)", r));
      quiet_exit(cluster, 2);
    }
  }

  ensemble::StoreOptions store;
  store.csv_path = o.out.empty() ? sweep->output_csv : std::filesystem::path(o.out);
  store.field = o.out.empty() ? "output.path" : "--out";
  if (o.jsonl || sweep->jsonl) store.jsonl_path = io::jsonl_path_for(store.csv_path);
  store.restart = o.restart;

  if (rank == 0) {
    for (const std::string& w : sweep->warnings) fmt::print(stderr, "warning: {}\n", w);
  }
  ProgressBar bar(rank == 0 && progress_wanted(o.quiet));
  ensemble::ExecuteOptions execute;
  execute.threads = o.threads;
  execute.progress = bar.callback();

  if (rank == 0 && o.verbose) {
    fmt::print(stderr, "topple sweep: {} runs = {} motions x {} objects; {} chunks of {} runs; {} rank{}; output {}\n",
               plan->runs(), plan->motions.size(), plan->objects.size(), plan->chunks(), plan->chunk_size(),
               cluster->size(), cluster->size() == 1 ? "" : "s", store.csv_path.string());
  }
  ensemble::SweepReport report;
  try {
    report = ensemble::run_to_files(*plan, store, execute, *cluster);
  } catch (const InputError&) {
    if (rank != 0) quiet_exit(cluster, 2);
    throw;
  }
  bar.finish();
  if (rank != 0 || o.quiet) return;
  if (o.verbose) {
    fmt::print(stderr, "topple sweep: chunks total={} already_done={} computed={} runs_computed={} "
                       "failed_verification={} threads={} ranks={} seconds={:.3f}{}\n",
               report.chunks, report.chunks_already_done, report.chunks_computed, report.runs_computed,
               report.chunks_failed_verification, report.threads, report.ranks, report.seconds,
               report.restarted ? " (restarted)" : "");
  }
  const std::string outputs =
      store.csv_path.string() + (store.jsonl_path ? " and " + store.jsonl_path->string() : std::string());
  if (report.was_complete) {
    fmt::print(stderr, "topple sweep: already complete, nothing to do: {} ({} rows)\n", outputs, report.runs);
    return;
  }
  if (report.chunks_failed_verification > 0) {
    fmt::print(stderr, "topple sweep: {} chunk{} in {} failed verification (checksum, length or position) and "
                       "{} computed again\n",
               report.chunks_failed_verification, report.chunks_failed_verification == 1 ? "" : "s",
               ensemble::parts_directory(store.csv_path).string(),
               report.chunks_failed_verification == 1 ? "was" : "were");
  }
  const double rate = report.seconds > 0.0 ? static_cast<double>(report.runs_computed) / report.seconds : 0.0;
  fmt::print(stderr, "topple sweep: wrote {} ({} rows); computed {} runs in {:.2f} s ({:.0f} runs/s){}\n", outputs,
             report.runs, report.runs_computed, report.seconds, rate,
             report.chunks_already_done > 0
                 ? fmt::format("; resumed: {} of {} chunks were already done", report.chunks_already_done,
                               report.chunks)
                 : std::string());
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run an ensemble (motions x objects x parameters) from a sweep file to a CSV table: all cores, MPI "
               "ranks under mpirun, resumable (rerun the same command)");
  cmd->add_option("file", o->file, "Sweep file (TOML; see docs/sweeps.md)")->required();
  cmd->add_option("--threads", o->threads, "Worker threads per process (default 0: every core it may use)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", o->out, "Output CSV (default: [output] path of the sweep file); chunks of an unfinished "
                                   "sweep live in OUT.parts/");
  cmd->add_flag("--jsonl", o->jsonl, "Also write JSON lines (OUT with the extension .jsonl)");
  cmd->add_flag("--restart", o->restart, "Discard the chunks of an earlier (or different) sweep to this output and "
                                         "start over");
  add_quiet_flag(*cmd, o->quiet, "no summary");
  cmd->add_flag("--verbose", o->verbose, "Plan and chunk counts (already done, computed) on stderr");
  cmd->callback([o] { run_sweep(*o); });
}

}  // namespace topple::cli
