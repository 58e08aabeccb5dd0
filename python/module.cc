// The Python module `granasym`: reading results, the constitutive models,
// calibration and runs, bound over the libraries (python/*.cc).
#include <pybind11/pybind11.h>

#include "common/provenance.h"
#include "python/bindings.h"

PYBIND11_MODULE(granasym, module) {
  module.doc() =
      "granasym: DEM results, study tables, constitutive models, calibration and runs "
      "(the C++ libraries, bound with pybind11)";
  module.attr("__version__") = granasym::ProgramVersion();
  granasym::python::BindErrors(module);
  granasym::python::BindResults(module);
  granasym::python::BindRuns(module);
#ifdef GRANASYM_PYTHON_HAS_MODELS
  granasym::python::BindModels(module);
  granasym::python::BindCalibration(module);
#endif
}
