// The misalignment study (paper §3.3): the journal tilted by θ in the y–z plane about its
// centre, lowered until its lowest rim point touches the bore, then pushed (−y): rigid, or
// deformable and pushed at its inner core (SPEC §2, so that no driven point lies on the rim
// that carries the contact), its surface then the mortar slave.
#include "fe_stage/study/study.h"

#include "common/units.h"

#include <cmath>

namespace clearjoint::fe
{
  StudyPlan misalignment_study(const FeScene &scene)
  {
    const auto &G = scene.geometry;
    const double theta = scene.misalignment.theta_deg * units::deg;
    StudyPlan p = joint_study(scene, "misalignment");
    // a finite cylinder with axis (0, sin θ, cos θ); the bottom of its rim at z < 0 is at
    // y_c − (L_J/2) sin θ − R_J cos θ and touches the bore (y = −R_B) at δ = 0
    p.obstacle.kind = RigidObstacle::Kind::tilted_cylinder;
    p.obstacle.tilt = theta;
    p.obstacle.offset = G.R_B - 0.5 * G.L_J() * std::sin(theta) - G.R_J() * std::cos(theta);
    p.tilted = true;
    p.full_length = true;
    p.journal_pose.tilt = theta;
    p.journal_pose.centre_y = -p.obstacle.offset;
    if (p.deformable_partner && scene.contact.mortar_slave == Contact::MortarSlave::automatic)
      p.journal_is_slave = true;
    return p;
  }
}  // namespace clearjoint::fe
