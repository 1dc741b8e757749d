// Boundary and material ids of the meshes fe_stage builds or reads: which face is a contact
// surface, a support, a symmetry plane or a loaded face. Every mesh file sets them; constraints,
// pairing and output read them.
#pragma once

#include <deal.II/base/types.h>

namespace clearjoint::fe::detail
{
  // Boundary ids of the generated meshes.
  constexpr dealii::types::boundary_id bid_free = 0;
  constexpr dealii::types::boundary_id bid_contact = 1;  // contact candidate surface
  constexpr dealii::types::boundary_id bid_fixed =
    2;  // supports (radial: all components; blocks: u_y)
  constexpr dealii::types::boundary_id bid_sym_x = 3;             // symmetry plane x = 0: u_x = 0
  constexpr dealii::types::boundary_id bid_sym_z = 4;             // symmetry plane z = 0: u_z = 0
  constexpr dealii::types::boundary_id bid_journal_surface = 5;   // journal's cylindrical surface
  constexpr dealii::types::boundary_id bid_journal_end = 6;       // journal end face z = L_J/2
  constexpr dealii::types::boundary_id bid_indenter_surface = 7;  // deformable indenter's bottom
  constexpr dealii::types::boundary_id bid_indenter_top = 8;  // deformable indenter's top (pushed)
}  // namespace clearjoint::fe::detail
