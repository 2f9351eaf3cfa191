#include "topple/core/output_file.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>
#include <system_error>

#include <fmt/format.h>

#include "topple/core/error.hpp"

namespace topple::io {
namespace {

// The registry of temporary files to unlink on SIGINT/SIGTERM. A signal handler may call only async-signal-safe
// functions (POSIX.1-2017 2.4.3): it reads fixed buffers and calls unlink() and _exit(), nothing else. This is the
// one piece of process-wide mutable state in the library, and it exists because signals are process-wide.
constexpr std::size_t kSlots = 256;
constexpr std::size_t kPathBytes = 4096;
struct Slot {
  std::atomic<bool> used{false};
  std::array<char, kPathBytes> path{};
};
std::array<Slot, kSlots> g_slots;
std::mutex g_register_mutex;

extern "C" void on_interrupt(int signo) {
  for (auto& s : g_slots) {
    if (s.used.load(std::memory_order_acquire)) ::unlink(s.path.data());
  }
  ::_exit(128 + signo);
}

std::string errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

}  // namespace

int register_temporary(const std::filesystem::path& path) noexcept {
  const std::string& text = path.native();
  if (text.size() + 1 > kPathBytes) return -1;
  std::lock_guard lock(g_register_mutex);
  for (std::size_t i = 0; i < kSlots; ++i) {
    if (!g_slots[i].used.load(std::memory_order_relaxed)) {
      std::memcpy(g_slots[i].path.data(), text.c_str(), text.size() + 1);
      g_slots[i].used.store(true, std::memory_order_release);
      return static_cast<int>(i);
    }
  }
  return -1;
}

void unregister_temporary(int slot) noexcept {
  if (slot < 0 || static_cast<std::size_t>(slot) >= kSlots) return;
  std::lock_guard lock(g_register_mutex);
  g_slots[static_cast<std::size_t>(slot)].used.store(false, std::memory_order_release);
}

void install_interrupt_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

OutputFile::OutputFile(std::filesystem::path final_path) : final_(std::move(final_path)) {
  // A directory (or a name ending in '/') can never be replaced by the rename in commit(): refuse it now, before any
  // computation, rather than after (the temporary would otherwise be made beside it, e.g. in '/').
  std::error_code dir_ec;
  if (!final_.has_filename() || std::filesystem::is_directory(final_, dir_ec)) {
    throw OutputError(fmt::format("cannot write '{}': it is a directory (give a file name)", final_.string()));
  }
  const auto dir = final_.parent_path();
  tmp_ = dir / fmt::format(".tmp-{}-{}", static_cast<long>(::getpid()), final_.filename().string());
  slot_ = register_temporary(tmp_);
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    const int err = errno;
    unregister_temporary(slot_);
    slot_ = -1;
    throw OutputError(fmt::format("cannot write '{}': {}", final_.string(), errno_text(err)));
  }
}

OutputFile::~OutputFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(tmp_, ec);
  }
  unregister_temporary(slot_);
}

void OutputFile::commit() {
  out_.flush();
  const bool wrote = static_cast<bool>(out_);
  const int err = errno;
  out_.close();
  std::error_code ec;
  if (!wrote || out_.fail()) {
    std::filesystem::remove(tmp_, ec);
    throw OutputError(fmt::format("cannot write '{}': {}", final_.string(),
                                  err != 0 ? errno_text(err) : std::string("write failed")));
  }
  std::filesystem::rename(tmp_, final_, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp_, ignored);
    throw OutputError(fmt::format("cannot rename '{}' to '{}': {}", tmp_.string(), final_.string(), ec.message()));
  }
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view text) {
  OutputFile f(path);
  f.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
  f.commit();
}

}  // namespace topple::io
