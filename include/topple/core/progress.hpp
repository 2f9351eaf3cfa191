#pragma once
// Progress of a long computation (an inversion, a fragility analysis, an overturning map, a sweep), reported by the
// library to whoever draws it: the library never prints, the front end (the CLI's progress bar on a terminal,
// nothing otherwise) decides what to show.
#include <cstddef>
#include <functional>

namespace topple {

/// Called from worker threads, possibly concurrently (keep it cheap and thread-safe), after each batch of runs with
/// the number of runs done and the number to do. Empty: no report.
using ProgressCallback = std::function<void(std::size_t done, std::size_t total)>;

}  // namespace topple
