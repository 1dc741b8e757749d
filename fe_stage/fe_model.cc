// The FE contact model (deal.II). One translation unit on purpose: a deal.II file costs ~30 s and
// 1.5 GB to compile, and dim = 3 is the only instantiation.
//
// Method (docs/fe.md has the equations):
//   - small-strain linear elasticity, FE_Q(p)^3 on hexahedra with a curved mapping MappingQ(max(2,p))
//     and cylindrical manifolds, parallel::distributed::Triangulation, Trilinos matrices;
//   - contact against a rigid obstacle (cylinder = the journal, sphere, plane) enforced EXACTLY
//     at the contact nodes by a primal–dual active set (as deal.II's step-41/42): an active node
//     gets the linearised non-penetration constraint n·u = −g0 as an AffineConstraints line on its
//     dominant displacement component; the contact force at a node is λ = (K u)·n from the
//     unconstrained stiffness K; a node is active next iteration iff λ − c·ĝ > c·ε. The converged
//     solution does not depend on c;
//   - the stiffness is constant (linear elasticity), so K and the part of the condensed matrix
//     from cells without contact nodes are assembled once; only the cells that hold contact nodes
//     are re-added when the active set changes; the AMG (ML, with the six rigid-body modes) is
//     built once and reused while it stays effective.
#include "fe_stage/fe_model.h"
#include "fe_stage/mortar.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"
#include "geometry/msh_check.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/revision.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>

#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <cstdlib>
#include <memory>

namespace clearjoint::fe
{
  using namespace dealii;
  constexpr int dim = 3;

  namespace
  {
    // Boundary ids of the generated meshes.
    constexpr types::boundary_id bid_free = 0;
    constexpr types::boundary_id bid_contact = 1;   // contact candidate surface
    constexpr types::boundary_id bid_fixed = 2;     // supports (radial: all components; blocks: u_y)
    constexpr types::boundary_id bid_sym_x = 3;     // symmetry plane x = 0: u_x = 0
    constexpr types::boundary_id bid_sym_z = 4;     // symmetry plane z = 0: u_z = 0
    constexpr types::boundary_id bid_journal_surface = 5;  // journal's cylindrical surface
    constexpr types::boundary_id bid_journal_end = 6;      // journal end face z = L_J/2
    constexpr types::boundary_id bid_indenter_surface = 7; // deformable indenter's bottom
    constexpr types::boundary_id bid_indenter_top = 8;     // deformable indenter's top (pushed)

    /// The deformable Hertz indenter: (x, η, z) ↦ (x, η + cap(r)·(1 − η/H), z), r = √(x²+z²),
    /// a block of height H whose bottom is cap(r) = p/(1 + p/c), p = r²/2R — Hertz's profile
    /// near the contact (at the contact radius a ≈ 0.3 mm it differs from r²/2R by p/c ≈ 5e-4
    /// relative) that levels off far away, so the block stays a block (c = H/2).
    class IndenterChart : public ChartManifold<dim, dim, dim>
    {
    public:
      IndenterChart(const double R, const double H) : R_(R), H_(H) {}
      double cap(const double x, const double z) const
      {
        const double p = (x * x + z * z) / (2.0 * R_);
        return p / (1.0 + p / (0.5 * H_));
      }
      Point<dim> pull_back(const Point<dim> &X) const override
      {
        const double c = cap(X[0], X[2]);
        return Point<dim>(X[0], (X[1] - c) / (1.0 - c / H_), X[2]);
      }
      Point<dim> push_forward(const Point<dim> &c) const override
      {
        return Point<dim>(c[0], c[1] + cap(c[0], c[2]) * (1.0 - c[1] / H_), c[2]);
      }
      std::unique_ptr<Manifold<dim, dim>> clone() const override
      {
        return std::make_unique<IndenterChart>(R_, H_);
      }

    private:
      double R_, H_;
    };

    /// Polar chart about the bearing axis (z): (φ, s, z) ↦ s·ρ(φ)·(sin φ, −cos φ) + z e_z, with φ
    /// measured from −y. For the bearing ρ ≡ 1 (s is the radius); for the journal, whose axis is
    /// offset to y = −c_r, ρ(φ) is the distance from the bearing axis to the journal's surface
    /// along the ray at φ, so s = 1 is the journal surface. Both bodies thus refine and place
    /// their surface nodes on the same rays: the bearing's and the journal's contact nodes pair
    /// up exactly (node-to-node along the bearing's normal) at every refinement level.
    class RayChart : public ChartManifold<dim, dim, dim>
    {
    public:
      RayChart(const double c_r, const double R_J, const bool journal)
        : ChartManifold<dim, dim, dim>(Tensor<1, dim>({2.0 * numbers::PI, 0.0, 0.0}))
        , c_r_(c_r), R_J_(R_J), journal_(journal)
      {}
      double rho(const double phi) const
      {
        if (!journal_)
          return 1.0;
        const double s = std::sin(phi), c = std::cos(phi);
        return c_r_ * c + std::sqrt(R_J_ * R_J_ - c_r_ * c_r_ * s * s);
      }
      Point<dim> pull_back(const Point<dim> &X) const override
      {
        const double phi = std::atan2(X[0], -X[1]);
        return Point<dim>(phi, std::hypot(X[0], X[1]) / rho(phi), X[2]);
      }
      Point<dim> push_forward(const Point<dim> &c) const override
      {
        const double r = c[1] * rho(c[0]);
        return Point<dim>(r * std::sin(c[0]), -r * std::cos(c[0]), c[2]);
      }
      std::unique_ptr<Manifold<dim, dim>> clone() const override
      {
        return std::make_unique<RayChart>(c_r_, R_J_, journal_);
      }

    private:
      double c_r_, R_J_;
      bool journal_;
    };

    /// A rigid obstacle moved by δ along −y. gap() returns the signed distance g0 of a reference
    /// point X from the obstacle surface (> 0 outside) and the unit normal n pointing from the
    /// obstacle toward X, so that the linearised gap of the displaced point is ĝ = g0 + n·u.
    struct Obstacle
    {
      /// cylinder: the aligned journal (axis z; bearing nodes beyond its ends never touch);
      /// tilted_cylinder: the journal of the misalignment study, a finite cylinder whose axis
      /// a = (0, sin θ, cos θ) lies in the y–z plane, with rims (its end circles) as edges.
      enum class Kind { cylinder, tilted_cylinder, sphere, plane } kind = Kind::cylinder;
      double radius = 0.0;      // [m] cylinder / sphere radius
      double offset = 0.0;      // [m] cylinders: centre at y = −offset − δ; sphere: y = radius − δ
      double half_length = std::numeric_limits<double>::infinity();  // [m] cylinder half length
      double tilt = 0.0;        // [rad] tilted_cylinder: θ

      /// Returns false if X can never touch the obstacle (beyond the cylinder's end).
      bool gap(const Point<dim> &X, const double delta, double &g0, Tensor<1, dim> &n) const
      {
        switch (kind)
          {
            case Kind::cylinder:
              {
                if (std::abs(X[2]) > half_length * (1.0 + 1e-10))
                  return false;
                const Point<dim> C(0.0, -offset - delta, X[2]);
                Tensor<1, dim> d = X - C;
                d[2] = 0.0;
                const double r = d.norm();
                n = d / r;
                g0 = r - radius;
                return true;
              }
            case Kind::tilted_cylinder:
              {
                // Distance to the solid finite cylinder: along the side within its length,
                // beyond an end to the nearest rim point (outside the rim circle) or to the end
                // face (inside it). A point inside is measured to the side: the bearing's bore
                // is pushed radially by the journal, never through the journal's end face.
                const Tensor<1, dim> a({0.0, std::sin(tilt), std::cos(tilt)});
                const Point<dim> C(0.0, -offset - delta, 0.0);
                const Tensor<1, dim> d = X - C;
                const double s = d * a;
                const Tensor<1, dim> r = d - s * a;
                const double rho = r.norm();
                const double beyond = std::abs(s) - half_length;
                if (beyond <= 0.0)
                  {
                    n = r / rho;
                    g0 = rho - radius;
                  }
                else if (rho <= radius)
                  {
                    n = (s > 0.0 ? 1.0 : -1.0) * a;
                    g0 = beyond;
                  }
                else
                  {
                    const Point<dim> rim = C + std::copysign(half_length, s) * a + (radius / rho) * r;
                    const Tensor<1, dim> v = X - rim;
                    g0 = v.norm();
                    n = v / g0;
                  }
                return true;
              }
            case Kind::sphere:
              {
                const Point<dim> C(0.0, radius - delta, 0.0);
                const Tensor<1, dim> d = X - C;
                const double r = d.norm();
                n = d / r;
                g0 = r - radius;
                return true;
              }
            case Kind::plane:
              {
                n = Tensor<1, dim>();
                n[1] = -1.0;
                g0 = -delta - X[1];
                return true;
              }
          }
        return false;
      }
    };

    /// A contact candidate node: its three displacement DoFs, reference position and the
    /// component whose DoF carries the contact constraint.
    struct ContactNode
    {
      std::array<types::global_dof_index, dim> dofs;
      /// Two-body contact: the other body's point facing this node is Σ weight·(partner node);
      /// node-to-node (matching meshes) has one partner of weight 1, a mortar coupling several.
      struct Partner
      {
        std::array<types::global_dof_index, dim> dofs;
        double weight = 1.0;
        bool driven_y = false;  // the partner's y-DoF is driven by the journal load
      };
      std::vector<Partner> partners;
      bool two_body = false;
      Point<dim> X;
      unsigned int constrained_component = 1;
      bool owned = false;   // owned by this rank (its x-DoF is locally owned)
      bool candidate = true;  // false: only watched for penetration, never constrained
      bool active = false;
      // Values of the last evaluation:
      double lambda = 0.0;  // [N] normal contact force on the body (≥ 0 in contact)
      double gap = 0.0;     // [m] linearised gap ĝ = g0 + n·u
      double weight = 0.0;  // [m²] ∫ φ_i dA over the contact surface (nodal area)
      Tensor<1, dim> n;
      double g0 = 0.0;
      // Coulomb friction (contact.mu > 0). An active node sticks (its whole relative
      // displacement is constrained: no new tangential slip) or slips (normal constraint, and
      // the friction force μλ·e with its own normal force λ, implicit in the linear system).
      bool stick = true;
      Tensor<1, dim> traction;     // [N] total contact force on this node (K u at its DoFs)
      Tensor<1, dim> slip_direction;  // unit tangent of the friction force on a slipping node
      Tensor<1, dim> direction_update;  // its last fixed-point update (relaxation)
      unsigned int stick_slip_flips = 0;  // in this increment (cycle breaking)
      unsigned int contact_flips = 0;     // active ↔ inactive, in this increment (friction)
      Tensor<1, dim> relative;     // [m] u − u_partner (rigid obstacle: − its translation)
      Tensor<1, dim> relative_converged;  // [m] the same at the last converged increment
    };

    /// Stress, strain, von Mises stress and principal strains from the displacement gradient.
    class StressPostprocessor : public DataPostprocessor<dim>
    {
    public:
      StressPostprocessor(const double lambda, const double mu) : lambda_(lambda), mu_(mu) {}

      void evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &in,
                                 std::vector<Vector<double>> &out) const override
      {
        for (unsigned int q = 0; q < in.solution_gradients.size(); ++q)
          {
            Tensor<2, dim> grad;
            for (unsigned int i = 0; i < dim; ++i)
              grad[i] = in.solution_gradients[q][i];
            const SymmetricTensor<2, dim> eps = symmetrize(grad);
            const SymmetricTensor<2, dim> sig =
              lambda_ * trace(eps) * unit_symmetric_tensor<dim>() + 2.0 * mu_ * eps;
            unsigned int k = 0;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                out[q][k++] = sig[i][j];
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                out[q][k++] = eps[i][j];
            const SymmetricTensor<2, dim> s = deviator(sig);
            out[q][k++] = std::sqrt(1.5 * (s * s));
            const auto ev = eigenvalues(eps);  // descending
            for (unsigned int i = 0; i < dim; ++i)
              out[q][k++] = ev[i];
          }
      }

      std::vector<std::string> get_names() const override
      {
        std::vector<std::string> names(9, "stress");
        names.resize(18, "strain");
        names.push_back("von_mises_stress");
        names.push_back("principal_strain_1");
        names.push_back("principal_strain_2");
        names.push_back("principal_strain_3");
        return names;
      }

      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override
      {
        std::vector<DataComponentInterpretation::DataComponentInterpretation> v(
          18, DataComponentInterpretation::component_is_part_of_tensor);
        v.resize(22, DataComponentInterpretation::component_is_scalar);
        return v;
      }

      UpdateFlags get_needed_update_flags() const override { return update_gradients; }

    private:
      double lambda_, mu_;
    };

    /// The DoFs of each node of a face, grouped per node (x, y, z), in face order.
    template <typename CellIterator>
    std::vector<std::array<types::global_dof_index, dim>>
    face_node_dofs(const CellIterator &cell, const unsigned int f,
                   std::vector<types::global_dof_index> &face_dofs)
    {
      const auto &fe = cell->get_fe();
      face_dofs.resize(fe.n_dofs_per_face());
      cell->face(f)->get_dof_indices(face_dofs);
      std::vector<std::array<types::global_dof_index, dim>> nodes(fe.n_dofs_per_face() / dim);
      for (unsigned int k = 0; k < face_dofs.size(); ++k)
        {
          const auto ci = fe.face_system_to_component_index(k);
          nodes[ci.second][ci.first] = face_dofs[k];
        }
      return nodes;
    }

    /// Appends the coarse cells of `body` to (vertices, cells) as a separate body with the given
    /// material id: its vertices are copied, never shared, so two bodies that touch stay apart
    /// (GridGenerator::merge_triangulations would glue their coincident vertices).
    void append_body(const Triangulation<dim> &body, const types::material_id material,
                     std::vector<Point<dim>> &vertices, std::vector<CellData<dim>> &cells)
    {
      auto [body_vertices, body_cells, body_sub] = GridTools::get_coarse_mesh_description(body);
      (void)body_sub;
      const unsigned int offset = vertices.size();
      vertices.insert(vertices.end(), body_vertices.begin(), body_vertices.end());
      for (auto c : body_cells)
        {
          for (auto &v : c.vertices)
            v += offset;
          c.material_id = material;
          cells.push_back(c);
        }
    }

    /// The part of v tangential to the unit normal n: (I − n nᵀ) v.
    Tensor<1, dim> tangential(const Tensor<1, dim> &v, const Tensor<1, dim> &n)
    {
      return v - (v * n) * n;
    }

    struct Failure
    {
      std::string reason;
    };

    class ContactModel
    {
    public:
      ContactModel(const FeScene &scene, const RunOptions &options);
      RunResult run();

    private:
      void make_grid();
      void make_radial_grid();
      void make_gmsh_grid();
      void set_joint_obstacle();
      void refine_joint_mesh();
      template <typename CellIterator>
      bool bore_gap_below(const CellIterator &cell, double limit) const;
      void make_block_grid();
      void setup_system();
      void build_fixed_constraints();
      void find_contact_nodes();
      void find_mortar_contact_nodes(const std::map<types::global_dof_index, Point<dim>> &support,
                                     std::map<types::global_dof_index, ContactNode> &by_x_dof);
      void make_matrices();
      void set_fixed_constraints_for(double delta);
      void assemble_static();
      void compute_nodal_weights();
      void set_obstacle_position(double delta);
      /// One increment to `delta` from the current state; throws Failure.
      IncrementRecord solve_increment(double delta);
      unsigned int solve_linear(TrilinosWrappers::MPI::Vector &x,
                                const TrilinosWrappers::MPI::Vector &b);
      void build_amg();
      void evaluate_contact(double delta);
      bool friction_cell_matrix(unsigned int k, FullMatrix<double> &M,
                                std::vector<types::global_dof_index> &ext) const;
      void condense_hanging(TrilinosWrappers::MPI::Vector &r);
      void write_fields(unsigned int counter, double delta);

      const FeScene &scene_;
      RunOptions options_;
      MPI_Comm comm_;
      const unsigned int rank_, n_ranks_;

      parallel::distributed::Triangulation<dim> tria_;
      std::unique_ptr<FESystem<dim>> fe_;
      std::unique_ptr<MappingQ<dim>> mapping_;
      DoFHandler<dim> dof_handler_;
      IndexSet owned_, relevant_;

      Obstacle obstacle_;
      double symmetry_factor_ = 1.0;
      double h_min_ = 0.0;
      double lame_lambda_ = 0.0, lame_mu_ = 0.0;

      AffineConstraints<double> hanging_constraints_; // hanging nodes only (residual condensing)
      AffineConstraints<double> fixed_constraints_;   // hanging nodes, symmetry, supports,
                                                      // journal load at δ = 1 (scaled by δ)
      AffineConstraints<double> fixed_delta_;         // the same at the current δ
      TrilinosWrappers::MPI::Vector rhs_static_unit_; // static cells' right-hand side at δ = 1
      std::vector<types::global_dof_index> loaded_y_dofs_;  // owned journal DoFs driven by δ
      std::vector<types::global_dof_index> loaded_sorted_;  // the same, sorted (lookups)
      bool two_body_ = false;
      bool friction_ = false;                         // contact.mu > 0
      bool nonsymmetric_ = false;                     // slipping nodes in A_ (GMRES, not CG)
      std::map<types::global_dof_index, unsigned int> slipping_;  // x-DoF → node (this iteration)
      AffineConstraints<double> constraints_;         // + contact lines of the active set
      TrilinosWrappers::SparseMatrix K_;              // unconstrained stiffness (reactions)
      TrilinosWrappers::SparseMatrix A_static_;       // condensed, cells without contact nodes
      TrilinosWrappers::SparseMatrix A_;              // condensed system of this iteration
      TrilinosWrappers::MPI::Vector solution_owned_, rhs_, residual_owned_;
      TrilinosWrappers::MPI::Vector solution_, residual_;  // ghosted
      std::vector<types::global_dof_index> support_y_dofs_;  // owned y-DoFs of the supports

      std::vector<ContactNode> nodes_;                 // locally relevant candidates
      std::vector<int> contact_cell_of_;               // active_cell_index → index or −1
      std::vector<FullMatrix<double>> contact_cell_matrices_;
      std::vector<std::vector<types::global_dof_index>> contact_cell_dofs_;

      std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg_;
      std::unique_ptr<Epetra_MultiVector> null_space_;
      unsigned int amg_reference_iterations_ = 0;
      bool use_direct_ = false;

      std::vector<std::pair<double, std::string>> pvd_records_;
      std::vector<std::string> field_files_;
      std::chrono::steady_clock::time_point start_;
      double t_assemble_ = 0, t_solve_ = 0, t_amg_ = 0, t_evaluate_ = 0;
    };

    /// Adds the seconds since construction to `target` on destruction.
    struct ScopedTimer
    {
      explicit ScopedTimer(double &target) : target_(target), t0_(std::chrono::steady_clock::now()) {}
      ~ScopedTimer()
      {
        target_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
      }
      double &target_;
      std::chrono::steady_clock::time_point t0_;
    };

    ContactModel::ContactModel(const FeScene &scene, const RunOptions &options)
      : scene_(scene)
      , options_(options)
      , comm_(options.comm)
      , rank_(Utilities::MPI::this_mpi_process(options.comm))
      , n_ranks_(Utilities::MPI::n_mpi_processes(options.comm))
      , tria_(options.comm, Triangulation<dim>::limit_level_difference_at_vertices)
      , dof_handler_(tria_)
      , start_(std::chrono::steady_clock::now())
    {
      const double E = scene.material.E, nu = scene.material.nu;
      lame_lambda_ = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
      lame_mu_ = E / (2.0 * (1.0 + nu));
      friction_ = scene.contact.mu > 0.0;
    }

    // ------------------------------------------------------------------------------------------
    // Geometry
    // ------------------------------------------------------------------------------------------

    /// The bearing ring (and, unless the journal is rigid, the journal) as hexahedra on the
    /// RayChart manifolds; φ is measured from −y toward +x: point = (r sin φ, −r cos φ).
    void ContactModel::make_radial_grid()
    {
      const auto &G = scene_.geometry;
      const auto &M = scene_.mesh;
      // full: no x = 0 symmetry plane (φ over 360°); full_z: no z = 0 plane (the whole length:
      // the tilted journal of the misalignment study breaks the axial symmetry).
      const bool misaligned = scene_.study == Study::misalignment;
      const bool full = scene_.full_model;
      const bool full_z = full || misaligned;
      const bool journal = scene_.loading.journal != JournalLoading::rigid;
      const unsigned int n_phi = full ? 2 * M.n_circumferential : M.n_circumferential;
      const unsigned int n_r =
        M.n_radial > 0 ? M.n_radial :
                         std::max(1u, static_cast<unsigned int>(std::lround(G.t_B / 2.0e-3)));
      const double R_o = G.R_B + G.t_B;
      const RayChart bearing_chart(G.c_r, G.R_J(), false), journal_chart(G.c_r, G.R_J(), true);

      // φ of vertex i; the full ring closes at φ = ±π (vertex index modulo n_phi).
      const unsigned int n_phi_vertices = full ? n_phi : n_phi + 1;
      const double phi0 = full ? -units::pi : 0.0;
      const double dphi = (full ? 2.0 * units::pi : units::pi) / n_phi;
      auto phi_of = [&](unsigned int i) { return phi0 + (i % n_phi_vertices) * dphi; };

      // --- bearing: 2D (r, φ) grid, local x along r (outward), local y along φ -------------
      std::vector<Point<2>> vertices;
      std::vector<CellData<2>> cells;
      auto bid = [&](unsigned int i, unsigned int j) {
        return (i % n_phi_vertices) * (n_r + 1) + j;
      };
      for (unsigned int i = 0; i < n_phi_vertices; ++i)
        for (unsigned int j = 0; j <= n_r; ++j)
          {
            const double r = G.R_B + (R_o - G.R_B) * j / n_r;
            vertices.emplace_back(r * std::sin(phi_of(i)), -r * std::cos(phi_of(i)));
          }
      for (unsigned int i = 0; i < n_phi; ++i)
        for (unsigned int j = 0; j < n_r; ++j)
          {
            CellData<2> c;
            c.vertices[0] = bid(i, j);
            c.vertices[1] = bid(i, j + 1);
            c.vertices[2] = bid(i + 1, j);
            c.vertices[3] = bid(i + 1, j + 1);
            c.material_id = 0;
            c.manifold_id = 0;
            cells.push_back(c);
          }
      Triangulation<2> bearing2d;
      bearing2d.create_triangulation(vertices, cells, SubCellData());

      // Axial slices: the journal's end L_J/2 is a mesh plane. The misalignment study's
      // journal is rigid; there the plane goes through its first touch point P1 at
      // z = −((L_J/2) cos θ − R_J sin θ) (and the mirrored plane through the diagonally
      // opposite rim point, which touches at θ_max), so a node sits where contact starts.
      const double theta = misaligned ? scene_.misalignment.theta_deg * units::deg : 0.0;
      const double zJ = 0.5 * G.L_J() * std::cos(theta) - G.R_J() * std::sin(theta);
      const double zB = 0.5 * G.L_B;
      const unsigned int n_in = std::max(1u, M.n_axial > 1 ? M.n_axial - 1 : 1u);
      std::vector<double> half_slices;
      for (unsigned int k = 0; k <= n_in; ++k)
        half_slices.push_back(zJ * k / n_in);
      const unsigned int n_out =
        std::max(1u, static_cast<unsigned int>(std::lround((zB - zJ) / (zJ / n_in))));
      auto mirror = [&](const std::vector<double> &half) {
        std::vector<double> sl;
        if (full_z)
          for (auto it = half.rbegin(); it != half.rend(); ++it)
            if (*it > 0.0)
              sl.push_back(-*it);
        sl.insert(sl.end(), half.begin(), half.end());
        return sl;
      };
      const std::vector<double> journal_slices = mirror(half_slices);
      for (unsigned int k = 1; k <= n_out; ++k)
        half_slices.push_back(zJ + (zB - zJ) * k / n_out);
      const std::vector<double> bearing_slices = mirror(half_slices);

      Triangulation<dim> bearing3d;
      GridGenerator::extrude_triangulation(bearing2d, bearing_slices, bearing3d);
      auto [all_vertices, all_cells, subcells] =
        GridTools::get_coarse_mesh_description(bearing3d);
      for (auto &c : all_cells)
        {
          c.material_id = 0;
          c.manifold_id = 0;
        }

      if (journal)
        {
          // --- journal cross-section: one ring layer s ∈ [s0, 1] on the rays of the bearing's
          // vertices, and a structured core whose boundary lies on s = s0 (Coons patch). -----
          const double s0 = 0.6;
          const unsigned int n = M.n_circumferential;  // cells over 180°
          const unsigned int Nx = full ? n / 2 : n / 4, Ny = n / 2;
          std::vector<Point<2>> jv;
          std::vector<CellData<2>> jc;
          auto ring_point = [&](unsigned int i, double s) {
            const Point<dim> p = journal_chart.push_forward(Point<dim>(phi_of(i), s, 0.0));
            return Point<2>(p[0], p[1]);
          };
          // ring vertices: (i, l), l = 0 (s0), 1 (surface)
          auto rid = [&](unsigned int i, unsigned int l) { return (i % n_phi_vertices) * 2 + l; };
          for (unsigned int i = 0; i < n_phi_vertices; ++i)
            {
              jv.push_back(ring_point(i, s0));
              jv.push_back(ring_point(i, 1.0));
            }
          for (unsigned int i = 0; i < n_phi; ++i)
            {
              CellData<2> c;
              c.vertices[0] = rid(i, 0);
              c.vertices[1] = rid(i, 1);
              c.vertices[2] = rid(i + 1, 0);
              c.vertices[3] = rid(i + 1, 1);
              c.material_id = 1;
              c.manifold_id = 1;
              jc.push_back(c);
            }
          // core boundary: ring index of boundary node (a, b), or −1 on the symmetry line
          // (half model) where the points run straight through the journal's centre.
          auto ring_index = [&](unsigned int a, unsigned int b) -> int {
            if (full)
              {
                // counter-clockwise from the bottom-left corner (φ = −3π/4 ↔ i = n/2)
                if (b == 0) return int(n / 2 + a);
                if (a == Nx) return int(n / 2 + Nx + b);
                if (b == Ny) return int((n / 2 + Nx + Ny + (Nx - a)) % n_phi);
                if (a == 0) return int((n / 2 + 2 * Nx + Ny + (Ny - b)) % n_phi);
                return -1;
              }
            if (b == 0) return int(a);
            if (a == Nx) return int(Nx + b);
            if (b == Ny) return int(Nx + Ny + (Nx - a));
            return -1;
          };
          const Point<2> centre(0.0, -G.c_r);
          auto boundary_point = [&](unsigned int a, unsigned int b) -> Point<2> {
            const int i = ring_index(a, b);
            if (i >= 0)
              return ring_point(i, s0);
            // half model, a = 0: bottom → centre → top, linear in each half
            const Point<2> bot = ring_point(0, s0), top = ring_point(n, s0);
            const double t = double(b) / Ny;
            return t <= 0.5 ? bot + (centre - bot) * (2.0 * t) : centre + (top - centre) * (2.0 * t - 1.0);
          };
          std::vector<int> core_id((Nx + 1) * (Ny + 1), -1);
          for (unsigned int b = 0; b <= Ny; ++b)
            for (unsigned int a = 0; a <= Nx; ++a)
              {
                const int i = ring_index(a, b);
                if (i >= 0)
                  {
                    core_id[b * (Nx + 1) + a] = rid(i, 0);
                    continue;
                  }
                Point<2> p;
                if (a == 0 || a == Nx || b == 0 || b == Ny)
                  p = boundary_point(a, b);
                else
                  {
                    const double u = double(a) / Nx, v = double(b) / Ny;
                    const Point<2> B = boundary_point(a, 0), T = boundary_point(a, Ny),
                                   Lp = boundary_point(0, b), R = boundary_point(Nx, b);
                    const Point<2> P00 = boundary_point(0, 0), P10 = boundary_point(Nx, 0),
                                   P01 = boundary_point(0, Ny), P11 = boundary_point(Nx, Ny);
                    p = Point<2>((1 - v) * B + v * T + (1 - u) * Lp + u * R -
                                 ((1 - u) * (1 - v) * P00 + u * (1 - v) * P10 +
                                  (1 - u) * v * P01 + u * v * P11));
                  }
                core_id[b * (Nx + 1) + a] = jv.size();
                jv.push_back(p);
              }
          for (unsigned int b = 0; b < Ny; ++b)
            for (unsigned int a = 0; a < Nx; ++a)
              {
                CellData<2> c;
                c.vertices[0] = core_id[b * (Nx + 1) + a];
                c.vertices[1] = core_id[b * (Nx + 1) + a + 1];
                c.vertices[2] = core_id[(b + 1) * (Nx + 1) + a];
                c.vertices[3] = core_id[(b + 1) * (Nx + 1) + a + 1];
                c.material_id = 1;
                c.manifold_id = numbers::flat_manifold_id;
                jc.push_back(c);
              }
          Triangulation<2> journal2d;
          GridTools::consistently_order_cells(jc);
          journal2d.create_triangulation(jv, jc, SubCellData());
          Triangulation<dim> journal3d;
          GridGenerator::extrude_triangulation(journal2d, journal_slices, journal3d, true);
          append_body(journal3d, 1, all_vertices, all_cells);
        }

      // One coarse mesh without vertex merging: the bodies touch at φ = 0 but stay separate.
      Triangulation<dim> serial;
      serial.create_triangulation(all_vertices, all_cells, SubCellData());

      const double tol = 1e-8 * G.R_B;
      for (const auto &cell : serial.active_cell_iterators())
        {
          const bool is_journal = cell->material_id() == 1;
          if (is_journal)
            {
              // ring cells: all vertices at s ≥ s0 − tol on the journal chart
              bool ring = true;
              for (const auto v : cell->vertex_indices())
                ring = ring && journal_chart.pull_back(cell->vertex(v))[1] > 0.6 - 1e-6;
              cell->set_all_manifold_ids(ring ? 1 : numbers::flat_manifold_id);
            }
          else
            cell->set_all_manifold_ids(0);
        }
      // ring faces toward the core carry the chart too (set after the core so they stay curved)
      for (const auto &cell : serial.active_cell_iterators())
        if (cell->material_id() == 1 && cell->manifold_id() == 1)
          cell->set_all_manifold_ids(1);

      for (const auto &cell : serial.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto face = cell->face(f);
              const Point<dim> c = face->center();
              bool on_inner = true, on_outer = true, on_x0 = true, on_journal = true;
              for (const auto v : face->vertex_indices())
                {
                  const Point<dim> &p = face->vertex(v);
                  const double rv = std::hypot(p[0], p[1]);
                  on_inner = on_inner && std::abs(rv - G.R_B) < tol;
                  on_outer = on_outer && std::abs(rv - R_o) < tol;
                  on_x0 = on_x0 && std::abs(p[0]) < tol;
                  on_journal =
                    on_journal && std::abs(std::hypot(p[0], p[1] + G.c_r) - G.R_J()) < tol;
                }
              types::boundary_id id = bid_free;
              if (cell->material_id() == 1)
                {
                  if (on_journal)
                    id = bid_journal_surface;
                  else if (std::abs(std::abs(c[2]) - zJ) < tol)
                    id = bid_journal_end;
                  else if (!full && on_x0)
                    id = bid_sym_x;
                  else if (!full_z && std::abs(c[2]) < tol)
                    id = bid_sym_z;
                }
              else if (on_inner)
                id = bid_contact;
              else if (on_outer)
                id = (c[1] > 0.0) ? bid_fixed : bid_free;
              else if (!full && on_x0)
                id = bid_sym_x;
              else if (!full_z && std::abs(c[2]) < tol)
                id = bid_sym_z;
              face->set_boundary_id(id);
            }

      tria_.copy_triangulation(serial);
      tria_.set_manifold(0, bearing_chart);
      tria_.set_manifold(1, journal_chart);

      set_joint_obstacle();
      refine_joint_mesh();
      symmetry_factor_ = (full ? 1.0 : 2.0) * (full_z ? 1.0 : 2.0);
    }

    /// The bearing of a user's Gmsh mesh (geometry.mesh, MSH 2.2 with the physical groups of
    /// docs/geometry.md). The mesh is read and checked without deal.II first (missing groups,
    /// non-hexahedra, inverted cells: an InputError listing every problem), then its bearing
    /// hexahedra become the coarse mesh on the bearing's polar chart, so Q2 curved faces follow
    /// the bore. Boundary ids come from the surface groups; boundary faces outside the groups
    /// that lie on x = 0 or z = 0 are symmetry planes, and set the symmetry factor. The journal
    /// is the scene's rigid cylinder (R_J, L_J from the geometry keys): a deformable journal
    /// from a Gmsh mesh needs node-to-segment contact, which this version does not have.
    void ContactModel::make_gmsh_grid()
    {
      const auto &G = scene_.geometry;
      // validate_scene has checked the mesh against the scene (groups, cells, bore radius,
      // journal loading, length) before any output was written
      const geometry::MshMesh msh = geometry::read_joint_mesh(G.mesh);
      auto tag_of = [&](const std::string &name, const int group_dim) {
        for (const auto &g : msh.groups)
          if (g.name == name && g.dim == group_dim)
            return g.tag;
        throw InputError(G.mesh, name, "(missing)", "a physical group of dimension " +
                                                      std::to_string(group_dim));
      };
      const int bearing = tag_of("bearing", 3);

      // Gmsh numbers a hexahedron's corners counter-clockwise per face, deal.II
      // lexicographically: deal.II corner i is Gmsh corner gmsh_corner[i].
      constexpr std::array<unsigned int, 8> gmsh_corner = {0, 1, 3, 2, 4, 5, 7, 6};
      std::vector<int> vertex_of(msh.nodes.size(), -1);
      std::vector<Point<dim>> vertices;
      auto vertex = [&](const std::size_t node) {
        if (vertex_of[node] < 0)
          {
            vertex_of[node] = static_cast<int>(vertices.size());
            const auto &x = msh.nodes[node];
            vertices.emplace_back(x[0], x[1], x[2]);
          }
        return static_cast<unsigned int>(vertex_of[node]);
      };
      std::vector<CellData<dim>> cells;
      for (const auto &e : msh.elements)
        if (e.type == 5 && e.physical == bearing)
          {
            CellData<dim> c;
            for (unsigned int i = 0; i < 8; ++i)
              c.vertices[i] = vertex(e.nodes[gmsh_corner[i]]);
            c.material_id = 0;
            c.manifold_id = 0;
            cells.push_back(c);
          }

      // Surface groups → boundary ids, keyed by the sorted corner vertices of each quad.
      std::map<std::array<unsigned int, 4>, types::boundary_id> face_id;
      const std::vector<std::pair<std::string, types::boundary_id>> surfaces = {
        {"bearing_contact", bid_contact}, {"bearing_fixed", bid_fixed}};
      for (const auto &[name, id] : surfaces)
        {
          const int tag = tag_of(name, 2);
          for (const auto &e : msh.elements)
            if (e.type == 3 && e.physical == tag)
              {
                std::array<unsigned int, 4> key;
                for (unsigned int i = 0; i < 4; ++i)
                  key[i] = vertex(e.nodes[i]);
                std::sort(key.begin(), key.end());
                face_id[key] = id;
              }
        }

      Triangulation<dim> serial;
      try
        {
          GridTools::consistently_order_cells(cells);
        }
      catch (const std::exception &)
        {
          // deal.II handles non-standard face orientations in 3D; ordering only saves work
        }
      serial.create_triangulation(vertices, cells, SubCellData());
      for (const auto &cell : serial.active_cell_iterators())
        cell->set_all_manifold_ids(0);  // faces and edges too: curved bore for the Q2 mapping
      const double plane_tol = 1e-8 * G.R_B;
      bool sym_x = false, sym_z = false;
      unsigned int n_contact = 0, n_fixed = 0;
      for (const auto &cell : serial.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto face = cell->face(f);
              std::array<unsigned int, 4> key;
              bool on_x0 = true, on_z0 = true;
              for (unsigned int v = 0; v < 4; ++v)
                {
                  key[v] = face->vertex_index(v);
                  on_x0 = on_x0 && std::abs(face->vertex(v)[0]) < plane_tol;
                  on_z0 = on_z0 && std::abs(face->vertex(v)[2]) < plane_tol;
                }
              std::sort(key.begin(), key.end());
              const auto it = face_id.find(key);
              types::boundary_id id = bid_free;
              if (it != face_id.end())
                id = it->second;
              else if (on_x0)
                id = bid_sym_x;
              else if (on_z0)
                id = bid_sym_z;
              n_contact += id == bid_contact;
              n_fixed += id == bid_fixed;
              sym_x = sym_x || id == bid_sym_x;
              sym_z = sym_z || id == bid_sym_z;
              face->set_boundary_id(id);
            }
      if (n_contact == 0 || n_fixed == 0)
        throw InputError(G.mesh, n_contact == 0 ? "bearing_contact" : "bearing_fixed",
                         "(no boundary face of the bearing)", "boundary faces of the bearing");

      tria_.copy_triangulation(serial);
      tria_.set_manifold(0, RayChart(G.c_r, G.R_J(), false));
      set_joint_obstacle();
      refine_joint_mesh();
      symmetry_factor_ = (sym_x ? 2.0 : 1.0) * (sym_z ? 2.0 : 1.0);
      if (rank_ == 0)
        log::info("fe_stage: " + G.mesh + ": " + std::to_string(cells.size()) +
                  " bearing hexahedra, symmetry planes" + (sym_x ? " x = 0" : "") +
                  (sym_z ? " z = 0" : "") + (sym_x || sym_z ? "" : " none") +
                  " (force factor " + format_value(symmetry_factor_) + ")");
    }

    /// The rigid journal (or, for two bodies, the journal's place for the candidate search):
    /// aligned, first touch at the bottom (0, −R_B); or tilted by θ in the y–z plane about its
    /// centre, lowered until its lowest rim point — the bottom of the rim at z < 0, at
    /// (0, y_c − (L_J/2) sin θ − R_J cos θ) — touches the bore (paper §3.3).
    void ContactModel::set_joint_obstacle()
    {
      const auto &G = scene_.geometry;
      obstacle_.radius = G.R_J();
      obstacle_.half_length = 0.5 * G.L_J();
      if (scene_.study == Study::misalignment)
        {
          const double theta = scene_.misalignment.theta_deg * units::deg;
          obstacle_.kind = Obstacle::Kind::tilted_cylinder;
          obstacle_.tilt = theta;
          obstacle_.offset = G.R_B - 0.5 * G.L_J() * std::sin(theta) - G.R_J() * std::cos(theta);
        }
      else
        {
          obstacle_.kind = Obstacle::Kind::cylinder;
          obstacle_.offset = G.c_r;
        }
    }

    /// True if the bore (r = R_B) within the cell's angular and axial extent comes closer than
    /// `limit` to the journal pushed to δ_max. Sampled on a 16 × 16 grid of the extent, not at
    /// the vertices only: a rim contact patch can be much smaller than a coarse cell.
    template <typename CellIterator>
    bool ContactModel::bore_gap_below(const CellIterator &cell, const double limit) const
    {
      double phi_lo = std::numeric_limits<double>::max(), phi_hi = -phi_lo;
      double z_lo = phi_lo, z_hi = -phi_lo;
      for (const auto v : cell->vertex_indices())
        {
          const Point<dim> &p = cell->vertex(v);
          const double phi = std::atan2(p[0], -p[1]);
          phi_lo = std::min(phi_lo, phi);
          phi_hi = std::max(phi_hi, phi);
          z_lo = std::min(z_lo, p[2]);
          z_hi = std::max(z_hi, p[2]);
        }
      if (phi_hi - phi_lo > units::pi)  // a cell of the full model across φ = ±π (the top)
        return false;
      constexpr unsigned int n = 16;
      const double R = scene_.geometry.R_B;
      for (unsigned int i = 0; i <= n; ++i)
        for (unsigned int j = 0; j <= n; ++j)
          {
            const double phi = phi_lo + (phi_hi - phi_lo) * i / n;
            const Point<dim> X(R * std::sin(phi), -R * std::cos(phi), z_lo + (z_hi - z_lo) * j / n);
            double g0;
            Tensor<1, dim> normal;
            if (obstacle_.gap(X, scene_.loading.delta_max, g0, normal) && g0 < limit)
              return true;
          }
      return false;
    }

    /// Global refinements, then `contact_refinements` rounds near the contact: the radial study
    /// refines the cells within contact_window_deg of the bottom (the mean vertex angle is the
    /// same for a bearing cell and the journal cell on the same rays); the misalignment study,
    /// whose contact is a small patch under one rim, the cells that hold contact candidates
    /// (a vertex within 2 δ_max of the journal pushed to δ_max; hanging nodes in the contact
    /// zone pass their force to their masters, see condense_hanging).
    void ContactModel::refine_joint_mesh()
    {
      const auto &M = scene_.mesh;
      for (unsigned int k = 0; k < M.global_refinements; ++k)
        tria_.refine_global(1);
      const double window = M.contact_window_deg * units::deg;
      const bool by_gap = scene_.study == Study::misalignment;
      for (unsigned int k = 0; k < M.contact_refinements; ++k)
        {
          for (const auto &cell : tria_.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                if (by_gap)
                  {
                    if (bore_gap_below(cell, 2.0 * scene_.loading.delta_max))
                      cell->set_refine_flag();
                    continue;
                  }
                double phi = 0.0;
                for (const auto v : cell->vertex_indices())
                  phi += std::abs(std::atan2(cell->vertex(v)[0], -cell->vertex(v)[1]));
                phi /= cell->n_vertices();
                if (phi < window)
                  cell->set_refine_flag();
              }
          tria_.execute_coarsening_and_refinement();
        }
    }

    /// The verification block [0,W]×[−H,0]×[0,W] (quarter model: symmetry planes x = 0, z = 0),
    /// roller support u_y = 0 at y = −H, contact on y = 0.
    void ContactModel::make_block_grid()
    {
      const auto &V = scene_.verification;
      const unsigned int n = V.n_cells;
      const IndenterChart chart(V.sphere_radius, V.indenter_height);
      if (!V.deformable_indenter)
        GridGenerator::subdivided_hyper_rectangle(tria_, {n, n, n},
                                                  Point<dim>(0.0, -V.block_height, 0.0),
                                                  Point<dim>(V.block_width, 0.0, V.block_width));
      else
        {
          // Two bodies in one triangulation that share no vertex (they touch at y = 0): the
          // block below (material 0) and the indenter above (material 1), meshed with
          // different cell counts so that their contact surfaces do not match.
          Triangulation<dim> lower, upper;
          const unsigned int m = V.indenter_n_cells;
          GridGenerator::subdivided_hyper_rectangle(lower, {n, n, n},
                                                    Point<dim>(0.0, -V.block_height, 0.0),
                                                    Point<dim>(V.block_width, 0.0, V.block_width));
          GridGenerator::subdivided_hyper_rectangle(upper, {m, m, m}, Point<dim>(0.0, 0.0, 0.0),
                                                    Point<dim>(V.block_width, V.indenter_height,
                                                               V.block_width));
          if (scene_.study == Study::hertz)
            GridTools::transform([&](const Point<dim> &p) { return chart.push_forward(p); },
                                 upper);
          std::vector<Point<dim>> vertices;
          std::vector<CellData<dim>> cells;
          append_body(lower, 0, vertices, cells);
          append_body(upper, 1, vertices, cells);
          tria_.create_triangulation(vertices, cells, SubCellData());
          if (scene_.study == Study::hertz)
            {
              for (const auto &cell : tria_.active_cell_iterators())
                if (cell->material_id() == 1)
                  cell->set_all_manifold_ids(1);
              tria_.set_manifold(1, chart);
            }
        }
      // Boundary ids from the face vertices (exact: they lie on the generating planes).
      const double tol = 1e-10 * V.block_width;
      for (const auto &cell : tria_.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              auto all = [&](auto &&pred) {
                for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
                  {
                    Point<dim> X = cell->face(f)->vertex(v);
                    if (cell->material_id() == 1 && scene_.study == Study::hertz)
                      X = chart.pull_back(X);
                    if (!pred(X))
                      return false;
                  }
                return true;
              };
              types::boundary_id id = bid_free;
              if (cell->material_id() == 1)
                {
                  if (all([&](const Point<dim> &X) { return std::abs(X[1]) < tol; }))
                    id = bid_indenter_surface;
                  else if (all([&](const Point<dim> &X) {
                             return std::abs(X[1] - V.indenter_height) < tol;
                           }))
                    id = bid_indenter_top;
                }
              else if (all([&](const Point<dim> &X) { return std::abs(X[1]) < tol; }))
                id = bid_contact;
              else if (all([&](const Point<dim> &X) { return std::abs(X[1] + V.block_height) < tol; }))
                id = bid_fixed;
              if (id == bid_free)
                {
                  if (all([&](const Point<dim> &X) { return std::abs(X[0]) < tol; }))
                    id = bid_sym_x;
                  else if (all([&](const Point<dim> &X) { return std::abs(X[2]) < tol; }))
                    id = bid_sym_z;
                }
              cell->face(f)->set_boundary_id(id);
            }
      if (scene_.study == Study::patch)
        {
          tria_.refine_global(V.contact_refinements);
          obstacle_.kind = Obstacle::Kind::plane;
        }
      else
        {
          // Graded: round k refines the cells within refine_radius·2^(n−1−k) of the contact
          // point, so the contact zone is uniformly fine and hanging nodes stay outside it.
          const unsigned int nr = V.contact_refinements;
          for (unsigned int k = 0; k < nr; ++k)
            {
              const double radius = V.refine_radius * std::pow(2.0, double(nr - 1 - k));
              for (const auto &cell : tria_.active_cell_iterators())
                if (cell->is_locally_owned())
                  {
                    // distance from the origin to the cell's bounding box
                    const auto box = cell->bounding_box();
                    double d2 = 0.0;
                    for (unsigned int i = 0; i < dim; ++i)
                      {
                        const double lo = box.lower_bound(i), hi = box.upper_bound(i);
                        const double di = std::max({lo, 0.0 - hi, 0.0});
                        d2 += di * di;
                      }
                    if (std::sqrt(d2) < radius)
                      cell->set_refine_flag();
                  }
              tria_.execute_coarsening_and_refinement();
            }
          obstacle_.kind = Obstacle::Kind::sphere;
          obstacle_.radius = V.sphere_radius;
        }
      symmetry_factor_ = 4.0;
    }

    void ContactModel::make_grid()
    {
      if (!scene_.geometry.mesh.empty())
        make_gmsh_grid();
      else if (scene_.study == Study::radial || scene_.study == Study::misalignment)
        make_radial_grid();
      else
        make_block_grid();
      h_min_ = Utilities::MPI::min(
        [&] {
          double h = std::numeric_limits<double>::max();
          for (const auto &cell : tria_.active_cell_iterators())
            if (cell->is_locally_owned())
              h = std::min(h, cell->minimum_vertex_distance());
          return h;
        }(),
        comm_);
    }

    // ------------------------------------------------------------------------------------------
    // DoFs, constraints, static matrices
    // ------------------------------------------------------------------------------------------

    void ContactModel::setup_system()
    {
      const bool joint = scene_.study == Study::radial || scene_.study == Study::misalignment;
      const unsigned int p = joint ? scene_.mesh.degree : 2;
      fe_ = std::make_unique<FESystem<dim>>(FE_Q<dim>(p), dim);
      mapping_ = std::make_unique<MappingQ<dim>>(std::max(2u, p));
      dof_handler_.distribute_dofs(*fe_);
      owned_ = dof_handler_.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler_, relevant_);

      two_body_ = joint ? scene_.loading.journal != JournalLoading::rigid :
                          scene_.verification.deformable_indenter;
      build_fixed_constraints();

      {
        const FEValuesExtractors::Scalar uy(1);
        const IndexSet sy = DoFTools::extract_boundary_dofs(dof_handler_, fe_->component_mask(uy),
                                                           {bid_fixed});
        for (const auto i : sy)
          if (owned_.is_element(i))
            support_y_dofs_.push_back(i);
      }

    }

    /// Hanging nodes, symmetry planes, supports and the journal load at δ = 1 on the locally
    /// relevant DoFs. With several ranks the lines are made consistent across ranks, so a rank
    /// also knows the constraints of the journal DoFs it was given as contact partners.
    void ContactModel::build_fixed_constraints()
    {
      const bool joint = scene_.study == Study::radial || scene_.study == Study::misalignment;
      loaded_y_dofs_.clear();
      const FEValuesExtractors::Scalar ux(0), uy(1), uz(2);
      fixed_constraints_.clear();
      fixed_constraints_.reinit(relevant_);
      DoFTools::make_hanging_node_constraints(dof_handler_, fixed_constraints_);
      hanging_constraints_.clear();
      hanging_constraints_.reinit(relevant_);
      DoFTools::make_hanging_node_constraints(dof_handler_, hanging_constraints_);
      if (n_ranks_ > 1)
        hanging_constraints_.make_consistent_in_parallel(owned_, relevant_, comm_);
      hanging_constraints_.close();
      const Functions::ZeroFunction<dim> zero(dim);
      VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_sym_x, zero,
                                               fixed_constraints_, fe_->component_mask(ux));
      VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_sym_z, zero,
                                               fixed_constraints_, fe_->component_mask(uz));
      if (joint)
        VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_fixed, zero,
                                                 fixed_constraints_);
      else
        VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_fixed, zero,
                                                 fixed_constraints_, fe_->component_mask(uy));
      // Journal load at δ = 1 (u_y = −1 m); every inhomogeneity is then scaled by δ.
      if (two_body_)
        {
          std::map<types::global_dof_index, Point<dim>> support;
          DoFTools::map_dofs_to_support_points(*mapping_, dof_handler_, support);
          Vector<double> down(dim);
          down[1] = -1.0;
          const Functions::ConstantFunction<dim> unit_push(down);
          if (!joint || scene_.loading.journal == JournalLoading::end_faces)
            {
              // the journal's end face, or the top of a deformable indenter
              AffineConstraints<double> load(relevant_);
              VectorTools::interpolate_boundary_values(*mapping_, dof_handler_,
                                                       joint ? bid_journal_end : bid_indenter_top,
                                                       unit_push, load, fe_->component_mask(uy));
              for (const auto &line : load.get_lines())
                {
                  // the reaction sums over every DoF of the set, hanging ones included (their
                  // share would otherwise be lost); only the free ones get the load line
                  if (owned_.is_element(line.index))
                    loaded_y_dofs_.push_back(line.index);
                  if (!fixed_constraints_.is_constrained(line.index))
                    {
                      fixed_constraints_.add_line(line.index);
                      fixed_constraints_.set_inhomogeneity(line.index, -1.0);
                    }
                }
            }
          else  // axis_line: the journal's y-DoFs on its axis x = 0, y = −c_r
            {
              const double tol = 1e-8 * scene_.geometry.R_B;
              std::vector<types::global_dof_index> dofs(fe_->n_dofs_per_cell()), axis_dofs;
              for (const auto &cell : dof_handler_.active_cell_iterators())
                if ((cell->is_locally_owned() || cell->is_ghost()) && cell->material_id() == 1)
                  {
                    cell->get_dof_indices(dofs);
                    for (unsigned int i = 0; i < dofs.size(); ++i)
                      if (fe_->system_to_component_index(i).first == 1)
                        {
                          const Point<dim> &p = support.at(dofs[i]);
                          if (std::abs(p[0]) < tol && std::abs(p[1] + scene_.geometry.c_r) < tol &&
                              std::find(axis_dofs.begin(), axis_dofs.end(), dofs[i]) ==
                                axis_dofs.end())
                            {
                              axis_dofs.push_back(dofs[i]);
                              if (owned_.is_element(dofs[i]))
                                loaded_y_dofs_.push_back(dofs[i]);
                              if (!fixed_constraints_.is_constrained(dofs[i]))
                                {
                                  fixed_constraints_.add_line(dofs[i]);
                                  fixed_constraints_.set_inhomogeneity(dofs[i], -1.0);
                                }
                            }
                        }
                  }
            }
          loaded_sorted_ = loaded_y_dofs_;
          std::sort(loaded_sorted_.begin(), loaded_sorted_.end());
          if (Utilities::MPI::sum(loaded_y_dofs_.size(), comm_) == 0)
            throw NumericalError(joint ? "fe_stage: no journal DoFs found for the loading " +
                                           to_string(scene_.loading.journal) :
                                         std::string("fe_stage: the indenter has no top face"));
        }
      if (n_ranks_ > 1)
        fixed_constraints_.make_consistent_in_parallel(owned_, relevant_, comm_);
      fixed_constraints_.close();
    }

    /// Matrices and vectors. The sparsity pattern is built with every candidate's contact line
    /// present, so any active set condenses into it (the two-body lines couple journal DoFs).
    void ContactModel::make_matrices()
    {
      AffineConstraints<double> worst(relevant_);
      for (const auto &cn : nodes_)
        if (cn.candidate)
          {
            const auto d = cn.dofs[cn.constrained_component];
            worst.add_line(d);
            for (unsigned int k = 0; k < dim; ++k)
              {
                if (k != cn.constrained_component)
                  worst.add_entry(d, cn.dofs[k], 1.0);
                for (const auto &p : cn.partners)
                  worst.add_entry(d, p.dofs[k], 1.0);
              }
            // a sticking node constrains its other free components to its partners too
            if (friction_)
              for (unsigned int k = 0; k < dim; ++k)
                if (k != cn.constrained_component &&
                    !fixed_constraints_.is_constrained(cn.dofs[k]))
                  {
                    worst.add_line(cn.dofs[k]);
                    for (const auto &p : cn.partners)
                      worst.add_entry(cn.dofs[k], p.dofs[k], 1.0);
                  }
          }
      worst.merge(fixed_constraints_, AffineConstraints<double>::left_object_wins, true);
      worst.close();
      // The union of the patterns with and without the contact lines: a master of a hanging node
      // may be a contact DoF, whose line is active in some iterations and not in others.
      DynamicSparsityPattern dsp(relevant_);
      DoFTools::make_sparsity_pattern(dof_handler_, dsp, fixed_constraints_, true);
      DoFTools::make_sparsity_pattern(dof_handler_, dsp, worst, true);
      // Any mix of active and inactive candidates must fit the pattern, not only "none" and
      // "all": condensing the contact line of a candidate d moves entries K(i, d) and K(d, j) of
      // every cell holding d — or holding a hanging DoF that hangs from d — to the DoFs of d's
      // line (its node's other components, the journal partner's components and their
      // masters). A free candidate's row in such a cell then couples to them too. Add these
      // couplings for every such cell explicitly.
      {
        std::map<types::global_dof_index, std::vector<types::global_dof_index>> line_dofs;
        for (const auto &cn : nodes_)
          if (cn.candidate)
            {
              std::vector<types::global_dof_index> v;
              for (unsigned int l = 0; l < dim; ++l)
                {
                  v.push_back(cn.dofs[l]);
                  for (const auto &p : cn.partners)
                    {
                      v.push_back(p.dofs[l]);
                      if (const auto *e = worst.get_constraint_entries(p.dofs[l]))
                        for (const auto &entry : *e)
                          v.push_back(entry.first);
                    }
                }
              for (unsigned int l = 0; l < dim; ++l)
                if (l == cn.constrained_component || friction_)
                  {
                    auto &target = line_dofs[cn.dofs[l]];
                    target.insert(target.end(), v.begin(), v.end());
                  }
            }
        std::vector<types::global_dof_index> cell_dofs(fe_->n_dofs_per_cell());
        for (const auto &cell : dof_handler_.active_cell_iterators())
          if (cell->is_locally_owned() || cell->is_ghost())
            {
              cell->get_dof_indices(cell_dofs);
              std::vector<types::global_dof_index> ps;
              auto collect = [&](const types::global_dof_index d) {
                const auto it = line_dofs.find(d);
                if (it != line_dofs.end())
                  ps.insert(ps.end(), it->second.begin(), it->second.end());
              };
              for (const auto d : cell_dofs)
                {
                  collect(d);
                  if (const auto *e = fixed_constraints_.get_constraint_entries(d))
                    for (const auto &entry : *e)
                      collect(entry.first);
                }
              if (ps.empty())
                continue;
              std::vector<types::global_dof_index> all = cell_dofs;
              all.insert(all.end(), ps.begin(), ps.end());
              std::sort(all.begin(), all.end());
              all.erase(std::unique(all.begin(), all.end()), all.end());
              for (const auto i : all)
                if (relevant_.is_element(i))
                  for (const auto j : all)
                    dsp.add(i, j);
            }
      }
      SparsityTools::distribute_sparsity_pattern(dsp, owned_, comm_, relevant_);
      K_.reinit(owned_, owned_, dsp, comm_);
      A_static_.reinit(owned_, owned_, dsp, comm_);
      A_.reinit(owned_, owned_, dsp, comm_);

      solution_owned_.reinit(owned_, comm_);
      rhs_.reinit(owned_, comm_);
      rhs_static_unit_.reinit(owned_, comm_);
      residual_owned_.reinit(owned_, comm_);
      solution_.reinit(owned_, relevant_, comm_);
      residual_.reinit(owned_, relevant_, comm_);

      const auto n_dofs = dof_handler_.n_dofs();
      switch (scene_.solver.linear)
        {
          case LinearSolver::direct: use_direct_ = true; break;
          case LinearSolver::cg_amg: use_direct_ = false; break;
          case LinearSolver::automatic:
            use_direct_ = n_dofs < scene_.solver.direct_below_dofs;
            break;
        }
    }

    void ContactModel::find_contact_nodes()
    {
      std::map<types::global_dof_index, Point<dim>> support;
      DoFTools::map_dofs_to_support_points(*mapping_, dof_handler_, support);

      // Candidates: surface nodes that could touch within the push (gap at δ_max below the
      // push itself, with a factor 2 margin). After every solve all surface nodes are checked
      // for penetration, so a window that was too small is an error, not a silent miss.
      const double window_gap = 2.0 * scene_.loading.delta_max;
      std::map<types::global_dof_index, ContactNode> by_x_dof;
      std::vector<types::global_dof_index> face_dofs(fe_->n_dofs_per_face());

      // Two bodies: the journal's surface nodes, keyed by (φ, z) — they lie on the same rays as
      // the bearing's (RayChart), so pairing is an exact lookup.
      auto key_of = [](const Point<dim> &p) {
        return std::make_pair(std::lround(std::atan2(p[0], -p[1]) / 1e-9),
                              std::lround(p[2] / 1e-11));
      };
      // Every rank gets every journal surface node (a few thousand): with several ranks the
      // journal cell facing a bearing node is often neither owned nor a ghost, so the owner of
      // each journal node contributes it (DoFs, position, whether its y-DoF is driven).
      struct JournalNode
      {
        std::array<types::global_dof_index, dim> dofs;
        Point<dim> X;
        bool driven_y = false;
      };
      std::map<std::pair<long, long>, JournalNode> journal_nodes;
      const bool mortar = two_body_ && scene_.study != Study::radial &&
                          scene_.study != Study::misalignment;
      if (two_body_ && !mortar)
        {
          std::vector<double> mine;  // per node: key φ, key z, 3 DoFs, X, driven flag
          std::set<types::global_dof_index> seen;
          for (const auto &cell : dof_handler_.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const auto f : cell->face_indices())
                if (cell->face(f)->at_boundary() &&
                    cell->face(f)->boundary_id() == bid_journal_surface)
                  for (const auto &dofs : face_node_dofs(cell, f, face_dofs))
                    if (owned_.is_element(dofs[0]) && seen.insert(dofs[0]).second)
                      {
                        const Point<dim> &X = support.at(dofs[0]);
                        const auto key = key_of(X);
                        mine.insert(mine.end(), {double(key.first), double(key.second),
                                                 double(dofs[0]), double(dofs[1]),
                                                 double(dofs[2]), X[0], X[1], X[2],
                                                 std::binary_search(loaded_sorted_.begin(),
                                                                    loaded_sorted_.end(),
                                                                    dofs[1]) ? 1.0 : 0.0});
                      }
          for (const auto &part : Utilities::MPI::all_gather(comm_, mine))
            for (std::size_t i = 0; i + 9 <= part.size(); i += 9)
              {
                JournalNode jn;
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    jn.dofs[c] = static_cast<types::global_dof_index>(part[i + 2 + c]);
                    jn.X[c] = part[i + 5 + c];
                  }
                jn.driven_y = part[i + 8] != 0.0;
                journal_nodes[{std::lround(part[i]), std::lround(part[i + 1])}] = jn;
              }
        }
      if (mortar)
        find_mortar_contact_nodes(support, by_x_dof);
      else
      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_contact)
              {
                for (const auto &dofs : face_node_dofs(cell, f, face_dofs))
                  {
                    if (by_x_dof.count(dofs[0]))
                      continue;
                    ContactNode cn;
                    cn.dofs = dofs;
                    cn.X = support.at(dofs[0]);
                    double g0;
                    Tensor<1, dim> n;
                    if (!obstacle_.gap(cn.X, scene_.loading.delta_max, g0, n))
                      continue;
                    cn.owned = owned_.is_element(dofs[0]);
                    if (g0 > window_gap)
                      {
                        cn.candidate = false;  // watched only
                        by_x_dof.emplace(dofs[0], cn);
                        continue;
                      }
                    // the dominant normal component not already constrained
                    std::array<unsigned int, dim> order = {0, 1, 2};
                    std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
                      return std::abs(n[a]) > std::abs(n[b]);
                    });
                    bool found = false;
                    for (const unsigned int c : order)
                      if (std::abs(n[c]) > 0.3 && !fixed_constraints_.is_constrained(dofs[c]))
                        {
                          cn.constrained_component = c;
                          found = true;
                          break;
                        }
                    // Hanging or supported nodes are skipped: they follow their masters.
                    if (!found)
                      continue;
                    if (two_body_)
                      {
                        const auto it = journal_nodes.find(key_of(cn.X));
                        if (it == journal_nodes.end())
                          throw NumericalError(
                            "fe_stage: no journal node faces the bearing node at (" +
                            format_value(cn.X[0]) + ", " + format_value(cn.X[1]) + ", " +
                            format_value(cn.X[2]) + ") m: the contact meshes do not match");
                        cn.two_body = true;
                        cn.partners = {{it->second.dofs, 1.0, it->second.driven_y}};
                        const Point<dim> &XJ = it->second.X;
                        const double rB = std::hypot(cn.X[0], cn.X[1]);
                        cn.n = Tensor<1, dim>({cn.X[0] / rB, cn.X[1] / rB, 0.0});
                        cn.g0 = rB - std::hypot(XJ[0], XJ[1]);  // along the common ray
                      }
                    by_x_dof.emplace(dofs[0], cn);
                  }
              }
      nodes_.clear();
      for (auto &[d, cn] : by_x_dof)
        nodes_.push_back(cn);

      // Partner DoFs this rank does not see yet become ghosts (solution values, constraint
      // lines), and then the masters of partners that hang (a journal face refined on one
      // side): closed lines have no chains, so two rounds suffice. After each round the fixed
      // constraints are rebuilt on the enlarged set and made consistent across ranks.
      if (two_body_ && n_ranks_ > 1)
        {
          auto add_ghosts = [&](const auto &dofs_of_partner) {
            IndexSet extra(dof_handler_.n_dofs());
            for (const auto &cn : nodes_)
              for (const auto &partner : cn.partners)
                for (const auto p : partner.dofs)
                  for (const auto d : dofs_of_partner(p))
                    if (!relevant_.is_element(d))
                      extra.add_index(d);
            extra.compress();
            if (Utilities::MPI::max(extra.n_elements(), comm_) == 0)
              return;  // collective: every rank takes the same branch
            relevant_.add_indices(extra);
            relevant_.compress();
            build_fixed_constraints();
          };
          add_ghosts([](const types::global_dof_index p) {
            return std::vector<types::global_dof_index>{p};
          });
          add_ghosts([&](const types::global_dof_index p) {
            std::vector<types::global_dof_index> masters;
            if (const auto *e = fixed_constraints_.get_constraint_entries(p))
              for (const auto &entry : *e)
                masters.push_back(entry.first);
            return masters;
          });
        }

      // Cells that hold a candidate DoF, or a hanging DoF that hangs from one: their condensed
      // contributions change with the active set (a hanging node's share moves on through the
      // contact line of its master); all other cells go into A_static once.
      IndexSet candidate_dofs(dof_handler_.n_dofs());
      for (const auto &cn : nodes_)
        if (cn.candidate)
          for (const auto d : cn.dofs)
            candidate_dofs.add_index(d);
      candidate_dofs.compress();
      IndexSet hanging_on_candidates(dof_handler_.n_dofs());
      for (const auto &line : fixed_constraints_.get_lines())
        for (const auto &entry : line.entries)
          if (candidate_dofs.is_element(entry.first))
            {
              hanging_on_candidates.add_index(line.index);
              break;
            }
      candidate_dofs.add_indices(hanging_on_candidates);
      candidate_dofs.compress();
      contact_cell_of_.assign(tria_.n_active_cells(), -1);
      std::vector<types::global_dof_index> cell_dofs(fe_->n_dofs_per_cell());
      unsigned int n = 0;
      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(cell_dofs);
            for (const auto d : cell_dofs)
              if (candidate_dofs.is_element(d))
                {
                  contact_cell_of_[cell->active_cell_index()] = n++;
                  break;
                }
          }
      contact_cell_matrices_.resize(n);
      contact_cell_dofs_.resize(n);
    }

    /// Two non-matching bodies (the verification block and a deformable indenter): dual mortar
    /// (mortar.h). Each slave node of the block's top face (the plane y = 0, normal −e_y into
    /// the block) gets ĝ = g̃0 + n·(u − Σ_m C_sm u_m) with the weighted gap g̃0 and the mortar
    /// coefficients C_sm of the indenter's bottom nodes; an active node's constraint is then the
    /// same kind of line as node-to-node contact, with several partners.
    void ContactModel::find_mortar_contact_nodes(
      const std::map<types::global_dof_index, Point<dim>> &support,
      std::map<types::global_dof_index, ContactNode> &by_x_dof)
    {
      std::vector<types::global_dof_index> face_dofs(fe_->n_dofs_per_face());
      using NodeDofs = std::array<types::global_dof_index, dim>;
      // Master faces from every rank (the face facing a slave node is often on no cell this
      // rank sees): per face its node count, then per node 3 DoFs and the position.
      std::vector<double> mine;
      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == bid_indenter_surface)
              {
                const auto nodes = face_node_dofs(cell, f, face_dofs);
                mine.push_back(double(nodes.size()));
                for (const auto &d : nodes)
                  {
                    const Point<dim> &X = support.at(d[0]);
                    mine.insert(mine.end(), {double(d[0]), double(d[1]), double(d[2]), X[0],
                                             X[1], X[2]});
                  }
              }
      std::vector<mortar::Face> master;
      std::map<long, NodeDofs> master_dofs;
      for (const auto &part : Utilities::MPI::all_gather(comm_, mine))
        for (std::size_t i = 0; i < part.size();)
          {
            const unsigned int nn = static_cast<unsigned int>(part[i++]);
            mortar::Face face;
            for (unsigned int k = 0; k < nn; ++k, i += 6)
              {
                NodeDofs d;
                for (unsigned int c = 0; c < dim; ++c)
                  d[c] = static_cast<types::global_dof_index>(part[i + c]);
                face.nodes.push_back(static_cast<long>(d[0]));
                face.X.push_back({part[i + 3], part[i + 4], part[i + 5]});
                master_dofs[static_cast<long>(d[0])] = d;
              }
            master.push_back(std::move(face));
          }
      // Slave faces: this rank's owned and ghost cells (every cell holding a DoF of an owned
      // cell is among them, so owned and ghost nodes of owned cells see all their faces).
      std::vector<mortar::Face> slave;
      std::map<long, NodeDofs> slave_dofs;
      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_contact)
              {
                mortar::Face face;
                for (const auto &d : face_node_dofs(cell, f, face_dofs))
                  {
                    const Point<dim> &X = support.at(d[0]);
                    face.nodes.push_back(static_cast<long>(d[0]));
                    face.X.push_back({X[0], X[1], X[2]});
                    slave_dofs[static_cast<long>(d[0])] = d;
                  }
                slave.push_back(std::move(face));
              }
      std::vector<mortar::SlaveNode> slave_nodes;
      for (const auto &[id, d] : slave_dofs)
        slave_nodes.push_back({id, {0.0, -1.0, 0.0}});
      mortar::Options options;
      // 8 × 3 Gauss points per direction of each slave face: the mortar integrals have kinks
      // where master faces end; their error (≈ 2e-3 of a master nodal force at 8 sub-intervals,
      // 8e-3 at 4, mortar_test) shows up as non-uniform pressure in the patch test.
      options.subdivisions = 8;
      // Quadrature points farther apart than this cannot close under a push of δ_max; their
      // nodes come out incomplete and are left out (they cannot touch).
      options.max_distance = 4.0 * scene_.loading.delta_max;
      const double window_gap = 2.0 * scene_.loading.delta_max;
      for (const auto &cp : mortar::couple(slave, slave_nodes, master, options))
        {
          const NodeDofs &dofs = slave_dofs.at(cp.node);
          if (!cp.complete || cp.weight <= 0.0 || fixed_constraints_.is_constrained(dofs[1]))
            continue;  // out of reach, or hanging (it follows its masters)
          ContactNode cn;
          cn.dofs = dofs;
          cn.X = support.at(dofs[0]);
          cn.owned = owned_.is_element(dofs[0]);
          cn.n = Tensor<1, dim>({0.0, -1.0, 0.0});
          cn.g0 = cp.gap;
          cn.two_body = true;
          cn.constrained_component = 1;
          cn.candidate = cp.gap <= window_gap;
          for (const auto &[m, w] : cp.masters)
            cn.partners.push_back({master_dofs.at(m), w, false});
          by_x_dof.emplace(dofs[0], cn);
        }
    }

    void ContactModel::assemble_static()
    {
      const unsigned int p = fe_->degree;
      const QGauss<dim> quadrature(p + 1);
      FEValues<dim> fe_values(*mapping_, *fe_, quadrature, update_gradients | update_JxW_values);
      const unsigned int n_dofs = fe_->n_dofs_per_cell();
      FullMatrix<double> cell_matrix(n_dofs, n_dofs);
      Vector<double> cell_rhs(n_dofs);
      std::vector<types::global_dof_index> dofs(n_dofs);
      const FEValuesExtractors::Vector u(0);
      std::vector<SymmetricTensor<2, dim>> eps(n_dofs);
      std::vector<double> div(n_dofs);

      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            cell_matrix = 0.0;
            for (const unsigned int q : fe_values.quadrature_point_indices())
              {
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    eps[i] = fe_values[u].symmetric_gradient(i, q);
                    div[i] = trace(eps[i]);
                  }
                const double JxW = fe_values.JxW(q);
                for (unsigned int i = 0; i < n_dofs; ++i)
                  for (unsigned int j = i; j < n_dofs; ++j)
                    cell_matrix(i, j) +=
                      (lame_lambda_ * div[i] * div[j] + 2.0 * lame_mu_ * (eps[i] * eps[j])) * JxW;
              }
            for (unsigned int i = 0; i < n_dofs; ++i)
              for (unsigned int j = 0; j < i; ++j)
                cell_matrix(i, j) = cell_matrix(j, i);
            cell->get_dof_indices(dofs);
            K_.add(dofs, cell_matrix);
            const int k = contact_cell_of_[cell->active_cell_index()];
            if (k >= 0)
              {
                contact_cell_matrices_[k] = cell_matrix;
                contact_cell_dofs_[k] = dofs;
              }
            else
              {
                cell_rhs = 0.0;
                fixed_constraints_.distribute_local_to_global(cell_matrix, cell_rhs, dofs,
                                                              A_static_, rhs_static_unit_);
              }
          }
      K_.compress(VectorOperation::add);
      A_static_.compress(VectorOperation::add);
      rhs_static_unit_.compress(VectorOperation::add);  // from the journal load at δ = 1
    }

    /// Nodal areas w_i = ∫ φ_i dA over the contact surface: the contact pressure of node i is
    /// λ_i / w_i (exact for a uniform pressure; Q2 face weights are all positive).
    void ContactModel::compute_nodal_weights()
    {
      const QGauss<dim - 1> fq(fe_->degree + 1);
      FEFaceValues<dim> fv(*mapping_, *fe_, fq, update_values | update_JxW_values);
      TrilinosWrappers::MPI::Vector w(owned_, comm_);
      std::vector<types::global_dof_index> dofs(fe_->n_dofs_per_cell());
      Vector<double> cell_w(fe_->n_dofs_per_cell());
      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_contact)
              {
                fv.reinit(cell, f);
                cell_w = 0.0;
                for (unsigned int i = 0; i < fe_->n_dofs_per_cell(); ++i)
                  for (const unsigned int q : fv.quadrature_point_indices())
                    cell_w(i) += fv.shape_value(i, q) * fv.JxW(q);
                cell->get_dof_indices(dofs);
                w.add(dofs, cell_w);
              }
      w.compress(VectorOperation::add);
      TrilinosWrappers::MPI::Vector wg(owned_, relevant_, comm_);
      wg = w;
      for (auto &cn : nodes_)
        cn.weight = wg[cn.dofs[0]];
    }

    void ContactModel::set_obstacle_position(const double delta)
    {
      for (auto &cn : nodes_)
        if (!cn.two_body)
          obstacle_.gap(cn.X, delta, cn.g0, cn.n);
    }

    /// The fixed constraints are linear in δ (supports and symmetry are homogeneous, the journal
    /// load is u_y = −δ, hanging nodes are linear): scale every inhomogeneity of the δ = 1 set.
    void ContactModel::set_fixed_constraints_for(const double delta)
    {
      fixed_delta_.clear();
      fixed_delta_.copy_from(fixed_constraints_);
      for (const auto &line : fixed_constraints_.get_lines())
        if (line.inhomogeneity != 0.0)
          fixed_delta_.set_inhomogeneity(line.index, delta * line.inhomogeneity);
    }

    // ------------------------------------------------------------------------------------------
    // Linear solver
    // ------------------------------------------------------------------------------------------

    void ContactModel::build_amg()
    {
      ScopedTimer timer(t_amg_);
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic = true;
      data.higher_order_elements = fe_->degree > 1;
      data.smoother_sweeps = 2;
      data.aggregation_threshold = 0.02;
      data.n_cycles = 1;
      data.w_cycle = false;
      Teuchos::ParameterList list;
      std::unique_ptr<Epetra_MultiVector> translation_modes;
      data.set_parameters(list, translation_modes, A_);

      // All six rigid-body modes (SPEC §5: with only the translations ML needs ~3x the
      // iterations). deal.II 9.4 passes only translations, so they go in through ML's list.
      std::map<types::global_dof_index, Point<dim>> support;
      DoFTools::map_dofs_to_support_points(*mapping_, dof_handler_, support);
      const Epetra_Map &map = A_.trilinos_matrix().DomainMap();
      null_space_ = std::make_unique<Epetra_MultiVector>(map, 6);
      std::vector<std::pair<types::global_dof_index, unsigned int>> comp(owned_.n_elements());
      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            std::vector<types::global_dof_index> dofs(fe_->n_dofs_per_cell());
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
              if (owned_.is_element(dofs[i]))
                {
                  const unsigned int local = owned_.index_within_set(dofs[i]);
                  const unsigned int c = fe_->system_to_component_index(i).first;
                  const Point<dim> &x = support.at(dofs[i]);
                  for (unsigned int m = 0; m < 6; ++m)
                    (*null_space_)[m][local] = 0.0;
                  (*null_space_)[c][local] = 1.0;
                  // rotations about x, y, z: ω × x
                  if (c == 0)
                    {
                      (*null_space_)[4][local] = x[2];
                      (*null_space_)[5][local] = -x[1];
                    }
                  else if (c == 1)
                    {
                      (*null_space_)[3][local] = -x[2];
                      (*null_space_)[5][local] = x[0];
                    }
                  else
                    {
                      (*null_space_)[3][local] = x[1];
                      (*null_space_)[4][local] = -x[0];
                    }
                }
          }
      list.set("null space: type", "pre-computed");
      list.set("null space: dimension", 6);
      list.set("null space: vectors", null_space_->Values());
      amg_ = std::make_unique<TrilinosWrappers::PreconditionAMG>();
      amg_->initialize(A_, list);
      amg_reference_iterations_ = 0;
    }

    unsigned int ContactModel::solve_linear(TrilinosWrappers::MPI::Vector &x,
                                            const TrilinosWrappers::MPI::Vector &b)
    {
      const double b_norm = b.l2_norm();
      if (!std::isfinite(b_norm))
        throw Failure{"non-finite right-hand side"};
      if (use_direct_)
        {
          SolverControl control(1, 0);
          TrilinosWrappers::SolverDirect::AdditionalData ad(false, "Amesos_Klu");
          TrilinosWrappers::SolverDirect direct(control, ad);
          try
            {
              direct.solve(A_, x, b);
            }
          catch (const std::exception &e)
            {
              throw Failure{std::string("direct solver (Amesos KLU) failed: ") + e.what()};
            }
          return 1;
        }
      if (b_norm == 0.0)
        {
          x = 0.0;
          return 0;
        }
      for (unsigned int attempt = 0; attempt < 2; ++attempt)
        {
          if (!amg_)
            build_amg();
          SolverControl control(scene_.solver.max_linear_iterations,
                                scene_.solver.tolerance * b_norm);
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
            control,  // right preconditioning: the tolerance applies to the true residual
            SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(100, true));
          try
            {
              if (nonsymmetric_)
                gmres.solve(A_, x, b, *amg_);
              else
                cg.solve(A_, x, b, *amg_);
            }
          catch (const SolverControl::NoConvergence &e)
            {
              if (attempt == 0)
                {
                  amg_.reset();  // the reused preconditioner may be stale: rebuild once
                  continue;
                }
              throw Failure{std::string(nonsymmetric_ ? "GMRES" : "CG") +
                            " did not converge in " + std::to_string(e.last_step) +
                            " iterations (residual " + format_value(e.last_residual) + ")"};
            }
          const unsigned int its = control.last_step();
          if (amg_reference_iterations_ == 0)
            amg_reference_iterations_ = std::max(1u, its);
          else if (its > 2 * amg_reference_iterations_ + 10)
            amg_.reset();  // reuse only while it stays effective; rebuilt at the next solve
          return its;
        }
      throw Failure{"linear solver failed"};
    }

    // ------------------------------------------------------------------------------------------
    // Contact: evaluation and active-set increments
    // ------------------------------------------------------------------------------------------

    /// λ_i = (K u)_i · n_i and ĝ_i = g0_i + n_i · u_i for every candidate node (ghosted values,
    /// so every rank evaluates the same numbers for the nodes it shares).
    /// A slipping node s carries the friction force μλ_s·e_s and its partners −w_p·μλ_s·e_s,
    /// with λ_s = n·(K u)_s its own normal contact force: rows (s,k) of the system get
    /// −μ e_k nᵀK_s and rows (p,k) +w_p μ e_k nᵀK_s (K_s: the rows of s's DoFs), cell by cell:
    /// the contact cell's matrix is extended by the partners' rows and condensed as a whole
    /// (so the constraints' inhomogeneities reach the right-hand side too). This makes A_
    /// non-symmetric (GMRES). Returns false if the cell holds no slipping node.
    bool ContactModel::friction_cell_matrix(const unsigned int k, FullMatrix<double> &M,
                                            std::vector<types::global_dof_index> &ext) const
    {
      const auto &dofs = contact_cell_dofs_[k];
      const auto &Kc = contact_cell_matrices_[k];
      ext = dofs;
      bool any = false;
      std::vector<std::pair<const ContactNode *, std::vector<double>>> rows_of;
      for (unsigned int i = 0; i < dofs.size(); ++i)
        {
          const auto it = slipping_.find(dofs[i]);
          if (it == slipping_.end())
            continue;
          const ContactNode &cn = nodes_[it->second];
          any = true;
          // n·(K_cell u) over this node's rows: one row over the cell's columns
          std::vector<double> row(dofs.size(), 0.0);
          for (unsigned int c = 0; c < dim; ++c)
            {
              const auto li = std::find(dofs.begin(), dofs.end(), cn.dofs[c]) - dofs.begin();
              for (unsigned int j = 0; j < dofs.size(); ++j)
                row[j] += cn.n[c] * Kc(li, j);
            }
          rows_of.emplace_back(&cn, std::move(row));
          for (const auto &p : cn.partners)
            for (const auto d : p.dofs)
              if (std::find(ext.begin(), ext.end(), d) == ext.end())
                ext.push_back(d);
        }
      if (!any)
        return false;
      M.reinit(ext.size(), ext.size());
      for (unsigned int i = 0; i < dofs.size(); ++i)
        for (unsigned int j = 0; j < dofs.size(); ++j)
          M(i, j) = Kc(i, j);
      const double mu = scene_.contact.mu;
      auto local = [&](const types::global_dof_index d) {
        return std::find(ext.begin(), ext.end(), d) - ext.begin();
      };
      for (const auto &[cn, row] : rows_of)
        for (unsigned int c = 0; c < dim; ++c)
          {
            const double f = mu * cn->slip_direction[c];
            const auto ls = local(cn->dofs[c]);
            for (unsigned int j = 0; j < dofs.size(); ++j)
              M(ls, j) -= f * row[j];
            for (const auto &p : cn->partners)
              {
                const auto lp = local(p.dofs[c]);
                for (unsigned int j = 0; j < dofs.size(); ++j)
                  M(lp, j) += p.weight * f * row[j];
              }
          }
      return true;
    }

    void ContactModel::evaluate_contact(const double delta)
    {
      K_.vmult(residual_owned_, solution_owned_);
      condense_hanging(residual_owned_);
      residual_ = residual_owned_;
      for (auto &cn : nodes_)
        {
          for (unsigned int c = 0; c < dim; ++c)
            {
              cn.traction[c] = residual_[cn.dofs[c]];
              cn.relative[c] = solution_[cn.dofs[c]];
              for (const auto &p : cn.partners)
                cn.relative[c] -= p.weight * solution_[p.dofs[c]];
            }
          if (!cn.two_body)
            cn.relative[1] += delta;  // a rigid obstacle moves by −δ e_y
          cn.lambda = cn.traction * cn.n;
          // ĝ = g0 + n·(u − u_partner); the rigid obstacle's motion is already in g0
          cn.gap = cn.g0 + cn.n * cn.relative - (cn.two_body ? 0.0 : delta * cn.n[1]);
        }
    }

    /// Moves the nodal forces K u of hanging DoFs to their masters (r_m += c_hm r_h, r_h = 0),
    /// as the condensed equations see them: a hanging node inside the contact zone passes its
    /// share of the contact force to the contact nodes it hangs from, and supports count the
    /// share of hanging support nodes. Without it the contact force misses those shares.
    void ContactModel::condense_hanging(TrilinosWrappers::MPI::Vector &r)
    {
      residual_ = r;  // ghosted copy: the hanging DoF's value on whichever rank owns its line
      TrilinosWrappers::MPI::Vector moved;
      moved.reinit(owned_, relevant_, comm_, true);  // writable: entries of masters elsewhere
      for (const auto &line : hanging_constraints_.get_lines())
        if (owned_.is_element(line.index))
          {
            const double rh = residual_[line.index];
            for (const auto &[m, c] : line.entries)
              moved[m] += c * rh;
            moved[line.index] -= rh;
          }
      moved.compress(VectorOperation::add);
      r += moved;
    }

    IncrementRecord ContactModel::solve_increment(const double delta)
    {
      IncrementRecord rec;
      rec.delta = delta;
      set_obstacle_position(delta);
      set_fixed_constraints_for(delta);
      const double c = scene_.contact.active_set_scale * scene_.material.E * h_min_;  // [N/m]
      // ε_g: a penetration below this is round-off, not contact (makes the active set
      // deterministic across rank counts). 1e-9 of the push is far below any physical effect.
      const double eps_g = 1e-9 * scene_.loading.delta_max;
      for (auto &cn : nodes_)
        cn.stick_slip_flips = cn.contact_flips = 0;
      double omega = 1.0;
      bool relaxation_history = false;

      unsigned int it = 0;
      for (; it < scene_.contact.max_iterations; ++it)
        {
          constraints_.clear();
          constraints_.reinit(relevant_);
          for (const auto &cn : nodes_)
            if (cn.active && friction_ && cn.stick)
              {
                // No new slip: u = Σ w·u_partner + P_t(r_conv + u_obstacle) − g0·n, with r_conv
                // the relative displacement of the last converged increment and P_t = I − n nᵀ
                // (the normal part is ĝ = 0). Components fixed by symmetry stay as they are.
                Tensor<1, dim> target = cn.relative_converged;
                if (!cn.two_body)
                  target[1] -= delta;
                target = tangential(target, cn.n) - cn.g0 * cn.n;  // (a rigid obstacle's g0 holds its motion already)
                for (unsigned int k = 0; k < dim; ++k)
                  if (!fixed_delta_.is_constrained(cn.dofs[k]))
                    {
                      constraints_.add_line(cn.dofs[k]);
                      for (const auto &p : cn.partners)
                        constraints_.add_entry(cn.dofs[k], p.dofs[k], p.weight);
                      constraints_.set_inhomogeneity(cn.dofs[k], target[k]);
                    }
              }
            else if (cn.active)
              {
                const unsigned int cc = cn.constrained_component;
                const auto d = cn.dofs[cc];
                constraints_.add_line(d);
                for (unsigned int k = 0; k < dim; ++k)
                  {
                    if (k != cc)
                      constraints_.add_entry(d, cn.dofs[k], -cn.n[k] / cn.n[cc]);
                    for (const auto &p : cn.partners)
                      constraints_.add_entry(d, p.dofs[k], p.weight * cn.n[k] / cn.n[cc]);
                  }
                constraints_.set_inhomogeneity(d, -cn.g0 / cn.n[cc]);
              }
          constraints_.merge(fixed_delta_, AffineConstraints<double>::left_object_wins, true);
          constraints_.close();

          std::unique_ptr<ScopedTimer> assemble_timer = std::make_unique<ScopedTimer>(t_assemble_);
          A_.copy_from(A_static_);
          rhs_ = 0.0;  // the static part δ·rhs_static_unit_ is added after compress(): adding
                       // into a vector whose last operation was an assignment is collective
          Vector<double> cell_rhs(fe_->n_dofs_per_cell());
          slipping_.clear();
          if (friction_)
            for (unsigned int i = 0; i < nodes_.size(); ++i)
              if (nodes_[i].candidate && nodes_[i].active && !nodes_[i].stick)
                slipping_[nodes_[i].dofs[0]] = i;
          nonsymmetric_ = Utilities::MPI::max(slipping_.empty() ? 0u : 1u, comm_) > 0;
          FullMatrix<double> friction_matrix;
          std::vector<types::global_dof_index> friction_dofs;
          for (unsigned int k = 0; k < contact_cell_matrices_.size(); ++k)
            if (friction_ && friction_cell_matrix(k, friction_matrix, friction_dofs))
              {
                Vector<double> zero(friction_dofs.size());
                constraints_.distribute_local_to_global(friction_matrix, zero, friction_dofs, A_,
                                                        rhs_);
              }
            else
              {
                cell_rhs = 0.0;
                constraints_.distribute_local_to_global(contact_cell_matrices_[k], cell_rhs,
                                                        contact_cell_dofs_[k], A_, rhs_);
              }
          A_.compress(VectorOperation::add);
          rhs_.compress(VectorOperation::add);
          rhs_.add(delta, rhs_static_unit_);
          assemble_timer.reset();

          constraints_.set_zero(solution_owned_);  // start from the previous solution
          {
            ScopedTimer timer(t_solve_);
            rec.linear_iterations += solve_linear(solution_owned_, rhs_);
          }
          ScopedTimer eval_timer(t_evaluate_);
          constraints_.distribute(solution_owned_);
          solution_ = solution_owned_;
          evaluate_contact(delta);

          // Normal: active where λ − c·ĝ > 0. Friction (the same semi-smooth complementarity,
          // Hüeber–Stadler–Wohlmuth): with t_T the tangential contact force and Δs_T the slip in
          // this increment, z = t_T − c·Δs_T; stick where |z| ≤ μ(λ − c·ĝ), else slip in the
          // direction e = z/|z| (the friction force μλ·e of the next solve; iterated until the
          // sets settle and no direction changes by more than 1e-5).
          unsigned int n_changed = 0;
          double max_direction_change = 0.0;
          double relax_num = 0.0, relax_den = 0.0;  // Σ r_old·(r − r_old), Σ |r − r_old|²
          std::vector<Tensor<1, dim>> direction_target(nodes_.size());
          for (unsigned int i = 0; i < nodes_.size(); ++i)
            {
              auto &cn = nodes_[i];
              if (!cn.candidate)
                continue;
              const double lambda_trial = cn.lambda - c * cn.gap;
              bool now = lambda_trial > c * eps_g;
              // With friction a node at the edge of the contact zone can cycle: active it pulls
              // (λ < 0, a fraction of a percent of the largest nodal force), released it
              // penetrates by ~1e-4 δ_max. After two flips it stays active (exact
              // non-penetration; the small pull stays in the force). Frictionless contact
              // does not cycle and is left as it is.
              if (friction_ && cn.candidate && now != cn.active && ++cn.contact_flips > 2)
                now = true;
              bool stick = cn.stick;
              if (friction_ && now)
                {
                  // (c ×0.01 … ×100 here converged slower or not at all)
                  const Tensor<1, dim> z =
                    tangential(cn.traction, cn.n) -
                    c * tangential(cn.relative - cn.relative_converged, cn.n);
                  const double bound = scene_.contact.mu * lambda_trial;
                  stick = z.norm() <= bound + c * eps_g;
                  // A node on the stick/slip boundary (|t_T| = μλ with no slip) can flip
                  // between the two every iteration; after two flips it stays slipping with
                  // its direction frozen: its force is μλ (Coulomb's bound) and its slip in
                  // this increment ~0 — both states' answer — and a direction that follows a
                  // ~0 slip would only oscillate.
                  if (cn.active && stick != cn.stick && ++cn.stick_slip_flips > 2)
                    stick = false;
                  const bool frozen = cn.stick_slip_flips > 2 && cn.active && !cn.stick;
                  if (!stick && !frozen)
                    {
                      const Tensor<1, dim> e = z / z.norm();
                      if (cn.active && !cn.stick)
                        {
                          direction_target[i] = e;
                          const Tensor<1, dim> r = e - cn.slip_direction;
                          if (cn.owned)
                            {
                              max_direction_change = std::max(max_direction_change, r.norm());
                              const Tensor<1, dim> d = r - cn.direction_update;
                              relax_num += cn.direction_update * d;
                              relax_den += d * d;
                            }
                        }
                      else
                        {
                          cn.slip_direction = e;  // starts slipping: no history
                          cn.direction_update = Tensor<1, dim>();
                        }
                    }
                }
              if (cn.owned && (now != cn.active || (friction_ && now && stick != cn.stick)))
                ++n_changed;
              cn.active = now;
              cn.stick = stick;
            }
          n_changed = Utilities::MPI::sum(n_changed, comm_);
          if (friction_)
            {
              // The slip directions converge linearly (ratio ≈ 0.45 on the radial study):
              // relax their update e ← e + ω (e_target − e), ω from the last two updates
              // (Irons–Tuck), kept in [0.1, 4] and restarted at 1 when the sets change.
              relax_num = Utilities::MPI::sum(relax_num, comm_);
              relax_den = Utilities::MPI::sum(relax_den, comm_);
              if (n_changed != 0 || !relaxation_history || relax_den <= 0.0)
                omega = 1.0;
              else
                omega = std::clamp(-omega * relax_num / relax_den, 0.1, 4.0);
              relaxation_history = n_changed == 0;
              for (unsigned int i = 0; i < nodes_.size(); ++i)
                if (direction_target[i].norm() > 0.0)
                  {
                    auto &cn = nodes_[i];
                    const Tensor<1, dim> r = direction_target[i] - cn.slip_direction;
                    const Tensor<1, dim> e = tangential(cn.slip_direction + omega * r, cn.n);
                    cn.slip_direction = e / e.norm();
                    cn.direction_update = r;
                  }
            }
          // slip directions settled: the friction forces are μλ·e to 1e-5 of μλ (~1e-7 of F,
          // friction being ~0.5 % of it)
          const bool forces_settled = Utilities::MPI::max(max_direction_change, comm_) <= 1e-5;
          if (n_changed == 0 && forces_settled)
            {
              ++it;
              break;
            }
          if (it + 1 == scene_.contact.max_iterations)
            throw Failure{"active set did not settle in " + std::to_string(it + 1) +
                          " iterations (" + std::to_string(n_changed) + " nodes still changing" +
                          (forces_settled ? "" : ", slip forces still changing") + ")"};
        }
      rec.contact_iterations = it;

      // Forces and checks.
      double f_contact = 0.0, max_pen = 0.0;
      double p_min = std::numeric_limits<double>::max(), p_max = -p_min;
      unsigned int n_act = 0, n_slip = 0;
      // the y-force a node's contact passes on: normal only, or with its friction force
      auto contact_force_y = [&](const ContactNode &cn) {
        return friction_ ? cn.traction[1] : cn.lambda * cn.n[1];
      };
      for (const auto &cn : nodes_)
        if (cn.owned)
          {
            max_pen = std::max(max_pen, -cn.gap);
            if (cn.active)
              {
                ++n_act;
                if (friction_ && !cn.stick)
                  ++n_slip;
                f_contact -= contact_force_y(cn);
                if (cn.weight > 0.0)
                  {
                    p_min = std::min(p_min, cn.lambda / cn.weight);
                    p_max = std::max(p_max, cn.lambda / cn.weight);
                  }
              }
          }
      double f_support = 0.0, f_load = 0.0;
      for (const auto d : support_y_dofs_)
        f_support += residual_owned_[d];
      for (const auto d : loaded_y_dofs_)
        f_load -= residual_owned_[d];
      // Where a contact partner's y-DoF is itself driven (the journal's rim on its end face),
      // the contact force reaches that DoF through the constraint, not through K u: add it.
      for (const auto &cn : nodes_)
        if (cn.active && cn.owned)
          for (const auto &p : cn.partners)
            if (p.driven_y)
              f_load -= p.weight * contact_force_y(cn);
      rec.force_load = two_body_ ? symmetry_factor_ * Utilities::MPI::sum(f_load, comm_) :
                                   symmetry_factor_ * Utilities::MPI::sum(f_contact, comm_);
      rec.force = symmetry_factor_ * Utilities::MPI::sum(f_contact, comm_);
      rec.force_support = symmetry_factor_ * Utilities::MPI::sum(f_support, comm_);
      rec.n_active = Utilities::MPI::sum(n_act, comm_);
      rec.n_slip = Utilities::MPI::sum(n_slip, comm_);
      rec.max_penetration = Utilities::MPI::max(max_pen, comm_);
      rec.pressure_min = Utilities::MPI::min(p_min, comm_);
      rec.pressure_max = Utilities::MPI::max(p_max, comm_);
      if (!std::isfinite(rec.force) || !std::isfinite(rec.force_support))
        throw Failure{"non-finite contact force"};
      // A pushed joint must touch somewhere: no active node means the journal slipped between
      // the contact nodes (a rim patch smaller than the cells), and F = 0 would be a wrong answer.
      if (rec.n_active == 0 && scene_.study != Study::patch && scene_.study != Study::hertz)
        throw Failure{"no contact node touches the journal at delta = " + format_value(delta) +
                      " m: the mesh is too coarse where the journal touches (raise "
                      "mesh.contact_refinements or mesh.global_refinements)"};
      // Watched (non-candidate) nodes must not penetrate: if one does, the candidate window was
      // too small and the result would be wrong, so the run stops instead.
      if (rec.max_penetration > 1e-6 * scene_.loading.delta_max)
        throw Failure{"penetration " + format_value(rec.max_penetration) +
                      " m at a contact-surface node (candidate window too small)"};
      return rec;
    }

    void ContactModel::write_fields(const unsigned int counter, const double delta)
    {
      const std::string dir = options_.output_dir + "/fields";
      // contact fields at the nodes, in the x/y/z slots of a system vector
      TrilinosWrappers::MPI::Vector cf_owned(owned_, comm_), ff_owned(owned_, comm_);
      for (const auto &cn : nodes_)
        if (cn.owned)
          {
            cf_owned[cn.dofs[0]] = cn.active && cn.weight > 0.0 ? cn.lambda / cn.weight : 0.0;
            cf_owned[cn.dofs[1]] = cn.gap;
            cf_owned[cn.dofs[2]] = cn.active ? 1.0 : 0.0;
            // friction: status 0 open, 1 stick, 2 slip; shear stress |t_T|/w; tangential
            // relative displacement of the node against the other body since the start
            const double shear = tangential(cn.traction, cn.n).norm();
            ff_owned[cn.dofs[0]] = !cn.active ? 0.0 : (friction_ && !cn.stick ? 2.0 : 1.0);
            ff_owned[cn.dofs[1]] = cn.active && cn.weight > 0.0 ? shear / cn.weight : 0.0;
            ff_owned[cn.dofs[2]] = tangential(cn.relative, cn.n).norm();
          }
      cf_owned.compress(VectorOperation::insert);
      ff_owned.compress(VectorOperation::insert);
      TrilinosWrappers::MPI::Vector cf(owned_, relevant_, comm_), ff(owned_, relevant_, comm_);
      cf = cf_owned;
      ff = ff_owned;

      StressPostprocessor post(lame_lambda_, lame_mu_);
      DataOut<dim> out;
      out.attach_dof_handler(dof_handler_);
      std::vector<DataComponentInterpretation::DataComponentInterpretation> vec(
        dim, DataComponentInterpretation::component_is_part_of_vector);
      out.add_data_vector(solution_, std::vector<std::string>(dim, "displacement"),
                          DataOut<dim>::type_dof_data, vec);
      out.add_data_vector(solution_, post);
      std::vector<DataComponentInterpretation::DataComponentInterpretation> sc(
        dim, DataComponentInterpretation::component_is_scalar);
      out.add_data_vector(cf, std::vector<std::string>{"contact_pressure", "contact_gap",
                                                       "contact_active"},
                          DataOut<dim>::type_dof_data, sc);
      out.add_data_vector(ff, std::vector<std::string>{"contact_status", "contact_shear",
                                                       "contact_slip"},
                          DataOut<dim>::type_dof_data, sc);
      Vector<float> subdomain(tria_.n_active_cells());
      for (auto &s : subdomain)
        s = static_cast<float>(tria_.locally_owned_subdomain());
      out.add_data_vector(subdomain, "subdomain");
      out.build_patches(*mapping_, fe_->degree, DataOut<dim>::curved_inner_cells);
      const std::string pvtu =
        out.write_vtu_with_pvtu_record(dir + "/", "solution", counter, comm_, 4, 0);
      if (rank_ == 0)
        {
          pvd_records_.emplace_back(delta, pvtu);
          const std::string pvd = dir + "/solution.pvd";
          std::ofstream f(pvd + ".tmp");
          DataOutBase::write_pvd_record(f, pvd_records_);
          f.close();
          std::filesystem::rename(pvd + ".tmp", pvd);
          field_files_.push_back(dir + "/" + pvtu);
        }
    }

    RunResult ContactModel::run()
    {
      RunResult result;
      result.n_ranks = n_ranks_;
      make_grid();
      setup_system();
      find_contact_nodes();
      make_matrices();
      assemble_static();
      compute_nodal_weights();
      result.n_dofs = dof_handler_.n_dofs();
      result.n_cells = tria_.n_global_active_cells();
      result.symmetry_factor = symmetry_factor_;
      result.h_min = h_min_;
      auto seconds = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      };
      result.setup_time = seconds();
      const bool fields = options_.write_fields && !options_.output_dir.empty();
      if (fields && rank_ == 0)
        std::filesystem::create_directories(options_.output_dir + "/fields");
      const unsigned int n_candidates = Utilities::MPI::sum(
        (unsigned int)std::count_if(nodes_.begin(), nodes_.end(),
                                    [](const ContactNode &c) { return c.owned && c.candidate; }),
        comm_);  // collective: outside the rank-0 branch
      if (rank_ == 0)
        log::info("fe_stage: " + std::to_string(result.n_cells) + " cells, " +
                  std::to_string(result.n_dofs) + " DoFs, " + std::to_string(n_candidates) +
                  " contact candidate nodes, " + std::to_string(contact_cell_matrices_.size()) +
                  " contact cells (rank 0), " + (use_direct_ ? "direct" : "CG+AMG") +
                  " solver, setup " + log::format_duration(result.setup_time));

      const auto &L = scene_.loading;
      const double step0 = L.delta_max / L.n_increments;
      solution_owned_ = 0.0;
      solution_ = 0.0;
      if (fields)
        {
          set_obstacle_position(0.0);
          evaluate_contact(0.0);
          write_fields(0, 0.0);
        }
      std::unique_ptr<log::Progress> progress;
      if (rank_ == 0)
        progress = std::make_unique<log::Progress>("fe_stage increments", L.delta_max * 1e6, "um");
      double delta_done = 0.0, delta_previous = 0.0;
      bool have_previous = false;
      TrilinosWrappers::MPI::Vector solution_previous(owned_, comm_);
      for (unsigned int inc = 1; inc <= L.n_increments; ++inc)
        {
          const double target = (inc == L.n_increments) ? L.delta_max : inc * step0;
          double step = target - delta_done;
          unsigned int cuts = 0;
          IncrementRecord rec;
          unsigned int total_contact_its = 0, total_linear_its = 0;
          while (delta_done < target)
            {
              const double try_delta = std::min(target, delta_done + step);
              // keep what converged so far, to restore after a failed attempt
              const TrilinosWrappers::MPI::Vector saved = solution_owned_;
              const std::vector<ContactNode> saved_nodes = nodes_;  // active set, friction
              try
                {
                  // Predictor: extrapolate the displacement linearly in δ from the last two
                  // converged states and start with every node the prediction penetrates
                  // activated (the active set then mostly settles in one or two iterations).
                  if (have_previous && delta_done > delta_previous)
                    {
                      const double ratio = (try_delta - delta_done) / (delta_done - delta_previous);
                      solution_owned_.sadd(1.0 + ratio, -ratio, solution_previous);
                      solution_ = solution_owned_;
                      set_obstacle_position(try_delta);
                      evaluate_contact(try_delta);
                      const double eps_g = 1e-9 * L.delta_max;
                      for (auto &cn : nodes_)
                        if (cn.candidate && cn.gap < -eps_g)
                          cn.active = true;
                    }
                  rec = solve_increment(try_delta);
                  for (auto &cn : nodes_)
                    cn.relative_converged = cn.relative;  // friction: slip counts from here
                  solution_previous = saved;
                  delta_previous = delta_done;
                  have_previous = true;
                  total_contact_its += rec.contact_iterations;
                  total_linear_its += rec.linear_iterations;
                  delta_done = try_delta;
                }
              catch (const Failure &f)
                {
                  solution_owned_ = saved;
                  solution_ = solution_owned_;
                  nodes_ = saved_nodes;
                  if (cuts >= L.max_cuts)
                    {
                      result.message = "increment " + std::to_string(inc) + " to delta = " +
                                       format_value(try_delta) + " m failed after " +
                                       std::to_string(cuts) + " cuts: " + f.reason;
                      if (rank_ == 0)
                        log::error("fe_stage: " + result.message);
                      result.wall_time = seconds();
                      result.field_files = field_files_;
                      return result;
                    }
                  ++cuts;
                  step *= 0.5;
                  if (rank_ == 0)
                    log::warning("fe_stage: increment " + std::to_string(inc) + " to delta = " +
                                 format_value(try_delta) + " m failed (" + f.reason +
                                 "); retrying with step " + format_value(step) + " m");
                }
            }
          rec.contact_iterations = total_contact_its;
          rec.linear_iterations = total_linear_its;
          rec.wall_time = seconds();
          result.increments.push_back(rec);
          if (options_.on_increment)
            options_.on_increment(rec);
          if (fields)
            write_fields(inc, target);
          if (progress)
            progress->update(target * 1e6);
        }
      result.complete = true;
      result.wall_time = seconds();
      if (rank_ == 0)
        log::info("fe_stage: time in contact assembly " + log::format_duration(t_assemble_) +
                  ", linear solves " + log::format_duration(t_solve_) + " (of which AMG setup " +
                  log::format_duration(t_amg_) + "), contact evaluation " +
                  log::format_duration(t_evaluate_));
      result.field_files = field_files_;
      if (rank_ == 0 && fields)
        result.field_files.push_back(options_.output_dir + "/fields/solution.pvd");
      return result;
    }
  } // namespace

  RunResult run_scene(const FeScene &scene, const RunOptions &options)
  {
    ContactModel model(scene, options);
    return model.run();
  }

  std::shared_ptr<void> make_runtime(int &argc, char **&argv)
  {
    return std::make_shared<Utilities::MPI::MPI_InitFinalize>(argc, argv, 1);
  }

  std::vector<std::pair<std::string, std::string>> fe_library_versions()
  {
    return {{"deal.II", DEAL_II_PACKAGE_VERSION},
            {"deal.II git", DEAL_II_GIT_SHORTREV},
            {"Trilinos", std::to_string(DEAL_II_TRILINOS_VERSION_MAJOR) + "." +
                           std::to_string(DEAL_II_TRILINOS_VERSION_MINOR) + "." +
                           std::to_string(DEAL_II_TRILINOS_VERSION_SUBMINOR)}};
  }
} // namespace clearjoint::fe
