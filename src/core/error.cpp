#include "topple/core/error.hpp"

#include <cmath>

#include <fmt/format.h>

namespace topple {
namespace {

std::string compose(const InputLocation& where, const std::string& problem) {
  std::string prefix;
  if (!where.file.empty()) {
    prefix = where.file;
    if (where.line) prefix += fmt::format(":{}", *where.line);
    prefix += ": ";
  } else if (where.line) {
    prefix = fmt::format("line {}: ", *where.line);
  }
  if (!where.field.empty()) prefix += where.field + ": ";
  return prefix + problem;
}

}  // namespace

InputError::InputError(InputLocation where, const std::string& problem)
    : std::runtime_error(compose(where, problem)), where_(std::move(where)), problem_(problem) {}

InputError parameter_error(const std::string& field, const std::string& problem) {
  return InputError(InputLocation{.file = {}, .line = {}, .field = field}, problem);
}

void require_positive(double value, const char* field, const char* what) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw parameter_error(field, fmt::format("{} must be positive and finite, got {}", what, value));
  }
}

}  // namespace topple
