// fe_stage is three-dimensional only (no templates on dim): the one place that says so.
#pragma once

#include <deal.II/base/config.h>

namespace clearjoint::fe::detail
{
  using namespace dealii;
  constexpr int dim = 3;
}  // namespace clearjoint::fe::detail
