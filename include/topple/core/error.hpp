#pragma once
// Errors that topple throws at its callers.
//
// Caller input (a file, a command-line value, a numpy array) that cannot be used throws InputError, whose message
// names where the problem is (file, line, field) and what it is. The CLI turns it into exit status 2; the Python
// package into topple.InputError. Internal invariants are asserts, not exceptions.
//
// A solver that stops at one of its limits (steps, events, root-finder iterations) throws a SolverError naming the
// limit and the parameters that caused it; a file that cannot be written (disk full, permission) throws an
// OutputError. Each has its own exit status (ExitStatus below; the CLI's documented contract).
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace topple {

/// The `topple` command's exit statuses (README "Exit status"). Other front ends map the same exceptions.
enum class ExitStatus : int {
  success = 0,
  internal_error = 1,   ///< a bug: an exception that is none of the kinds below
  bad_input = 2,        ///< InputError
  solver_limit = 3,     ///< SolverError: a step, event or iteration limit reached
  output_failure = 4,   ///< OutputError: a result could not be written (disk full, permission, I/O error)
  interrupted = 130,    ///< SIGINT (128 + 2); SIGTERM gives 143 (128 + 15)
};

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

/// A solver reached one of its limits (max steps, max events, root-finder iterations) before the end of the motion.
/// The message quotes the limit and the parameters that led to it. Derived types name the limit kind.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The kinds of solver limit (after Boost.Odeint's step_adjustment_error / no_progress_error). Each message says
// which limit (by its option name), its value, where in time it was reached and the parameters of the run.

/// More integrator steps than the caller's cap (RockingOptions::max_steps).
class StepLimitError : public SolverError {
 public:
  using SolverError::SolverError;
};

/// More events (slip starts and stops, impacts, uplifts) inside one sample interval, or without time advancing, than
/// the solver's cap: a sign of an input outside the model (e.g. accelerations of 1e300 g).
class EventLimitError : public SolverError {
 public:
  using SolverError::SolverError;
};

/// A root finder (TOMS 748, or bracketed Newton on a dense polynomial, for events) used up its iterations without
/// bracketing the root to its tolerance.
class RootFindingError : public SolverError {
 public:
  using SolverError::SolverError;
};

/// A search over many solver runs (an overturning-amplitude scan) reached its cap on runs (ThresholdSearch::max_runs).
class SearchLimitError : public SolverError {
 public:
  using SolverError::SolverError;
};

/// A result file could not be written or renamed into place (disk full, permission denied, I/O error). The message
/// names the path and the system's reason. Never a partial file under the final name (io/output_file.hpp).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Convenience: an InputError about a named parameter (no file).
[[nodiscard]] InputError parameter_error(const std::string& field, const std::string& problem);

/// Throws parameter_error(field, "<what> must be positive and finite, got <value>") unless 0 < value < inf.
void require_positive(double value, const char* field, const char* what);

/// Calls `f()`; an InputError it throws about a parameter (no file) whose field the library named `from` in one of
/// `names` is thrown again as parameter_error(to, problem): the name the caller typed (a CLI option, a Python keyword).
/// Any other error passes unchanged. The front ends use it so that every message names what the user wrote.
template <class F>
auto with_field_names(std::initializer_list<std::pair<std::string_view, std::string_view>> names, F&& f)
    -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    if (!e.where().file.empty()) throw;
    for (const auto& [from, to] : names) {
      if (e.where().field == from) throw parameter_error(std::string(to), e.problem());
    }
    throw;
  }
}

}  // namespace topple
