// The deformable journal's placement (fe_stage/mesh/journal_pose.h): the tilted journal of the
// misalignment study, meshed aligned and then turned about x and moved.
#include "fe_stage/mesh/journal_pose.h"

#include <gtest/gtest.h>

#include <cmath>

using clearjoint::fe::JournalPose;

namespace
{
  // the default geometry (SPEC §2), m
  constexpr double R_B = 10e-3, c_r = 0.5e-3, R_J = 9.5e-3, L_J = 18e-3;

  JournalPose tilted(const double theta)
  {
    JournalPose p;
    p.tilt = theta;
    p.aligned_centre_y = -c_r;
    // the misalignment study's placement: its lowest rim point on the bore
    p.centre_y = -(R_B - 0.5 * L_J * std::sin(theta) - R_J * std::cos(theta));
    return p;
  }
} // namespace

// The aligned journal's lowest point at its z < 0 end lands on the bore (y = −R_B) at the first
// touch point P1 of the rigid tilted cylinder, z = −((L_J/2) cos θ − R_J sin θ); the axis turns
// to (0, sin θ, cos θ). 1e-15 m: round-off of a few products of 1e-2 m numbers.
TEST(JournalPose, TheLowestRimPointTouchesTheBoreAtP1)
{
  const double theta = 2.0 * M_PI / 180.0;
  const JournalPose p = tilted(theta);
  const auto P1 = p.to_world({0.0, -c_r - R_J, -0.5 * L_J});
  EXPECT_NEAR(P1[0], 0.0, 1e-15);
  EXPECT_NEAR(P1[1], -R_B, 1e-15);
  EXPECT_NEAR(P1[2], -(0.5 * L_J * std::cos(theta) - R_J * std::sin(theta)), 1e-15);
  const auto a = p.rotate({0.0, 0.0, 1.0});
  EXPECT_NEAR(a[1], std::sin(theta), 1e-16);
  EXPECT_NEAR(a[2], std::cos(theta), 1e-16);
}

// to_local inverts to_world, rotate_back inverts rotate, and the placement keeps lengths (a
// rigid motion). 1e-15: round-off.
TEST(JournalPose, IsARigidMotionAndItsInverse)
{
  const JournalPose p = tilted(0.05);
  const std::array<double, 3> x = {3e-3, -4e-3, 7e-3}, y = {-1e-3, 2e-3, -8e-3};
  const auto X = p.to_world(x), Y = p.to_world(y);
  const auto back = p.to_local(X);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(back[k], x[k], 1e-15);
  auto dist = [](const std::array<double, 3> &a, const std::array<double, 3> &b) {
    return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  };
  EXPECT_NEAR(dist(X, Y), dist(x, y), 1e-15);
  const auto v = p.rotate_back(p.rotate(x));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(v[k], x[k], 1e-15);
  EXPECT_FALSE(p.identity());
  JournalPose aligned;
  aligned.aligned_centre_y = aligned.centre_y = -c_r;
  EXPECT_TRUE(aligned.identity());
}
