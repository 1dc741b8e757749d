// Dual-mortar pairing of non-matching surfaces (mortar.h): the verification block and its
// deformable indenter, and the joint's bore and deformable journal (contact.pairing: mortar).
#include "fe_stage/contact/contact_pairing.h"
#include "fe_stage/contact/mortar.h"
#include "fe_stage/core/face_dofs.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace clearjoint::fe::detail
{
  namespace
  {
    using NodeDofs = std::array<types::global_dof_index, dim>;

    /// The master surface as every rank sees it: its faces (nodes by x-DoF, at the positions
    /// searched), and per node its DoFs, whether its y-DoF is driven by the load (the
    /// journal's rim under end-face loading), its displacement (0 in the reference search)
    /// and where it was meshed.
    struct MasterSurface
    {
      std::vector<mortar::Face> faces;
      std::map<long, std::pair<NodeDofs, bool>> dofs;
      std::map<long, Tensor<1, dim>> u;
      std::map<long, Point<dim>> X;
    };

    /// Master faces from every rank (the face facing a slave node is often on no cell this
    /// rank sees): per face its node count, then per node 3 DoFs, the position searched
    /// (position(dofs)), the driven flag, its displacement and its mesh position.
    template <typename Position>
    MasterSurface gather_master_surface(
      const DofSpace &dofs, const std::map<types::global_dof_index, Point<dim>> &support,
      const types::boundary_id master_id, const TrilinosWrappers::MPI::Vector *u,
      const Position &position, MPI_Comm comm)
    {
      std::vector<types::global_dof_index> face_dofs(dofs.fe().n_dofs_per_face());
      std::vector<double> mine;
      for (const auto &cell : dofs.handler().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == master_id)
              {
                const auto nodes = face_node_dofs(cell, f, face_dofs);
                mine.push_back(double(nodes.size()));
                for (const auto &d : nodes)
                  {
                    const Point<dim> x = position(d);
                    const Point<dim> &X = support.at(d[0]);
                    const bool driven = dofs.is_loaded_y_dof(d[1]);
                    mine.insert(mine.end(), {double(d[0]), double(d[1]), double(d[2]), x[0], x[1],
                                             x[2], driven ? 1.0 : 0.0});
                    for (unsigned int c = 0; c < dim; ++c)
                      mine.push_back(u ? (*u)[d[c]] : 0.0);
                    mine.insert(mine.end(), {X[0], X[1], X[2]});
                  }
              }
      MasterSurface m;
      for (const auto &part : Utilities::MPI::all_gather(comm, mine))
        for (std::size_t i = 0; i < part.size();)
          {
            const unsigned int nn = static_cast<unsigned int>(part[i++]);
            mortar::Face face;
            for (unsigned int k = 0; k < nn; ++k, i += 13)
              {
                m.X[static_cast<long>(part[i])] =
                  Point<dim>(part[i + 10], part[i + 11], part[i + 12]);
                NodeDofs d;
                for (unsigned int c = 0; c < dim; ++c)
                  d[c] = static_cast<types::global_dof_index>(part[i + c]);
                face.nodes.push_back(static_cast<long>(d[0]));
                face.X.push_back({part[i + 3], part[i + 4], part[i + 5]});
                m.dofs[static_cast<long>(d[0])] = {d, part[i + 6] != 0.0};
                m.u[static_cast<long>(d[0])] =
                  Tensor<1, dim>({part[i + 7], part[i + 8], part[i + 9]});
              }
            m.faces.push_back(std::move(face));
          }
      return m;
    }

    /// The slave surface: faces of this rank's owned and ghost cells (every cell holding a
    /// DoF of an owned cell is among them, so owned and ghost nodes of owned cells see all
    /// their faces), at the positions searched; a joint's faces with a node beyond |z| >
    /// z_end are left out. Per node (by x-DoF) its DoFs.
    struct SlaveSurface
    {
      std::vector<mortar::Face> faces;
      std::map<long, NodeDofs> dofs;
    };

    template <typename Position>
    SlaveSurface collect_slave_surface(const DofSpace &dofs,
                                       const std::map<types::global_dof_index, Point<dim>> &support,
                                       const types::boundary_id slave_id, const bool joint,
                                       const double z_end, const Position &position)
    {
      std::vector<types::global_dof_index> face_dofs(dofs.fe().n_dofs_per_face());
      SlaveSurface sl;
      for (const auto &cell : dofs.handler().active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == slave_id)
              {
                const auto nodes = face_node_dofs(cell, f, face_dofs);
                if (joint && std::any_of(nodes.begin(), nodes.end(), [&](const NodeDofs &d) {
                      return std::abs(support.at(d[0])[2]) > z_end;
                    }))
                  continue;
                mortar::Face face;
                for (const auto &d : nodes)
                  {
                    const Point<dim> x = position(d);
                    face.nodes.push_back(static_cast<long>(d[0]));
                    face.X.push_back({x[0], x[1], x[2]});
                    sl.dofs[static_cast<long>(d[0])] = d;
                  }
                sl.faces.push_back(std::move(face));
              }
      return sl;
    }

    /// Two deformable bodies coupled by dual mortar: the block and its indenter, the bore and
    /// the deformable journal (contact.pairing: mortar).
    class MortarPairing : public ContactPairing
    {
    public:
      explicit MortarPairing(const PairingContext &context)
        : c_(context)
      {}

      /// Each slave node gets (contact/mortar.h)
      /// ĝ = g̃0 + n·(u − Σ_m C_sm u_m) with the weighted gap g̃0 and the mortar coefficients C_sm
      /// of the master surface's nodes; an active node's constraint is then the same kind of line
      /// as node-to-node contact, with several partners.
      ///   blocks: slave = the block's top face (the plane y = 0, n = −e_y into the block),
      ///           master = the indenter's bottom;
      ///   joint:  slave = the bore's faces that lie over the journal's length (n radial, into the
      ///           bearing), master = the journal's cylindrical surface;
      ///   joint, plan.journal_is_slave (the tilted journal): slave = the journal's cylindrical
      ///           surface (n toward its own axis, into the journal), master = the bore.
      ///
      /// With `u` (ghosted; contact.sliding finite) the coupling is found between the surfaces as
      /// deformed by u, x = X + u, and each node's g0 is set so that its linearised gap at u is the
      /// weighted gap found there: ĝ(u) = g0 + n·(u_s − Σ_m C_sm u_m) = g̃(x). Normals stay those of
      /// the reference surfaces (small deformation of each body; the sliding is between them).
      Nodes find(const std::map<types::global_dof_index, Point<dim>> &support,
                 const TrilinosWrappers::MPI::Vector *u) const override
      {
        // a node's position in the configuration searched: X, or X + u; the rolling study's
        // turning journal (the master) placed in the bearing's frame by its pose
        const bool turning_journal = c_.plan.journal_turns_deformable();
        auto position = [&](const std::array<types::global_dof_index, dim> &d,
                            const bool master_node = false) {
          Point<dim> x = support.at(d[0]);
          Tensor<1, dim> ud;
          if (u)
            for (unsigned int c = 0; c < dim; ++c)
              ud[c] = (*u)[d[c]];
          return turning_journal && master_node ? c_.frame.place(x, ud) : x + ud;
        };
        const bool joint = c_.plan.mesh == StudyPlan::Mesh::joint;
        const bool journal_slave = joint && c_.plan.journal_is_slave;
        const types::boundary_id slave_id = slave_surface(c_.plan);
        const types::boundary_id master_id = journal_slave ? bid_contact :
                                             joint         ? bid_journal_surface :
                                                             bid_indenter_surface;
        auto slave_normal = [&](const Point<dim> &X) {
          if (!joint)
            return Tensor<1, dim>({0.0, -1.0, 0.0});
          if (journal_slave)
            {
              // −(radial direction from the journal's own axis), turned with the journal
              const Point<dim> l = c_.bodies.journal_local(X);
              const double y = l[1] + c_.scene.geometry.c_r;
              const double r = std::hypot(l[0], y);
              const auto n = c_.plan.journal_pose.rotate({-l[0] / r, -y / r, 0.0});
              return Tensor<1, dim>({n[0], n[1], n[2]});
            }
          if (turning_journal)
            {
              // along the journal's radius through the bore node (X: where it is now), as
              // set_obstacle_position keeps it
              const double x = X[0] - c_.frame.centre[0], y = X[1] - c_.frame.centre[1];
              const double r = std::hypot(x, y);
              return Tensor<1, dim>({x / r, y / r, 0.0});
            }
          const double r = std::hypot(X[0], X[1]);
          return Tensor<1, dim>({X[0] / r, X[1] / r, 0.0});
        };
        // Bore as slave: a bore face beyond the journal's end faces no journal face, and a dual
        // basis function is non-zero on its whole face, so such a face would make the rim nodes it
        // shares incomplete (and drop them) — it is left out: the journal's ends are mesh planes.
        // (The journal as slave lies wholly over the longer bore.)
        const double z_end = joint && !journal_slave ? c_.plan.obstacle.half_length * (1.0 + 1e-9) :
                                                       std::numeric_limits<double>::infinity();

        const MasterSurface master = gather_master_surface(
          c_.dofs, support, master_id, u, [&](const NodeDofs &d) { return position(d, true); },
          c_.comm);
        const SlaveSurface slave =
          collect_slave_surface(c_.dofs, support, slave_id, joint, z_end,
                                [&](const NodeDofs &d) { return position(d); });
        std::vector<mortar::SlaveNode> slave_nodes;
        for (const auto &[id, d] : slave.dofs)
          {
            const Tensor<1, dim> n = slave_normal(turning_journal ? position(d) : support.at(d[0]));
            slave_nodes.push_back({id, {n[0], n[1], n[2]}});
          }
        mortar::Options options;
        // 8 × 3 Gauss points per direction of each slave face: the mortar integrals have kinks
        // where master faces end; their error (≈ 2e-3 of a master nodal force at 8 sub-intervals,
        // 8e-3 at 4, mortar_test) shows up as non-uniform pressure in the patch test.
        options.subdivisions = 8;
        // Blocks: quadrature points farther apart than this cannot close under a push of δ_max;
        // their nodes come out incomplete and are left out (they cannot touch). Joint: every bore
        // point over the journal faces it within 2 c_r (the top of the bore), so all of them are
        // paired and watched for penetration, as on common rays.
        options.max_distance = joint ?
                                 2.0 * c_.scene.geometry.c_r + 4.0 * c_.scene.loading.delta_max :
                                 4.0 * c_.scene.loading.delta_max;
        const double window_gap = 2.0 * c_.scene.loading.delta_max;
        Nodes by_x_dof;
        for (const auto &cp : mortar::couple(slave.faces, slave_nodes, master.faces, options))
          {
            const NodeDofs &dofs = slave.dofs.at(cp.node);
            if (!cp.complete || cp.weight <= 0.0)
              continue;  // out of reach
            ContactNode cn;
            cn.dofs = dofs;
            cn.X = support.at(dofs[0]);
            cn.owned = c_.dofs.owned().is_element(dofs[0]);
            cn.n = slave_normal(turning_journal ? position(dofs) : cn.X);
            if (!c_.contact.choose_constrained_component(cn, cn.n))
              continue;  // hanging or supported: it follows its masters
            cn.g0 = cp.gap;
            cn.two_body = true;
            cn.candidate = cp.gap <= window_gap;
            if (turning_journal)
              {
                // as with the rigid journal: every node the journal passes close to on its path
                // (so that the candidates, and the pattern, do not change from step to step)
                double g_path = 0.0;
                Tensor<1, dim> n_path;
                rolling_gap_on_path(c_.scene, c_.obstacle, cn.X, g_path, n_path);
                cn.candidate = g_path <= window_gap;
              }
            Tensor<1, dim> relative;  // u_s − Σ C_sm u_m (0 in the reference search)
            if (u)
              for (unsigned int c = 0; c < dim; ++c)
                relative[c] = (*u)[dofs[c]];
            for (const auto &[m, w] : cp.masters)
              {
                const auto &[mdofs, driven] = master.dofs.at(m);
                cn.partners.push_back({mdofs, w, driven});
                relative -= w * master.u.at(m);
                cn.partner_X += w * master.X.at(m);
                cn.partner_weight += w;
              }
            // (the turning journal: g0 and n are set at each iterate by set_obstacle_position)
            cn.g0 -= cn.n * relative;
            cn.gap = cp.gap;  // the weighted gap where it was searched (follow_sliding compares)
            by_x_dof.emplace(dofs[0], cn);
          }
        return by_x_dof;
      }

    private:
      const PairingContext c_;
    };
  }  // namespace

  std::unique_ptr<ContactPairing> make_mortar_pairing(const PairingContext &context)
  {
    return std::make_unique<MortarPairing>(context);
  }
}  // namespace clearjoint::fe::detail
