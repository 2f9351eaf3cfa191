#pragma once
// Result files that are never partial under their final name.
//
// Every file topple writes (CSV, JSON, GeoJSON, HTML, SVG/PNG scripts) goes through OutputFile: the bytes go to a
// temporary file beside the final path (".tmp-<pid>-<name>", same directory so that the rename is atomic on POSIX),
// and commit() flushes, checks and renames it into place. A write that fails (disk full, permission, I/O error)
// throws OutputError (exit status 4) and removes the temporary file; an OutputFile destroyed without commit() (an
// exception on the way) removes it too. install_interrupt_cleanup() makes SIGINT and SIGTERM remove every
// temporary file still open and exit 130 / 143, so no kill but SIGKILL leaves a temporary behind, and none leaves a
// partial file under a final name.
#include <filesystem>
#include <fstream>
#include <string_view>

namespace topple::io {

class OutputFile {
 public:
  /// Opens the temporary file for `final_path`; throws OutputError naming the path when it cannot be created.
  explicit OutputFile(std::filesystem::path final_path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();

  /// The stream to write to (binary mode).
  [[nodiscard]] std::ostream& stream() noexcept { return out_; }
  [[nodiscard]] const std::filesystem::path& final_path() const noexcept { return final_; }
  [[nodiscard]] const std::filesystem::path& temporary_path() const noexcept { return tmp_; }

  /// Flushes, closes and renames the temporary file to the final path. Throws OutputError (and removes the
  /// temporary file) when any write failed or the rename fails.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path tmp_;
  std::ofstream out_;
  int slot_ = -1;  ///< index in the interrupt-cleanup registry, -1 when not registered
  bool committed_ = false;
};

/// Writes `text` to `path` through an OutputFile (temporary name, then rename).
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

/// Installs SIGINT/SIGTERM handlers that unlink every uncommitted OutputFile's temporary file and _exit with
/// 128 + the signal number (130, 143). Call once, early in main(). Idempotent.
void install_interrupt_cleanup();

/// Registers a temporary path created outside OutputFile (e.g. a store's chunk being written) for removal on
/// SIGINT/SIGTERM. Returns a slot for unregister_temporary (-1 when the registry is full: the path is then not
/// cleaned on a signal, never an error). Async-signal-safe cleanup; registration itself takes a mutex.
int register_temporary(const std::filesystem::path& path) noexcept;
void unregister_temporary(int slot) noexcept;

}  // namespace topple::io
