#pragma once
// A field of a result type: its name (with its unit, e.g. "residual_displacement_m") and how to read it from a
// result. A result type has one table of fields (topple/solvers/summary_fields.hpp), and every writer reads the table: the
// JSON objects (topple/output/write.hpp), the columns of a sweep (topple/ensemble/sweep.hpp) and the Python properties, so a
// field is named, converted and documented in one place.
#include <cstdint>
#include <string>
#include <variant>

namespace topple {

/// One value of a result: null (does not apply: a first slip that never happened), boolean, integer, double or
/// text. The ensemble engine's cells are the same type (ensemble::Value).
using FieldValue = std::variant<std::monostate, bool, std::int64_t, double, std::string>;

template <class Result>
struct Field {
  const char* name;                       ///< with its unit, as the JSON key, the CSV column and the Python property
  FieldValue (*get)(const Result& result);
  /// Position among a sweep's result columns (topple sweep), or -1 when the field is not a sweep result (an input
  /// echoed in the JSON, such as the friction coefficient, which a sweep writes among its object columns). The
  /// sweep's order predates the table and is part of its output format, hence its own position here.
  int sweep_column = -1;
};

}  // namespace topple
