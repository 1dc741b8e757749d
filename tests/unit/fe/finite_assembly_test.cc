// The total-Lagrangian assembly (core/finite_strain_assembly.cc, issue 30) on the patch test's
// block, built from the model's owners directly (Bodies, DofSpace, Assembler, the J2 law):
//   - rigid rotations (90° about z, a half turn about x) leave no internal force;
//   - the assembled tangent K_t(u) is the derivative of the internal force f_int(u) = K_t u − b
//     (central differences) at a finite, plastic, non-homogeneous deformation — which checks
//     the geometric part δ_ik S_JL and the material part F ℂ Fᵀ of A = dP/dF, and their
//     assembly.
#include "common/strict_reader.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/material/j2_law.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"
#include "fe_stage/study/study.h"
#include "tests/verification/fe/contact_free_body.h"

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>

using namespace clearjoint;
using namespace clearjoint::fe;
using namespace clearjoint::fe::detail;
using dealii::Point;
using dealii::Tensor;

namespace
{
  FeScene block_scene()
  {
    return scene_from_json(parse_yaml_string("schema: clearjoint.fe/1\n"
                                             "study: patch\n"
                                             "contact: {mu: 0}\n"
                                             "material: {model: elastoplastic, kinematics: finite}\n"
                                             "verification: {n_cells: 2, contact_refinements: 0}\n",
                                             "test"),
                           "test");
  }

  /// A displacement field u(X) as a deal.II function of three components.
  class Displacement : public dealii::Function<dim>
  {
  public:
    explicit Displacement(std::function<Tensor<1, dim>(const Point<dim> &)> u)
      : dealii::Function<dim>(dim)
      , u_(std::move(u))
    {}
    double value(const Point<dim> &X, const unsigned int c) const override { return u_(X)[c]; }

  private:
    std::function<Tensor<1, dim>(const Point<dim> &)> u_;
  };

  /// The patch test's block (quarter model, 2 × 2 × 2 Q2 cells) with the model's owners.
  struct Block : test::ContactFreeBody
  {
    Block()
      : ContactFreeBody(block_scene())
    {
      system.use_tangent();  // the operator is the tangent, with its load
    }

    dealii::TrilinosWrappers::MPI::Vector interpolate(const Displacement &u) const
    {
      dealii::TrilinosWrappers::MPI::Vector v(dofs.owned(), comm);
      dealii::VectorTools::interpolate(bodies.mapping(), dofs.handler(), u, v);
      return v;
    }

    /// f_int(u) = K_t u − b from one assembly at u (owned vector in and out); the law's
    /// history stays the committed, virgin one, so every call is the same function of u.
    dealii::TrilinosWrappers::MPI::Vector internal_force(
      const dealii::TrilinosWrappers::MPI::Vector &u)
    {
      dealii::TrilinosWrappers::MPI::Vector ghosted(dofs.owned(), dofs.relevant(), comm);
      ghosted = u;
      system.assemble_finite_tangent(*law, ghosted);
      dealii::TrilinosWrappers::MPI::Vector f(dofs.owned(), comm);
      system.operator_matrix().vmult(f, u);
      f -= system.load();
      return f;
    }
  };

  Tensor<2, dim> rotation(const unsigned int axis, const double angle)
  {
    Tensor<2, dim> R;
    const unsigned int a = (axis + 1) % dim, b = (axis + 2) % dim;
    R[axis][axis] = 1.0;
    R[a][a] = R[b][b] = std::cos(angle);
    R[a][b] = -std::sin(angle);
    R[b][a] = std::sin(angle);
    return R;
  }
}  // namespace

TEST(FiniteAssembly, RigidRotationsLeaveNoInternalForce)
{
  Block block;
  // the scale: the internal force of a 0.1 % uniaxial stretch (elastic, about E·1e-3·area)
  const double scale =
    block
      .internal_force(block.interpolate(Displacement(
        [](const Point<dim> &X) { return Tensor<1, dim>({0.0, 1e-3 * X[1], 0.0}); })))
      .linfty_norm();
  ASSERT_GT(scale, 0.0);
  for (const auto &[axis, angle] : {std::pair{2u, M_PI / 2}, std::pair{0u, M_PI}})
    {
      const Tensor<2, dim> R = rotation(axis, angle);
      const auto u = block.interpolate(Displacement([&](const Point<dim> &X) {
        return Tensor<1, dim>(R * Tensor<1, dim>(X) - Tensor<1, dim>(X));
      }));
      const double f = block.internal_force(u).linfty_norm();
      std::printf("rotation by %g rad about axis %u: |f_int| = %.3g N (0.1 %% stretch: %.3g N)\n",
                  angle, axis, f, scale);
      // 1e-9 of a 0.1 % strain's force: RᵀR − I is a few ε of the interpolated field (Q2
      // represents the linear field (R − I)X exactly), times E, against a strain of 1e-3
      EXPECT_LT(f, 1e-9 * scale);
    }
}

TEST(FiniteAssembly, TangentIsTheDerivativeOfTheInternalForce)
{
  Block block;
  const double H = block.scene.verification.block_height;
  // a finite, plastic, non-homogeneous deformation: 15 % compression, shear and bending
  // (strains 0.05–0.2; the SPEC table yields at 8e-4)
  const auto u = block.interpolate(Displacement([&](const Point<dim> &X) {
    const double x = X[0] / H, y = X[1] / H, z = X[2] / H;
    return Tensor<1, dim>(
      {H * (0.08 * y + 0.05 * x * y), H * (-0.15 * y + 0.04 * x * x), H * (0.06 * z + 0.03 * x * z)});
  }));
  // a direction with every DoF moving (smooth, so that it stays a small strain change)
  const auto v = block.interpolate(Displacement([&](const Point<dim> &X) {
    const double x = X[0] / H, y = X[1] / H, z = X[2] / H;
    return Tensor<1, dim>({H * std::sin(1.0 + 2.0 * x + y), H * std::cos(0.5 + y - z),
                           H * std::sin(0.3 + x * z)});
  }));
  block.internal_force(u);
  dealii::TrilinosWrappers::MPI::Vector Kv(block.dofs.owned(), block.comm);
  block.system.operator_matrix().vmult(Kv, v);
  // h: 1e-7 of the field's size, so that the strain changes by ~1e-7 — small enough for
  // O(h²) ~ 1e-14 truncation, large enough that cancellation costs ε/1e-7 ~ 1e-9 — and no
  // point changes between elastic and plastic within ±h
  const double h = 1e-7;
  auto up = u, um = u;
  up.add(h, v);
  um.add(-h, v);
  auto fd = block.internal_force(up);
  fd -= block.internal_force(um);
  fd /= 2.0 * h;
  auto diff = fd;
  diff -= Kv;
  std::printf("|K v| = %.6g N/m, |FD - K v| = %.3g N/m\n", Kv.linfty_norm(),
              diff.linfty_norm());
  // 1e-6: the central difference's cancellation error (ε · |f| / h ~ 1e-8 of |K v| here) with
  // room; a tangent without its geometric part misses S/E ~ 1e-3 of it
  EXPECT_LT(diff.linfty_norm(), 1e-6 * Kv.linfty_norm());
}
