#include "analysis/report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "analysis/calibration_selections.h"
#include "analysis/quasi_static_selection.h"
#include "analysis/rate_files.h"
#include "analysis/report_images.h"
#include "common/error.h"
#include "common/text_file.h"
#include "tests/analysis/rate_states_fixture.h"

namespace granasym::analysis {
namespace {
namespace fs = std::filesystem;

void Write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// The smallest file the report takes for a PNG: the signature and the IEND
// chunk (what it checks; it does not decode images).
const std::string kPng =
    std::string("\x89PNG\r\n\x1a\n") + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);

int Count(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

fs::path EmptyStudy(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "report" / name;
  fs::remove_all(dir);
  Write(dir / "study.toml",
        "# written by granasym study run\nprogramme = \"paper\"\nprogramme_file = \"paper.toml\"\n"
        "scale = \"tiny\"\nthreads = 1\nreplicates = 2\ncount = 400\nncl = \"ncl\"\n"
        "program_version = \"0.1.0+test\"\n");
  return dir;
}

// A study folder with every input of the report, in the formats of the
// contracts (analysis/report.h); texts carry markup that must come out escaped.
fs::path FullStudy(const std::string& name) {
  const fs::path dir = EmptyStudy(name);
  Write(dir / "asymptotic_states.csv",
        "replicate,kind,status,case,case_name,stage,psi_epsilon_deg,p_kpa,e,ln_1_plus_e,"
        "psi_sigma_deg,q_over_p,ocr,p_e_star_kpa,ncl_reference,run,figures,flags,detector,message\n"
        "1,ncl,detected,r1/ncl,ncl,stage_alpha,0,100.123456,0.8,0.5877866649,1.5,0.03,1,100,ncl,"
        "ncl,\"8, 16\",,compression: a window,all stages completed\n"
        "1,csl,drifting,r1/nc100_psi90,nc100_psi90,stage_beta,90,20.5,0.77,0.57,29.7,1.21,4.8,"
        "98.9,ncl,nc{p}_psi{psi},\"16\",rate_affected,isochoric: a window,"
        "\"still drifting: psi_sigma changed by 1.2 (< 1), say \"\"<b>bold</b>\"\" & more\"\n"
        "2,none,no_result,r2/oc,oc,,,,,,,,,,,oc,\"Sec. 5.2\",,,not run\n");
  Write(dir / "asymptotic_states_summary.csv",
        "case_name,stage,kind,replicates,detected,p_kpa_mean,p_kpa_ci95,psi_sigma_deg_mean,"
        "psi_sigma_deg_ci95\n"
        "ncl,stage_alpha,ncl,2,2,100.5,3.25,1.5,\n");
  Write(dir / "ncl_fit.csv",
        "replicate,case,points,detected,drifting,N,lambda_star,p_min_kpa,p_max_kpa\n"
        "1,ncl,5,1,4,0.6860190313,0.02522864244,30.47,597.39\n");
  Write(dir / "path_convergence.csv",
        "# paths of one psi_epsilon join where ln(1+e) and psi_sigma agree\n"
        "replicate,kind,psi_epsilon_deg,case_a,case_b,status,joined_at_p_kpa,ln_1_plus_e,"
        "psi_sigma_deg,overlap_from_p_kpa,overlap_to_p_kpa\n"
        "1,compression,30,nc20_psi30,nc5_psi30,joined,119.1,0.56,7.56,20.4,2000.9\n");
  Write(dir / "cases/r1/ncl/case.toml",
        "id = \"r1/ncl\"\nname = \"ncl\"\nreplicate = 1\nkey = \"aaaa1111\"\nparent = \"\"\n"
        "run = \"ncl\"\nfigures = \"8, 16\"\n");
  Write(dir / "cases/r1/ncl/done.toml",
        "key = \"aaaa1111\"\ntermination = \"completed\"\nmessage = \"all stages completed\"\n"
        "steps = 1000\nparticles = 400\nwall_seconds = 2.5\n");
  Write(dir / "cases/r1/nc100_psi90/case.toml",
        "id = \"r1/nc100_psi90\"\nname = \"nc100_psi90\"\nreplicate = 1\nkey = \"bbbb2222\"\n"
        "parent = \"r1/ncl\"\nrun = \"nc{p}_psi{psi}\"\nfigures = \"16\"\n");
  Write(dir / "cases/r1/nc100_psi90/done.toml",
        "key = \"bbbb2222\"\ntermination = \"completed\"\nmessage = \"all stages completed\"\n"
        "steps = 1600\nparticles = 400\nwall_seconds = 1.5\n");
  Write(dir / "cases/r2/oc/case.toml",
        "id = \"r2/oc\"\nname = \"oc\"\nreplicate = 2\nkey = \"cccc3333\"\nparent = \"\"\n");
  Write(dir / "models/fig5_psi45_ocr1/done.toml",
        "key = \"dddd4444\"\ntermination = \"completed\"\nmessage = \"reached_end\"\nsteps = 0\n"
        "particles = 0\nwall_seconds = 0.008\n");
  Write(dir / "figures/index.tsv",
        "stem\tfigure\ttitle\tcaption\n"
        "fig16_psi\t16\tψ_σ against ψ_ε\tAll paths; p < 100 kPa & \"quoted\" <i>markup</i>\n"
        "fig08_overlap\t8\tOverlaps\tNot drawn yet\n");
  Write(dir / "figures/fig16_psi.png", kPng);
  Write(dir / "figures/fig16_psi.pdf", "%PDF");
  Write(dir / "figures/fig16_psi.csv", "x,y\n");
  const fs::path clay = dir / "calibration/hypoplastic_clay";
  Write(clay / "parameters.csv",
        "parameter,value,std_error,ci95_low,ci95_high,status\n"
        "lambda_star,0.0252,0.0011,0.023,0.0274,fitted\n"
        "phi_c_deg,29.9,,,,at_bound\n"
        "kappa_star,0.004,0.01,-0.016,0.024,undetermined\n");
  Write(clay / "warnings.txt", "phi_c_deg at its upper bound\n\nkappa_star <undetermined>\n");
  Write(clay / "summary.txt", "Ceres: CONVERGENCE after 12 iterations <ok>\n");
  Write(clay / "model.toml", "[model]\nkind = \"hypoplastic_clay\"\n");
  return dir;
}

// What gnuplot 5.4's `set terminal svg mouse standalone` writes for a plot
// with two hypertext labels (`with labels hypertext`), shortened: its script,
// event handlers, ids in both quotes, references to them, and a label text
// with markup, an apostrophe and gnuplot's JavaScript escapes.
const char kGnuplotSvg[] = R"svg(<?xml version="1.0" encoding="utf-8"  standalone="no"?>
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">
<svg  onload="if (typeof(gnuplot_svg)!='undefined') gnuplot_svg.Init(evt)"
 width="600" height="400"
 viewBox="0 0 600 400"
 xmlns="http://www.w3.org/2000/svg"
 xmlns:xlink="http://www.w3.org/1999/xlink"
>

<title>Gnuplot</title>
<desc>Produced by GNUPLOT 5.4 patchlevel 4 </desc>

<script type="text/javascript" > <![CDATA[
var x = document.querySelectorAll('svg'); if (x.length < 2) { '<g id="not-an-element">'; }
]]>
</script>

<!-- Tie mousing to entire bounding box of the plot -->
<rect x="0" y="0" width="600" height="400" fill="#ffffff" stroke="black" stroke-width="1"
onclick="gnuplot_svg.toggleCoordBox(evt)"  onmousemove="gnuplot_svg.moveCoordBox(evt)"/>
<g id="gnuplot_canvas" onclick="gnuplot_svg.toggleCoordBox(evt)" onmousemove="gnuplot_svg.moveCoordBox(evt)">
<defs>
	<circle id='gpPt5' stroke-width='0.222' stroke='currentColor' cx='0' cy='0' r='1'/>
	<use xlink:href='#gpPt5' id='gpPt6' fill='currentColor' stroke='none'/>
	<filter id='textbox' filterUnits='objectBoundingBox' x='0' y='0' height='1' width='1'>
	  <feFlood flood-color='white' flood-opacity='1' result='bgnd'/>
	</filter>
</defs>
	<g id="gnuplot_plot_1" ><title>states</title>
	<g id="gnuplot_plot_1_keyentry" visibility="visible" onclick="gnuplot_svg.toggleVisibility(evt,'gnuplot_plot_1')">
	</g>
	<g onmousemove="gnuplot_svg.showHypertext(evt,'case nc100_psi90\nreplicate 2\nkind csl &amp; &lt;b> it\'s')" onmouseout="gnuplot_svg.hideHypertext()"><title> </title>
	<use xlink:href='#gpPt6' transform='translate(54.53,260.67) scale(4.50)' color='rgb(  0,   0,   0)'/></g>
	<g onmousemove="gnuplot_svg.showHypertext(evt,'case ncl\nreplicate 1')" onmouseout="gnuplot_svg.hideHypertext()">
	<use xlink:href='#gpPt6' transform='translate(574.82,157.34) scale(4.50)'/></g>
	<text filter="url(#textbox)"><tspan font-family="Arial" >p &lt; 1</tspan></text>
	</g>
<script type="text/javascript"><![CDATA[
gnuplot_svg.plot_term_xmax = 600;
]]>
</script>
</g>
  <text id="hypertext" class="hypertext" pointer-events="none" visibility="hidden"> </text>
  <image x='10' y='694' width='16' height='16' xlink:href='data:image/png;base64,iVBORw0KGgo'
    onclick='gnuplot_svg.toggleGrid();'/>
</svg>
)svg";

TEST(StudyReportImages, GnuplotSvgInlineHasTooltipsPrefixedIdsAndNoScript) {
  const report::InlineSvg svg =
      report::MakeInlineSvg(kGnuplotSvg, "fig16-", "Figure 16: ψ_σ & p", "fig16.svg");
  const std::string& m = svg.markup;
  EXPECT_EQ(svg.tooltips, 2);
  // The hover texts, unescaped and then escaped for HTML, in the groups' titles.
  EXPECT_NE(m.find("<g class=\"hover\"><title>case nc100_psi90\nreplicate 2\nkind csl &amp; "
                   "&lt;b&gt; it&#39;s</title>"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("<g class=\"hover\"><title>case ncl\nreplicate 1</title>"), std::string::npos);
  EXPECT_EQ(Count(m, "<title> </title>"), 0);
  // No script, no handler, no declaration; the curve's own title stays.
  for (const char* gone :
       {"<script", "gnuplot_svg", "onload", "onclick", "onmouse", "<?xml", "<!DOCTYPE", "<!--",
        "Gnuplot</title>", "not-an-element", "hypertext", "<image"}) {
    EXPECT_EQ(m.find(gone), std::string::npos) << gone;
  }
  EXPECT_NE(m.find("<title>states</title>"), std::string::npos);
  // Every id and every reference to one carries the figure's prefix.
  for (const char* prefixed :
       {"id=\"fig16-gnuplot_canvas\"", "id=\"fig16-gpPt5\"", "xlink:href=\"#fig16-gpPt5\"",
        "id=\"fig16-gpPt6\"", "xlink:href=\"#fig16-gpPt6\"", "filter=\"url(#fig16-textbox)\"",
        "id=\"fig16-gnuplot_plot_1_keyentry\""}) {
    EXPECT_NE(m.find(prefixed), std::string::npos) << prefixed;
  }
  EXPECT_EQ(Count(m, " id=\""), Count(m, " id=\"fig16-"));
  EXPECT_EQ(Count(m, "href=\"#"), Count(m, "href=\"#fig16-"));
  // The root is the element, labelled; the text keeps its entities.
  EXPECT_EQ(m.rfind("<svg ", 0), 0u) << m.substr(0, 80);
  EXPECT_NE(m.find("aria-label=\"Figure 16: ψ_σ &amp; p\""), std::string::npos);
  EXPECT_NE(m.find("viewBox=\"0 0 600 400\""), std::string::npos);
  EXPECT_NE(m.find("p &lt; 1"), std::string::npos);
  EXPECT_EQ(m.substr(m.size() - 6), "</svg>");
}

TEST(StudyReportImages, AnSvgThatIsNotOneIsAnErrorNamingTheFile) {
  for (const std::string& bad :
       {std::string("\x89PNG\r\n\x1a\n binary"), std::string("<svg width=\"1\"><g></svg>"),
        std::string("<svg><g id=\"a></g></svg>"), std::string("<?xml version=\"1.0\"?>\n")}) {
    try {
      report::MakeInlineSvg(bad, "p-", "label", "figures/x.svg");
      FAIL() << "accepted: " << bad;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("figures/x.svg: line "), std::string::npos)
          << error.what();
    }
  }
}

TEST(StudyReportImages, DataUriIsBase64WithPadding) {
  EXPECT_EQ(report::DataUri("image/png", "Man"), "data:image/png;base64,TWFu");
  EXPECT_EQ(report::DataUri("image/png", "Ma"), "data:image/png;base64,TWE=");
  EXPECT_EQ(report::DataUri("image/png", "M"), "data:image/png;base64,TQ==");
  EXPECT_EQ(report::DataUri("image/png", std::string("\xff\xfe\x00", 3)),
            "data:image/png;base64,//4A");
}

// The page is one file: each figure inline as SVG (ids apart per figure), or
// its PNG as a data URI when it has no SVG; the files are linked below it.
TEST(StudyReport, FiguresAreInlineSvgOrDataUrisAndLinkedBelow) {
  const fs::path dir = FullStudy("inline_figures");
  Write(dir / "figures/index.tsv",
        "stem\tfigure\ttitle\tcaption\n"
        "fig16_psi\t16\tψ_σ against ψ_ε\tAll paths\n"
        "fig17_asbs\t17\tSections\tThe same SVG again\n"
        "fig08_overlap\t8\tOverlaps\tA PNG only\n");
  Write(dir / "figures/fig16_psi.svg", kGnuplotSvg);
  Write(dir / "figures/fig17_asbs.svg", kGnuplotSvg);
  Write(dir / "figures/fig08_overlap.png", kPng);
  const ReportSummary summary = WriteReport(dir.string());
  EXPECT_EQ(summary.figures, 3);
  EXPECT_EQ(summary.figures_missing, 0);
  const std::string html = ReadTextFile(summary.html_path);
  const std::string md = ReadTextFile(summary.markdown_path);
  EXPECT_EQ(Count(html, "<svg "), 2);
  EXPECT_EQ(Count(html, "<g class=\"hover\"><title>case ncl\nreplicate 1</title>"), 2);
  EXPECT_NE(html.find("id=\"fig16_psi-gpPt6\""), std::string::npos);
  EXPECT_NE(html.find("id=\"fig17_asbs-gpPt6\""), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("onmouse"), std::string::npos);
  // No image is linked: the PNG without an SVG is in the page.
  EXPECT_EQ(Count(html, "<img "), 1);
  EXPECT_NE(html.find("<img src=\"data:image/png;base64,iVBORw0KGgoAAAAASUVORK5CYII=\""),
            std::string::npos);
  EXPECT_EQ(html.find("src=\"figures/"), std::string::npos);
  // Below each figure its files; report.md links the PNG (else the SVG).
  EXPECT_NE(html.find("Files: <a href=\"figures/fig16_psi.png\"><code>PNG</code></a> · <a "
                      "href=\"figures/fig16_psi.pdf\"><code>PDF</code></a> · <a "
                      "href=\"figures/fig16_psi.svg\"><code>SVG</code></a>"),
            std::string::npos);
  EXPECT_NE(md.find("](figures/fig16_psi.png)"), std::string::npos);
  EXPECT_NE(md.find("](figures/fig17_asbs.svg)"), std::string::npos);
  EXPECT_NE(md.find("](figures/fig08_overlap.png)"), std::string::npos);
  // A broken SVG stops the report, naming it.
  Write(dir / "figures/fig17_asbs.svg", "\x89PNG\r\n");
  try {
    WriteReport(dir.string());
    FAIL() << "a PNG written as .svg was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("fig17_asbs.svg: line "), std::string::npos)
        << error.what();
  }
}

TEST(StudyReport, HtmlEscapingReplacesEveryMarkupCharacter) {
  EXPECT_EQ(HtmlEscaped("a<b>&\"c\"'d'"), "a&lt;b&gt;&amp;&quot;c&quot;&#39;d&#39;");
  EXPECT_EQ(HtmlEscaped("plain ψ_σ"), "plain ψ_σ");
}

// A figure of a section ("Sec. 5.2") lists the rows that name that section,
// not those of figure 5.
TEST(StudyReport, TheStatesBehindASectionAreTheRowsThatNameIt) {
  const fs::path dir = FullStudy("section");
  Write(dir / "figures/index.tsv",
        "stem\tfigure\ttitle\tcaption\n"
        "sec52_time_step\tSec. 5.2\tTime-step independence\tΔt against Δt/5\n");
  const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
  EXPECT_NE(html.find("1 row of the state table behind Sec. 5.2"), std::string::npos);
  EXPECT_EQ(html.find("names figure 5"), std::string::npos);
}

// Figure numbers are compared whole: a row serving Sec. 5.2 is not behind
// figure 5 (the models' element tests), nor a row of figure 5 behind Sec. 5.2;
// "5.2" in the index is the section too.
TEST(StudyReport, FigureFiveIsNotSectionFivePointTwo) {
  const fs::path dir = FullStudy("figure_five");
  Write(dir / "figures/index.tsv",
        "stem\tfigure\ttitle\tcaption\n"
        "fig05_model_paths\t5\tModel paths\tThe models' element tests\n"
        "sec52_time_step\tSec. 5.2\tTime-step independence\tΔt against Δt/5\n"
        "sec52_old\t5.2\tTime-step independence\tAn older index\n"
        "fig12_triaxial\t12\tTriaxial\tNo case serves it\n");
  const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
  EXPECT_NE(html.find("Figure 5 draws the constitutive models&#39; element tests"),
            std::string::npos);
  EXPECT_EQ(html.find("names figure 5"), std::string::npos);
  EXPECT_EQ(Count(html, "1 row of the state table behind Sec. 5.2"), 2);
  EXPECT_NE(
      html.find("No row of the state table names figure 12: no case of this study serves it."),
      std::string::npos);
  EXPECT_NE(html.find("<h3 id=\"sec-52-time-step-independence\">Sec. 5.2: Time-step "
                      "independence</h3>"),
            std::string::npos);
}

// Figure 21 draws the detected critical and drained triaxial states of every
// case of the study's own sample; its rows are those, not the NCL rows of the
// cases that serve it.
TEST(StudyReport, TheRowsBehindFigure21AreTheCriticalStatesItDraws) {
  const fs::path dir = FullStudy("figure_21");
  Write(dir / "asymptotic_states.csv",
        "replicate,kind,status,case,case_name,stage,psi_epsilon_deg,p_kpa,q_over_p,source,figures\n"
        "1,ncl,detected,r1/ncl,ncl,p100,0,100,0.01,replicate,\"8, 21, 22\"\n"
        "1,csl,detected,r1/nc100_psi90,nc100_psi90,psi90,90,20.5,1.21,replicate,\"10, 16\"\n"
        "2,csl,drifting,r2/nc100_psi90,nc100_psi90,psi90,90,21.5,1.22,replicate,\"10, 16\"\n"
        "1,triaxial,detected,r1/tx100,tx100,shear,,150,1.25,replicate,\"12, 13\"\n"
        "1,csl,detected,r1/phi0_nc100_psi90,phi0_nc100_psi90,psi90,90,5,0.3,replicate,20\n"
        "1,csl,detected,r1/dt5_nc100_psi90,dt5_nc100_psi90,psi90,90,20,1.2,replicate,Sec. 5.2\n"
        "0,csl,detected,mean/nc100_psi90,nc100_psi90,psi90,90,21,1.21,ensemble,\"10, 16\"\n");
  Write(dir / "figures/index.tsv",
        "stem\tfigure\ttitle\tcaption\n"
        "fig21_friction_inertial\t21\tM against I\tCritical states\n"
        "fig22_inertial\t22\tI against p\tThe NCL path\n");
  const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
  const size_t at = html.find(
      "The 2 detected critical (csl) and drained triaxial states that "
      "figure 21 draws");
  ASSERT_NE(at, std::string::npos) << html;
  const std::string rows = html.substr(at, html.find("</details>", at) - at);
  EXPECT_NE(rows.find("<td>r1/nc100_psi90</td>"), std::string::npos) << rows;
  EXPECT_NE(rows.find("<td>r1/tx100</td>"), std::string::npos);
  for (const char* not_drawn : {"r1/ncl", "r2/nc100_psi90", "phi0", "dt5", "mean/"}) {
    EXPECT_EQ(rows.find(not_drawn), std::string::npos) << not_drawn;
  }
  // Figure 22 draws the paths of the cases that serve it: the NCL's row.
  EXPECT_NE(html.find("1 row of the state table behind figure 22 (the rows of the cases that "
                      "serve it)"),
            std::string::npos);
}

// The models' outcomes from fit_status.toml, each with its honest label;
// never a green "fitted" in a model that is not.
TEST(StudyReport, EachModelShowsItsOutcomeFromFitStatus) {
  const fs::path dir = FullStudy("fit_status");
  const fs::path clay = dir / "calibration/hypoplastic_clay";
  const struct {
    const char* status;
    const char* label;
    const char* css;
  } cases[] = {{"converged", "fitted", "status-fitted"},
               {"converged_inadmissible", "fitted, inadmissible", "status-inadmissible"},
               {"at_bound", "fitted, at a bound", "status-at_bound"},
               {"no_convergence", "failed", "status-failed"},
               {"failed", "failed", "status-failed"}};
  for (const auto& c : cases) {
    Write(clay / "fit_status.toml", std::string("status = \"") + c.status +
                                        "\"\nreason = \"the fit said why <" + c.status + ">\"\n");
    const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
    EXPECT_NE(html.find(std::string("<td class=\"") + c.css + "\">" + c.label +
                        "</td><td class=\"text\">the fit said why &lt;" + c.status + "&gt;</td>"),
              std::string::npos)
        << c.status;
    EXPECT_NE(html.find(std::string("Outcome: ") + c.label + ". the fit said why"),
              std::string::npos)
        << c.status;
    const size_t model = html.find("<h3 id=\"calibration-hypoplastic_clay\">");
    const std::string section = html.substr(model, html.find("<h3", model + 1) - model);
    const bool green = std::string(c.status) == "converged";
    EXPECT_EQ(section.find("<td class=\"status-fitted\">fitted</td>") != std::string::npos, green)
        << c.status;
    EXPECT_EQ(section.find("<td>fitted</td>") != std::string::npos, !green) << c.status;
  }
  Write(clay / "fit_status.toml", "status = \"fine\"\nreason = \"?\"\n");
  try {
    WriteReport(dir.string());
    FAIL() << "status 'fine' was accepted";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("fit_status.toml"), std::string::npos) << what;
    EXPECT_NE(what.find("status"), std::string::npos) << what;
    EXPECT_NE(what.find("converged_inadmissible"), std::string::npos) << what;
  }
  Write(clay / "fit_status.toml", "status = \"converged\"\n");
  EXPECT_THROW(WriteReport(dir.string()), InputError);
}

// Without fit_status.toml (an earlier calibration) the outcome is derived
// from the fit's termination, the admissibility warnings (not the misfit
// ones) and the parameters at a bound, and says so.
TEST(StudyReport, AnOutcomeWithoutFitStatusIsDerivedAndSaysSo) {
  const fs::path dir = FullStudy("derived_status");
  const fs::path clay = dir / "calibration/hypoplastic_clay";
  auto outcome = [&](const std::string& summary, const std::string& warnings) {
    Write(clay / "summary.txt", summary);
    Write(clay / "warnings.txt", warnings);
    const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
    const size_t at = html.find("<td class=\"status-");
    return html.substr(at, html.find("</td><td class=\"text\">", at) - at) + " | " +
           html.substr(html.find("Outcome: "), 300);
  };
  const std::string converged =
      "model: hypoplastic_clay\n\nceres: converged after 34 iterations, 899 evaluations\n";
  // The fixture's phi_c_deg is at_bound.
  std::string text = outcome(converged, "structural_misfit: ncl: the model is below\n");
  EXPECT_NE(text.find("status-at_bound\">fitted, at a bound"), std::string::npos) << text;
  EXPECT_NE(text.find("Derived by the report (no fit_status.toml"), std::string::npos) << text;
  EXPECT_NE(text.find("ceres converged, with phi_c_deg at a bound"), std::string::npos) << text;
  text = outcome(converged,
                 "ocr_below_one: 7 states above the NCL\nasbs_outside: beyond p/p_e* = 1\n"
                 "structural_misfit: ncl\n");
  EXPECT_NE(text.find("status-inadmissible\">fitted, inadmissible"), std::string::npos) << text;
  EXPECT_NE(text.find("the fitted model is inadmissible (ocr_below_one, asbs_outside in "
                      "warnings.txt)"),
            std::string::npos)
      << text;
  text = outcome("ceres: no_convergence after 100 iterations\n", "asbs_outside: far\n");
  EXPECT_NE(text.find("status-failed\">failed"), std::string::npos) << text;
  EXPECT_NE(text.find("ceres stopped before a convergence criterion was met"), std::string::npos)
      << text;
  text = outcome("ceres: failure after 0 iterations\n", "");
  EXPECT_NE(text.find("status-failed\">failed"), std::string::npos) << text;
  Write(clay / "parameters.csv",
        "parameter,value,std_error,ci95_low,ci95_high,status\n"
        "lambda_star,0.0252,0.0011,0.023,0.0274,fitted\n");
  text = outcome(converged, "structural_misfit: ncl\n");
  EXPECT_NE(text.find("status-fitted\">fitted"), std::string::npos) << text;
  text = outcome("no termination line\n", "");
  EXPECT_NE(text.find("status-fitted\">fitted"), std::string::npos) << text;
  EXPECT_NE(text.find("the fitter&#39;s termination is not in summary.txt"), std::string::npos)
      << text;
}

// The header names the folder absolutely: "folder ." says nothing.
TEST(StudyReport, TheHeaderNamesTheFolderAbsolutely) {
  const fs::path dir = FullStudy("relative");
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  std::string html;
  try {
    html = ReadTextFile(WriteReport(".").html_path);
  } catch (...) {
    fs::current_path(before);
    throw;
  }
  fs::current_path(before);
  EXPECT_NE(html.find("; folder <code>" + HtmlEscaped(fs::canonical(dir).string()) + "</code>."),
            std::string::npos);
}

TEST(StudyReport, EveryFigureOfTheIndexAppearsWithItsImageOrAMissingNote) {
  const fs::path dir = FullStudy("figures");
  const ReportSummary summary = WriteReport(dir.string());
  EXPECT_EQ(summary.figures, 2);
  EXPECT_EQ(summary.figures_missing, 1);
  const std::string html = ReadTextFile(summary.html_path);
  const std::string md = ReadTextFile(summary.markdown_path);
  EXPECT_NE(html.find("Figure 16: ψ_σ against ψ_ε"), std::string::npos);
  EXPECT_NE(html.find("Figure 8: Overlaps"), std::string::npos);
  EXPECT_EQ(Count(html, "<img "), 1);
  EXPECT_NE(html.find("<img src=\"data:image/png;base64,"), std::string::npos);
  EXPECT_NE(html.find("href=\"figures/fig16_psi.pdf\""), std::string::npos);
  EXPECT_NE(html.find("href=\"figures/fig16_psi.csv\""), std::string::npos);
  EXPECT_NE(html.find("<code>figures/fig08_overlap.png</code> is missing"), std::string::npos);
  EXPECT_NE(md.find("![Figure 16: ψ\\_σ against ψ\\_ε](figures/fig16_psi.png)"), std::string::npos)
      << md;
  EXPECT_NE(md.find("`figures/fig08_overlap.png` is missing"), std::string::npos);
  // The states behind figure 16: the two rows that name it, not the third.
  EXPECT_NE(html.find("2 rows of the state table behind figure 16"), std::string::npos);
  EXPECT_NE(html.find("1 row of the state table behind figure 8"), std::string::npos);
  EXPECT_EQ(summary.absent, (std::vector<std::string>{
                                "calibration/hypoplastic_sand/", "calibration/modified_cam_clay/",
                                "figures/fig08_overlap.png", "findings.csv"}));
}

// A truncated PNG and a file that is no PNG are reported as invalid and
// counted as not drawn, never shown.
TEST(StudyReport, ATruncatedOrFakePngIsReportedInvalidNotShown) {
  for (const std::string& bad : {kPng.substr(0, kPng.size() - 3), std::string("GIF89a fake")}) {
    const fs::path dir = FullStudy("bad_png");
    Write(dir / "figures/fig16_psi.png", bad);
    const ReportSummary summary = WriteReport(dir.string());
    EXPECT_EQ(summary.figures, 2);
    EXPECT_EQ(summary.figures_missing, 2);  // fig08 has no image; fig16's is invalid
    const std::string html = ReadTextFile(summary.html_path);
    EXPECT_EQ(Count(html, "<img "), 0);
    EXPECT_NE(html.find("<code>figures/fig16_psi.png</code> is not a valid PNG ("),
              std::string::npos);
    EXPECT_EQ(html.find("href=\"figures/fig16_psi.png\""), std::string::npos);
    EXPECT_NE(html.find(bad.size() > 12 ? "truncated" : "no PNG signature"), std::string::npos);
    EXPECT_NE(
        std::find(summary.absent.begin(), summary.absent.end(), "figures/fig16_psi.png (invalid)"),
        summary.absent.end());
  }
}

TEST(StudyReport, EveryStateRowAppearsInBothFiles) {
  const fs::path dir = FullStudy("states");
  const ReportSummary summary = WriteReport(dir.string());
  EXPECT_EQ(summary.states, 3);
  const std::string html = ReadTextFile(summary.html_path);
  const std::string md = ReadTextFile(summary.markdown_path);
  for (const char* stage : {"stage_alpha", "stage_beta"}) {
    EXPECT_NE(html.find(std::string("<td>") + stage + "</td>"), std::string::npos) << stage;
    EXPECT_NE(md.find(std::string("| ") + stage + " |"), std::string::npos) << stage;
  }
  // Folded by kind, the counts in the summary; messages unwrapped.
  for (const char* group : {"<details><summary>csl: 1 row (1 drifting)</summary>",
                            "<details><summary>ncl: 1 row (1 detected)</summary>",
                            "<details><summary>none: 1 row (1 no_result)</summary>"}) {
    EXPECT_NE(html.find(group), std::string::npos) << group;
  }
  EXPECT_NE(html.find("<td>still drifting: psi_sigma changed"), std::string::npos);
  // The row without a result, by its message; every case links to its scene.
  EXPECT_NE(html.find("<td class=\"status-no_result\">no_result</td>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"cases/r2/oc/scene.toml\">r2/oc</a>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"flagged\">rate_affected</td>"), std::string::npos);
  // Numbers shortened, detectors listed once.
  EXPECT_NE(html.find("<td class=\"num\">100.1</td>"), std::string::npos);
  EXPECT_NE(html.find("D2: isochoric: a window"), std::string::npos);
  // Quoted fields with commas and quotes stay one field.
  EXPECT_NE(html.find("still drifting: psi_sigma changed by 1.2 (&lt; 1), say "
                      "&quot;&lt;b&gt;bold&lt;/b&gt;&quot; &amp; more"),
            std::string::npos);
  // The replicate summary pairs means with their intervals.
  EXPECT_NE(html.find("<th>p_kpa (mean ± 95 %)</th>"), std::string::npos);
  EXPECT_NE(html.find("100.5 ± 3.2"), std::string::npos);
  EXPECT_NE(html.find("<p>paths of one psi_epsilon join where ln(1+e) and psi_sigma agree</p>"),
            std::string::npos);
  EXPECT_NE(html.find("<td class=\"status-joined\">joined</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">0.686</td><td class=\"num\">0.02523</td>"),
            std::string::npos);
}

// The ensemble rows (the replicates' mean paths) are listed with their
// source and counted apart from the replicates' rows.
TEST(StudyReport, EnsembleRowsAreListedWithTheirSourceAndCountedApart) {
  const fs::path dir = FullStudy("ensemble");
  Write(dir / "asymptotic_states.csv",
        "replicate,kind,status,case,case_name,stage,psi_epsilon_deg,p_kpa,source,figures\n"
        "1,csl,drifting,r1/nc100_psi90,nc100_psi90,psi90,90,20.5,replicate,16\n"
        "2,csl,drifting,r2/nc100_psi90,nc100_psi90,psi90,90,21.5,replicate,16\n"
        "0,csl,detected,mean/nc100_psi90,nc100_psi90,psi90,90,21,ensemble,16\n");
  const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
  EXPECT_NE(html.find("<td>ensemble</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>csl (ensemble mean)</td>"), std::string::npos);
  EXPECT_NE(html.find("2 rows, 2 drifting; and 1 ensemble-mean rows"), std::string::npos);
}

// The answers first: the findings, the fitted parameters, the figures; then
// the rate study and the tables.
TEST(StudyReport, ThePageAnswersFirst) {
  const fs::path dir = FullStudy("order");
  Write(dir / "findings.csv",
        "source,claim,verdict,numbers,rule\nFig. 16,the CSL exists,reproduced,M = 1.2,a rule\n");
  const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
  std::vector<std::string> order;
  for (size_t at = html.find("<h2 id=\""); at != std::string::npos;
       at = html.find("<h2 id=\"", at + 1)) {
    order.push_back(html.substr(at + 8, html.find('"', at + 8) - at - 8));
  }
  EXPECT_EQ(order, (std::vector<std::string>{
                       "findings-the-papers-claims-in-this-study", "fitted-parameters", "figures",
                       "overview", "asymptotic-states", "replicate-summary", "ncl-fits",
                       "path-convergence", "run-times-and-keys", "provenance"}));
}

TEST(StudyReport, NoTextOfTheInputsIsTakenAsMarkup) {
  const fs::path dir = FullStudy("escaping");
  const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
  for (const char* raw : {"<b>bold", "<i>markup", "<undetermined>", "<ok>"}) {
    EXPECT_EQ(html.find(raw), std::string::npos) << raw;
  }
  for (const char* escaped :
       {"&lt;i&gt;markup&lt;/i&gt;", "p &lt; 100 kPa &amp; &quot;quoted&quot;",
        "kappa_star &lt;undetermined&gt;", "12 iterations &lt;ok&gt;"}) {
    EXPECT_NE(html.find(escaped), std::string::npos) << escaped;
  }
  // Self-contained: no scripts, no stylesheets or images from elsewhere.
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("src=\"/"), std::string::npos);
  EXPECT_EQ(Count(html, "<style>"), 1);
}

TEST(StudyReport, CalibrationShowsIntervalsStatusesWarningsAndSummary) {
  const fs::path dir = FullStudy("calibration");
  const ReportSummary summary = WriteReport(dir.string());
  EXPECT_EQ(summary.models_calibrated, 1);
  const std::string html = ReadTextFile(summary.html_path);
  EXPECT_NE(html.find("3 parameters (1 at_bound, 1 fitted, 1 undetermined)"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">[0.023, 0.0274]</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"status-at_bound\">at_bound</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"status-undetermined\">undetermined</td>"), std::string::npos);
  // The blank line is not a warning; the list is folded, counted by code.
  EXPECT_NE(html.find("<details><summary>2 warnings (2 other), from "
                      "<code>calibration/hypoplastic_clay/warnings.txt</code></summary>"),
            std::string::npos);
  EXPECT_NE(html.find("<li>phi_c_deg at its upper bound</li>"), std::string::npos);
  EXPECT_NE(html.find("<details><summary>Summary of the fit"), std::string::npos);
  EXPECT_NE(html.find("href=\"calibration/hypoplastic_clay/model.toml\""), std::string::npos);
  EXPECT_NE(html.find("<code>calibration/modified_cam_clay/</code> is absent (run "
                      "<code>granasym study calibrate"),
            std::string::npos);
}

// A calibration with profile likelihoods (parameters.csv's profile columns)
// and the Pareto figure: the flags in the table, a sentence naming the flat
// ones, the Pareto PNG inline; profiles.csv without its PNG is a note.
TEST(StudyReport, CalibrationShowsProfileFlagsAndTheParetoFigure) {
  const fs::path dir = FullStudy("profiles");
  const fs::path clay = dir / "calibration/hypoplastic_clay";
  Write(clay / "parameters.csv",
        "parameter,value,std_error,ci95_low,ci95_high,status,profile_low,profile_high,profile\n"
        "lambda_star,0.0252,0.0011,0.023,0.0274,fitted,0.0231,0.0276,determined\n"
        "r,0.4,,,,undetermined,0.09,,flat\n"
        "kappa_star,0.004,,,,fixed,,,\n");
  Write(clay / "plot_data/pareto.csv", "weight\n0.5\n");
  Write(clay / "plot_data/pareto.png", "not really a PNG either");
  Write(clay / "plot_data/profiles.csv", "parameter,value\n");
  const ReportSummary summary = WriteReport(dir.string());
  const std::string html = ReadTextFile(summary.html_path);
  const std::string md = ReadTextFile(summary.markdown_path);
  EXPECT_NE(html.find("<th>profile 95 % interval</th>"), std::string::npos) << html;
  EXPECT_NE(html.find("<td class=\"num\">[0.0231, 0.0276]</td><td>determined</td>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<td class=\"num\">[0.09, —]</td><td class=\"status-undetermined\">flat: "
                      "not determined</td>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<td>not profiled</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("1 determined (lambda_star); 1 flat, not determined (r)."), std::string::npos)
      << html;
  EXPECT_NE(md.find("![Pareto front: hypoplastic_clay](calibration/hypoplastic_clay/plot_data/"
                    "pareto.png)"),
            std::string::npos)
      << md;
  EXPECT_NE(html.find("<code>calibration/hypoplastic_clay/plot_data/profiles.png</code> is "
                      "missing (its data"),
            std::string::npos)
      << html;
  EXPECT_NE(std::find(summary.absent.begin(), summary.absent.end(),
                      "calibration/hypoplastic_clay/plot_data/profiles.png"),
            summary.absent.end());
}

// Two selections of one model (issue 36 §2): the paper-rate calibration in
// calibration/<model>/ and the quasi-static one in
// calibration/quasi_static/<model>/ each get a section, and the default's
// opens with both side by side: value [interval] and verdict per selection,
// "undetermined (profile flat)" where the profile is flat; the model counts
// once; parameters_by_selection.csv holds the same.
TEST(StudyReport, BothSelectionsOfAModelSideBySide) {
  const fs::path dir = FullStudy("selections");
  const fs::path paper = dir / "calibration/modified_cam_clay";
  const fs::path quasi = dir / "calibration/quasi_static/modified_cam_clay";
  Write(paper / "parameters.csv",
        "parameter,value,std_error,ci95_low,ci95_high,status,profile_low,profile_high,profile,"
        "units\n"
        "phi_c_deg,25.1,0.3,24.5,25.7,fitted,24.6,25.6,determined,deg\n"
        "poisson_ratio,0.3,,,,undetermined,,,flat,1\n");
  Write(paper / "fit_status.toml", "status = \"converged\"\nreason = \"converged\"\n");
  Write(quasi / "parameters.csv",
        "parameter,value,std_error,ci95_low,ci95_high,status,profile_low,profile_high,profile,"
        "units\n"
        "phi_c_deg,19.9,0.3,19.3,20.5,fitted,19.4,20.4,determined,deg\n"
        "poisson_ratio,0.25,0.01,0.23,0.27,fitted,0.22,0.28,determined,1\n");
  Write(quasi / "fit_status.toml", "status = \"at_bound\"\nreason = \"at a bound\"\n");
  EXPECT_EQ(WriteParametersBySelection(dir.string(), {"modified_cam_clay", "hypoplastic_clay"}),
            (dir / kParametersBySelectionFile).string());
  const std::string csv = ReadTextFile((dir / kParametersBySelectionFile).string());
  EXPECT_NE(csv.find("modified_cam_clay,phi_c_deg,deg,25.1,24.6,25.6,profile,fitted,determined,"
                     "fitted,19.9,19.4,20.4,profile,fitted,determined,fitted,converged,at_bound\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("modified_cam_clay,poisson_ratio,1,0.3,,,,undetermined,flat,undetermined "
                     "(profile flat),0.25,0.22,0.28,profile,fitted,determined,fitted,"),
            std::string::npos)
      << csv;
  const ReportSummary summary = WriteReport(dir.string());
  const std::string html = ReadTextFile(summary.html_path);
  for (const char* text :
       {"<th>paper rate (all detected states): value [95 % interval]</th>",
        "<th>quasi-static: value [95 % interval]</th>", "<th>unit</th>",
        "<td class=\"num\">25.1 [24.6, 25.6]</td>", "<td class=\"num\">19.9 [19.4, 20.4]</td>",
        "undetermined (profile flat)</td>", "id=\"calibration-modified_cam_clay-quasi-static\"",
        "Calibration: modified_cam_clay (quasi-static)", "A paper uses"}) {
    EXPECT_NE(html.find(text), std::string::npos) << text;
  }
  // The side-by-side table comes before the default's own table.
  const size_t section = html.find("id=\"calibration-modified_cam_clay\"");
  ASSERT_NE(section, std::string::npos);
  EXPECT_LT(html.find("quasi-static: value [95 % interval]", section),
            html.find("<th>standard error</th>", section));
}

TEST(StudyReport, RunTimesCountEachCaseOwnStepsAndTotal) {
  const fs::path dir = FullStudy("run_times");
  const std::string html = ReadTextFile(WriteReport(dir.string()).html_path);
  // nc100_psi90 continues the 1000 steps of ncl: 600 of its own.
  EXPECT_NE(html.find("<td class=\"num\">600</td><td class=\"num\">1600</td>"), std::string::npos);
  EXPECT_NE(html.find("2 finished cases: 1600 steps of their own, 6.4e+05 particle-steps, 4.0 s"),
            std::string::npos);
  EXPECT_NE(html.find("<tr class=\"total\"><td>total: 2 finished of 3</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"status-not_run\">not_run</td>"), std::string::npos);
  EXPECT_NE(html.find("<code>bbbb2222</code>"), std::string::npos);
  EXPECT_NE(html.find("<code>dddd4444</code>"), std::string::npos);
  // Provenance: the study record, every key.
  EXPECT_NE(html.find("<td><code>program_version</code></td><td>0.1.0+test</td>"),
            std::string::npos);
  EXPECT_NE(html.find("Scale tiny: 2 replicates of 400 spheres, 1 thread per case; computed by "),
            std::string::npos);
}

TEST(StudyReport, AbsentInputsAreStatedInTheirPlace) {
  const fs::path dir = EmptyStudy("absent");
  const ReportSummary summary = WriteReport((dir / "").string());  // a trailing '/' is fine
  const std::string html = ReadTextFile(summary.html_path);
  const std::string md = ReadTextFile(summary.markdown_path);
  const std::string folder = dir.string();
  EXPECT_NE(html.find("Figures not drawn: run <code>granasym study figures " + folder + "</code>"),
            std::string::npos);
  EXPECT_NE(md.find("Figures not drawn: run `granasym study figures " + folder + "`"),
            std::string::npos);
  EXPECT_EQ(Count(html, "Not calibrated: "), 3);
  for (const char* file : {"asymptotic_states.csv", "asymptotic_states_summary.csv", "ncl_fit.csv",
                           "path_convergence.csv"}) {
    EXPECT_NE(html.find(std::string("<code>") + file + "</code> is absent"), std::string::npos)
        << file;
  }
  EXPECT_NE(html.find("No case folders"), std::string::npos);
  // The four tables, three models, the figure index and the findings.
  EXPECT_EQ(summary.absent.size(), 9u);
  EXPECT_NE(html.find("findings.csv is absent"), std::string::npos);
  EXPECT_NE(summary.Text().find("absent: asymptotic_states.csv"), std::string::npos);
  // Every section is in the contents, with the anchor its heading has.
  for (const char* anchor : {"overview", "figures", "fitted-parameters", "asymptotic-states",
                             "replicate-summary", "ncl-fits", "path-convergence",
                             "run-times-and-keys", "provenance", "calibration-hypoplastic_clay"}) {
    EXPECT_NE(html.find(std::string("<a href=\"#") + anchor + "\">"), std::string::npos) << anchor;
    EXPECT_NE(html.find(std::string(" id=\"") + anchor + "\">"), std::string::npos) << anchor;
    EXPECT_NE(md.find(std::string("](#") + anchor + ")"), std::string::npos) << anchor;
  }
}

TEST(StudyReport, BadInputIsAnErrorNamingTheFile) {
  const fs::path none = fs::temp_directory_path() / "granasym_tests" / "report" / "not_a_study";
  fs::remove_all(none);
  fs::create_directories(none);
  try {
    WriteReport(none.string());
    FAIL() << "a folder without study.toml was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("study.toml: not a study folder"), std::string::npos);
  }
  const fs::path dir = FullStudy("bad_parameters");
  Write(dir / "calibration/hypoplastic_clay/parameters.csv", "parameter,value\nlambda_star,1\n");
  try {
    WriteReport(dir.string());
    FAIL() << "parameters.csv without its columns was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("parameters.csv: missing column 'status'"),
              std::string::npos)
        << error.what();
  }
  const fs::path stem = FullStudy("bad_stem");
  Write(stem / "figures/index.tsv", "stem\tfigure\ttitle\tcaption\n../secret\t1\tt\tc\n");
  try {
    WriteReport(stem.string());
    FAIL() << "a stem outside figures/ was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("index.tsv: line 2: stem '../secret'"),
              std::string::npos)
        << error.what();
  }
}

TEST(StudyReport, TheRateStudySectionAppearsOnlyWithRateFiles) {
  const fs::path dir = FullStudy("rate");
  const std::string before = ReadTextFile(WriteReport(dir.string()).html_path);
  EXPECT_EQ(before.find("Rate study"), std::string::npos);
  EXPECT_EQ(before.find("rate_summary.csv"), std::string::npos);
  // With a stiffness variant at I* = 1e-3 (ψ_σ one degree higher): its table.
  std::vector<RateState> states = rate_fixture::CriticalStates();
  for (const RateState& s : rate_fixture::CriticalStates()) {
    if (s.rule == dem::RateRule::kInertial && s.rate() == 1e-3) {
      RateState soft = s;
      soft.youngs_modulus_mpa = 100;
      soft.psi_sigma_deg += 1.0;
      states.push_back(soft);
    }
  }
  WriteRateFiles(dir.string(), RateStudy::Analyse(states));
  const ReportSummary summary = WriteReport(dir.string());
  const std::string html = ReadTextFile(summary.html_path);
  const std::string md = ReadTextFile(summary.markdown_path);
  EXPECT_NE(html.find("<h2 id=\"rate-study\">Rate study</h2>"), std::string::npos);
  EXPECT_NE(md.find("## Rate study"), std::string::npos);
  for (const char* file : {kRateIndependenceFile, kRateQuasiStaticFile, kRateLinesFile,
                           kRateSummaryFile, kRateStiffnessFile}) {
    EXPECT_NE(html.find(std::string("href=\"") + file + "\""), std::string::npos) << file;
  }
  EXPECT_EQ(Count(html, "<td class=\"status-invalid\">stiffness_dependent</td>"), 2);
  // The answers first: the isochoric limits and the verdict counts.
  EXPECT_NE(md.find("The answers, from the tables below:"), std::string::npos);
  EXPECT_NE(md.find("Stiffness scaling against E = 500 MPa (ψ\\_σ and the CSL per start and rate): "
                    "2 stiffness_dependent."),
            std::string::npos)
      << md.substr(md.find("The answers"), 2000);
  // Verdicts and comparisons in the status colours; means with their intervals.
  EXPECT_EQ(Count(html, "<td class=\"status-invalid\">rate_dependent</td>"), 2);
  EXPECT_NE(html.find("<td class=\"status-invalid\">differ</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"status-detected\">agree</td>"), std::string::npos);
  EXPECT_NE(html.find("psi_sigma_deg_smallest (mean ± 95 %)"), std::string::npos);
  EXPECT_NE(html.find("limit (mean ± 95 %)"), std::string::npos);
  // The tables' comments state the fit and the criterion.
  EXPECT_NE(html.find("Welch"), std::string::npos);
  EXPECT_NE(html.find("da Cruz et al. 2005"), std::string::npos);
  // A missing table is named where it would be, and among the absent inputs.
  fs::remove(dir / kRateLinesFile);
  const ReportSummary partial = WriteReport(dir.string());
  EXPECT_NE(std::find(partial.absent.begin(), partial.absent.end(), kRateLinesFile),
            partial.absent.end());
  EXPECT_NE(ReadTextFile(partial.html_path).find("<code>rate_lines.csv</code> is absent"),
            std::string::npos);
}

TEST(Report, TheRateSectionSaysHowFarTheExtensionStatesGo) {
  const fs::path dir = FullStudy("rate_extension");
  std::vector<RateState> states = rate_fixture::CriticalStates();
  for (const RateState& s : rate_fixture::ExtensionSweep()) states.push_back(s);
  WriteRateFiles(dir.string(), RateStudy::Analyse(states));
  const ReportSummary summary = WriteReport(dir.string());
  const std::string html = ReadTextFile(summary.html_path);
  const std::string md = ReadTextFile(summary.markdown_path);
  for (const char* file : {kRateExtensionLimitFile, kRateExtensionFile}) {
    EXPECT_NE(html.find(std::string("href=\"") + file + "\""), std::string::npos) << file;
  }
  EXPECT_NE(html.find("How far the extension states go"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"status-invalid\">liquefied</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"status-detected\">limit_d</td>"), std::string::npos);
  EXPECT_NE(html.find("liquefied at psi_epsilon = 110 deg"), std::string::npos);
  EXPECT_NE(md.find("psi_epsilon(d) = 120.0 +- "), std::string::npos);
  EXPECT_NE(html.find("psi_d_deg (mean ± 95 %)"), std::string::npos);
}

}  // namespace
}  // namespace granasym::analysis
