// Reading results: a DEM result file (dem/run_record.h), a study's state
// table (study/state_table.h); a calibration's folder: python/calibration.cc.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "python/bindings.h"
#include "study/state_table.h"

namespace py = pybind11;

namespace granasym::python {
namespace {

namespace record = dem::record;

// A DEM result file, read once.
struct DemResult {
  std::string path;
  TimeSeries series;
  std::vector<dem::StageRecord> stages;
  std::optional<dem::RunSummary> summary;
  std::string info, note;
};

DemResult ReadResult(const std::string& path) {
  const Hdf5File file = Hdf5File::OpenRead(path);
  DemResult result;
  result.path = path;
  if (!file.Exists(record::kSeries)) {
    throw InputError(path + ": no " + record::kSeries + " group: not a granasym DEM result");
  }
  result.series = TimeSeries::Read(file, record::kSeries);
  if (file.Exists(record::kStages)) result.stages = dem::ReadStageRecords(file);
  if (file.Exists(record::kSummary)) {
    result.summary = dem::ReadSummary(file);
    result.note = dem::PartialResultNote(file);
  } else {
    result.note = path + ": no " + record::kSummary + ": the run has not written its results";
  }
  result.info = dem::DescribeResult(file);
  return result;
}

py::dict SeriesArrays(const DemResult& result) {
  py::dict arrays;
  for (const TimeSeries::Column& column : result.series.columns()) {
    arrays[py::str(column.name)] = Array(result.series.Values(column.name));
  }
  return arrays;
}

py::dict SeriesUnits(const DemResult& result) {
  py::dict units;
  for (const TimeSeries::Column& column : result.series.columns()) {
    units[py::str(column.name)] = column.units;
  }
  return units;
}

py::object SeriesFrame(const DemResult& result) {
  std::vector<std::pair<std::string, py::object>> columns;
  for (const TimeSeries::Column& column : result.series.columns()) {
    columns.emplace_back(column.name, Array(result.series.Values(column.name)));
  }
  return DataFrame(columns, SeriesUnits(result));
}

// One row per stage: its record and, where its detector ran, its asymptote,
// under the names of the result file's attributes.
py::object StagesFrame(const DemResult& result) {
  std::vector<std::string> name, type, stop, flags, kind, status;
  std::vector<double> first, last, failed, detected, p, e, psi_sigma, psi_epsilon, q_over_p,
      coordination, i_dmin, i_dmax, overlap;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (const dem::StageRecord& stage : result.stages) {
    name.push_back(stage.name);
    type.push_back(stage.type);
    first.push_back(static_cast<double>(stage.first_row));
    last.push_back(static_cast<double>(stage.last_row));
    stop.push_back(stage.stop_reason);
    failed.push_back(stage.failed ? 1 : 0);
    flags.push_back(stage.validity.FlagNames());
    const dem::AsymptoteRecord* a = stage.asymptote ? &*stage.asymptote : nullptr;
    kind.push_back(a ? ToString(a->path_kind) : "");
    status.push_back(a ? ToString(a->status) : "");
    detected.push_back(a ? (a->detected ? 1 : 0) : kNaN);
    p.push_back(a ? a->mean_stress_kpa : kNaN);
    e.push_back(a ? a->void_ratio : kNaN);
    psi_sigma.push_back(a ? a->psi_sigma_deg : kNaN);
    psi_epsilon.push_back(a ? a->psi_epsilon_deg : kNaN);
    q_over_p.push_back(a ? a->q_over_p : kNaN);
    coordination.push_back(a ? a->mechanical_coordination : kNaN);
    i_dmin.push_back(a ? a->inertial_number_dmin : kNaN);
    i_dmax.push_back(a ? a->inertial_number_dmax : kNaN);
    overlap.push_back(a ? a->max_relative_overlap : kNaN);
  }
  auto texts = [](const std::vector<std::string>& values) { return py::cast(values); };
  py::dict units;
  units[record::kAsymptoteMeanStressKpa] = "kPa";
  units[record::kAsymptotePsiSigmaDeg] = "deg";
  units[record::kAsymptotePsiEpsilonDeg] = "deg";
  return DataFrame({{record::kStageName, texts(name)},
                    {record::kStageType, texts(type)},
                    {record::kStageFirstRow, Array(first).attr("astype")("int64")},
                    {record::kStageLastRow, Array(last).attr("astype")("int64")},
                    {record::kStageStopReason, texts(stop)},
                    {record::kStageFailed, Array(failed).attr("astype")("bool")},
                    {record::kValidityFlags, texts(flags)},
                    {record::kAsymptotePathKind, texts(kind)},
                    {record::kAsymptoteStatus, texts(status)},
                    {record::kAsymptoteDetected, Array(detected)},
                    {record::kAsymptoteMeanStressKpa, Array(p)},
                    {record::kAsymptoteVoidRatio, Array(e)},
                    {record::kAsymptotePsiSigmaDeg, Array(psi_sigma)},
                    {record::kAsymptotePsiEpsilonDeg, Array(psi_epsilon)},
                    {record::kAsymptoteQOverP, Array(q_over_p)},
                    {record::kAsymptoteMechanicalCoordination, Array(coordination)},
                    {record::kAsymptoteInertialNumberDmin, Array(i_dmin)},
                    {record::kAsymptoteInertialNumberDmax, Array(i_dmax)},
                    {record::kAsymptoteMaxRelativeOverlap, Array(overlap)}},
                   units);
}

}  // namespace

py::dict SummaryDict(const dem::RunSummary& s) {
  py::dict d;
  d[record::kTermination] = ToString(s.termination);
  d[record::kMessage] = s.message;
  d[record::kValidity] = s.validity;
  d[record::kSteps] = s.steps;
  d[record::kParticles] = s.particles;
  d[record::kSimulatedTime] = s.simulated_time;
  d[record::kWallSeconds] = s.wall_seconds;
  d[record::kLoopSeconds] = s.loop_seconds;
  d[record::kParticleStepsPerSecond] = s.particle_steps_per_second;
  d[record::kNeighborBuilds] = s.neighbor_builds;
  d[record::kRows] = s.rows;
  d[record::kStagesCompleted] = s.stages_completed;
  d[record::kThreads] = s.threads;
  d[record::kTimeStep] = s.time_step;
  d[record::kTimeStepMin] = s.min_time_step;
  d[record::kTimeStepMax] = s.max_time_step;
  d[record::kTimeStepRule] = s.time_step_rule;
  d[record::kStiffnessScaling] = s.stiffness_scaling;
  return d;
}

void BindResults(py::module_& module) {
  py::class_<DemResult>(module, "DemResult",
                        "A DEM result file (RUN.h5): its series, stages and summary.")
      .def_readonly("path", &DemResult::path)
      .def_property_readonly("series", &SeriesFrame,
                             "the recorded rows as a DataFrame, one column per output column "
                             "(units in the names and in attrs['units'])")
      .def_property_readonly("arrays", &SeriesArrays, "the series as numpy arrays by column name")
      .def_property_readonly("units", &SeriesUnits, "the units of each series column")
      .def_property_readonly("stages", &StagesFrame,
                             "one row per stage: its record and, where its detector ran, its "
                             "asymptote (asymptote_*; NaN and '' where none)")
      .def_property_readonly(
          "summary",
          [](const DemResult& r) -> py::object {
            return r.summary ? py::object(SummaryDict(*r.summary)) : py::object(py::none());
          },
          "the run's summary (termination, message, counters, times; None before the run "
          "wrote it)")
      .def_property_readonly(
          "final", [](const DemResult& r) { return r.note.empty(); },
          "whether the file is the result of a completed run (else see `note`)")
      .def_readonly("note", &DemResult::note,
                    "'' for a final result; else why it is not one and how to continue it")
      .def_readonly("info", &DemResult::info, "what the file holds, as `granasym export --info`")
      .def("__repr__", [](const DemResult& r) {
        return "<granasym.DemResult " + r.path + ": " + std::to_string(r.series.rows()) +
               " rows, " + std::to_string(r.stages.size()) + " stages>";
      });
  module.def("read_result", &ReadResult, py::arg("path"),
             "Reads a DEM result file (granasym dem run, a study's case result.h5).");

  module.def(
      "read_state_table",
      [](const std::string& directory, bool ensemble) {
        std::vector<study::StateRow> rows = study::ReadStateTable(directory);
        if (!ensemble) rows = study::WithoutEnsembleRows(std::move(rows));
        std::vector<std::pair<std::string, py::object>> columns;
        py::dict units;
        for (const study::StateTableColumn& column : study::StateTableColumns(rows)) {
          if (column.text) {
            columns.emplace_back(column.name, py::cast(column.texts));
          } else if (column.integer) {
            columns.emplace_back(column.name, Array(column.numbers).attr("astype")("int64"));
          } else {
            columns.emplace_back(column.name, Array(column.numbers));
          }
          if (!column.units.empty() && column.units != "1")
            units[py::str(column.name)] = column.units;
        }
        return DataFrame(columns, units);
      },
      py::arg("directory"), py::arg("ensemble") = true,
      "A study's table of asymptotic states (DIR/asymptotic_states.h5) as a DataFrame with the "
      "columns of asymptotic_states.csv; ensemble=False leaves out the ensemble-mean rows.");
}

}  // namespace granasym::python
