// Issue 30 item 1: does plastic incompressibility lock fe_stage's elements? The thick-walled
// cylinder in plane strain, elastic–perfectly plastic (von Mises, a flat hardening table),
// expanded by a prescribed radial displacement of its bore, the outer surface free: once the
// whole wall flows, the bore pressure reaches Hill's limit
//     p_L = (2/√3) σ_y ln(b/a)
// and stays there — the flow is isochoric, u_r = C/r, and nothing hardens. Elements that lock
// under the plastic incompressibility constraint carry more than p_L, and more the further they
// are pushed (Nagtegaal, Parks & Rice 1974 showed it on this problem); elements that do not
// lock approach p_L from below and level off. Built from the model's owners (Bodies, DofSpace,
// Assembler, the J2 law — the radial study's bearing ring, its rigid journal unmeshed), with
// the bore's displacement prescribed instead of a contact: R_B = a = 10 mm, b = 14 mm.
#include "common/document_reader.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/material/material_law.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/mesh/boundary_ids.h"
#include "fe_stage/scene.h"
#include "fe_stage/study/study.h"
#include "tests/verification/fe/contact_free_body.h"

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/matrix_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

using namespace clearjoint;
using namespace clearjoint::fe;
using namespace clearjoint::fe::detail;
using namespace dealii;

namespace
{
  constexpr double sigma_y = 168.2e6;  // [Pa] the SPEC table's initial yield stress, held flat

  /// The radial study's ring with the flat table; its material stays elastic as the radial
  /// study allows (the test makes the J2 law), so finite kinematics is set here, not read.
  FeScene cylinder_scene(const unsigned int degree, const unsigned int n_radial, const bool finite)
  {
    FeScene s = scene_from_json(
      parse_yaml_string("schema: clearjoint.fe/1\n"
                        "study: radial\n"
                        "loading: {journal: rigid}\n"
                        "contact: {mu: 0}\n"
                        "material: {hardening: [[0, 168.2e6], [1.0, 168.2e6]]}\n"
                        "mesh: {degree: " +
                          std::to_string(degree) + ", n_circumferential: 8, n_radial: " +
                          std::to_string(n_radial) + ", n_axial: 1, contact_refinements: 0}\n",
                        "test"),
      "test");
    if (finite)
      s.material.kinematics = Material::Kinematics::finite;
    return s;
  }

  /// u = u_a e_r on the bore (in the cross-section; u_z = 0).
  class RadialDisplacement : public Function<dim>
  {
  public:
    explicit RadialDisplacement(const double u_a)
      : Function<dim>(dim)
      , u_a_(u_a)
    {}
    double value(const Point<dim> &X, const unsigned int c) const override
    {
      return c == 2 ? 0.0 : u_a_ * X[c] / std::hypot(X[0], X[1]);
    }

  private:
    double u_a_;
  };

  /// The bearing ring with the model's owners, pushed open at its bore.
  struct Cylinder : test::ContactFreeBody
  {
    TrilinosWrappers::MPI::Vector u;
    /// the held DoFs besides the bore: plane strain (every u_z) and the symmetry plane x = 0
    std::map<types::global_dof_index, double> held;
    /// each bore DoF's share of e_r (x/r, y/r or 0): the radial reaction is Σ f_i e_r,i
    std::map<types::global_dof_index, double> bore_radial;
    double bore_area = 0.0;  // [m²] of the ring as meshed (its symmetry parts)
    double a = 0.0, b = 0.0;

    Cylinder(const unsigned int degree, const unsigned int n_radial, const bool finite)
      : ContactFreeBody(cylinder_scene(degree, n_radial, finite))
    {
      a = scene.geometry.R_B;
      b = scene.geometry.R_B + scene.geometry.t_B;
      system.assemble_static(law->elastic(), {});
      system.use_tangent();
      u.reinit(dofs.owned(), comm);

      const FEValuesExtractors::Scalar x(0), z(2);
      for (const auto i : DoFTools::extract_dofs(dofs.handler(), dofs.fe().component_mask(z)))
        held[i] = 0.0;
      VectorTools::interpolate_boundary_values(bodies.mapping(), dofs.handler(), bid_sym_x,
                                               Functions::ZeroFunction<dim>(dim), held,
                                               dofs.fe().component_mask(x));
      VectorTools::interpolate_boundary_values(bodies.mapping(), dofs.handler(), bid_contact,
                                               RadialDisplacement(1.0), bore_radial);
      const QGauss<dim - 1> fq(dofs.fe().degree + 1);
      FEFaceValues<dim> fv(bodies.mapping(), dofs.fe(), fq, update_JxW_values);
      for (const auto &cell : dofs.handler().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_contact)
              {
                fv.reinit(cell, f);
                for (const unsigned int q : fv.quadrature_point_indices())
                  bore_area += fv.JxW(q);
              }
      bore_area = Utilities::MPI::sum(bore_area, comm);
    }

    bool finite() const { return scene.material.kinematics == Material::Kinematics::finite; }

    /// Hill's limit pressure [Pa] with the bore opened by u_a: small strain on the radii as
    /// meshed; finite strain on the current ones, b' from the isochoric flow (b'² − a'² =
    /// b² − a²; the elastic volume change, ~(1 − 2ν) σ_y/E = 3e-4, left out).
    double limit_pressure(const double u_a) const
    {
      if (!finite())
        return 2.0 / std::sqrt(3.0) * sigma_y * std::log(b / a);
      const double a1 = a + u_a, b1 = std::sqrt(b * b - a * a + a1 * a1);
      return 2.0 / std::sqrt(3.0) * sigma_y * std::log(b1 / a1);
    }

    /// The internal force f_int(u) = K_t u − b at u from one assembly there (the points' trial
    /// states then belong to u).
    TrilinosWrappers::MPI::Vector internal_force()
    {
      TrilinosWrappers::MPI::Vector ghosted(dofs.owned(), dofs.relevant(), comm);
      ghosted = u;
      if (finite())
        system.assemble_finite_tangent(*law, ghosted);
      else
        system.assemble_tangent(*law, ghosted);
      TrilinosWrappers::MPI::Vector f(dofs.owned(), comm);
      system.operator_matrix().vmult(f, u);
      f -= system.load();
      return f;
    }

    /// The bore pushed to u_a [m] from the last state by Newton's method (each iteration solves
    /// K_t u_new = b with the held and prescribed DoFs), the history committed there; returns
    /// the bore pressure [Pa] and the iterations it took (0: no convergence in 30).
    std::pair<double, unsigned int> push_to(const double u_a, const double tolerance)
    {
      std::map<types::global_dof_index, double> prescribed = held;
      VectorTools::interpolate_boundary_values(bodies.mapping(), dofs.handler(), bid_contact,
                                               RadialDisplacement(u_a), prescribed);
      unsigned int it = 1;
      for (;; ++it)
        {
          if (it > 30)
            return {0.0, 0};
          internal_force();  // the tangent and its load at u
          TrilinosWrappers::SparseMatrix A;
          A.copy_from(system.operator_matrix());
          TrilinosWrappers::MPI::Vector rhs(system.load()), x(u);
          MatrixTools::apply_boundary_values(prescribed, A, x, rhs, false);
          SolverControl control(1, 0);
          TrilinosWrappers::SolverDirect direct(control);
          direct.solve(A, x, rhs);
          x -= u;
          u += x;
          if (x.linfty_norm() <= tolerance)
            break;
        }
      const TrilinosWrappers::MPI::Vector f = internal_force();  // at the converged u
      for (std::size_t p = 0;
           p < std::size_t(bodies.triangulation().n_active_cells()) * system.n_q_points(); ++p)
        law->commit(p);
      double radial = 0.0;
      for (const auto &[i, e_r] : bore_radial)
        if (dofs.owned().is_element(i))
          radial += f[i] * e_r;
      // on the bore's area now (plane strain: its length stays; finite strain: its radius grew)
      const double area = finite() ? bore_area * (a + u_a) / a : bore_area;
      return {Utilities::MPI::sum(radial, comm) / area, it};
    }
  };

  struct Curve
  {
    std::vector<double> u_a, p;  // [m], [Pa]
  };

  /// The bore pushed to 0.5 % of its radius (~4× the displacement at which the whole wall of
  /// the incompressible solution flows, u_a ≈ σ_y b²/(√3·2G a) = 12 µm) in 20 equal steps.
  Curve push(Cylinder &c, const char *name)
  {
    const double u_max = 5e-3 * c.a;
    Curve curve;
    constexpr unsigned int n_steps = 20;
    for (unsigned int k = 1; k <= n_steps; ++k)
      {
        const double u_a = u_max * k / n_steps;
        // converged when the correction is 1e-9 of the push: far below the 1e-3 the
        // assertions resolve, reached quadratically once the plastic zone settles
        const auto [p, iterations] = c.push_to(u_a, 1e-9 * u_max);
        EXPECT_GT(iterations, 0u) << name << ": no convergence at u_a = " << u_a;
        if (iterations == 0)
          return curve;
        curve.u_a.push_back(u_a);
        curve.p.push_back(p);
        std::printf("%s: u_a %.3e m, p %.6e Pa, p/p_L %.5f, %u Newton iterations\n", name, u_a, p,
                    p / c.limit_pressure(u_a), iterations);
      }
    return curve;
  }
}  // namespace

// Q2 (fe_stage's default, 3 × 3 × 3 Gauss points) on the ring as the studies mesh it: two cells
// through the wall, eight over the half turn. Measured when the test was written: p/p_L 0.9936
// at 1.5·10⁻³ a, 1.00009 at the end, +0.026 % over the last quarter (trilinear elements, with
// four cells through the wall, ended 0.24 % low and still rising 0.22 % over it: this radial
// flow hardly locks even them — the test shows that Q2 reaches the limit and stays there, not
// that no deformation could lock it).
TEST(PlasticLocking, QuadraticElementsReachHillsLimitPressureAndLevelOff)
{
  Cylinder c(2, 2, false);
  const Curve curve = push(c, "Q2, small strain");
  ASSERT_EQ(curve.p.size(), 20u);
  const double p_L = c.limit_pressure(0.0);
  EXPECT_NEAR(p_L, 65.35e6, 0.01e6);  // (2/√3) 168.2 MPa ln 1.4
  // the last pressure within 0.1 % of p_L (measured 9e-5 above: the discretisation's share),
  // and rising by less than 0.1 % over the last quarter of the push: a locking element keeps
  // carrying more, and overshoots p_L by several percent
  EXPECT_NEAR(curve.p.back() / p_L, 1.0, 1e-3);
  EXPECT_LT(curve.p.back() / curve.p[14] - 1.0, 1e-3);
}

// The same in finite strain (total Lagrangian, J2 in the logarithmic strain space): at the
// end the bore has opened by 0.5 % and the wall thinned, so the limit on the current radii is
// 0.7 % below the small-strain one; the pressure must follow it, not the small-strain value,
// and so fall once the wall flows (geometric softening, which small strain cannot show).
// Measured: p/p_L' 0.9925 at 1.5·10⁻³ a, 1.00000 at the end, falling 0.17 % over the last
// quarter.
TEST(PlasticLocking, FiniteStrainReachesTheLimitOnTheCurrentRadii)
{
  Cylinder c(2, 2, true);
  const Curve curve = push(c, "Q2, finite strain");
  ASSERT_EQ(curve.p.size(), 20u);
  const double p_L = c.limit_pressure(curve.u_a.back());
  EXPECT_LT(p_L / c.limit_pressure(0.0), 0.995);
  // 2e-3: the small-strain test's 1e-3 plus the elastic volume change left out of p_L (3e-4)
  // and the Cauchy against Kirchhoff stress (J − 1, the same size)
  EXPECT_NEAR(curve.p.back() / p_L, 1.0, 2e-3);
  EXPECT_LT(curve.p.back(), curve.p[14]);
}
