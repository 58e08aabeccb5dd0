// The C++ errors (common/error.h) as Python exceptions carrying their message.
#include <pybind11/pybind11.h>

#include "common/error.h"
#include "python/bindings.h"

namespace py = pybind11;

namespace granasym::python {
namespace {
// granasym.FileError (the module holds the reference).
PyObject* file_error_type = nullptr;
}  // namespace

void BindErrors(py::module_& module) {
  // Bad input: a ValueError, so that `except ValueError` catches it too.
  py::register_exception<InputError>(module, "InputError", PyExc_ValueError);
  auto runtime = py::register_exception<RuntimeError>(module, "RuntimeError", PyExc_RuntimeError);
  // A file that cannot be written: a granasym.RuntimeError and an OSError.
  py::object file_bases = py::make_tuple(runtime, py::handle(PyExc_OSError));
  py::object file_error = py::reinterpret_steal<py::object>(
      PyErr_NewException("granasym.FileError", file_bases.ptr(), nullptr));
  module.attr("FileError") = file_error;
  file_error_type = file_error.ptr();
  py::register_exception<InvariantError>(module, "InvariantError", PyExc_AssertionError);
  // FileError is derived from RuntimeError in C++: its translator comes
  // after (pybind11 tries the translators registered last first).
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const FileError& e) {
      PyErr_SetString(file_error_type, e.what());
    }
  });
}

}  // namespace granasym::python
