#include "common/strict_reader.h"

#include "common/atomic_file.h"
#include "common/error.h"

#include <cmath>

namespace clearjoint
{
  bool Range::contains(const double v) const
  {
    if (!std::isfinite(v))
      return false;
    const bool lo_ok = lo_open ? v > lo : v >= lo;
    const bool hi_ok = hi_open ? v < hi : v <= hi;
    return lo_ok && hi_ok;
  }

  std::string Range::describe() const
  {
    auto fmt = [](double v) {
      if (std::isinf(v))
        return std::string(v < 0 ? "-inf" : "inf");
      return format_value(v);
    };
    std::string s = std::string(lo_open || std::isinf(lo) ? "(" : "[") + fmt(lo) + ", " +
                    fmt(hi) + (hi_open || std::isinf(hi) ? ")" : "]");
    if (!unit.empty())
      s += " " + unit;
    return s;
  }

  StrictObject::StrictObject(const nlohmann::json &value, std::string file, std::string prefix)
    : value_(&value)
    , file_(std::move(file))
    , prefix_(std::move(prefix))
  {
    if (!value.is_object())
      throw InputError(file_, prefix_.empty() ? "(top level)" : prefix_, json_excerpt(value),
                       "a mapping of keys to values");
  }

  std::string StrictObject::path_of(const std::string &key) const
  {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }

  void StrictObject::fail(const std::string &key, const std::string &value,
                          const std::string &allowed, const std::string &detail) const
  {
    throw InputError(file_, path_of(key), value, allowed, detail);
  }

  bool StrictObject::has(const std::string &key) const
  {
    return value_->contains(key) && !(*value_)[key].is_null();
  }

  const nlohmann::json &StrictObject::require(const std::string &key)
  {
    read_keys_.insert(key);
    if (!value_->contains(key))
      fail(key, "(missing)", "a value must be given");
    return (*value_)[key];
  }

  const nlohmann::json &StrictObject::raw(const std::string &key) { return require(key); }

  double StrictObject::number(const std::string &key, const Range &range)
  {
    const auto &v = require(key);
    if (!v.is_number())
      fail(key, json_excerpt(v), "a number in " + range.describe());
    const double d = v.get<double>();
    if (!range.contains(d))
      fail(key, format_value(d), range.describe());
    return d;
  }

  double StrictObject::number_or(const std::string &key, const double fallback,
                                 const Range &range)
  {
    read_keys_.insert(key);
    return has(key) ? number(key, range) : fallback;
  }

  long StrictObject::integer(const std::string &key, const long lo, const long hi)
  {
    const auto &v = require(key);
    const std::string allowed = "an integer in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]";
    if (!v.is_number_integer())
      fail(key, json_excerpt(v), allowed);
    const long i = v.get<long>();
    if (i < lo || i > hi)
      fail(key, std::to_string(i), allowed);
    return i;
  }

  long StrictObject::integer_or(const std::string &key, const long fallback, const long lo,
                                const long hi)
  {
    read_keys_.insert(key);
    return has(key) ? integer(key, lo, hi) : fallback;
  }

  bool StrictObject::boolean(const std::string &key)
  {
    const auto &v = require(key);
    if (!v.is_boolean())
      fail(key, json_excerpt(v), "true or false");
    return v.get<bool>();
  }

  bool StrictObject::boolean_or(const std::string &key, const bool fallback)
  {
    read_keys_.insert(key);
    return has(key) ? boolean(key) : fallback;
  }

  std::string StrictObject::string(const std::string &key, const std::vector<std::string> &allowed)
  {
    const auto &v = require(key);
    std::string choices;
    for (const auto &a : allowed)
      choices += (choices.empty() ? "" : "|") + a;
    if (!v.is_string())
      fail(key, json_excerpt(v), allowed.empty() ? "a string" : "one of " + choices);
    const std::string s = v.get<std::string>();
    if (!allowed.empty())
    {
      bool ok = false;
      for (const auto &a : allowed)
        ok = ok || (a == s);
      if (!ok)
        fail(key, s, "one of " + choices);
    }
    return s;
  }

  std::string StrictObject::string_or(const std::string &key, const std::string &fallback,
                                      const std::vector<std::string> &allowed)
  {
    read_keys_.insert(key);
    return has(key) ? string(key, allowed) : fallback;
  }

  std::vector<double> StrictObject::number_array(const std::string &key, const Range &range,
                                                 const std::size_t min_size)
  {
    const auto &v = require(key);
    if (!v.is_array() || v.size() < min_size)
      fail(key, json_excerpt(v),
           "a list of at least " + std::to_string(min_size) + " numbers in " + range.describe());
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i)
    {
      if (!v[i].is_number() || !range.contains(v[i].get<double>()))
        fail(key + "[" + std::to_string(i) + "]", json_excerpt(v[i]), range.describe());
      out.push_back(v[i].get<double>());
    }
    return out;
  }

  StrictObject StrictObject::object(const std::string &key)
  {
    return StrictObject(require(key), file_, path_of(key));
  }

  std::vector<StrictObject> StrictObject::object_array(const std::string &key)
  {
    const auto &v = require(key);
    if (!v.is_array())
      fail(key, json_excerpt(v), "a list of mappings");
    std::vector<StrictObject> out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out.emplace_back(v[i], file_, path_of(key) + "[" + std::to_string(i) + "]");
    return out;
  }

  void StrictObject::expect_schema(const std::string &expected)
  {
    const auto &v = require("schema");
    if (!v.is_string() || v.get<std::string>() != expected)
      fail("schema", v.is_string() ? v.get<std::string>() : json_excerpt(v), expected,
           "this build reads only that schema and major version");
  }

  void StrictObject::finish() const
  {
    for (auto it = value_->begin(); it != value_->end(); ++it)
      if (read_keys_.count(it.key()) == 0)
      {
        std::string known;
        for (const auto &k : read_keys_)
          known += (known.empty() ? "" : ", ") + k;
        fail(it.key(), json_excerpt(it.value()), "no such key",
             "unknown key; valid keys here: " + known);
      }
  }
} // namespace clearjoint
