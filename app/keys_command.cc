#include "app/keys_command.h"

#include <cstdio>
#include <string>
#include <vector>

#include "app/enum_option.h"
#include "common/key_table.h"
#include "dem/scene_keys.h"
#include "study/figure_settings.h"
#include "study/programme.h"
#ifdef GRANASYM_HAVE_CALIBRATION
#include "calibration/calibration_config.h"
#endif

namespace granasym {

void RegisterKeysCommand(CLI::App& app) {
  static std::vector<const KeyTable*> tables = {&dem::SceneKeys(), &dem::StageKeys(),
                                                &study::ProgrammeKeys()};
#ifdef GRANASYM_HAVE_CALIBRATION
  tables.push_back(&calibration::CalibrationKeys());
#endif
  tables.push_back(&study::FigureKeys());
  std::vector<std::string> kinds;
  for (const KeyTable* table : tables) kinds.push_back(table->kind());

  CLI::App* keys = app.add_subcommand(
      "keys",
      "the keys of the input files (unit, valid values, default, meaning), from the tables the "
      "parsers use");
  static std::string kind;
  static KeyFormat format = KeyFormat::kText;
  std::string names;
  for (const std::string& name : kinds) names += (names.empty() ? "" : ", ") + name;
  keys->add_option("kind", kind, "which file's keys: " + names + " (default: all)")
      ->check(CLI::IsMember(kinds));
  AddEnumOption(keys, "--format", &format, "output format");
  keys->callback([] {
    bool first = true;
    for (const KeyTable* table : tables) {
      if (!kind.empty() && table->kind() != kind) continue;
      std::printf("%s%s", first ? "" : "\n", table->Render(format).c_str());
      first = false;
    }
  });
}

}  // namespace granasym
