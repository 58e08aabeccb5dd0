#include "common/time_series.h"

#include <sstream>

#include "common/csv_table.h"
#include "common/error.h"
#include "common/hdf5_file.h"

namespace granasym {

TimeSeries::TimeSeries(std::vector<Column> columns)
    : columns_(std::move(columns)), values_(columns_.size()) {}

void TimeSeries::AddRow(const std::vector<double>& values) {
  GRANASYM_CHECK(values.size() == columns_.size())
      << values.size() << " values for " << columns_.size() << " columns";
  for (size_t c = 0; c < values.size(); ++c) values_[c].push_back(values[c]);
}

size_t TimeSeries::Index(const std::string& name) const {
  for (size_t c = 0; c < columns_.size(); ++c) {
    if (columns_[c].name == name) return c;
  }
  throw RuntimeError("time series has no column '" + name + "'");
}

const std::vector<double>& TimeSeries::Values(const std::string& name) const {
  return values_[Index(name)];
}

double TimeSeries::Last(const std::string& name) const {
  const std::vector<double>& values = Values(name);
  GRANASYM_CHECK(!values.empty()) << "column '" << name << "' is empty";
  return values.back();
}

void TimeSeries::Write(Hdf5File& file, const std::string& group) const {
  file.CreateGroup(group);
  std::string order;
  for (size_t c = 0; c < columns_.size(); ++c) {
    const std::string path = group + "/" + columns_[c].name;
    file.WriteDoubles(path, values_[c], columns_[c].units);
    if (!columns_[c].description.empty()) {
      file.SetAttribute(path, "description", columns_[c].description);
    }
    order += (c ? "," : "") + columns_[c].name;
  }
  file.SetAttribute(group, "columns", order);
  file.SetAttribute(group, "rows", static_cast<int64_t>(rows()));
}

TimeSeries TimeSeries::Read(const Hdf5File& file, const std::string& group) {
  std::vector<Column> columns;
  std::stringstream order(file.ReadStringAttribute(group, "columns"));
  std::string name;
  while (std::getline(order, name, ',')) {
    const std::string path = group + "/" + name;
    Column column{name, "", ""};
    if (file.HasAttribute(path, "units")) column.units = file.ReadStringAttribute(path, "units");
    if (file.HasAttribute(path, "description")) {
      column.description = file.ReadStringAttribute(path, "description");
    }
    columns.push_back(column);
  }
  TimeSeries series(columns);
  // Every column holds one value per row: a shorter one would be read past its end.
  const int64_t rows = file.HasAttribute(group, "rows") ? file.ReadIntAttribute(group, "rows") : -1;
  for (size_t c = 0; c < columns.size(); ++c) {
    const std::string path = group + "/" + columns[c].name;
    series.values_[c] = file.ReadDoubles(path);
    const size_t expected = rows >= 0 ? static_cast<size_t>(rows) : series.values_[0].size();
    if (series.values_[c].size() != expected) {
      throw InputError(file.path() + ": dataset " + path + " has " +
                       std::to_string(series.values_[c].size()) + " rows, the series " +
                       std::to_string(expected) +
                       " (the file is corrupt, or not written by granasym)");
    }
  }
  return series;
}

void TimeSeries::WriteCsv(const std::string& path) const {
  std::vector<std::string> names;
  for (const Column& column : columns_) names.push_back(column.name);
  ::granasym::WriteCsv(path, names, values_);
}

}  // namespace granasym
