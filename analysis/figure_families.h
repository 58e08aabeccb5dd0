// The figure families of analysis/figure_data.h, each a file that turns the
// study folder (figures::Context) into its figures' data files and entries
// of figures/index.tsv; WriteFigureData calls them in the paper's order.
// Internal to the analysis library.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "analysis/figure_context.h"
#include "analysis/rate_study.h"

namespace granasym::analysis::figures {

// figure_data.cc: the models' element tests (Fig. 5): the programme's
// [[model_run]]s, and the calibrated models' paths A, B, C.
FigureSpec Fig05(const Context& ctx);
std::vector<FigureSpec> Fig05Calibrated(const Context& ctx);

// figure_paths.cc: the DEM's paths (paper Sec. 4): the isotropic NCL with
// its unload/reload cycles (Fig. 9), the families of isochoric, drained
// triaxial, compression and extension paths with their asymptotic states
// (Figs. 10, 11, 13–15), and the drained paths against shear strain (Fig. 12).
FigureSpec Fig09(const Context& ctx);
struct FamilySpec {
  std::string figure, stem, title, what;
  // States of other cases drawn for reference (grey squares), by kind.
  std::vector<std::pair<TableKind, std::string>> reference_kinds;
  bool draw_csl = false;  // the CSL fit in panel (b), besides the NCL
};
FigureSpec PathFamily(const Context& ctx, const FamilySpec& family);
FigureSpec Fig12(const Context& ctx);

// figure_states.cc: the asymptotic states together (Fig. 16), the ASBS's
// constant-e cross-sections (Figs. 17, 18) and the stretching directions
// along drained triaxial paths (Fig. 19), with the calibrated models.
FigureSpec Fig16(const Context& ctx);
FigureSpec Fig17(const Context& ctx);
FigureSpec Fig18(const Context& ctx);
FigureSpec Fig19(const Context& ctx);

// figure_checks.cc: the checks of the DEM (paper Sec. 5): overlaps along
// the NCL (Fig. 8), contact friction (Fig. 20), the time step (Sec. 5.2) and
// the inertial number (Figs. 21, 22).
FigureSpec Fig08(const Context& ctx);
FigureSpec Fig20(const Context& ctx);
FigureSpec Sec52(const Context& ctx);
FigureSpec Fig21(const Context& ctx);
FigureSpec Fig22(const Context& ctx);

// figure_rate.cc: the rate study's figures rate (a)–(e) (analysis/rate_study.h).
FigureSpec RatePsiSigma(const Context& ctx, const RateStudy& rate);
FigureSpec RateLines(const Context& ctx, const RateStudy& rate);
FigureSpec RateCriticalState(const Context& ctx, const RateStudy& rate);
FigureSpec RateExtension(const Context& ctx, const RateStudy& rate);
FigureSpec RateAgainstModels(const Context& ctx, const RateStudy& rate);

}  // namespace granasym::analysis::figures
