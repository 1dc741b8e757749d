// A CSV table of records: each column's name, unit and value in one place, so a column cannot
// be added to the header without its unit and its value (no parallel lists to keep in step).
// No deal.II.
#pragma once

#include "common/csv.h"

#include <functional>
#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// One column of a table of `Record`s: its header name, its unit (as in the units line) and
  /// how its value is taken from a record.
  template <class Record>
  struct Column
  {
    std::string name, unit;
    std::function<double(const Record &)> value;
  };

  template <class Record>
  using Columns = std::vector<Column<Record>>;

  template <class Record>
  std::vector<std::string> column_names(const Columns<Record> &columns)
  {
    std::vector<std::string> names;
    for (const auto &c : columns)
      names.push_back(c.name);
    return names;
  }

  template <class Record>
  std::vector<std::string> column_units(const Columns<Record> &columns)
  {
    std::vector<std::string> units;
    for (const auto &c : columns)
      units.push_back(c.unit);
    return units;
  }

  /// The row of one record, in column order.
  template <class Record>
  std::vector<double> table_row(const Columns<Record> &columns, const Record &r)
  {
    std::vector<double> row;
    row.reserve(columns.size());
    for (const auto &c : columns)
      row.push_back(c.value(r));
    return row;
  }

  /// Streams records to a CSV file with a units line (common/csv.h: written to a temporary
  /// name, renamed into place on commit).
  template <class Record>
  class RecordCsv
  {
  public:
    RecordCsv(const std::string &path, Columns<Record> columns,
              const std::vector<std::string> &comments)
      : columns_(std::move(columns))
      , csv_(path, column_names(columns_), column_units(columns_), comments)
    {}
    void write(const Record &r) { csv_.write_row(table_row(columns_, r)); }
    /// "# status: complete", or "# status: incomplete: <message>" for a run that stopped early.
    void commit(const bool complete, const std::string &message)
    {
      if (complete)
        csv_.commit();
      else
        csv_.commit_incomplete(message);
    }

  private:
    Columns<Record> columns_;
    CsvWriter csv_;
  };
}  // namespace clearjoint::fe
