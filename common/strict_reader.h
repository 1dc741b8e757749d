// Strict reading of YAML and JSON input files.
//
// Files are parsed by common/document_reader.h (YAML converted to JSON: plain scalars written as
// numbers become numbers, quoted scalars stay strings), so one reader checks both formats alike:
//   - every value is read through StrictObject, which knows the key path ("geometry.t_B");
//   - a missing required key, a value of the wrong type or outside its range, and (on finish())
//     any key that was never read, raise InputError naming file, key path, value and range;
//   - expect_schema() rejects a wrong or missing "schema: clearjoint.<kind>/<major>".
#pragma once

#include "common/document_reader.h"  // read_structured_file & co.: the hardened parsers

#include <nlohmann/json.hpp>

#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace clearjoint
{
  /// An interval of allowed values with its unit, printed in messages as e.g. "(0, inf) m".
  struct Range
  {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false, hi_open = false;
    std::string unit;

    static Range any(std::string unit = "") { return {.unit = std::move(unit)}; }
    static Range positive(std::string unit = "")
    {
      return {.lo = 0.0, .lo_open = true, .unit = std::move(unit)};
    }
    static Range non_negative(std::string unit = "")
    {
      return {.lo = 0.0, .unit = std::move(unit)};
    }
    static Range closed(double lo, double hi, std::string unit = "")
    {
      return {.lo = lo, .hi = hi, .unit = std::move(unit)};
    }
    static Range open(double lo, double hi, std::string unit = "")
    {
      return {.lo = lo, .hi = hi, .lo_open = true, .hi_open = true, .unit = std::move(unit)};
    }

    bool contains(double v) const;
    std::string describe() const;
  };

  class StrictObject
  {
  public:
    /// Throws InputError if `value` is not an object. key_prefix is "" at the top level.
    StrictObject(const nlohmann::json &value, std::string file, std::string key_prefix = "");

    /// True if the key is present and not null. Does not mark the key as read.
    bool has(const std::string &key) const;
    /// Marks an optional key as known (so finish() accepts it, e.g. when it is null).
    void allow(const std::string &key) { read_keys_.insert(key); }

    double number(const std::string &key, const Range &range);
    double number_or(const std::string &key, double fallback, const Range &range);
    long integer(const std::string &key, long lo, long hi);
    long integer_or(const std::string &key, long fallback, long lo, long hi);
    bool boolean(const std::string &key);
    bool boolean_or(const std::string &key, bool fallback);
    /// If `allowed` is non-empty, the value must be one of them.
    std::string string(const std::string &key, const std::vector<std::string> &allowed = {});
    std::string string_or(const std::string &key, const std::string &fallback,
                          const std::vector<std::string> &allowed = {});
    std::vector<double> number_array(const std::string &key, const Range &range,
                                     std::size_t min_size = 0);
    StrictObject object(const std::string &key);
    /// Each element of an array of objects.
    std::vector<StrictObject> object_array(const std::string &key);
    /// The raw value (marks the key as read); throws if missing.
    const nlohmann::json &raw(const std::string &key);

    /// Reads "schema" and checks it equals `expected` (e.g. "clearjoint.law/1").
    void expect_schema(const std::string &expected);

    /// Throws InputError for the first key that no accessor read (unknown or misspelt key).
    void finish() const;

    std::string path_of(const std::string &key) const;
    const std::string &file() const { return file_; }
    /// Throws an InputError for `key` with the given value text and allowed range text.
    [[noreturn]] void fail(const std::string &key, const std::string &value,
                           const std::string &allowed, const std::string &detail = "") const;

  private:
    const nlohmann::json &require(const std::string &key);

    const nlohmann::json *value_;
    std::string file_, prefix_;
    mutable std::set<std::string> read_keys_;
  };
} // namespace clearjoint
