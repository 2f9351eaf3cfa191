#pragma once
// The progress bar of the long commands (invert, fragility, spectrum, sweep) and the --quiet flag every command has.
// The library reports progress through a ProgressCallback (topple/core/progress.hpp); the bar draws it on stderr, only
// when stderr is a terminal and --quiet is not given (pipes, files and CI logs get nothing).
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

#include <CLI/CLI.hpp>

#include "topple/core/progress.hpp"

namespace topple::cli {

/// "  1234/10000 runs  12%  [####      ]  560 runs/s  ETA 0:15" on stderr, redrawn at most 10 times a second.
class ProgressBar {
 public:
  /// Draws nothing unless `enabled` (see progress_wanted). `label` prefixes the line (e.g. the site inverted).
  explicit ProgressBar(bool enabled, std::string label = {});
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Thread-safe; a call while another thread draws is skipped (the next one draws).
  void update(std::size_t done, std::size_t total);
  /// Ends the line (when anything was drawn) and starts the clock again for a next computation with `label`.
  void finish(std::string label = {});
  /// The library's callback drawing into this bar (which must outlive the computation).
  [[nodiscard]] ProgressCallback callback();

 private:
  void draw(std::size_t done, std::size_t total, std::chrono::steady_clock::time_point now);

  bool enabled_;
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_{};
  bool drawn_ = false;
  std::mutex mutex_;
};

/// Whether a command should draw a progress bar: not `quiet`, and stderr is a terminal.
[[nodiscard]] bool progress_wanted(bool quiet);

/// "1:05", "2:03:04": a duration for the ETA.
[[nodiscard]] std::string format_duration(double seconds);

/// Adds --quiet to `cmd` with the help text every command shares, `what` saying what it silences besides the bar.
void add_quiet_flag(CLI::App& cmd, bool& quiet, const std::string& what = "");

}  // namespace topple::cli
