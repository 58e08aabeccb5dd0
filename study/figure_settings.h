// What a user chooses about a study's figures, from the programme's
// [figures] table (kept in the study folder's study.toml) or from the flags
// of `granasym study figures`, which override it key by key:
//
//   [figures]
//   levels = [0.53, 0.56]         # ln(1+e) of the ASBS cross-sections (Fig. 17)
//   fig18_level = 0.55            # ln(1+e) of Fig. 18's cross-section
//   cases = ["nc*", "oc20_*"]     # case names drawn (shell patterns); default all
//   exclude_cases = ["*_psi150"]  # case names left out (after `cases`)
//   only = ["10", "fig16_asymptotic_states"]  # figures drawn (paper numbers or stems)
//   models = ["hypoplastic_clay"] # calibrated models overlaid; [] for none
//   replicates = true             # draw every replicate's path under the mean
//
// No key is a computation input: changing them changes no case key.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace granasym {
class ConfigTable;
class KeyTable;
}  // namespace granasym

namespace granasym::study {

// The calibrated models a study can overlay, in the order figures draw them.
extern const std::vector<std::string> kFigureModels;

// The keys of the [figures] table (common/key_table.h; `granasym keys figures`).
const KeyTable& FigureKeys();

struct FigureSettings {
  std::vector<double> levels;         // empty: chosen from the data
  std::optional<double> fig18_level;  // absent: the level of the OC ψ_ε = 90° path
  std::vector<std::string> cases;     // empty: every case
  std::vector<std::string> exclude_cases;
  std::vector<std::string> only;                   // empty: every figure
  std::optional<std::vector<std::string>> models;  // absent: every calibrated model
  bool replicates = false;

  // Reads the keys of `table` (the [figures] table); InputError naming the
  // key, the value and what is valid.
  static FigureSettings FromConfig(const ConfigTable& table);
  // The [figures] table of a TOML file (absent: the defaults).
  static FigureSettings FromFile(const std::string& path);
  // The keys that differ from the defaults, as TOML lines under a
  // [figures] header ("" when every key is at its default).
  std::string ToToml() const;
  // `other`'s keys that are set (non-default) replace this one's.
  void Override(const FigureSettings& other);

  // Whether a case named `name` is drawn (`cases`, then `exclude_cases`).
  bool IncludesCase(const std::string& name) const;
  // Whether the figure `stem` (paper figure `figure`, e.g. "10", "Sec. 5.2")
  // is drawn.
  bool IncludesFigure(const std::string& stem, const std::string& figure) const;
  // Whether the model `name` is overlaid.
  bool Overlays(const std::string& name) const;
};

}  // namespace granasym::study
