#pragma once
// FFTW's planner is not thread-safe (FFTW manual, sec. 5.2): every plan creation and destruction in the library takes
// this one lock (defined in spectra.cpp); executing a plan on its own arrays does not need it.
#include <mutex>

namespace topple::detail {
[[nodiscard]] std::mutex& fftw_planner_mutex();
}  // namespace topple::detail
