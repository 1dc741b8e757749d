#include "fit_stage/student_t.h"

#include <gtest/gtest.h>

using namespace clearjoint::fit;

// Two-sided 95 % critical values t(0.975, ν) from standard tables (6 digits).
TEST(StudentT, QuantilesMatchTables)
{
  const std::pair<double, double> table[] = {
    {1, 12.7062}, {2, 4.30265}, {4, 2.77645}, {8, 2.30600}, {10, 2.22814}, {30, 2.04227},
    {120, 1.97993}};
  for (const auto &[dof, t] : table)
    EXPECT_NEAR(student_t_quantile(0.975, dof), t, 1e-4 * t) << "dof " << dof;  // table digits
}

TEST(StudentT, CdfIsSymmetricAndInvertsTheQuantile)
{
  for (const double dof : {1.0, 3.0, 17.0})
    for (const double p : {0.01, 0.3, 0.5, 0.9, 0.999})
    {
      const double t = student_t_quantile(p, dof);
      EXPECT_NEAR(student_t_cdf(t, dof), p, 1e-12);
      EXPECT_NEAR(student_t_cdf(-t, dof), 1 - p, 1e-12);
    }
}
