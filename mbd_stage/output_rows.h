// The rows of timeseries.csv (SPEC §4): which columns a scene has, and one row per output time
// from the system's evaluation there — slider motion, crank angle (continuous over turns),
// journal eccentricity and contact forces, ground reactions, energies and work, constraint
// violation, Euler-parameter norm error. Also keeps the extremes of those rows that the
// summary and the tests read (E0, energy-balance error, constraint drift).
#pragma once

#include "mbd_stage/multibody_system.h"
#include "mbd_stage/scene.h"
#include "mbd_stage/simulation.h"

#include <string>
#include <vector>

namespace clearjoint::mbd
{
  /// The names of a clearance joint's three contacts, in ClearanceJoint's order (0, 1, 2).
  inline const char *const contact_names[ClearanceJoint::n_contacts] = {"radial", "axial_pos",
                                                                        "axial_neg"};

  /// The columns a scene's timeseries has, and the bodies and joints they read.
  struct OutputColumns
  {
    std::vector<std::string> names, units;
    int slider = -1, crank = -1;     ///< body indices; −1 when the scene has no such output
    std::vector<int> ground_joints;  ///< joints with ground on one side: their reactions
  };
  OutputColumns make_output_columns(const Scene &scene, const MultibodySystem &sys);

  /// The crank's rotation about its axis since t = 0 [rad], continuous over whole turns: the
  /// relative angle of the Euler parameters lies in (−π, π], so each jump of more than π
  /// between consecutive calls counts a turn.
  class CrankAngle
  {
  public:
    CrankAngle(const Vector4 &e0, const Vector3 &axis);
    double operator()(const Vector4 &e);

  private:
    Vector4 e0_;
    Vector3 axis_;
    double previous_ = 0.0, turns_ = 0.0;
  };

  /// Appends one row per output time to the result (rows, E0 and the running extremes).
  class OutputRows
  {
  public:
    OutputRows(const Scene &scene, const MultibodySystem &sys, const OutputColumns &columns);
    /// `ev` is the system's evaluation at t; the first call fixes E0.
    void append(double t, const SystemEvaluation &ev, SimulationResult &res);

  private:
    const Scene &scene_;
    const OutputColumns &columns_;
    CrankAngle crank_angle_;
    bool have_E0_ = false;
  };
} // namespace clearjoint::mbd
