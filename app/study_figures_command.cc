// `granasym study figures DIR [--out OUT] [--only STEM]... [--level X]...`:
// writes the figure data (analysis/figure_data.h) under OUT/figures/data/
// (OUT is DIR unless --out names another folder), draws every figure with
// the gnuplot scripts of plots/study/ (copied to OUT/figures/scripts/, run
// through OUT/figures/<stem>.plt) into OUT/figures/<stem>.png, .pdf and
// .svg, and writes OUT/figures/index.tsv (a figure that could not be drawn
// has the reason in its caption). What is drawn comes from study.toml's
// [figures] table (the programme's), each flag overriding its key
// (study/figure_settings.h).
#include "app/study_figures_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/figure_data.h"
#include "app/figure_drawing.h"
#include "common/error.h"
#include "common/stopwatch.h"

namespace granasym {
namespace {
namespace fs = std::filesystem;

struct FiguresFlags {
  std::string directory, out;
  study::FigureSettings settings;  // the flags' settings (unset: study.toml's)
  std::vector<double> fig18_level;
  std::vector<std::string> models;
  bool data_only = false;
};

void RunFigures(FiguresFlags flags) {
  const Stopwatch clock;
  analysis::FigureDataOptions options;
  options.settings = study::FigureSettings::FromFile(flags.directory + "/study.toml");
  if (!flags.fig18_level.empty()) flags.settings.fig18_level = flags.fig18_level.front();
  if (!flags.models.empty()) {
    if (flags.models == std::vector<std::string>{"none"}) flags.models.clear();
    for (const std::string& model : flags.models) {
      if (std::find(study::kFigureModels.begin(), study::kFigureModels.end(), model) ==
          study::kFigureModels.end()) {
        throw InputError("--model " + model +
                         ": not a calibrated model (hypoplastic_clay, modified_cam_clay, "
                         "hypoplastic_sand, or none)");
      }
    }
    flags.settings.models = flags.models;
  }
  options.settings.Override(flags.settings);
  options.out = flags.out.empty() ? flags.directory : flags.out;
  std::vector<analysis::FigureSpec> figures = analysis::WriteFigureData(flags.directory, options);
  // A name in `only` that is no figure of this study is a mistake, not an empty drawing.
  for (const std::string& name : options.settings.only) {
    if (std::none_of(figures.begin(), figures.end(), [&](const analysis::FigureSpec& f) {
          return f.stem == name || f.figure == name;
        })) {
      std::string valid;
      for (const analysis::FigureSpec& f : figures) valid += (valid.empty() ? "" : ", ") + f.stem;
      throw InputError("--only " + name + ": no figure of this study has that stem or number (" +
                       valid + ")");
    }
  }
  std::vector<analysis::FigureSpec> drawn_now;
  for (const analysis::FigureSpec& f : figures) {
    if (options.settings.IncludesFigure(f.stem, f.figure)) drawn_now.push_back(f);
  }
  const int failed = DrawFigures(options.out, &drawn_now, flags.data_only);
  for (analysis::FigureSpec& f : figures) {
    for (const analysis::FigureSpec& d : drawn_now) {
      if (d.stem == f.stem) f = d;
    }
  }
  analysis::WriteFigureIndex(options.out, figures);
  const long drawn =
      flags.data_only
          ? 0
          : std::count_if(drawn_now.begin(), drawn_now.end(),
                          [](const analysis::FigureSpec& f) { return f.not_drawn.empty(); });
  std::printf("%ld figures drawn, %d failed, in %.1f s; index: %s/figures/index.tsv\n", drawn,
              failed, clock.Seconds(), options.out.c_str());
  if (failed > 0) throw CLI::RuntimeError(4);
}

}  // namespace

void RegisterStudyFiguresCommand(CLI::App* study) {
  static FiguresFlags flags;
  CLI::App* figures = study->add_subcommand(
      "figures",
      "the paper's figures from a study folder: DIR/figures/<stem>.png, .pdf and .svg, their data "
      "under DIR/figures/data/, captions in DIR/figures/index.tsv");
  figures->add_option("dir", flags.directory, "study folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  figures->add_option("--out", flags.out,
                      "draw into OUT/figures/ instead of DIR/figures/ (the study is only read)");
  figures->add_option("--only", flags.settings.only,
                      "draw only these figures: stems (fig16_asymptotic_states) or paper "
                      "numbers (16)");
  figures
      ->add_option("--level", flags.settings.levels,
                   "ln(1+e) of an ASBS cross-section of Fig. 17 (repeat for several; "
                   "default: chosen from the states)")
      ->check(CLI::Range(0.0, 1.5));
  figures
      ->add_option("--fig18-level", flags.fig18_level,
                   "ln(1+e) of Fig. 18's cross-section (default: the level of the OC "
                   "ψ_ε = 90° path)")
      ->expected(1)
      ->check(CLI::Range(0.0, 1.5));
  figures->add_option("--case", flags.settings.cases,
                      "draw only cases whose name matches (shell pattern, e.g. 'nc*'; repeat)");
  figures->add_option("--exclude-case", flags.settings.exclude_cases,
                      "leave out cases whose name matches (shell pattern; repeat)");
  figures->add_option("--model", flags.models,
                      "overlay only these calibrated models (repeat; 'none' for none)");
  figures->add_flag("--replicates", flags.settings.replicates,
                    "draw every replicate's path under the ensemble mean");
  figures->add_flag("--data-only", flags.data_only, "write the data and the index, draw nothing");
  figures->callback([] { RunFigures(flags); });
}

}  // namespace granasym
