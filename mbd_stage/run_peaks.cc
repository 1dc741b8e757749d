#include "mbd_stage/run_peaks.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::mbd
{
  PeakTracker::PeakTracker(const Scene &scene, const MultibodySystem &sys, const int slider)
    : scene_(scene)
    , sys_(sys)
    , slider_(slider)
  {
    peaks_.joint_force.assign(sys.clearance_joints().size(), 0.0);
  }

  void PeakTracker::radial_force(const double t, const std::size_t c, const double F_n)
  {
    peaks_.joint_force[c] = std::max(peaks_.joint_force[c], F_n);
    if (F_n > peaks_.contact_force)
    {
      peaks_.contact_force = F_n;
      peaks_.contact_force_time = t;
    }
    // The first impact of the first clearance joint: the one the golden tests compare.
    const ContactState &s = sys_.clearance_joints()[c]->state(0);
    if (c == 0 && s.n_impacts == 1 && s.active)
      peaks_.first_impact_force = std::max(peaks_.first_impact_force, F_n);
  }

  void PeakTracker::at_state(const double t, const SystemEvaluation &ev)
  {
    for (std::size_t c = 0; c < ev.clearance.size(); ++c)
    {
      const ContactResult &r = ev.clearance[c].contacts[0];
      radial_force(t, c, r.F_n);
      peaks_.penetration = std::max(peaks_.penetration, r.delta);
    }
    if (slider_ >= 0)
      peaks_.slider_acceleration = std::max(
        peaks_.slider_acceleration, std::abs(ev.acceleration_G(slider_).dot(scene_.slider->axis)));
  }

  void PeakTracker::at_sample(const double t, const std::vector<double> &radial_forces)
  {
    for (std::size_t c = 0; c < radial_forces.size(); ++c)
      radial_force(t, c, radial_forces[c]);
  }
} // namespace clearjoint::mbd
