// A study programme: one TOML file that declares the sample, the shared
// preparation states and the cases that branch from them, with lists that
// expand into cases. Layout (every key with its meaning: `granasym keys programme`):
//
//   [study]
//   name = "paper"
//   description = "..."     # optional: a line about the programme (read, not used)
//   ncl = "ncl"             # the run whose ψ_ε = 0° stages give the study's NCL (OCR, p_e*)
//   [scale.tiny]            # the sphere count (and so the cell) and the replicates
//   count = 300
//   replicates = 2          # samples with seeds seed, seed + 1, ...
//   [scale.tiny.only]       # optional: the values of `vary` and `each` lists kept at
//   p = [20]                #   this scale (a list left empty drops its run's cases)
//   [scale.tiny.variables]  # optional: placeholders {var} with a value per scale; every
//   strain_cap = 0.1        #   scale defines the same names
//   [sample]                # the generated sample, at the reference count and cell
//   reference_count = 150000
//   reference_cell_size_mm = 31.0
//   seed = 1
//   gsd = "table.csv"       # optional; default: the reduced Zbraslav GSD
//   max_attempts = 200000   # optional: placements tried per sphere (as in a scene)
//   [scene.material]        # scene tables shared by every run (material, numerics, output)
//   [[run]]
//   name = "nc{p}_psi{psi}" # placeholders {var} take the values of `vary`
//   from = "ncl@p{p}"       # "sample", "RUN" (its final state) or "RUN@STAGE"
//   vary = { p = [20, 50], psi = [30, 60] }   # every combination is one case
//   figures = "14"
//   [run.scene.material]    # optional overrides of the shared scene tables
//   [[run.stage]]           # scene [[stage]] tables; `each = { p = [...] }`
//   ...                     # repeats one stage for every value
//   [[model_run]]           # a constitutive-model element test (Fig. 5): name, vary,
//   [model_run.model] ...   # figures, and the tables of `granasym model run`
//   [figures]               # optional: ASBS levels, cases, models of the figures
//                           # (study/figure_settings.h; kept in study.toml)
//
// A string that is exactly "{var}" becomes the variable's value with its
// type (a number stays a number); "{var}" inside a longer string is replaced
// by the value's shortest exact decimal text.
//
// A programme is expanded at one scale: `only` keeps the values of every
// list of that variable that it names (a value that no list holds, or a
// variable that no list varies, is an error: a misspelt restriction would
// otherwise run the whole programme), and the scale's `variables` are
// defined in every run, stage and scene table (a `vary` or `each` variable
// of the same name is an error).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "study/case_record.h"
#include "study/figure_settings.h"

namespace granasym {
class KeyTable;
}  // namespace granasym

namespace granasym::study {

enum class Scale { kTiny, kSmall, kMedium, kPaper };
}  // namespace granasym::study

template <>
struct granasym::EnumNames<granasym::study::Scale> {
  static constexpr EnumEntry<study::Scale> kEntries[] = {
      {study::Scale::kTiny, "tiny", "the whole programme in well under two minutes (CI)"},
      {study::Scale::kSmall, "small", "a few thousand spheres: the default main job"},
      {study::Scale::kMedium, "medium",
       "tens of thousands of spheres: between the main job and the paper (e.g. noise.toml)"},
      {study::Scale::kPaper, "paper", "the paper's 150 000 spheres in a 31 mm cell"},
  };
};

namespace granasym::study {

using granasym::FromString;
using granasym::ToString;

struct ScaleSpec {
  int64_t count = 0;   // spheres
  int replicates = 1;  // samples with different seeds
  // [scale.<name>.only]: list variable → the values kept (as text).
  std::map<std::string, std::vector<std::string>> only;
  // [scale.<name>.variables]: placeholder → value (as text).
  std::map<std::string, std::string> variables;
};

// The generated sample. The cell side scales with the count at constant
// initial porosity: L = L_ref (count / count_ref)^(1/3).
struct SampleSpec {
  int64_t reference_count = 150000;
  double reference_cell_size_mm = 31.0;
  int64_t seed = 1;
  std::string gsd_path;  // resolved relative to the programme; empty: the default
  int64_t max_attempts = 200000;
  double CellSizeMm(int64_t count) const;
};

// One expanded case: a DEM run that starts from the sample or from a state
// of another case.
struct CaseSpec {
  std::string name;          // unique within the programme, a valid folder name
  std::string parent;        // case name; empty: the sample
  std::string parent_stage;  // a stage of the parent; empty: its final state
  std::string scene_body;    // the scene's TOML without its [sample] table
  std::vector<std::string> stage_names;
  std::vector<double> stage_psi_epsilon;         // a strain-path stage's ψ_ε (°), else NaN
  std::string run;                               // the name template of the [[run]] it came from
  FigureSet figures;                             // what it serves (checked: study/case_record.h)
  std::map<std::string, std::string> variables;  // `vary` values, as text
};

// One expanded constitutive-model element test (a [[model_run]] entry): the
// TOML of `granasym model run` ([model], [initial], [integration], [[stage]]).
struct ModelCaseSpec {
  std::string name;  // unique among the model runs
  FigureSet figures;
  std::map<std::string, std::string> variables;
  std::string text;
};

// The keys of a programme file (common/key_table.h; `granasym keys
// programme`): the parser refuses a key outside its table's entries here.
const KeyTable& ProgrammeKeys();

struct Programme {
  // A programme's cases are refused above this many (of one `vary`, or in
  // all, at its scale and with its replicates), before anything is planned.
  static constexpr size_t kMaxCases = 100000;
  // A case name is a folder name (with the study folder's path and the
  // replicate's, it must stay within the file system's limits).
  static constexpr size_t kMaxNameLength = 120;
  std::string origin;  // the file
  std::string name, description;
  std::string ncl_case;  // may be empty
  std::map<Scale, ScaleSpec> scales;
  Scale scale = Scale::kTiny;  // the scale the cases are expanded at
  SampleSpec sample;
  std::vector<CaseSpec> cases;  // parents before children, at `scale`
  std::vector<ModelCaseSpec> model_cases;
  FigureSettings figures;  // [figures]: what `study figures` draws (no case depends on it)

  // The programme expanded at `scale` (InputError when it has no such scale).
  static Programme Load(const std::string& path, Scale scale);
  // `base_directory` resolves relative paths (the GSD table).
  static Programme Parse(const std::string& text, const std::string& origin,
                         const std::string& base_directory, Scale scale);
  const CaseSpec* Find(const std::string& name) const;
  const ScaleSpec& At(Scale scale) const;  // InputError when the programme lacks it
  const ScaleSpec& Current() const { return At(scale); }
};

}  // namespace granasym::study
