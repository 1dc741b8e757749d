// Adds the wall seconds of a scope to a running total (the time breakdown fe_stage logs).
#pragma once

#include <chrono>

namespace clearjoint::fe::detail
{
  /// Adds the seconds since construction to `target` on destruction.
  struct ScopedTimer
  {
    explicit ScopedTimer(double &target)
      : target_(target)
      , t0_(std::chrono::steady_clock::now())
    {}
    ~ScopedTimer()
    {
      target_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    }
    double &target_;
    std::chrono::steady_clock::time_point t0_;
  };
}  // namespace clearjoint::fe::detail
