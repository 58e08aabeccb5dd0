// The parts of the Python module, one function per file of python/ that adds
// its classes and functions to the module (python/module.cc calls them),
// and the conversions they share (python/convert.cc).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

namespace granasym::python {

// granasym.InputError (a ValueError), RuntimeError, FileError (an OSError
// too) and InvariantError: the C++ errors with their messages.
void BindErrors(pybind11::module_& module);
// read_result, read_state_table, read_calibration (python/results.cc).
void BindResults(pybind11::module_& module);
// Model, model_kinds (python/models.cc).
void BindModels(pybind11::module_& module);
// calibrate, Calibration (python/calibration.cc).
void BindCalibration(pybind11::module_& module);
// run_scene, run_programme (python/runs.cc).
void BindRuns(pybind11::module_& module);

// A numpy array holding a copy of `values`.
pybind11::array_t<double> Array(const std::vector<double>& values);
// A pandas DataFrame of the named columns (numpy arrays or lists), in order,
// with attrs["units"] = `units` (column name → unit; columns without one are
// left out).
pybind11::object DataFrame(const std::vector<std::pair<std::string, pybind11::object>>& columns,
                           const pybind11::dict& units = pybind11::dict());
// A DataFrame read by pandas from CSV text (the files' own text).
pybind11::object DataFrameFromCsv(const std::string& text);

// TOML text of a Python value: a bool, int, float, str, a list or tuple of
// them, or a dict (an inline table); InputError naming `key` otherwise.
std::string TomlValue(const pybind11::handle& value, const std::string& key);
// The body of a TOML table: one `key = value` line per item of `table`.
std::string TomlTable(const pybind11::dict& table, const std::string& name);

}  // namespace granasym::python
