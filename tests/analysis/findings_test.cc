#include "analysis/findings.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "analysis/figure_context.h"
#include "common/csv_table.h"
#include "study/state_table.h"

namespace granasym::analysis {
namespace {

namespace fs = std::filesystem;
using figures::CaseData;
using figures::Context;
using study::StateRow;
using study::TableKind;
using study::TableStatus;

constexpr double kN = 0.69, kLambda = 0.026;  // the study's NCL

const Finding& Find(const std::vector<Finding>& findings, const std::string& id) {
  for (const Finding& f : findings) {
    if (f.id == id) return f;
  }
  static const Finding none;
  ADD_FAILURE() << "no finding " << id;
  return none;
}

CaseData Case(const std::string& name, int replicate = 1, double friction = 0.5,
              double time_step = 1.2e-7) {
  CaseData c;
  c.name = name;
  c.replicate = replicate;
  c.finished = true;
  c.friction = friction;
  c.time_step = time_step;
  return c;
}

// The NCL case: ψ_ε = 0° from 1 to 1000 kPa, ln(1+e) = N − λ* ln p + curvature (ln p)².
CaseData NclCase(double curvature, int replicate = 1) {
  CaseData c = Case("ncl", replicate);
  for (int k = 0; k <= 200; ++k) {
    const double lnp = std::log(1000.0) * k / 200;
    c.path.p.push_back(std::exp(lnp));
    c.path.ln_v.push_back(kN - kLambda * lnp + curvature * lnp * lnp);
    c.path.psi_sigma.push_back(0);
  }
  c.stage_psi_epsilon = {0};
  return c;
}

StateRow Row(const std::string& name, TableKind kind, double psi_epsilon, double p, double ln_v,
             double psi_sigma, int replicate = 1, const std::string& ncl = "ncl") {
  StateRow row;
  row.case_name = name;
  row.case_id = "r" + std::to_string(replicate) + "/" + name;
  row.stage = "s";
  row.replicate = replicate;
  row.kind = kind;
  row.status = TableStatus::kDetected;
  row.psi_epsilon_deg = psi_epsilon;
  row.p_kpa = p;
  row.ln_1_plus_e = ln_v;
  row.e = std::expm1(ln_v);
  row.psi_sigma_deg = psi_sigma;
  row.q_over_p = 3 / std::sqrt(2.0) * std::tan(psi_sigma * M_PI / 180);
  row.ocr = std::exp((kN - ln_v) / kLambda) / p;
  row.ncl_reference = ncl;
  row.inertial_number_dmax = 0.05;
  return row;
}

// `ctx` with its cases' samples classified (as ReadContext does).
Context Classified(Context ctx) {
  ClassifySamples(&ctx);
  return ctx;
}

Context Study() {
  Context ctx;
  ctx.study_ncl = "ncl";
  ctx.ncl_fits[{1, "ncl"}] = NclLine{kN, kLambda};
  return ctx;
}

// Critical states on a line parallel to the NCL (OCR 3), ψ_σ falling with p.
void AddCriticalStates(Context* ctx, double csl_lambda, double psi_slope) {
  for (double p : {20.0, 50.0, 100.0, 200.0, 500.0}) {
    const std::string name = "nc" + std::to_string(static_cast<int>(p)) + "_psi90";
    const double ln_v = kN - std::log(3.0) * kLambda - csl_lambda * std::log(p);
    ctx->states.push_back(
        Row(name, TableKind::kCsl, 90, p, ln_v, 26 + psi_slope * std::log(p / 100)));
    ctx->cases.push_back(Case(name));
  }
}

TEST(Findings, EveryClaimHasAVerdictAndAStudyWithoutCasesTestsNothing) {
  const std::vector<Finding> findings = ComputeFindings(Study());
  EXPECT_GE(findings.size(), 16u);
  for (const Finding& f : findings) {
    EXPECT_EQ(f.verdict, Verdict::kNotTested) << f.id << ": " << f.numbers;
    EXPECT_FALSE(f.claim.empty()) << f.id;
    EXPECT_FALSE(f.rule.empty()) << f.id;
    EXPECT_FALSE(f.source.empty()) << f.id;
    EXPECT_FALSE(f.numbers.empty()) << f.id << " says why it is not tested";
  }
}

TEST(Findings, AStraightNclIsLinearAndACurvedOneIsNot) {
  Context straight = Study();
  straight.cases.push_back(NclCase(0.0));
  EXPECT_EQ(Find(ComputeFindings(straight), "ncl_linear").verdict, Verdict::kReproduced);
  Context curved = Study();
  curved.cases.push_back(NclCase(0.004));  // the slope changes by a factor 2.5 over 20–1000 kPa
  const Finding f = Find(ComputeFindings(curved), "ncl_linear");
  EXPECT_EQ(f.verdict, Verdict::kNotReproduced) << f.numbers;
}

TEST(Findings, AParallelCslIsReproducedAndAFlatOneIsNot) {
  Context parallel = Study();
  AddCriticalStates(&parallel, kLambda, -2.5);
  // The NCL through the ensemble rows (replicate 0) is not a replicate's.
  parallel.ncl_fits[{0, "ncl"}] = NclLine{kN, 0.01};
  const std::vector<Finding> a = ComputeFindings(parallel);
  EXPECT_EQ(Find(a, "csl_parallel_ncl").verdict, Verdict::kReproduced)
      << Find(a, "csl_parallel_ncl").numbers;
  EXPECT_NE(Find(a, "csl_parallel_ncl").numbers.find("λ*(NCL) = 0.026;"), std::string::npos)
      << Find(a, "csl_parallel_ncl").numbers;
  // ψ_σ falls by 2.5° per unit ln p at I(d_max) = 0.05: the paper's rate effect.
  EXPECT_EQ(Find(a, "csl_psi_falls_with_p").verdict, Verdict::kReproduced);
  Context flat = Study();
  AddCriticalStates(&flat, 0.002, 0.0);
  const std::vector<Finding> b = ComputeFindings(flat);
  EXPECT_EQ(Find(b, "csl_parallel_ncl").verdict, Verdict::kNotReproduced);
  EXPECT_EQ(Find(b, "csl_psi_falls_with_p").verdict, Verdict::kNotReproduced);
}

TEST(Findings, FrictionlessAndSmallerTimeStepStatesStayOutOfTheStudysOwnMaterial) {
  Context ctx = Study();
  AddCriticalStates(&ctx, kLambda, -2.5);
  // A frictionless state far off the CSL, whose OCR refers to the study's
  // NCL (its own NCL was not determined): it must not bend the CSL.
  ctx.cases.push_back(Case("phi0_nc100_psi90", 1, 0.0));
  ctx.states.push_back(Row("phi0_nc100_psi90", TableKind::kCsl, 90, 100, 0.40, 18));
  ctx.cases.push_back(Case("dt5_nc100_psi90", 1, 0.5, 2.4e-8));
  ctx.states.push_back(Row("dt5_nc100_psi90", TableKind::kCsl, 90, 100.5,
                           kN - std::log(3.0) * kLambda - kLambda * std::log(100.5), 26.1));
  const std::vector<Finding> findings = ComputeFindings(Classified(ctx));
  const Finding& csl = Find(findings, "csl_parallel_ncl");
  EXPECT_EQ(csl.verdict, Verdict::kReproduced) << csl.numbers;
  EXPECT_NE(csl.numbers.find("through 5 states"), std::string::npos) << csl.numbers;
  const Finding& friction = Find(findings, "frictionless_alike");
  EXPECT_EQ(friction.verdict, Verdict::kPartly) << friction.numbers;  // no φ = 0 NCL fit
  const Finding& step = Find(findings, "time_step_independent");
  EXPECT_EQ(step.verdict, Verdict::kReproduced) << step.numbers;
}

TEST(Findings, ExtensionStatesWithRisingOcrOnJoinedLinesAreNormalExtensionLines) {
  Context ctx = Study();
  int k = 0;
  for (double psi : {95.0, 100.0, 105.0, 110.0}) {
    for (double start : {500.0, 1000.0}) {
      const std::string name = "nc" + std::to_string(static_cast<int>(start)) + "_psi" +
                               std::to_string(static_cast<int>(psi));
      const double ocr = 4 + (psi - 95) / 5;  // rising with ψ_ε
      const double p = 2.0 + k++ % 2;
      const double ln_v = kN - kLambda * std::log(ocr * p);
      ctx.states.push_back(Row(name, TableKind::kExtension, psi, p, ln_v, 30 + (psi - 95)));
      ctx.cases.push_back(Case(name));
    }
    StateRow joined = Row("joined", TableKind::kExtension, psi, 2.5, 0.6, 30);
    joined.stage = study::table::kStageJoined;
    ctx.states.push_back(joined);
  }
  const std::vector<Finding> findings = ComputeFindings(Classified(ctx));
  const Finding& lines = Find(findings, "normal_extension_lines");
  EXPECT_EQ(lines.verdict, Verdict::kReproduced) << lines.numbers;
  // No path beyond 110°: whether d is reached is not tested.
  EXPECT_EQ(Find(findings, "limit_d").verdict, Verdict::kNotTested);
  // A 120° path that is a gas, and d is not reached (σ_r/p = 0.24 at 45°).
  StateRow gas = Row("nc1000_psi120", TableKind::kExtension, 120, 0.1, 0.7, 50);
  gas.status = TableStatus::kGas;
  ctx.states.push_back(gas);
  EXPECT_EQ(Find(ComputeFindings(Classified(ctx)), "limit_d").verdict, Verdict::kReproduced);
  // A state at σ_r ≈ 0 (ψ_σ = 54°): the limit d found, unlike the paper.
  ctx.states.push_back(Row("nc1000_psi110", TableKind::kExtension, 110, 1, 0.66, 54.5));
  const Finding& d = Find(ComputeFindings(Classified(ctx)), "limit_d");
  EXPECT_EQ(d.verdict, Verdict::kNotReproduced) << d.numbers;
}

// Without isochoric critical states (a quasi-static set whose CSL comes from
// drained tests), the drained states at ψ_ε ≈ 90° are the critical states;
// when they reach the largest q/p_e* they are the apex, and the critical
// state is not "left of the apex" however far left the mean sits.
TEST(Findings, DrainedCriticalStatesThatReachTheLargestStressAreTheApex) {
  Context ctx = Study();
  for (double p : {100.0, 200.0, 500.0}) {
    const std::string name = "nc" + std::to_string(static_cast<int>(p)) + "_drained";
    const double ln_v = kN - std::log(3.0) * kLambda - kLambda * std::log(p);  // OCR 3
    ctx.states.push_back(Row(name, TableKind::kTriaxial, 90.4, p, ln_v, 20));
    ctx.cases.push_back(Case(name));
    const std::string extension = "nc" + std::to_string(static_cast<int>(p)) + "_psi95";
    const double ext_v = kN - std::log(8.0) * kLambda - kLambda * std::log(p);  // OCR 8
    ctx.states.push_back(Row(extension, TableKind::kExtension, 95, p, ext_v, 15));
    ctx.cases.push_back(Case(extension));
  }
  Finding f = Find(ComputeFindings(Classified(ctx)), "asbs_shape");
  EXPECT_NE(f.verdict, Verdict::kReproduced) << f.numbers;
  EXPECT_NE(f.numbers.find("drained critical states p/p_e* = 0.333"), std::string::npos)
      << f.numbers;
  EXPECT_NE(f.numbers.find("the critical states are the apex"), std::string::npos) << f.numbers;
  // An extension state of larger q/p_e* near the NCL: the apex, the critical
  // states left of it.
  const double near_v = kN - std::log(1.1) * kLambda - kLambda * std::log(50.0);
  ctx.states.push_back(Row("nc50_psi110", TableKind::kExtension, 110, 50, near_v, 40));
  ctx.cases.push_back(Case("nc50_psi110"));
  f = Find(ComputeFindings(Classified(ctx)), "asbs_shape");
  EXPECT_NE(f.verdict, Verdict::kNotReproduced) << f.numbers;
  EXPECT_NE(f.numbers.find("apex at ψ_ε = 110° (extension)"), std::string::npos) << f.numbers;
}

TEST(Findings, TheCsvNamesEveryFindingWithItsVerdict) {
  const fs::path dir =
      fs::temp_directory_path() / ("granasym_findings_" + std::to_string(getpid()));
  fs::create_directories(dir);
  Context ctx = Study();
  ctx.cases.push_back(NclCase(0.0));
  const std::vector<Finding> findings = ComputeFindings(Classified(ctx));
  WriteFindings(dir.string(), findings);
  const CsvTextTable table = CsvTextTable::ReadFile((dir / kFindingsFile).string());
  ASSERT_EQ(table.rows.size(), findings.size());
  const size_t id = table.Column("id"), verdict = table.Column("verdict");
  table.Column("source");
  table.Column("numbers");
  table.Column("rule");
  EXPECT_EQ(table.rows[0][id], "ncl_linear");
  EXPECT_EQ(table.rows[0][verdict], "reproduced");
  EXPECT_NE(FindingsLine(findings).find("1 reproduced"), std::string::npos)
      << FindingsLine(findings);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granasym::analysis
