#include "pipeline/run_eta.h"

#include "common/log.h"

#include <algorithm>

namespace clearjoint::pipeline
{
  RunEta::RunEta(std::map<std::string, int> planned, std::optional<double> fe_case_time,
                 std::optional<double> pipeline_time, std::optional<double> impact_time,
                 std::optional<double> rolling_time,
                 std::optional<double> impact_deformable_time)
    : fe_case_time_(fe_case_time)
    , pipeline_time_(pipeline_time)
    , own_times_{{"fe_impact", impact_time},
                 {"fe_impact_deformable", impact_deformable_time},
                 {"fe_rolling", rolling_time}}
  {
    for (const auto &[stage, n] : planned)
      stages_[stage].planned = n;
  }

  void RunEta::set_concurrency(const int slots, std::map<std::string, int> slots_per_task)
  {
    slots_ = std::max(1, slots);
    slots_per_task_ = std::move(slots_per_task);
  }

  void RunEta::finished(const std::string &stage, const bool ran, const double wall_time_s)
  {
    Stage &s = stages_[stage];
    if (ran)
    {
      ++s.ran;
      s.ran_seconds += wall_time_s;
    }
    else
      ++s.reused;
    ++n_done_;
  }

  int RunEta::n_total() const
  {
    int total = 0;
    for (const auto &[name, s] : stages_)
      total += std::max(s.planned, s.ran + s.reused);
    return total;
  }

  std::optional<double> RunEta::prior_seconds(const std::string &stage) const
  {
    if (!fe_case_time_)
      return std::nullopt;
    if (stage == "fe_stage")
      return *fe_case_time_;
    if (const auto own = own_times_.find(stage); own != own_times_.end())
      return own->second;
    if (!pipeline_time_)
      return std::nullopt;
    int n_fe = 0, n_other = 0;
    double own_studies = 0.0;  // the impact and rolling studies' measured share
    for (const auto &[name, s] : stages_)
      if (const auto own = own_times_.find(name); own != own_times_.end())
        own_studies += s.planned * own->second.value_or(0.0);
      else
        (name == "fe_stage" ? n_fe : n_other) += s.planned;
    if (n_other == 0)
      return std::nullopt;
    // A preset measured on a bigger pipeline than this one may leave nothing for the rest:
    // never below zero.
    return std::max(0.0, (*pipeline_time_ - n_fe * *fe_case_time_ - own_studies) / n_other);
  }

  std::optional<RunEta::Left> RunEta::time_left() const
  {
    Left left;
    bool any_known = false;
    double work = 0.0, longest = 0.0;  // [slot·s], [s]
    for (const auto &[name, s] : stages_)
    {
      const int remaining = std::max(0, s.planned - s.ran - s.reused);
      if (remaining == 0)
        continue;
      double per_task = 0.0;
      if (s.ran > 0)
        per_task = s.ran_seconds / s.ran;
      else if (const auto prior = prior_seconds(name))
        per_task = *prior;
      else if (s.reused == 0)
      {
        left.lower_bound = true;
        continue;
      }
      const int done = s.ran + s.reused;
      const double ran_fraction = done > 0 ? double(s.ran) / done : 1.0;
      const auto slots = slots_per_task_.find(name);
      const int task_slots =
        std::min(slots_, slots == slots_per_task_.end() ? 1 : std::max(1, slots->second));
      work += remaining * per_task * ran_fraction * task_slots;
      longest = std::max(longest, per_task * ran_fraction);
      any_known = true;
    }
    left.seconds = std::max(work / slots_, longest);
    if (!any_known && left.lower_bound)
      return std::nullopt;
    return left;
  }

  std::string RunEta::describe_next(const int n_running) const
  {
    std::string out = "task " + std::to_string(std::min(n_done_ + n_running + 1, n_total())) +
                      " of " + std::to_string(n_total()) +
                      (n_running > 0 ? " (" + std::to_string(n_running) + " running)" : "");
    if (const auto left = time_left())
      out += (left->lower_bound ? ", at least " : ", about ") + log::format_duration(left->seconds) +
             " left";
    return out;
  }
} // namespace clearjoint::pipeline
