// CSV tables with a units line, the format of every table clearjoint writes:
//
//   # any comment lines (provenance, notes)
//   # units: m,N,1,s
//   delta,force,n_iterations,wall_time
//   1e-06,338.2,3,0.12
//   ...
//   # status: complete            <- last line; "incomplete: <reason>" if a run stopped early
//
// The reader accepts '#' comment lines anywhere, a "# units:" line, blank lines, and files
// without units or status lines (external data); it rejects ragged rows and non-numbers,
// naming the file and line.
#pragma once

#include "common/atomic_file.h"

#include <memory>
#include <string>
#include <vector>

namespace clearjoint
{
  struct CsvTable
  {
    std::string source;                 // file it was read from (for messages)
    std::vector<std::string> columns;   // header names
    std::vector<std::string> units;     // one per column, empty if the file has no units line
    std::vector<std::vector<double>> rows;
    std::vector<std::string> comments;  // comment lines without the leading '#'
    std::string status;                 // "complete", "incomplete: ...", or "" if absent

    /// Index of a column; throws InputError naming the file and the columns present.
    std::size_t column_index(const std::string &name) const;
    bool has_column(const std::string &name) const;
    std::vector<double> column(const std::string &name) const;
    /// Unit of a column ("" if the file has no units line).
    std::string unit_of(const std::string &name) const;
  };

  /// 1 GiB: a 10 s MBD time series at 10 µs output steps is ~100 MB; anything beyond is not a
  /// table clearjoint wrote or can use.
  inline constexpr std::size_t max_csv_bytes = std::size_t(1) << 30;

  /// Reads a CSV file (comma-separated; whitespace-separated also accepted for reference data).
  /// Rejects (InputError naming file and line): bytes that are not UTF-8, a column named twice,
  /// ragged rows, values that are not finite numbers (nan, inf, 1e400).
  CsvTable read_csv(const std::string &path);
  /// The same from text already in memory; `source` names it in messages.
  CsvTable parse_csv(const std::string &text, const std::string &source);

  /// Streams rows to a temporary file and renames it into place on commit(), so readers never
  /// see half a table. Rows are written with 17 significant digits (lossless for doubles).
  class CsvWriter
  {
  public:
    CsvWriter(const std::string &path, std::vector<std::string> columns,
              std::vector<std::string> units, const std::vector<std::string> &comments = {});
    void write_row(const std::vector<double> &values);
    /// Appends "# status: complete" and renames into place.
    void commit();
    /// Appends "# status: incomplete: <reason>" and renames into place: what a run reached is
    /// kept, and no reader mistakes it for a finished table.
    void commit_incomplete(const std::string &reason);
    std::size_t n_rows() const { return n_rows_; }

  private:
    std::unique_ptr<AtomicFile> file_;
    std::size_t n_columns_, n_rows_ = 0;
  };
} // namespace clearjoint
