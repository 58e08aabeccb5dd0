// Conversions shared by the module's parts: arrays, DataFrames, and Python
// values as TOML text, so that the module's inputs go through the parsers of
// the input files (their checks and messages) rather than checks of its own.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/text_file.h"
#include "python/bindings.h"

namespace py = pybind11;

namespace granasym::python {

py::array_t<double> Array(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

py::object DataFrame(const std::vector<std::pair<std::string, py::object>>& columns,
                     const py::dict& units) {
  py::dict data;
  for (const auto& [name, values] : columns) data[py::str(name)] = values;
  py::object frame = py::module_::import("pandas").attr("DataFrame")(data);
  frame.attr("attrs")["units"] = units;
  return frame;
}

py::object DataFrameFromCsv(const std::string& text) {
  const py::object buffer = py::module_::import("io").attr("StringIO")(text);
  return py::module_::import("pandas").attr("read_csv")(buffer);
}

std::string TomlValue(const py::handle& value, const std::string& key) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return std::to_string(value.cast<long long>());
  if (py::isinstance<py::float_>(value)) {
    const double x = value.cast<double>();
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    // Always with a point or an exponent: TOML reads it as a float.
    std::string text = fmt::format("{:.17g}", x);
    if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
    return text;
  }
  if (py::isinstance<py::str>(value)) return TomlQuoted(value.cast<std::string>());
  // numpy scalars and arrays: as the Python values they hold.
  if (py::hasattr(value, "dtype") && py::hasattr(value, "tolist")) {
    return TomlValue(value.attr("tolist")(), key);
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string text = "[";
    int k = 0;
    for (const py::handle item : value) {
      text += (k == 0 ? "" : ", ") + TomlValue(item, fmt::format("{}[{}]", key, k));
      ++k;
    }
    return text + "]";
  }
  if (py::isinstance<py::dict>(value)) {
    std::string text = "{";
    int k = 0;
    for (const auto& [name, item] : value.cast<py::dict>()) {
      const std::string item_key = py::str(name).cast<std::string>();
      text += (k++ == 0 ? "" : ", ") + TomlQuoted(item_key) + " = " +
              TomlValue(item, key + "." + item_key);
    }
    return text + "}";
  }
  throw InputError(fmt::format("{} = {}: expected a number, a string, a bool, a list or a dict",
                               key, py::repr(value).cast<std::string>()));
}

std::string TomlTable(const py::dict& table, const std::string& name) {
  std::string text;
  for (const auto& [key, value] : table) {
    if (!py::isinstance<py::str>(key)) {
      throw InputError(
          fmt::format("{}: key {} is not a string", name, py::repr(key).cast<std::string>()));
    }
    const std::string k = key.cast<std::string>();
    text += TomlQuoted(k) + " = " + TomlValue(value, name.empty() ? k : name + "." + k) + "\n";
  }
  return text;
}

}  // namespace granasym::python
