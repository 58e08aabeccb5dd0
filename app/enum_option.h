// Command-line options that take an enumeration, spelled as in its name table
// (common/enum_names.h), so that flags, config files and results agree.
//
//   JacobianKind jacobian = JacobianKind::kExact;
//   AddEnumOption(run, "--jacobian", &jacobian, "Jacobian of the implicit integrators");
//
// gives `--jacobian exact|finite_difference` with the default and each name's
// description in --help; any other value fails to parse with the allowed names.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <type_traits>

#include "common/enum_names.h"

namespace granasym {

// A CLI11 transform that turns a table name into the value CLI11 stores in an
// enumeration option (its underlying integer); integers and unknown names are
// rejected, naming the allowed names.
template <typename E>
CLI::Validator EnumNameTransformer() {
  std::string names;
  for (const auto& entry : EnumEntries<E>())
    names += (names.empty() ? "" : "|") + std::string(entry.name);
  return CLI::Validator(
      [](std::string& input) -> std::string {
        const std::optional<E> value = FromString<E>(input);
        if (!value) return "'" + input + "' is not valid: expected " + AllowedNames<E>();
        input = std::to_string(static_cast<std::underlying_type_t<E>>(*value));
        return std::string();
      },
      names, "ENUM NAME");
}

// Adds `name` to `app`, storing into `*value` (whose current value is the
// default shown in --help); the help text lists the names with their
// descriptions where the table gives them.
template <typename E>
CLI::Option* AddEnumOption(CLI::App* app, const std::string& name, E* value,
                           const std::string& description) {
  std::string help = description;
  for (const auto& entry : EnumEntries<E>()) {
    if (std::string(entry.description).empty()) continue;
    help += std::string("\n  ") + entry.name + ": " + entry.description;
  }
  return app->add_option(name, *value, help)
      ->transform(EnumNameTransformer<E>())
      ->type_name("NAME")
      ->default_str(ToString(*value));
}

}  // namespace granasym
