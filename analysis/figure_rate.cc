// The rate study's figures (rate (a)-(e)): analysis/figure_families.h.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "analysis/figure_families.h"
#include "analysis/quasi_static_selection.h"

namespace granasym::analysis::figures {
namespace {

// Sets `<name>_min` and `<name>_max` for a script's `set xrange`.
void SetRange(FigureSpec* spec, const std::string& name, const AxisRange& range) {
  const auto [lo, hi] = range.Padded();
  spec->variables.emplace_back(name + "_min", fmt::format("{:.8g}", lo));
  spec->variables.emplace_back(name + "_max", fmt::format("{:.8g}", hi));
}

// Colour (linetype) of each rate: the I* ascending, then the constant ‖D‖.
std::map<std::pair<int, double>, int> RateColours(const RateStudy& rate) {
  std::set<std::pair<int, double>> rates;
  for (const RateGroup& g : rate.groups) rates.insert({static_cast<int>(g.key.rule), g.key.rate});
  std::vector<std::pair<int, double>> order(rates.begin(), rates.end());
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    const bool ia = a.first == static_cast<int>(dem::RateRule::kInertial);
    const bool ib = b.first == static_cast<int>(dem::RateRule::kInertial);
    return ia != ib ? ia : a.second < b.second;
  });
  std::map<std::pair<int, double>, int> colours;
  for (size_t k = 0; k < order.size(); ++k) colours[order[k]] = static_cast<int>(k) + 1;
  return colours;
}

std::string RateTitle(int rule, double rate) {
  return RateKey{0, 0, 0, static_cast<dem::RateRule>(rule), rate}.RateLabel();
}

// Gnuplot words ("a b" "c") of the rates' legend titles, in colour order.
std::string RateTitles(const std::map<std::pair<int, double>, int>& colours) {
  std::vector<std::string> titles(colours.size());
  for (const auto& [rate, colour] : colours) {
    titles[static_cast<size_t>(colour - 1)] = RateTitle(rate.first, rate.second);
  }
  std::string words;
  for (const std::string& t : titles) words += (words.empty() ? "\"" : " \"") + t + "\"";
  return words;
}

// The colour of the fixed I* nearest a measured I (the first colour when none).
int NearestRateColour(const std::map<std::pair<int, double>, int>& colours, double inertial) {
  int best = 1;
  double distance = std::numeric_limits<double>::infinity();
  for (const auto& [key, colour] : colours) {
    if (key.first != static_cast<int>(dem::RateRule::kInertial) || !(inertial > 0)) continue;
    const double d = std::abs(std::log(inertial / key.second));
    if (d < distance) distance = d, best = colour;
  }
  return best;
}

double Zeroed(double v) { return std::isfinite(v) ? v : 0.0; }
// The half-width of an interval of a positive value on a log axis: at most
// 0.9 of the value (the lower end stays positive).
double LogHalfWidth(double mean, double half_width) {
  return std::min(Zeroed(half_width), 0.9 * mean);
}

// Point types: filled for the reference Young's modulus, open for others;
// a triangle for ψ_ε = 0°, a circle at 90°, a square beyond (rate_lines.gp).
int DirectionPoint(double psi, bool reference_modulus) {
  const int filled = std::abs(psi) < 1e-6 ? 9 : std::abs(psi - 90) < 1e-6 ? 7 : 5;
  return reference_modulus ? filled : filled - 1;
}

// The note on the moduli of the rate groups and the drained groups.
std::string ModulusNote(const RateStudy& rate, double reference) {
  std::set<double> moduli;
  for (const RateGroup& g : rate.groups) moduli.insert(g.key.youngs_modulus_mpa);
  for (const DrainedGroup& g : rate.drained.groups) moduli.insert(g.youngs_modulus_mpa);
  if (!std::isfinite(reference)) return "";
  std::string others;
  for (double e : moduli) {
    if (e != reference) others += (others.empty() ? "" : ", ") + Short(e);
  }
  return others.empty()
             ? fmt::format("E = {} MPa", Short(reference))
             : fmt::format("filled: E = {} MPa, open: E = {} MPa", Short(reference), others);
}

// The drained cases' materials (drained_study.h, each read from its case's
// scene) and a legend label for each. When E alone varies, a material is
// drawn filled (the reference E) or open and labelled "E = 500 MPa". When
// more varies (the study of what sets M, issue 39 §2: the damping, the
// stiffness ratio, the time step), each material is a series of its own: its
// own colour (from `first_colour`), labelled by the parts in which the
// materials differ ("χ = 0.05, k_t/k_n = 0.3, f = 0.3"), the shared parts in
// the figure's note, and drawn side by side in x (Dodge) so that materials
// measured at one I or p do not hide each other.
struct DrainedMaterials {
  std::map<DrainedMaterial, int> index;  // in map order, from 0
  std::array<bool, 4> varies{};          // E, χ, k_t/k_n, f
  bool beyond_modulus = false;           // anything but E varies
  int first_colour = 1;
  bool Separate() const { return beyond_modulus; }
  static std::string Part(const DrainedMaterial& m, int k) {
    switch (k) {
      case 0:
        return fmt::format("E = {} MPa", Short(std::get<0>(m)));
      case 1:
        return fmt::format("χ = {:g}", std::get<1>(m));
      case 2:
        return fmt::format("k_t/k_n = {:g}", std::get<2>(m));
      default:
        return std::get<3>(m) > 0 ? fmt::format("f = {:g}", std::get<3>(m))
                                  : std::string("a fixed time step");
    }
  }
  // The parts in which the materials differ (E alone when nothing does).
  std::string Text(const DrainedMaterial& m) const {
    if (!beyond_modulus) return Part(m, 0);
    std::string text;
    for (int k = 0; k < 4; ++k) {
      if (varies[static_cast<size_t>(k)]) text += (text.empty() ? "" : ", ") + Part(m, k);
    }
    return text;
  }
  // The parts beyond E that every material shares ("" when none, or when
  // the materials are not separate series).
  std::string Shared() const {
    if (!beyond_modulus || index.empty()) return "";
    std::string text;
    for (int k = 1; k < 4; ++k) {
      if (!varies[static_cast<size_t>(k)]) {
        text += (text.empty() ? "" : ", ") + Part(index.begin()->first, k);
      }
    }
    return text;
  }
  int Colour(const DrainedMaterial& m) const { return first_colour + index.at(m); }
  // A point type: the filled triangle, open for another E when E alone varies.
  double Point(bool reference) const { return beyond_modulus || reference ? 9.0 : 8.0; }
  // The factor by which material m's x is drawn: 4 % apart on a log axis,
  // centred; 1 when the materials are not separate series.
  double Dodge(const DrainedMaterial& m) const {
    if (!beyond_modulus) return 1.0;
    return std::pow(1.04, index.at(m) - (static_cast<double>(index.size()) - 1) / 2);
  }
  // The legend's words: titles and colours in material order.
  std::string Titles() const {
    std::string words;
    for (const auto& [m, k] : index)
      words += fmt::format("{}\"{}\"", words.empty() ? "" : " ", Text(m));
    return words;
  }
  std::string Colours() const {
    std::string words;
    for (const auto& [m, k] : index)
      words += fmt::format("{}{}", words.empty() ? "" : " ", Colour(m));
    return words;
  }
  // What the caption says of the series.
  std::string Caption() const {
    if (!beyond_modulus) return "";
    std::string shared = Shared();
    return fmt::format(
        " The drained cases' {} materials (read from their scenes) are series of their own, one "
        "colour each, labelled by what differs between them (χ: Cundall's local damping, "
        "k_t/k_n: the stiffness ratio, f: the time step as a fraction of the critical one, E: "
        "Young's modulus){}, and drawn side by side, 4 % apart in x, so that materials at one "
        "rate do not hide each other (the data files keep the measured values).",
        index.size(), shared.empty() ? "" : "; shared: " + shared);
  }
};
DrainedMaterials MaterialsOf(const RateStudy& rate, int first_colour = 1) {
  DrainedMaterials m;
  m.first_colour = first_colour;
  std::set<double> parts[4];
  for (const DrainedGroup& g : rate.drained.groups) {
    const DrainedMaterial material = MaterialOf(g);
    m.index.emplace(material, 0);
    parts[0].insert(std::get<0>(material));
    parts[1].insert(std::get<1>(material));
    parts[2].insert(std::get<2>(material));
    parts[3].insert(std::get<3>(material));
  }
  int k = 0;
  for (auto& [material, index] : m.index) index = k++;
  for (size_t p = 0; p < 4; ++p) m.varies[p] = parts[p].size() > 1;
  m.beyond_modulus = m.varies[1] || m.varies[2] || m.varies[3];
  return m;
}

// The figure's note: the moduli, and the drained materials' shared parts.
std::string MaterialNote(const RateStudy& rate, double reference,
                         const DrainedMaterials& materials) {
  const std::string modulus = ModulusNote(rate, reference), shared = materials.Shared();
  if (shared.empty()) return modulus;
  return modulus.empty() ? shared : modulus + ", " + shared;
}

}  // namespace

FigureSpec RatePsiSigma(const Context& ctx, const RateStudy& rate) {
  const double reference = rate.ReferenceModulus();
  FigureSpec spec =
      Spec("rate_psi_sigma_p", "rate (a)", "Asymptotic ψ_σ against p at each rate",
           "The asymptotic stress obliquity ψ_σ against the asymptotic mean stress p of the rate "
           "cases, one panel per ψ_ε: the mean over the replicates' usable states of each start "
           "(NC at p_0) and rate, with the 95 % intervals of both means (Student t; none below two "
           "states), one colour per rate (the fixed inertial numbers I* and the paper's constant "
           "‖D‖), lines joining the starts of one rate; " +
               ModulusNote(rate, reference) +
               ". The last panel: the drained triaxial cases (σ_r = p_0, triangles), one curve "
               "per rank of the axial rate at each σ_r, coloured as the I* nearest their measured "
               "I (rate_drained.csv): where the isochoric paths liquefy as I* falls, these keep "
               "a critical state. If the paper's p-dependence of ψ_σ (its Sec. 5.3) is a rate "
               "effect, the curves flatten and coincide as I* falls. Data: rate_summary.csv.",
           "rate_psi_sigma.gp");
  const auto colours = RateColours(rate);
  // Materials of their own take the colours after the rates'.
  const DrainedMaterials materials = MaterialsOf(rate, static_cast<int>(colours.size()) + 1);
  spec.caption += materials.Caption();
  std::map<double,
           std::map<std::pair<double, std::pair<int, double>>, std::vector<const RateGroup*>>>
      panels;  // ψ_ε → (E, rate) → groups
  for (const RateGroup& g : rate.groups) {
    if (g.used == 0) continue;
    panels[g.key.psi_epsilon_deg]
          [{g.key.youngs_modulus_mpa, {static_cast<int>(g.key.rule), g.key.rate}}]
              .push_back(&g);
  }
  // The drained cases (σ_r = p_0): one curve per (E, rank of the axial rate
  // at each σ_r, slowest first), coloured as the I* nearest its measured I
  // (or as its material, DrainedMaterials).
  std::map<std::pair<DrainedMaterial, int>, std::vector<const DrainedGroup*>> drained;
  {
    std::map<std::pair<DrainedMaterial, double>, std::vector<const DrainedGroup*>> by_start;
    for (const DrainedGroup& g : rate.drained.groups) {
      if (g.used > 0 && std::isfinite(g.psi_sigma_deg.mean)) {
        by_start[{MaterialOf(g), g.radial_stress_kpa}].push_back(&g);
      }
    }
    for (auto& [start, groups] : by_start) {
      std::sort(groups.begin(), groups.end(), [](const DrainedGroup* a, const DrainedGroup* b) {
        return a->axial_strain_rate < b->axial_strain_rate;
      });
      for (size_t r = 0; r < groups.size(); ++r) {
        drained[{start.first, static_cast<int>(r)}].push_back(groups[r]);
      }
    }
  }
  auto nearest_colour = [&colours](double inertial) {
    return NearestRateColour(colours, inertial);
  };
  if (panels.empty() && drained.empty()) {
    return NotDrawn(spec, "no rate case has a usable asymptotic state");
  }
  std::string panel_titles, panel_blocks, ranges[4];
  int k = 0;
  auto add_ranges = [&ranges](const AxisRange& x, const AxisRange& y) {
    const auto [x_lo, x_hi] = x.Padded();
    const auto [y_lo, y_hi] = y.Padded();
    const double values[4] = {x_lo, x_hi, y_lo, y_hi};
    for (int r = 0; r < 4; ++r) {
      ranges[r] += fmt::format("{}{:.8g}", ranges[r].empty() ? "" : " ", values[r]);
    }
  };
  for (const auto& [psi, curves] : panels) {
    ++k;
    AxisRange x{}, y{};
    x.log = true;
    BlockFile file(
        {"p_kpa", "p_ci95", "psi_sigma_deg", "psi_sigma_ci95", "point_type", "colour", "drawn_at"});
    for (const auto& [curve, groups] : curves) {
      std::vector<const RateGroup*> sorted = groups;
      std::sort(sorted.begin(), sorted.end(), [](const RateGroup* a, const RateGroup* b) {
        return a->p_kpa.mean < b->p_kpa.mean;
      });
      std::vector<std::vector<double>> rows;
      for (const RateGroup* g : sorted) {
        x.Add(g->p_kpa.mean, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width));
        y.Add(g->psi_sigma_deg.mean, g->psi_sigma_deg.half_width);
        rows.push_back({g->p_kpa.mean, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width),
                        g->psi_sigma_deg.mean, Zeroed(g->psi_sigma_deg.half_width),
                        static_cast<double>(DirectionPoint(90, curve.first == reference)),
                        static_cast<double>(colours.at(curve.second)), g->p_kpa.mean});
      }
      file.Add(fmt::format("{}, E = {} MPa", RateTitle(curve.second.first, curve.second.second),
                           Short(curve.first)),
               rows);
    }
    file.Write(ctx.File(fmt::format("rate_psi_sigma_{}.tsv", k)));
    panel_titles += fmt::format("{}\"ψ_ε = {}°\"", panel_titles.empty() ? "" : " ", Short(psi));
    panel_blocks += fmt::format("{}{}", panel_blocks.empty() ? "" : " ", file.blocks());
    add_ranges(x, y);
  }
  if (!drained.empty()) {
    ++k;
    AxisRange x{}, y{};
    x.log = true;
    BlockFile file(
        {"p_kpa", "p_ci95", "psi_sigma_deg", "psi_sigma_ci95", "point_type", "colour", "drawn_at"});
    for (const auto& [curve, groups] : drained) {
      std::vector<double> inertial;
      for (const DrainedGroup* g : groups) inertial.push_back(g->inertial_number_dmax.mean);
      const double i_mean = Estimate::Of(inertial).mean;
      std::vector<std::vector<double>> rows;
      for (const DrainedGroup* g : groups) {  // ascending σ_r
        const double drawn_at = g->p_kpa.mean * materials.Dodge(curve.first);
        x.Add(drawn_at, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width));
        y.Add(g->psi_sigma_deg.mean, g->psi_sigma_deg.half_width);
        rows.push_back({g->p_kpa.mean, LogHalfWidth(g->p_kpa.mean, g->p_kpa.half_width),
                        g->psi_sigma_deg.mean, Zeroed(g->psi_sigma_deg.half_width),
                        materials.Point(std::get<0>(curve.first) == reference),
                        static_cast<double>(materials.Separate() ? materials.Colour(curve.first)
                                                                 : nearest_colour(i_mean)),
                        drawn_at});
      }
      file.Add(fmt::format("drained, I ≈ {:.2g}, {}", i_mean, materials.Text(curve.first)), rows);
    }
    file.Write(ctx.File(fmt::format("rate_psi_sigma_{}.tsv", k)));
    panel_titles += fmt::format("{}\"drained, σ_r = p_0\"", panel_titles.empty() ? "" : " ");
    panel_blocks += fmt::format("{}{}", panel_blocks.empty() ? "" : " ", file.blocks());
    add_ranges(x, y);
  }
  Set(&spec, "panel_x_min", ranges[0]);
  Set(&spec, "panel_x_max", ranges[1]);
  Set(&spec, "panel_y_min", ranges[2]);
  Set(&spec, "panel_y_max", ranges[3]);
  Set(&spec, "n_panels", k);
  Set(&spec, "panel_titles", panel_titles);
  Set(&spec, "panel_blocks", panel_blocks);
  Set(&spec, "n_rates", static_cast<int>(colours.size()));
  Set(&spec, "rate_titles", RateTitles(colours));
  Set(&spec, "n_materials", materials.Separate() ? static_cast<int>(materials.index.size()) : 0);
  Set(&spec, "material_titles", materials.Titles());
  Set(&spec, "material_colours", materials.Colours());
  Set(&spec, "modulus_note", MaterialNote(rate, reference, materials));
  return spec;
}

FigureSpec RateLines(const Context& ctx, const RateStudy& rate) {
  const double reference = rate.ReferenceModulus();
  FigureSpec spec =
      Spec("rate_csl_ncl", "rate (b)", "NCL, CSL and NEL at each rate",
           fmt::format(
               "ln(1+e) against p (log scale) of the rate cases' usable asymptotic states, all "
               "replicates and starts: ψ_ε = 0° (triangles: the NCL at that rate), 90° (circles: "
               "the CSL), other directions (squares: e.g. the NEL of 100°); {}; one colour per "
               "rate. Lines: ln(1+e) = N − λ ln p fitted through the states of one direction and "
               "rate (at least two starts; at ψ_ε = 0°, whose states all lie at the stress cap, "
               "the mean of the paths' own lines past their first unit of ln p: a least-squares "
               "secant of an NCL that steepens with p), drawn over their p range; rate_lines.csv "
               "gives N, λ "
               "and ln(1+e) at {} kPa with its 95 % interval. Diamonds: the critical states of "
               "the drained triaxial cases (σ_r = p_0, every replicate), coloured as the I* "
               "nearest their measured I: the CSL where the isochoric paths liquefy. Data: "
               "rate_states.csv, rate_drained_states.csv.",
               ModulusNote(rate, reference), Short(rate.options.reference_p_kpa)),
           "rate_lines.gp");
  const auto colours = RateColours(rate);
  // Rows: p, ln(1+e), point type, colour, p drawn at.
  std::map<std::tuple<double, double, int, double>, std::vector<std::vector<double>>> blocks;
  int directions[3] = {0, 0, 0};  // states at ψ_ε = 0°, 90° and others
  for (const RateState& s : rate.states) {
    if (!rate.Usable(s)) continue;
    ++directions[std::abs(s.psi_epsilon_deg) < 1e-6        ? 0
                 : std::abs(s.psi_epsilon_deg - 90) < 1e-6 ? 1
                                                           : 2];
    blocks[{s.psi_epsilon_deg, s.youngs_modulus_mpa, static_cast<int>(s.rule), s.rate()}].push_back(
        {s.p_kpa, s.ln_1_plus_e,
         static_cast<double>(DirectionPoint(s.psi_epsilon_deg, s.youngs_modulus_mpa == reference)),
         static_cast<double>(colours.at({static_cast<int>(s.rule), s.rate()})), s.p_kpa});
  }
  // The drained cases' critical states (σ_r = p_0): diamonds, one block
  // per material and σ_r, coloured as the I* nearest their measured I (or
  // as their material, DrainedMaterials).
  const DrainedMaterials materials = MaterialsOf(rate, static_cast<int>(colours.size()) + 1);
  std::map<std::pair<DrainedMaterial, double>, std::vector<std::vector<double>>> drained;
  for (const DrainedState& s : rate.drained.states) {
    if (!rate.Usable(s)) continue;
    const DrainedMaterial m = MaterialOf(s);
    drained[{m, s.radial_stress_kpa}].push_back(
        {s.p_kpa, s.ln_1_plus_e, s.youngs_modulus_mpa == reference ? 13.0 : 12.0,
         static_cast<double>(materials.Separate()
                                 ? materials.Colour(m)
                                 : NearestRateColour(colours, s.inertial_number_dmax)),
         s.p_kpa * materials.Dodge(m)});
  }
  spec.caption += materials.Caption();
  if (blocks.empty() && drained.empty()) {
    return NotDrawn(spec, "no rate case has a usable asymptotic state");
  }
  AxisRange x{}, y{};
  x.log = true;
  auto add_range = [&x, &y](const auto& all) {
    for (const auto& [key, rows] : all) {
      for (const std::vector<double>& row : rows) {
        x.Add(row[4]);
        y.Add(row[1]);
      }
    }
  };
  add_range(blocks);
  add_range(drained);
  BlockFile states({"p_kpa", "ln_1_plus_e", "point_type", "colour", "drawn_at"});
  for (const auto& [key, rows] : blocks) {
    states.Add(fmt::format("ψ_ε = {}°, E = {} MPa, {}", Short(std::get<0>(key)),
                           Short(std::get<1>(key)), RateTitle(std::get<2>(key), std::get<3>(key))),
               rows);
  }
  for (const auto& [key, rows] : drained) {
    states.Add(
        fmt::format("drained, σ_r = {} kPa, {}", Short(key.second), materials.Text(key.first)),
        rows);
  }
  states.Write(ctx.File("rate_lines_states.tsv"));
  BlockFile lines({"p_kpa", "ln_1_plus_e", "colour"});
  for (const RateLine& l : rate.lines) {
    if (!l.valid()) continue;
    const double colour = colours.at({static_cast<int>(l.rule), l.rate});
    std::vector<std::vector<double>> rows;
    for (double p : {l.p_min_kpa, l.p_max_kpa}) {
      rows.push_back({p, l.n - l.lambda * std::log(p), colour});
      y.Add(rows.back()[1]);
    }
    lines.Add(fmt::format("ψ_ε = {}°, E = {} MPa, {}: N = {:.4f}, λ = {:.4f}",
                          Short(l.psi_epsilon_deg), Short(l.youngs_modulus_mpa),
                          RateKey{0, 0, 0, l.rule, l.rate}.RateLabel(), l.n, l.lambda),
              rows);
  }
  if (lines.blocks() > 0) lines.Write(ctx.File("rate_lines_fits.tsv"));
  SetRange(&spec, "x", x);
  SetRange(&spec, "y", y);
  Set(&spec, "n_states", states.blocks());
  Set(&spec, "n_lines", lines.blocks());
  Set(&spec, "n_drained", drained.empty() ? 0 : 1);
  Set(&spec, "n_ncl", directions[0] > 0 ? 1 : 0);
  Set(&spec, "n_csl", directions[1] > 0 ? 1 : 0);
  Set(&spec, "n_other", directions[2] > 0 ? 1 : 0);
  Set(&spec, "n_rates", static_cast<int>(colours.size()));
  Set(&spec, "rate_titles", RateTitles(colours));
  Set(&spec, "n_materials", materials.Separate() ? static_cast<int>(materials.index.size()) : 0);
  Set(&spec, "material_titles", materials.Titles());
  Set(&spec, "material_colours", materials.Colours());
  Set(&spec, "modulus_note", MaterialNote(rate, reference, materials));
  return spec;
}

// Rate (d), issue 10 §3: σ_r/p of the extension sweep against ψ_ε, one
// colour per sweep (E, rate, p_0); liquefied steps on the zero line, and
// ψ_ε(d) with its interval where a sweep reached the limit d.
FigureSpec RateExtension(const Context& ctx, const RateStudy& rate) {
  FigureSpec spec =
      Spec("rate_extension", "rate (d)", "Extension states up to the limit d",
           "The asymptotic σ_r/p = 1 − (q/p)/3 of the rate cases with ψ_ε ≥ 90° against ψ_ε (means "
           "over the replicates' usable states with their 95 % intervals), one colour per sweep "
           "(E, rate, start p_0). σ_r/p = 0 is the limit d (ψ_σ = 54.74°). Crosses on the zero "
           "line: steps at which most replicates liquefied (a gas: mechanical coordination below 3 "
           "or p below 0.5 kPa; no asymptote). Squares with horizontal bars: ψ_ε(d), the root of "
           "the least-squares line of σ_r/p through the last steps, with its 95 % interval. Data: "
           "rate_extension.csv, rate_extension_limit.csv.",
           "rate_extension.gp");
  using SweepKey = std::tuple<double, int, double, double>;
  auto key_of = [](double e_mpa, dem::RateRule rule, double r, double p0) {
    return SweepKey{e_mpa, static_cast<int>(rule), r, p0};
  };
  std::map<SweepKey, int> colour_of;
  for (const ExtensionLimit& l : rate.extension_limits) {
    colour_of.emplace(key_of(l.youngs_modulus_mpa, l.rule, l.rate, l.start_p_kpa),
                      static_cast<int>(colour_of.size()) + 1);
  }
  if (colour_of.empty()) return NotDrawn(spec, "no rate case runs at ψ_ε > 90°");
  auto title = [](const SweepKey& k) {
    return fmt::format("E = {} MPa, {}, NC {} kPa", Short(std::get<0>(k)),
                       RateTitle(std::get<1>(k), std::get<2>(k)), Short(std::get<3>(k)));
  };
  std::map<SweepKey, std::vector<std::vector<double>>> steps, liquefied;
  AxisRange x{}, y{};
  y.Add(0.0);
  for (const ExtensionStep& st : rate.extension_steps) {
    const SweepKey k = key_of(st.youngs_modulus_mpa, st.rule, st.rate, st.start_p_kpa);
    const auto colour = colour_of.find(k);
    if (colour == colour_of.end()) continue;
    x.Add(st.psi_epsilon_deg);
    if (st.status == "liquefied") {
      liquefied[k].push_back({st.psi_epsilon_deg, 0.0, static_cast<double>(colour->second)});
    } else if (st.used > 0 && std::isfinite(st.sigma_r_over_p.mean)) {
      y.Add(st.sigma_r_over_p.mean, st.sigma_r_over_p.half_width);
      steps[k].push_back({st.psi_epsilon_deg, st.sigma_r_over_p.mean,
                          Zeroed(st.sigma_r_over_p.half_width),
                          static_cast<double>(colour->second)});
    }
  }
  BlockFile step_file({"psi_epsilon_deg", "sigma_r_over_p", "sigma_r_over_p_ci95", "colour"});
  for (const auto& [k, rows] : steps) step_file.Add(title(k), rows);
  BlockFile liquefied_file({"psi_epsilon_deg", "sigma_r_over_p", "colour"});
  for (const auto& [k, rows] : liquefied) liquefied_file.Add(title(k), rows);
  BlockFile limit_file({"psi_epsilon_deg", "psi_epsilon_ci95", "sigma_r_over_p", "colour"});
  for (const ExtensionLimit& l : rate.extension_limits) {
    if (l.result != "limit_d" || !std::isfinite(l.psi_d_deg.mean)) continue;
    const SweepKey k = key_of(l.youngs_modulus_mpa, l.rule, l.rate, l.start_p_kpa);
    x.Add(l.psi_d_deg.mean, l.psi_d_deg.half_width);
    limit_file.Add(title(k) + ": " + l.Text(), {{l.psi_d_deg.mean, Zeroed(l.psi_d_deg.half_width),
                                                 0.0, static_cast<double>(colour_of.at(k))}});
  }
  if (step_file.blocks() > 0) step_file.Write(ctx.File("rate_extension_steps.tsv"));
  if (liquefied_file.blocks() > 0) liquefied_file.Write(ctx.File("rate_extension_liquefied.tsv"));
  if (limit_file.blocks() > 0) limit_file.Write(ctx.File("rate_extension_limits.tsv"));
  std::string sweep_titles;
  std::vector<std::string> ordered(colour_of.size());
  for (const auto& [k, colour] : colour_of) ordered[static_cast<size_t>(colour - 1)] = title(k);
  for (const std::string& t : ordered) {
    sweep_titles += fmt::format("{}\"{}\"", sweep_titles.empty() ? "" : " ", t);
  }
  SetRange(&spec, "x", x);
  SetRange(&spec, "y", y);
  Set(&spec, "n_steps", step_file.blocks());
  Set(&spec, "n_liquefied", liquefied_file.blocks());
  Set(&spec, "n_limits", limit_file.blocks());
  Set(&spec, "n_sweeps", static_cast<int>(colour_of.size()));
  Set(&spec, "sweep_titles", sweep_titles);
  return spec;
}

// Rate (e), issue 10 §4: the quasi-static asymptotic states (the rate
// cases at the I* the models were calibrated to, calibration/quasi_static.toml,
// or the default selection) beside the paper-rate ones (constant ‖D‖) at the
// reference modulus, with the calibrated models of this folder.
FigureSpec RateAgainstModels(const Context& ctx, const RateStudy& rate) {
  std::optional<QuasiStaticSelection> selection = ReadQuasiStaticSelection(ctx.directory);
  const bool calibrated = selection.has_value();
  if (!selection) selection = SelectQuasiStatic(rate);
  FigureSpec spec = Spec(
      "rate_against_models", "rate (e)",
      "Quasi-static and paper-rate asymptotic states against the calibrated models",
      fmt::format(
          "The asymptotic states of the rate cases at {} (filled circles: the quasi-static "
          "set{}) and at the paper's constant ‖D‖ (open diamonds), E = {} MPa, all ψ_ε: (a) ψ_σ "
          "against ψ_ε, the means over the replicates of each start with their 95 % intervals; "
          "(b) ln(1+e) against p, every usable state, one colour per ψ_ε, with the drained "
          "triaxial states of the quasi-static set (filled triangles: the slowest axial rate of "
          "each σ_r, rate_drained_states.csv). Lines: the models "
          "calibrated in this folder to the quasi-static set (`granasym study calibrate`), "
          "their ψ_σ(ψ_ε) in (a) and their asymptotic lines in (b). Data: rate_summary.csv, "
          "rate_states.csv.",
          selection->valid() ? fmt::format("I* = {:g}", selection->inertial_number)
                             : std::string("the smallest I*"),
          calibrated ? ", calibration/quasi_static.toml" : ", not yet calibrated",
          Short(selection->youngs_modulus_mpa)),
      "rate_models.gp");
  if (!selection->valid()) return NotDrawn(spec, selection->reason);
  const double e_mpa = selection->youngs_modulus_mpa, i_star = selection->inertial_number;
  auto quasi = [&](dem::RateRule rule, double r) {
    return rule == dem::RateRule::kInertial && r == i_star;
  };
  // (a) group means of each set (0: quasi-static, 1: the paper rate); (b) states.
  std::vector<std::vector<double>> set_rows[2];
  for (const RateGroup& g : rate.groups) {
    if (g.key.youngs_modulus_mpa != e_mpa || g.used == 0) continue;
    const int set = quasi(g.key.rule, g.key.rate)            ? 0
                    : g.key.rule == dem::RateRule::kConstant ? 1
                                                             : -1;
    if (set < 0) continue;
    // Side by side at each ψ_ε, so that the intervals do not hide each other.
    set_rows[set].push_back({g.key.psi_epsilon_deg + (set == 0 ? -0.6 : 0.6), g.psi_sigma_deg.mean,
                             Zeroed(g.psi_sigma_deg.half_width)});
  }
  // Tics at the swept directions, so that the sets drawn side by side read
  // as one ψ_ε each, also on a narrow sweep (91° and 95°).
  std::set<double> swept;
  for (const RateGroup& g : rate.groups) {
    if (g.key.youngs_modulus_mpa == e_mpa && g.used > 0) swept.insert(g.key.psi_epsilon_deg);
  }
  std::string psi_tics;
  for (double psi : swept) {
    psi_tics += fmt::format("{}\"{}\" {}", psi_tics.empty() ? "(" : ", ", Short(psi), Short(psi));
  }
  if (!psi_tics.empty()) psi_tics += ")";
  Set(&spec, "psi_tics", psi_tics);
  if (!swept.empty()) {  // the directions with room for the side-by-side sets
    const double room = std::max(2.0, 0.05 * (*swept.rbegin() - *swept.begin()));
    SetNumber(&spec, "psi_x_min", *swept.begin() - room);
    SetNumber(&spec, "psi_x_max", *swept.rbegin() + room);
  }
  const char* set_files[2] = {"rate_models_quasi_static.tsv", "rate_models_paper_rate.tsv"};
  for (int set = 0; set < 2; ++set) {
    if (set_rows[set].empty()) continue;
    BlockFile means({"psi_epsilon_deg", "psi_sigma_deg", "psi_sigma_ci95"});
    means.Add(set == 0 ? fmt::format("I* = {:g}", i_star) : std::string("constant ‖D‖"),
              set_rows[set]);
    means.Write(ctx.File(set_files[set]));
  }
  std::map<double, std::vector<std::vector<double>>> by_psi;
  std::set<double> directions;
  for (const RateState& s : rate.states) {
    if (s.youngs_modulus_mpa != e_mpa || !rate.Usable(s)) continue;
    const bool is_quasi = quasi(s.rule, s.rate());
    if (!is_quasi && s.rule != dem::RateRule::kConstant) continue;
    directions.insert(s.psi_epsilon_deg);
    by_psi[s.psi_epsilon_deg].push_back({s.p_kpa, s.ln_1_plus_e, is_quasi ? 7.0 : 12.0});
  }
  // The drained cases of the quasi-static set: the critical state under stress control.
  std::vector<std::vector<double>> drained_rows;
  for (const DrainedState& s : rate.drained.states) {
    if (std::find(selection->drained_cases.begin(), selection->drained_cases.end(), s.case_name) !=
            selection->drained_cases.end() &&
        s.youngs_modulus_mpa == e_mpa && rate.Usable(s)) {
      drained_rows.push_back({s.p_kpa, s.ln_1_plus_e, 9.0});
    }
  }
  if (by_psi.empty() && drained_rows.empty()) {
    return NotDrawn(spec, "no usable state at the selected rates");
  }
  BlockFile states({"p_kpa", "ln_1_plus_e", "point_type"});
  std::string psi_titles;
  for (const auto& [psi, rows] : by_psi) {
    states.Add(fmt::format("ψ_ε = {}°", Short(psi)), rows);
    psi_titles += fmt::format("{}\"ψ_ε = {}°\"", psi_titles.empty() ? "" : " ", Short(psi));
  }
  if (!drained_rows.empty()) {
    states.Add("drained triaxial, slowest axial rate", drained_rows);
    psi_titles += fmt::format("{}\"drained\"", psi_titles.empty() ? "" : " ");
  }
  states.Write(ctx.File("rate_models_states.tsv"));
  // The models: ψ_σ(ψ_ε) over the swept range, lines at the study's directions.
  BlockFile curves({"psi_epsilon_deg", "psi_sigma_deg"});
  BlockFile lines({"p_kpa", "ln_1_plus_e"});
  const double lo = *directions.begin() - 5, hi = *directions.rbegin() + 5;
  for (const ModelOverlay& model : ctx.models) {
    std::vector<std::vector<double>> curve, rows;
    for (size_t k = 0; k < model.psi_epsilon_deg.size() && k < model.psi_sigma_deg.size(); ++k) {
      if (model.psi_epsilon_deg[k] >= lo && model.psi_epsilon_deg[k] <= hi) {
        curve.push_back({model.psi_epsilon_deg[k], model.psi_sigma_deg[k]});
      }
    }
    for (const ModelOverlay::Line& line : model.lines) {
      if (line.psi_epsilon_deg < lo || line.psi_epsilon_deg > hi) continue;
      for (size_t k = 0; k < line.ln_p.size(); ++k) {
        rows.push_back({std::exp(line.ln_p[k]), line.ln_1_plus_e[k]});
      }
      rows.push_back({});
    }
    if (curve.empty() || rows.empty()) continue;
    curves.Add(model.title, curve);
    lines.Add(model.title, rows);
  }
  if (curves.blocks() > 0) {
    curves.Write(ctx.File("rate_models_curves.tsv"));
    lines.Write(ctx.File("rate_models_lines.tsv"));
  }
  spec.caption += " " + ctx.models_note;
  Set(&spec, "n_models", curves.blocks());
  Set(&spec, "n_psi", states.blocks());
  Set(&spec, "psi_titles", psi_titles);
  Set(&spec, "quasi_title", fmt::format("I* = {:g}", i_star));
  Set(&spec, "n_quasi_static", set_rows[0].empty() ? 0 : 1);
  Set(&spec, "n_paper_rate", set_rows[1].empty() ? 0 : 1);
  return spec;
}

namespace {

// The caption of rate (c) and its spec.
FigureSpec CriticalStateSpec(const RateStudy& rate, double reference) {
  return Spec(
      "rate_critical_state_ratio", "rate (c)",
      "Critical-state stress ratio M against the inertial number, and its quasi-static limit",
      fmt::format(
          "M = q/p of the ψ_ε = 90° asymptotic states against their measured I(d_max) (means "
          "over the replicates with 95 % intervals of both; circles: fixed I*, diamonds: the "
          "paper's constant ‖D‖; triangles: drained triaxial compression at σ_r = p_0 and a "
          "constant axial rate, rate_drained.csv), one colour per start p_0; {}. Lines: the "
          "quasi-static fit M = M_0 + b·I through the states of the {} smallest I* (of every "
          "axial rate for the drained cases; least squares: the "
          "small-I form of the μ(I) laws of the paper's refs. [10], da Cruz et al. 2005, "
          "and [29], Jop et al. 2006); the "
          "points at the left edge are M_0 = M(I → 0) with its 95 % interval "
          "(rate_quasi_static.csv, rate_drained_limit.csv). Band: the published "
          "critical-state ratio of frictional spheres without rolling resistance, {}. "
          "Dashed: I = 10^{{-2}} (quasi-static, paper Sec. 5.3) and 10^{{-3}} (SPEC §8.2).",
          ModulusNote(rate, reference), rate.options.fit_rates, rate.options.literature_m.source),
      "rate_critical_state.gp");
}

// The points of rate (c): the group means of M against I(d_max), one curve
// per (E, p_0) of the ψ_ε = 90° groups and per (E, σ_r) of the drained ones.
struct CriticalStatePoints {
  using Rows = std::vector<std::vector<double>>;
  std::map<std::pair<double, double>, Rows> isochoric;         // (E, start p)
  std::map<std::pair<DrainedMaterial, double>, Rows> drained;  // (material, σ_r)
  double i_min = 1e300;                                        // the smallest measured I
};

CriticalStatePoints CriticalStateGroups(const RateStudy& rate, double reference,
                                        const std::map<double, int>& colour_of,
                                        const DrainedMaterials& materials) {
  CriticalStatePoints points;
  // Columns: I, its interval, M, its interval, point type, colour, drawn at.
  auto row = [&](const Estimate& i, const Estimate& m, double point, int colour, double dodge) {
    points.i_min = std::min(points.i_min, i.mean);
    return std::vector<double>{
        i.mean, LogHalfWidth(i.mean, i.half_width), m.mean,        Zeroed(m.half_width),
        point,  static_cast<double>(colour),        i.mean * dodge};
  };
  for (const RateGroup& g : rate.groups) {
    if (std::abs(g.key.psi_epsilon_deg - 90) > 1e-6 || g.used == 0) continue;
    if (!(g.inertial_number_dmax.mean > 0) || !std::isfinite(g.q_over_p.mean)) continue;
    const bool ref = g.key.youngs_modulus_mpa == reference;
    const int point = g.key.rule == dem::RateRule::kInertial ? (ref ? 7 : 6) : (ref ? 13 : 12);
    points.isochoric[{g.key.youngs_modulus_mpa, g.key.start_p_kpa}].push_back(
        row(g.inertial_number_dmax, g.q_over_p, point, colour_of.at(g.key.start_p_kpa), 1.0));
  }
  // The drained cases (constant σ_r = p_0): triangles, one block per
  // (material, σ_r), coloured as their σ_r, or as their material when the
  // materials are series of their own.
  for (const DrainedGroup& g : rate.drained.groups) {
    if (g.used == 0 || !(g.inertial_number_dmax.mean > 0) || !std::isfinite(g.q_over_p.mean)) {
      continue;
    }
    const DrainedMaterial m = MaterialOf(g);
    const int colour =
        materials.Separate() ? materials.Colour(m) : colour_of.at(g.radial_stress_kpa);
    points.drained[{m, g.radial_stress_kpa}].push_back(
        row(g.inertial_number_dmax, g.q_over_p, materials.Point(g.youngs_modulus_mpa == reference),
            colour, materials.Dodge(m)));
  }
  return points;
}

// The quasi-static lines M_0 + b·I of rate (c), from the left edge `i_left`
// to the largest I fitted, and their limits M_0 at the edge; returns the
// number of lines.
int WriteCriticalStateFits(const Context& ctx, const RateStudy& rate, double reference,
                           const std::map<double, int>& colour_of,
                           const DrainedMaterials& materials, double i_left, AxisRange* y) {
  BlockFile fits({"inertial_number", "q_over_p", "q_over_p_ci95", "point_type", "colour"});
  BlockFile limits({"inertial_number", "q_over_p", "q_over_p_ci95", "point_type", "colour"});
  auto add_fit = [&](const std::string& title, double m0, double half_width, double slope,
                     double i_max, double line_point, double limit_point, int colour,
                     double dodge) {
    std::vector<std::vector<double>> rows;
    for (int k = 0; k <= 20; ++k) {
      const double i = std::exp(std::log(i_left) + (std::log(i_max) - std::log(i_left)) * k / 20);
      rows.push_back({i, m0 + slope * i, 0.0, line_point, static_cast<double>(colour)});
    }
    fits.Add(title, rows);
    limits.Add(title, {{i_left * dodge, m0, Zeroed(half_width), limit_point,
                        static_cast<double>(colour)}});
    y->Add(m0, half_width);
    y->Add(rows.back()[1]);
  };
  for (const QuasiStaticFit& f : rate.quasi_static) {
    if (f.quantity != "q_over_p" || std::abs(f.psi_epsilon_deg - 90) > 1e-6 || !f.valid()) continue;
    const auto colour = colour_of.find(f.start_p_kpa);
    if (colour == colour_of.end()) continue;
    const bool ref = f.youngs_modulus_mpa == reference;
    add_fit(fmt::format("E = {} MPa, NC {} kPa: M_0 = {:.3f}", Short(f.youngs_modulus_mpa),
                        Short(f.start_p_kpa), f.limit.mean),
            f.limit.mean, f.limit.half_width, f.slope.mean, f.i_max, ref ? 7.0 : 6.0,
            ref ? 5.0 : 4.0, colour->second, 1.0);
  }
  for (const DrainedLimit& l : rate.drained.limits) {
    if (!l.valid()) continue;
    const DrainedMaterial m = MaterialOf(l);
    int colour = 0;
    if (materials.Separate()) {
      colour = materials.Colour(m);
    } else if (const auto start = colour_of.find(l.radial_stress_kpa); start != colour_of.end()) {
      colour = start->second;
    } else {
      continue;
    }
    const double point = materials.Point(l.youngs_modulus_mpa == reference);
    add_fit(fmt::format("{}, drained at sigma_r = {} kPa: M_0 = {:.3f}", materials.Text(m),
                        Short(l.radial_stress_kpa), l.m.mean),
            l.m.mean, l.m.half_width, l.m_slope.mean, l.i_max, point, point, colour,
            materials.Dodge(m));
  }
  if (fits.blocks() > 0) {
    fits.Write(ctx.File("rate_critical_state_fits.tsv"));
    limits.Write(ctx.File("rate_critical_state_limits.tsv"));
  }
  return fits.blocks();
}

}  // namespace

FigureSpec RateCriticalState(const Context& ctx, const RateStudy& rate) {
  const double reference = rate.ReferenceModulus();
  const LiteratureBand& band = rate.options.literature_m;
  FigureSpec spec = CriticalStateSpec(rate, reference);
  // Colours by start; point types by modulus (filled reference) and rule.
  // Drained materials that are series of their own take the colours after
  // the starts' (DrainedMaterials).
  const bool separate = MaterialsOf(rate).Separate();
  std::set<double> starts;
  bool any_drained = false;
  for (const RateGroup& g : rate.groups) {
    if (std::abs(g.key.psi_epsilon_deg - 90) < 1e-6 && g.used > 0) starts.insert(g.key.start_p_kpa);
  }
  for (const DrainedGroup& g : rate.drained.groups) {
    if (g.used > 0 && !separate) starts.insert(g.radial_stress_kpa);
    any_drained = any_drained || g.used > 0;
  }
  if (starts.empty() && !any_drained) {
    return NotDrawn(spec, "no ψ_ε = 90° or drained rate case has a usable asymptotic state");
  }
  std::map<double, int> colour_of;
  std::string start_titles;
  for (double p : starts) {
    colour_of[p] = static_cast<int>(colour_of.size()) + 1;
    start_titles += fmt::format("{}\"NC {} kPa\"", start_titles.empty() ? "" : " ", Short(p));
  }
  const DrainedMaterials materials = MaterialsOf(rate, static_cast<int>(colour_of.size()) + 1);
  spec.caption += materials.Caption();
  CriticalStatePoints points = CriticalStateGroups(rate, reference, colour_of, materials);
  if (points.isochoric.empty() && points.drained.empty()) {
    return NotDrawn(spec, "no ψ_ε = 90° or drained rate state has a measured I");
  }
  AxisRange x{}, y{};
  x.log = true;
  y.Add(band.low);
  y.Add(band.high);
  auto add_ranges = [&x, &y](const auto& curves) {
    for (const auto& [curve, rows] : curves) {
      for (const std::vector<double>& row : rows) {
        x.Add(row[6], row[1]);
        y.Add(row[2], row[3]);
      }
    }
  };
  add_ranges(points.isochoric);
  add_ranges(points.drained);
  BlockFile groups({"inertial_number", "inertial_number_ci95", "q_over_p", "q_over_p_ci95",
                    "point_type", "colour", "drawn_at"});
  for (auto& [curve, rows] : points.isochoric) {
    std::sort(rows.begin(), rows.end());
    groups.Add(fmt::format("E = {} MPa, NC {} kPa", Short(curve.first), Short(curve.second)), rows);
  }
  for (auto& [curve, rows] : points.drained) {
    std::sort(rows.begin(), rows.end());
    groups.Add(fmt::format("{}, drained at sigma_r = {} kPa", materials.Text(curve.first),
                           Short(curve.second)),
               rows);
  }
  groups.Write(ctx.File("rate_critical_state_groups.tsv"));
  // The quasi-static lines and limits, drawn from a left edge a third of
  // the smallest measured I (the axis reaches it only when there are some).
  const double i_left = points.i_min / 3;
  const int fits = WriteCriticalStateFits(ctx, rate, reference, colour_of, materials, i_left, &y);
  if (fits > 0) {
    x.Add(i_left);
    if (materials.Separate()) x.Add(i_left * materials.Dodge(materials.index.begin()->first));
  }
  SetRange(&spec, "x", x);
  SetRange(&spec, "y", y);
  Set(&spec, "n_groups", groups.blocks());
  Set(&spec, "n_fits", fits);
  Set(&spec, "n_starts", static_cast<int>(colour_of.size()));
  Set(&spec, "start_titles", start_titles);
  Set(&spec, "n_materials", materials.Separate() ? static_cast<int>(materials.index.size()) : 0);
  Set(&spec, "material_titles", materials.Titles());
  Set(&spec, "material_colours", materials.Colours());
  Set(&spec, "n_isochoric", static_cast<int>(points.isochoric.size()));
  Set(&spec, "n_drained", static_cast<int>(points.drained.size()));
  // The note: the moduli, what the materials share and, with separate
  // materials at one σ_r, that σ_r.
  std::string note = MaterialNote(rate, reference, materials);
  std::set<double> radial;
  for (const auto& [curve, rows] : points.drained) radial.insert(curve.second);
  if (materials.Separate() && radial.size() == 1) {
    note += fmt::format(", σ_r = {} kPa", Short(*radial.begin()));
  }
  Set(&spec, "modulus_note", note);
  spec.variables.emplace_back("band_low", fmt::format("{:g}", band.low));
  spec.variables.emplace_back("band_high", fmt::format("{:g}", band.high));
  SetNumber(&spec, "i_left", i_left);
  return spec;
}

}  // namespace granasym::analysis::figures
