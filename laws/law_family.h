// A law family, schema clearjoint.law_family/1: one law per value of a parameter (the
// misalignment θ in rad, the bearing thickness t_B in m, ...), and the rule that interpolates
// between them:
//
// {
//   "schema": "clearjoint.law_family/1",
//   "parameter": {"name": "theta", "unit": "rad"},
//   "delta_ref": 5e-5,                                     // m, common reference penetration
//   "interpolation": "piecewise-linear in the parameter of ln F(delta_ref) and n",
//   "out_of_range": "error" | "clamp" | "extend",          // for the parameter, not δ
//   "members": [ {"value": 0.0, "law": {clearjoint.law/1}}, ... ]   // strictly increasing
// }
//
// K is never interpolated directly: K carries units N/m^n, so with n varying it is not a
// physical quantity on its own. The family interpolates ln F_ref and n, then K = F_ref/δ_ref^n.
#pragma once

#include "laws/law_file.h"

#include <string>
#include <vector>

namespace clearjoint::laws
{
  inline constexpr const char *law_family_schema = "clearjoint.law_family/1";

  struct LawFamilyMember
  {
    double value;  ///< parameter value in the family's unit (SI)
    LawFile law;
  };

  class LawFamily
  {
  public:
    LawFamily() = default;
    /// Members sorted by value (strictly increasing required), at least 2.
    LawFamily(std::string parameter, std::string unit, double delta_ref,
              std::vector<LawFamilyMember> members, RangePolicy parameter_policy);

    /// The power law at parameter value p (interpolated). Outside the members' range the
    /// parameter policy applies (error: throws InputError; clamp: end member; extend: linear
    /// extrapolation), and n_parameter_out_of_range() counts it.
    PowerLaw at(double p) const;
    /// Valid δ range at p: the intersection of the two neighbouring members' ranges.
    std::pair<double, double> valid_range_at(double p) const;

    const std::string &parameter() const { return parameter_; }
    const std::string &unit() const { return unit_; }
    double delta_ref() const { return delta_ref_; }
    const std::vector<LawFamilyMember> &members() const { return members_; }
    RangePolicy parameter_policy() const { return policy_; }
    std::uint64_t n_parameter_out_of_range() const { return n_out_; }

  private:
    /// Index i of the interval [v_i, v_{i+1}] used for p, and the weight of member i+1.
    std::pair<std::size_t, double> locate(double p) const;

    std::string parameter_, unit_;
    double delta_ref_ = 0.0;
    std::vector<LawFamilyMember> members_;
    RangePolicy policy_ = RangePolicy::error;
    mutable std::uint64_t n_out_ = 0;
  };

  nlohmann::json to_json(const LawFamily &family);
  LawFamily law_family_from_json(const nlohmann::json &j, const std::string &source);
  LawFamily read_law_family(const std::string &path);
  void write_law_family(const std::string &path, const LawFamily &family);

  /// Reads the "schema" of a law or law-family file without validating the rest (to dispatch).
  std::string peek_schema(const std::string &path);
} // namespace clearjoint::laws
