// A table of named columns with units, filled row by row during a run and
// written to HDF5 (one dataset per column, with a `units` attribute) or CSV.
#pragma once

#include <string>
#include <vector>

namespace granasym {

class Hdf5File;

class TimeSeries {
 public:
  struct Column {
    std::string name;   // e.g. "p_kpa"
    std::string units;  // e.g. "kPa", "1" for dimensionless
    std::string description;
  };

  TimeSeries() = default;
  explicit TimeSeries(std::vector<Column> columns);

  // Appends one row; `values` follows the column order.
  void AddRow(const std::vector<double>& values);
  size_t rows() const { return values_.empty() ? 0 : values_[0].size(); }
  const std::vector<Column>& columns() const { return columns_; }
  size_t Index(const std::string& name) const;  // RuntimeError if unknown
  const std::vector<double>& Values(const std::string& name) const;
  double Last(const std::string& name) const;

  // Writes every column below `group` (e.g. "/series").
  void Write(Hdf5File& file, const std::string& group) const;
  // Reads the columns written by Write, in the order given by the file's
  // "columns" attribute (InputError when a column's length is not the rows').
  static TimeSeries Read(const Hdf5File& file, const std::string& group);
  void WriteCsv(const std::string& path) const;

 private:
  std::vector<Column> columns_;
  std::vector<std::vector<double>> values_;  // per column
};

}  // namespace granasym
