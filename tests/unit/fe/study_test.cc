// The studies' plans (fe_stage/study/): each places its rigid obstacle where it first touches
// the bearing or block (gap 0 at the first touch point, positive elsewhere), and pairs and
// checks as its study needs. Tolerance 1e-15 m: closed-form placement against lengths of 1e-2 m,
// a few ulps.
#include "common/units.h"
#include "fe_stage/study/study.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint;
using namespace clearjoint::fe;

TEST(StudyPlan, RadialJournalTouchesTheBoreBottomAtDeltaZero)
{
  FeScene scene;  // the defaults: R_B 10 mm, c_r 0.5 mm (SPEC §2)
  const StudyPlan p = plan_study(scene);
  EXPECT_EQ(p.name, "radial");
  EXPECT_EQ(p.mesh, StudyPlan::Mesh::joint);
  EXPECT_TRUE(p.deformable_partner);  // end_faces journal
  EXPECT_EQ(p.pairing, StudyPlan::Pairing::mortar);  // the default pairing (contact.pairing)
  FeScene rays = scene;
  rays.contact.pairing = Contact::Pairing::node_to_node;
  EXPECT_EQ(plan_study(rays).pairing, StudyPlan::Pairing::common_rays);
  EXPECT_TRUE(p.must_touch);
  double g0;
  Vec3 n;
  const double R_B = scene.geometry.R_B;
  ASSERT_TRUE(p.obstacle.gap({0.0, -R_B, 0.0}, 0.0, g0, n));
  EXPECT_NEAR(g0, 0.0, 1e-15);
  ASSERT_TRUE(p.obstacle.gap({R_B * std::sin(0.3), -R_B * std::cos(0.3), 0.0}, 0.0, g0, n));
  EXPECT_GT(g0, 0.0);

  scene.loading.journal = JournalLoading::rigid;
  EXPECT_EQ(plan_study(scene).pairing, StudyPlan::Pairing::obstacle);
  EXPECT_FALSE(plan_study(scene).deformable_partner);
}

TEST(StudyPlan, TiltedJournalTouchesAtItsLowestRimPoint)
{
  FeScene scene;
  scene.study = Study::misalignment;
  scene.loading.journal = JournalLoading::rigid;
  for (const double theta_deg : {0.5, 1.0, 2.5, 3.28})
    {
      scene.misalignment.theta_deg = theta_deg;
      const StudyPlan p = plan_study(scene);
      EXPECT_TRUE(p.tilted);
      const auto &G = scene.geometry;
      const double theta = theta_deg * units::deg;
      // the rim at z < 0: its lowest point is at z = −((L_J/2) cos θ − R_J sin θ) on the bore's
      // bottom line (paper §3.3)
      const double z1 = -(0.5 * G.L_J() * std::cos(theta) - G.R_J() * std::sin(theta));
      double g0;
      Vec3 n;
      ASSERT_TRUE(p.obstacle.gap({0.0, -G.R_B, z1}, 0.0, g0, n));
      EXPECT_NEAR(g0, 0.0, 1e-15) << "theta " << theta_deg;
      // pushed by δ it penetrates there by about δ (the rim's normal is nearly −y)
      ASSERT_TRUE(p.obstacle.gap({0.0, -G.R_B, z1}, 2e-5, g0, n));
      EXPECT_LT(g0, -1.9e-5);
      // every other bore point along the bottom line and round the bore is clear at δ = 0
      for (const double z : {z1 + 1e-3, z1 + 5e-3, 0.0, -z1, -z1 + 1e-4})
        {
          ASSERT_TRUE(p.obstacle.gap({0.0, -G.R_B, z}, 0.0, g0, n));
          EXPECT_GT(g0, 0.0) << "z " << z;
        }
    }
}

// The core-loaded deformable tilted journal: placed by the pose that puts its lowest rim point
// on the rigid tilted journal's first touch point, paired by mortar with its own surface as the
// slave (the rim bears on the bore); the aligned journal keeps the bore as the slave.
TEST(StudyPlan, DeformableTiltedJournalIsPlacedLikeTheRigidOneAndIsTheSlave)
{
  FeScene scene;
  scene.study = Study::misalignment;
  scene.loading.journal = JournalLoading::core;
  scene.misalignment.theta_deg = 2.0;
  const StudyPlan p = plan_study(scene);
  EXPECT_TRUE(p.deformable_partner);
  EXPECT_EQ(p.pairing, StudyPlan::Pairing::mortar);
  EXPECT_TRUE(p.journal_is_slave);
  const auto &G = scene.geometry;
  const auto P1 = p.journal_pose.to_world({0.0, -G.c_r - G.R_J(), -0.5 * G.L_J()});
  double g0;
  Vec3 n;
  ASSERT_TRUE(p.obstacle.gap({P1[0], P1[1], P1[2]}, 0.0, g0, n));
  EXPECT_NEAR(g0, 0.0, 1e-15);
  EXPECT_NEAR(P1[1], -G.R_B, 1e-15);

  FeScene radial;
  radial.loading.journal = JournalLoading::core;
  EXPECT_FALSE(plan_study(radial).journal_is_slave);
  EXPECT_TRUE(plan_study(radial).journal_pose.identity());
  radial.contact.mortar_slave = Contact::MortarSlave::journal;
  EXPECT_TRUE(plan_study(radial).journal_is_slave);
}

TEST(StudyPlan, VerificationBlocks)
{
  FeScene scene;
  scene.study = Study::hertz;
  StudyPlan p = plan_study(scene);
  EXPECT_EQ(p.mesh, StudyPlan::Mesh::block);
  EXPECT_TRUE(p.hertz);
  EXPECT_FALSE(p.must_touch);
  EXPECT_EQ(p.obstacle.kind, RigidObstacle::Kind::sphere);
  double g0;
  Vec3 n;
  ASSERT_TRUE(p.obstacle.gap({0.0, 0.0, 0.0}, 0.0, g0, n));
  EXPECT_NEAR(g0, 0.0, 1e-15);  // the sphere touches the block's top at the origin
  scene.verification.deformable_indenter = true;
  EXPECT_EQ(plan_study(scene).pairing, StudyPlan::Pairing::mortar);

  scene.study = Study::patch;
  p = plan_study(scene);
  EXPECT_FALSE(p.hertz);
  EXPECT_EQ(p.obstacle.kind, RigidObstacle::Kind::plane);
  EXPECT_EQ(p.body_names[1], "indenter");
}
