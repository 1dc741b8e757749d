// The peaks of a run that the summary reports: contact force (overall, per clearance joint, and
// during the first impact), penetration and slider acceleration. Tracked at every accepted step
// and output time, and — for the contact force — at the interior samples the integrator takes
// while a contact is in compression, so a peak between step ends is not missed.
#pragma once

#include "mbd_stage/multibody_system.h"
#include "mbd_stage/scene.h"

#include <vector>

namespace clearjoint::mbd
{
  struct RunPeaks
  {
    double contact_force = 0.0;       ///< [N] max radial F_n over all clearance joints
    double contact_force_time = 0.0;  ///< [s] when it occurred
    double first_impact_force = 0.0;  ///< [N] max radial F_n of joint 0 during its first impact
    double penetration = 0.0;         ///< [m] max radial δ
    double slider_acceleration = 0.0; ///< [m/s²] max |a · slider axis|
    std::vector<double> joint_force;  ///< [N] max radial F_n per clearance joint
  };

  class PeakTracker
  {
  public:
    /// slider: body index of the slider output, −1 if none.
    PeakTracker(const Scene &scene, const MultibodySystem &sys, int slider);
    /// At an accepted step or an output time: the full evaluation of the system there.
    void at_state(double t, const SystemEvaluation &ev);
    /// At an interior sample of a step: the radial contact forces only (no constraint solve).
    void at_sample(double t, const std::vector<double> &radial_forces);
    const RunPeaks &peaks() const { return peaks_; }

  private:
    /// The radial force F_n of clearance joint c at time t.
    void radial_force(double t, std::size_t c, double F_n);

    const Scene &scene_;
    const MultibodySystem &sys_;
    int slider_;
    RunPeaks peaks_;
  };
} // namespace clearjoint::mbd
