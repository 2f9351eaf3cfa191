// The progress bar (moved here from `topple sweep`, which introduced it, so that every long command shares it).
#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace topple::cli {

ProgressBar::ProgressBar(bool enabled, std::string label)
    : enabled_(enabled), label_(std::move(label)), start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (!enabled_) return;
  const std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another thread is drawing
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && done < total && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  draw(done, total, now);
}

void ProgressBar::finish(std::string label) {
  if (!enabled_) return;
  const std::lock_guard lock(mutex_);
  if (drawn_) std::fputs("\n", stderr);
  drawn_ = false;
  label_ = std::move(label);
  start_ = std::chrono::steady_clock::now();
}

ProgressCallback ProgressBar::callback() {
  if (!enabled_) return {};
  return [this](std::size_t done, std::size_t total) { update(done, total); };
}

void ProgressBar::draw(std::size_t done, std::size_t total, std::chrono::steady_clock::time_point now) {
  constexpr int kWidth = 30;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  const auto filled = static_cast<int>(fraction * kWidth);
  const std::string eta = rate > 0.0 ? format_duration(static_cast<double>(total - done) / rate) : "?";
  fmt::print(stderr, "\r{}  {}/{} runs {:3.0f}% [{}{}] {:.0f} runs/s  ETA {}   ", label_, done, total,
             100.0 * fraction, std::string(static_cast<std::size_t>(filled), '#'),
             std::string(static_cast<std::size_t>(kWidth - filled), ' '), rate, eta);
  std::fflush(stderr);
  drawn_ = true;
}

bool progress_wanted(bool quiet) { return !quiet && ::isatty(STDERR_FILENO) != 0; }

std::string format_duration(double seconds) {
  const auto s = static_cast<long long>(seconds + 0.5);
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

void add_quiet_flag(CLI::App& cmd, bool& quiet, const std::string& what) {
  cmd.add_flag("--quiet", quiet,
               "No progress bar" + (what.empty() ? std::string() : ", " + what) +
                   " on stderr (the bar is drawn only when stderr is a terminal; errors are always printed)");
}

}  // namespace topple::cli
