#pragma once
// Enum <-> text, one way for every enum the library names: a constexpr table of (value, name) per enum beside its
// name function, and one lookup. A value that is in no table (an integer cast to the enum) is "unknown", the same
// fallback everywhere; the parsers keep their own aliases and messages and may read the same table.
#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace topple {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

/// The name of `value` in `table`, "unknown" when it is not there.
template <class E, std::size_t N>
[[nodiscard]] constexpr std::string_view enum_name(const std::array<EnumName<E>, N>& table, E value) noexcept {
  for (const EnumName<E>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "unknown";
}

/// The value named `name` in `table`, none when no entry has that name.
template <class E, std::size_t N>
[[nodiscard]] constexpr std::optional<E> enum_from_name(const std::array<EnumName<E>, N>& table,
                                                        std::string_view name) noexcept {
  for (const EnumName<E>& entry : table) {
    if (entry.name == name) return entry.value;
  }
  return std::nullopt;
}

}  // namespace topple
