#include "app/study_report_command.h"

#include <cstdio>
#include <string>

#include "analysis/report.h"

namespace granasym {

void RegisterStudyReportCommand(CLI::App* study) {
  CLI::App* report = study->add_subcommand(
      "report",
      "write DIR/index.html (one self-contained file: the findings and fitted parameters "
      "first, then the figures inline with hover labels, then the states, run times and "
      "provenance) and DIR/report.md");
  static std::string directory;
  report->add_option("dir", directory, "study folder")->required()->check(CLI::ExistingDirectory);
  report->callback([] {
    const analysis::ReportSummary summary = analysis::WriteReport(directory);
    std::printf("%s", summary.Text().c_str());
  });
}

}  // namespace granasym
