// The names of an enum's values as data: one constexpr table per enum serves its to_string,
// its parsing, the lists of valid names in error messages, and through to_string the archive's
// HDF5 enum types and JSON. A hand-written switch per direction could disagree with its inverse;
// one table cannot. Here in the lowest layer so that every layer can name its enums with it.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace gjklab {

/// One row of a name table.
template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

/// A name table: one row per enumerator, in value order from 0 without gaps (checked with
/// in_value_order), so that naming a value is an index. Written with std::to_array:
///   inline constexpr auto kColourNames = std::to_array<EnumName<Colour>>({{Colour::red, "red"}});
template <class E, std::size_t N>
using EnumNames = std::array<EnumName<E>, N>;

/// Whether row i names value i for every row: the table's order is the enum's.
template <class E, std::size_t N>
constexpr bool in_value_order(const EnumNames<E, N>& names) {
  for (std::size_t i = 0; i < N; ++i)
    if (static_cast<std::size_t>(names[i].value) != i) return false;
  return true;
}

/// Whether the table ends at `last`, the enum's last enumerator (with in_value_order: every
/// enumerator has its row).
template <class E, std::size_t N>
constexpr bool ends_at(const EnumNames<E, N>& names, E last) {
  return N > 0 && names[N - 1].value == last;
}

/// The value's name, or "unknown" for a value past the table (a corrupt or foreign byte).
template <class E, std::size_t N>
constexpr std::string_view name_of(const EnumNames<E, N>& names, E value) {
  const auto i = static_cast<std::size_t>(value);
  return i < N ? names[i].name : "unknown";
}

/// The value with this name, or nothing.
template <class E, std::size_t N>
constexpr std::optional<E> value_named(const EnumNames<E, N>& names, std::string_view name) {
  for (const EnumName<E>& row : names)
    if (row.name == name) return row.value;
  return std::nullopt;
}

/// Every value of the table, in its order.
template <class E, std::size_t N>
constexpr std::array<E, N> values_of(const EnumNames<E, N>& names) {
  std::array<E, N> values{};
  for (std::size_t i = 0; i < N; ++i)
    values[i] = names[i].value;
  return values;
}

/// "a, b, c": the valid names, for error messages.
template <class E, std::size_t N>
std::string names_list(const EnumNames<E, N>& names, std::string_view separator = ", ") {
  std::string out;
  for (const EnumName<E>& row : names) {
    if (!out.empty()) out += separator;
    out += row.name;
  }
  return out;
}

}  // namespace gjklab
