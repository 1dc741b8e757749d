// Thrown when a law with policy "error" is evaluated outside its valid δ range.
#pragma once

#include "common/error.h"

namespace clearjoint::laws
{
  class LawRangeError : public NumericalError
  {
  public:
    /// All lengths in m; the message states them in mm and m.
    LawRangeError(double delta, double delta_min, double delta_max);
    double delta() const { return delta_; }

  private:
    double delta_;
  };
} // namespace clearjoint::laws
