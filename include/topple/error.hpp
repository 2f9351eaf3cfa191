#pragma once
// Errors that topple throws at its callers.
//
// Caller input (a file, a command-line value, a numpy array) that cannot be used throws InputError, whose message
// names where the problem is (file, line, field) and what it is. The CLI turns it into exit status 2; the Python
// package into topple.InputError. Internal invariants are asserts, not exceptions.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

namespace topple {

/// Where in the caller's input a problem sits. Every part is optional: a command-line option has a field but no
/// file; a reader error has a file and a line.
struct InputLocation {
  std::string file;                ///< path as given by the caller; empty when not from a file
  std::optional<std::size_t> line; ///< 1-based line number in `file`
  std::string field;               ///< option, key or column name (e.g. "--mu", "NPTS", "object[2].width")
};

/// Bad caller input: malformed file, inconsistent header, out-of-range parameter.
class InputError : public std::runtime_error {
 public:
  InputError(InputLocation where, const std::string& problem);
  explicit InputError(const std::string& problem) : InputError(InputLocation{}, problem) {}

  [[nodiscard]] const InputLocation& where() const noexcept { return where_; }
  [[nodiscard]] const std::string& problem() const noexcept { return problem_; }

 private:
  InputLocation where_;
  std::string problem_;
};

/// Convenience: an InputError about a named parameter (no file).
[[nodiscard]] InputError parameter_error(const std::string& field, const std::string& problem);

}  // namespace topple
