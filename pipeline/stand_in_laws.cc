#include "pipeline/stand_in_laws.h"

#include "laws/law_family.h"
#include "laws/law_file.h"
#include "pipeline/sweep_values.h"

#include <algorithm>

#ifndef CLEARJOINT_SOURCE_DIR
#define CLEARJOINT_SOURCE_DIR "."
#endif

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  StandInLaws::StandInLaws(fs::path folder, const std::vector<FeSweep> &sweeps)
    : folder_(std::move(folder))
    , sweeps_(sweeps)
  {
  }

  std::string StandInLaws::for_choice(const LawChoice &choice)
  {
    if (choice.file)
      return fs::absolute(*choice.file).string();
    const std::string &law = paper_law();
    if (choice.value || !choice.value_keyword.empty())
      return law;
    return family(*choice.sweep);
  }

  const std::string &StandInLaws::paper_law()
  {
    if (paper_law_.empty())
    {
      paper_law_ = (folder_ / "stand_in_law.json").string();
      laws::write_law_file(paper_law_, laws::read_law_file(std::string(CLEARJOINT_SOURCE_DIR) +
                                                           "/laws/paper_tB4.json"));
    }
    return paper_law_;
  }

  const std::string &StandInLaws::family(const std::string &sweep_name)
  {
    auto &family = families_[sweep_name];
    if (family.empty())
    {
      const FeSweep *sweep = nullptr;
      for (const auto &s : sweeps_)
        if (s.name == sweep_name)
          sweep = &s;
      const laws::LawFile law = laws::read_law_file(paper_law_);
      const SiValue lo = to_si(sweep->values.front(), sweep->unit);
      const SiValue hi = to_si(sweep->values.back(), sweep->unit);
      family = (folder_ / ("stand_in_family_" + sweep->name + ".json")).string();
      // Two members, the same law at both ends of the values (one apart when they coincide, so
      // that the family has a range).
      laws::write_law_family(
        family, laws::LawFamily(sweep->parameter, lo.unit, law.delta_ref,
                                {{std::min(lo.value, hi.value), law},
                                 {std::max(lo.value, hi.value) + (lo.value == hi.value ? 1.0 : 0.0),
                                  law}},
                                laws::RangePolicy::clamp));
    }
    return family;
  }
} // namespace clearjoint::pipeline
