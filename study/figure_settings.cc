#include "study/figure_settings.h"

#include <fmt/format.h>
#include <fnmatch.h>

#include <algorithm>
#include <filesystem>

#include "common/config.h"
#include "common/error.h"
#include "common/key_table.h"
#include "common/text_file.h"

namespace granasym::study {

const std::vector<std::string> kFigureModels = {"hypoplastic_clay", "modified_cam_clay",
                                                "hypoplastic_sand"};

namespace {

// ln(1+e) of a granular packing lies well inside (0, 1.5): e from 0 to 3.5.
constexpr Range kLevelRange = {0.0, 1.5, false, true};

std::string TomlList(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + TomlQuoted(item);
  return "[" + text + "]";
}

bool Matches(const std::vector<std::string>& patterns, const std::string& name) {
  return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& pattern) {
    return fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
  });
}

}  // namespace

const KeyTable& FigureKeys() {
  auto strings = [](const char* key, const char* valid, const char* fallback, const char* meaning) {
    return KeySpec{"figures", key,      KeyType::kStrings, "", Range::Any(),
                   valid,     fallback, meaning,           ""};
  };
  static const KeyTable table(
      "figures",
      "the [figures] table of a programme (kept in the study's study.toml): what `granasym "
      "study figures` draws; its flags override it key by key, and no key changes a case",
      {
          {"figures", "levels", KeyType::kNumbers, "", kLevelRange, "", "chosen from the data",
           "ln(1+e) of the ASBS cross-sections (Fig. 17)", ""},
          {"figures", "fig18_level", KeyType::kNumber, "", kLevelRange, "",
           "the level of the OC psi_epsilon = 90 deg path", "ln(1+e) of Fig. 18's cross-section",
           ""},
          strings("cases", "case names or shell patterns", "every case", "the cases drawn"),
          strings("exclude_cases", "case names or shell patterns", "none",
                  "cases left out (after `cases`)"),
          strings("only", "paper figure numbers or file stems (e.g. 10, fig16_asymptotic_states)",
                  "every figure", "the figures drawn"),
          strings("models", "hypoplastic_clay, modified_cam_clay, hypoplastic_sand; [] for none",
                  "every calibrated model", "the calibrated models overlaid"),
          {"figures", "replicates", KeyType::kBool, "", Range::Any(), "true or false", "false",
           "draw every replicate's path under the mean", ""},
      });
  return table;
}

FigureSettings FigureSettings::FromConfig(const ConfigTable& table) {
  table.UseKeys({&FigureKeys()});
  FigureSettings s;
  if (table.Has("levels")) s.levels = table.GetDoubles("levels", kLevelRange);
  if (table.Has("fig18_level")) s.fig18_level = table.GetDouble("fig18_level", kLevelRange);
  if (table.Has("cases")) s.cases = table.GetStrings("cases");
  if (table.Has("exclude_cases")) s.exclude_cases = table.GetStrings("exclude_cases");
  if (table.Has("only")) s.only = table.GetStrings("only");
  if (table.Has("models")) {
    s.models = table.GetStrings("models");
    for (const std::string& model : *s.models) {
      if (std::find(kFigureModels.begin(), kFigureModels.end(), model) == kFigureModels.end()) {
        table.Fail("models", "names '" + model + "', not a calibrated model: expected any of " +
                                 TomlList(kFigureModels) + " (or [] for none)");
      }
    }
  }
  s.replicates = table.GetBool("replicates", false);
  for (const std::string& pattern : s.cases) {
    if (pattern.empty()) table.Fail("cases", "holds an empty pattern: give case names or globs");
  }
  table.CheckNoUnknownKeys();
  return s;
}

FigureSettings FigureSettings::FromFile(const std::string& path) {
  if (!std::filesystem::exists(path)) return {};
  const ConfigTable file = ConfigTable::ParseFile(path);
  if (!file.Has("figures")) return {};
  return FromConfig(file.GetTable("figures"));
}

std::string FigureSettings::ToToml() const {
  std::string text;
  if (!levels.empty()) {
    std::string list;
    for (double v : levels) list += (list.empty() ? "" : ", ") + fmt::format("{}", v);
    text += "levels = [" + list + "]\n";
  }
  if (fig18_level) text += fmt::format("fig18_level = {}\n", *fig18_level);
  if (!cases.empty()) text += "cases = " + TomlList(cases) + "\n";
  if (!exclude_cases.empty()) text += "exclude_cases = " + TomlList(exclude_cases) + "\n";
  if (!only.empty()) text += "only = " + TomlList(only) + "\n";
  if (models) text += "models = " + TomlList(*models) + "\n";
  if (replicates) text += "replicates = true\n";
  return text.empty() ? "" : "[figures]\n" + text;
}

void FigureSettings::Override(const FigureSettings& other) {
  if (!other.levels.empty()) levels = other.levels;
  if (other.fig18_level) fig18_level = other.fig18_level;
  if (!other.cases.empty()) cases = other.cases;
  if (!other.exclude_cases.empty()) exclude_cases = other.exclude_cases;
  if (!other.only.empty()) only = other.only;
  if (other.models) models = other.models;
  if (other.replicates) replicates = true;
}

bool FigureSettings::IncludesCase(const std::string& name) const {
  if (!cases.empty() && !Matches(cases, name)) return false;
  return !Matches(exclude_cases, name);
}

bool FigureSettings::IncludesFigure(const std::string& stem, const std::string& figure) const {
  if (only.empty()) return true;
  return std::find(only.begin(), only.end(), stem) != only.end() ||
         std::find(only.begin(), only.end(), figure) != only.end();
}

bool FigureSettings::Overlays(const std::string& name) const {
  return !models || std::find(models->begin(), models->end(), name) != models->end();
}

}  // namespace granasym::study
