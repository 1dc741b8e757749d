// The plan's contact pairing (contact_pairing.h), and the rolling study's gap along the journal's
// path, which the obstacle and mortar pairings both use to choose their candidates.
#include "fe_stage/contact/contact_pairing.h"

#include "common/units.h"

#include <cmath>

namespace clearjoint::fe::detail
{
  std::unique_ptr<ContactPairing> make_contact_pairing(const PairingContext &context)
  {
    switch (context.plan.pairing)
      {
        case StudyPlan::Pairing::obstacle:
          return make_obstacle_pairing(context);
        case StudyPlan::Pairing::common_rays:
          return make_common_ray_pairing(context);
        case StudyPlan::Pairing::mortar:
          return make_mortar_pairing(context);
      }
    throw std::logic_error("make_contact_pairing: unknown pairing");
  }

  void rolling_gap_on_path(const FeScene &scene, const RigidObstacle &obstacle, const Point<dim> &X,
                           double &g0, Tensor<1, dim> &n)
  {
    const double a = std::atan2(X[0], -X[1]);
    const double sweep = scene.rolling.omega_B * rolling_end_time(scene);
    RigidObstacle o = obstacle;
    o.frame_angle = rolling_path_distance(scene, a) == 0.0 ?
                      -a :
                      (std::abs(std::remainder(a, 2.0 * units::pi)) <
                           std::abs(std::remainder(a + sweep, 2.0 * units::pi)) ?
                         0.0 :
                         sweep);
    Vec3 normal;
    o.gap({X[0], X[1], X[2]}, scene.loading.delta_max, g0, normal);
    n = Tensor<1, dim>({normal[0], normal[1], normal[2]});
  }
}  // namespace clearjoint::fe::detail
