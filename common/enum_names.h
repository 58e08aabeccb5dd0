// One name table per enumeration, the only spelling of its values in config
// files, on the command line, in HDF5 attributes and in CSV output (Ceres
// types.h: ToString/FromString pairs, here generated from the table).
//
// An enumeration declares its table once, next to its declaration (at
// namespace granasym scope, after the enclosing class for a nested enum):
//
//   enum class JacobianKind { kExact, kFiniteDifference };
//   template <>
//   struct EnumNames<JacobianKind> {
//     static constexpr EnumEntry<JacobianKind> kEntries[] = {
//         {JacobianKind::kExact, "exact", "automatic differentiation"},
//         {JacobianKind::kFiniteDifference, "finite_difference"},  // description optional
//     };
//   };
//
// and gets ToString, FromString, AllowedNames, EnumValues and EnumEntries here,
// ConfigTable::GetEnum (common/config.h) and AddEnumOption (app/enum_option.h).
// The table order is the order of messages and help texts. Using any of these
// for an enumeration without a table, or with a repeated value or name, is a
// compile error (static_assert) that names EnumNames.
//
// Lookup: the functions are templates in namespace granasym, found by ADL for
// enumerations declared there; a nested namespace (granasym::calibration)
// brings them in with `using granasym::ToString;` and `using
// granasym::FromString;`. A non-template ToString(E) of a namespace (dem/)
// stays the better match for its own enumerations.
#pragma once

#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace granasym {

template <typename E>
struct EnumEntry {
  E value;
  const char* name;              // snake_case; never empty
  const char* description = "";  // one line for help texts; may be empty
};

// Specialise with `static constexpr EnumEntry<E> kEntries[] = {...};`. The
// primary template has no table.
template <typename E>
struct EnumNames {};

namespace enum_names_internal {

template <typename E, typename = void>
struct HasTable : std::false_type {};
template <typename E>
struct HasTable<E, std::void_t<decltype(EnumNames<E>::kEntries)>> : std::true_type {};

template <typename E>
constexpr bool IsConsistent() {
  const auto& entries = EnumNames<E>::kEntries;
  for (size_t i = 0; i < std::size(entries); ++i) {
    if (entries[i].name == nullptr || std::string_view(entries[i].name).empty()) return false;
    if (entries[i].description == nullptr) return false;
    for (size_t j = 0; j < i; ++j) {
      if (entries[i].value == entries[j].value) return false;
      if (std::string_view(entries[i].name) == std::string_view(entries[j].name)) return false;
    }
  }
  return true;
}

template <typename E>
inline constexpr EnumEntry<E> kNoEntries[1] = {{E{}, "unknown"}};

}  // namespace enum_names_internal

// The table of E, checked at compile time.
template <typename E>
constexpr const auto& EnumEntries() {
  static_assert(std::is_enum_v<E>, "EnumNames tables are for enumerations");
  static_assert(enum_names_internal::HasTable<E>::value,
                "no name table for this enumeration: specialise granasym::EnumNames<E> next to "
                "its declaration (common/enum_names.h)");
  if constexpr (enum_names_internal::HasTable<E>::value) {
    static_assert(enum_names_internal::IsConsistent<E>(),
                  "granasym::EnumNames<E>::kEntries repeats a value or a name, or has an empty "
                  "name");
    return EnumNames<E>::kEntries;
  } else {
    return enum_names_internal::kNoEntries<E>;  // only reached after the static_assert above
  }
}

// The name of `value`; "unknown" for a value missing from the table.
template <typename E, typename = std::enable_if_t<std::is_enum_v<E>>>
constexpr const char* ToString(E value) {
  for (const auto& entry : EnumEntries<E>()) {
    if (entry.value == value) return entry.name;
  }
  return "unknown";
}

// The one-line description of `value` ("" when the table gives none).
template <typename E, typename = std::enable_if_t<std::is_enum_v<E>>>
constexpr const char* EnumDescription(E value) {
  for (const auto& entry : EnumEntries<E>()) {
    if (entry.value == value) return entry.description;
  }
  return "";
}

// The value named `name` (exact, case-sensitive match); nullopt when unknown.
template <typename E>
constexpr std::optional<E> FromString(std::string_view name) {
  for (const auto& entry : EnumEntries<E>()) {
    if (name == entry.name) return entry.value;
  }
  return std::nullopt;
}

// Ceres style: false (and `*value` untouched) when `name` is unknown.
template <typename E, typename = std::enable_if_t<std::is_enum_v<E>>>
bool FromString(std::string_view name, E* value) {
  const std::optional<E> parsed = FromString<E>(name);
  if (parsed) *value = *parsed;
  return parsed.has_value();
}

// Every value, in table order.
template <typename E>
std::vector<E> EnumValues() {
  std::vector<E> values;
  for (const auto& entry : EnumEntries<E>()) values.push_back(entry.value);
  return values;
}

// The names of `values` for messages: "a", "a or b", "a, b or c".
template <typename E>
std::string AllowedNames(const std::vector<E>& values) {
  std::string text;
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) text += i + 1 == values.size() ? " or " : ", ";
    text += ToString(values[i]);
  }
  return text;
}

// The names of all values of E, e.g. "exact or finite_difference".
template <typename E>
std::string AllowedNames() {
  return AllowedNames(EnumValues<E>());
}

}  // namespace granasym
