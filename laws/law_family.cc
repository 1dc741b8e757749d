#include "laws/law_family.h"

#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/strict_reader.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::laws
{
  LawFamily::LawFamily(std::string parameter, std::string unit, const double delta_ref,
                       std::vector<LawFamilyMember> members, const RangePolicy policy)
    : parameter_(std::move(parameter))
    , unit_(std::move(unit))
    , delta_ref_(delta_ref)
    , members_(std::move(members))
    , policy_(policy)
  {
    if (members_.size() < 2)
      throw InputError("", "members", std::to_string(members_.size()) + " laws",
                       "at least 2 laws in a family");
    if (!(delta_ref_ > 0.0))
      throw InputError("", "delta_ref", format_value(delta_ref_), "(0, inf) m");
    for (std::size_t i = 1; i < members_.size(); ++i)
      if (!(members_[i].value > members_[i - 1].value))
        throw InputError("", "members[" + std::to_string(i) + "].value",
                         format_value(members_[i].value),
                         "> " + format_value(members_[i - 1].value) +
                           " (values strictly increasing)");
  }

  std::pair<std::size_t, double> LawFamily::locate(const double p) const
  {
    const double lo = members_.front().value, hi = members_.back().value;
    if (p < lo || p > hi)
    {
      ++n_out_;
      if (policy_ == RangePolicy::error)
        throw InputError("", parameter_, format_value(p) + " " + unit_,
                         "[" + format_value(lo) + ", " + format_value(hi) + "] " + unit_,
                         "outside the law family; its out_of_range policy is 'error'");
      if (policy_ == RangePolicy::clamp)
        return p < lo ? std::make_pair(std::size_t(0), 0.0)
                      : std::make_pair(members_.size() - 2, 1.0);
    }
    std::size_t i = 0;
    while (i + 2 < members_.size() && p > members_[i + 1].value)
      ++i;
    const double w = (p - members_[i].value) / (members_[i + 1].value - members_[i].value);
    return {i, w};
  }

  PowerLaw LawFamily::at(const double p) const
  {
    const auto [i, w] = locate(p);
    const auto &a = members_[i].law.law, &b = members_[i + 1].law.law;
    const double ln_F = (1 - w) * std::log(a.force(delta_ref_)) + w * std::log(b.force(delta_ref_));
    const double n = (1 - w) * a.n + w * b.n;
    if (!(n > 0.0))
      throw NumericalError("law family '" + parameter_ + "' extrapolated to n = " +
                           format_value(n) + " at " + format_value(p) + " " + unit_);
    return PowerLaw{std::exp(ln_F) / std::pow(delta_ref_, n), n};
  }

  std::pair<double, double> LawFamily::valid_range_at(const double p) const
  {
    const auto [i, w] = locate(p);
    (void)w;
    const auto &a = members_[i].law, &b = members_[i + 1].law;
    return {std::max(a.delta_min, b.delta_min), std::min(a.delta_max, b.delta_max)};
  }

  nlohmann::json to_json(const LawFamily &f)
  {
    nlohmann::json j;
    j["schema"] = law_family_schema;
    j["parameter"] = {{"name", f.parameter()}, {"unit", f.unit()}};
    j["delta_ref"] = f.delta_ref();
    j["interpolation"] = "piecewise-linear in the parameter of ln F(delta_ref) and n";
    j["out_of_range"] = to_string(f.parameter_policy());
    j["members"] = nlohmann::json::array();
    for (const auto &m : f.members())
      j["members"].push_back({{"value", m.value}, {"law", to_json(m.law)}});
    return j;
  }

  LawFamily law_family_from_json(const nlohmann::json &j, const std::string &source)
  {
    StrictObject top(j, source);
    top.expect_schema(law_family_schema);
    auto par = top.object("parameter");
    const std::string name = par.string("name");
    const std::string unit = par.string("unit");
    par.finish();
    const double delta_ref = top.number("delta_ref", Range::positive("m"));
    top.string("interpolation", {"piecewise-linear in the parameter of ln F(delta_ref) and n"});
    const RangePolicy policy =
      parse_range_policy(top.string("out_of_range", {"error", "clamp", "extend"}));
    std::vector<LawFamilyMember> members;
    for (auto &m : top.object_array("members"))
    {
      LawFamilyMember member{m.number("value", Range::any(unit)),
                             law_from_json(m.raw("law"), source, m.path_of("law"))};
      m.finish();
      members.push_back(std::move(member));
    }
    top.finish();
    try
    {
      return LawFamily(name, unit, delta_ref, std::move(members), policy);
    }
    catch (const InputError &e)
    {
      throw InputError(std::string(e.what()) + " in '" + source + "'");
    }
  }

  LawFamily read_law_family(const std::string &path)
  {
    return law_family_from_json(read_json_file(path), path);
  }

  void write_law_family(const std::string &path, const LawFamily &family)
  {
    write_file_atomically(path, json_text(to_json(family)) + "\n");
  }

  std::string peek_schema(const std::string &path)
  {
    const auto j = read_json_file(path);
    if (!j.is_object() || !j.contains("schema") || !j["schema"].is_string())
      throw InputError(path, "schema", "(missing)",
                       std::string(law_schema) + " or " + law_family_schema);
    return j["schema"].get<std::string>();
  }
} // namespace clearjoint::laws
