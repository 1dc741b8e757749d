// fe_stage's own error estimate read from its manifest (laws/own_error_estimate.h).
#include "laws/own_error_estimate.h"

#include <cstdio>

namespace clearjoint::laws
{
  std::optional<OwnErrorEstimate> read_own_error_estimate(const nlohmann::json &fe_manifest)
  {
    const nlohmann::json::json_pointer at("/extra/adaptive/estimated_error_F_max/value");
    if (!fe_manifest.is_object() || !fe_manifest.contains(at) || !fe_manifest.at(at).is_number())
      return std::nullopt;
    const nlohmann::json &a = fe_manifest.at(nlohmann::json::json_pointer("/extra/adaptive"));
    OwnErrorEstimate e;
    e.relative = a.at(nlohmann::json::json_pointer("/estimated_error_F_max/value")).get<double>();
    const auto method = a["estimated_error_F_max"].value("method", std::string());
    e.method = method;
    // fe_stage's fallback, "change in the last cycle (not extrapolated; not a bound)" (before
    // 2026-11-29 "... (a lower bound)", which it never was): the phrase both share
    e.last_change = method.find("change in the last cycle") != std::string::npos;
    if (const auto c = a.find("cycles"); c != a.end() && c->is_array() && !c->empty())
    {
      e.n_meshes = static_cast<int>(c->size());
      if (const auto n = c->back().find("n_dofs"); n != c->back().end() && n->is_number())
        e.n_dofs = n->get<double>();
    }
    return e;
  }

  std::string describe_own_estimate(const OwnErrorEstimate &e)
  {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.2g %%", 100.0 * e.relative);
    if (e.last_change)
      return std::string("~") + buf +
             " (the change in the last cycle, not extrapolated: " + last_change_record + ")";
    return std::string(buf) + " (extrapolated)";
  }
}  // namespace clearjoint::laws
