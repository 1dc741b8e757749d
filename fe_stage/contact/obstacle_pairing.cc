// The node pairings of the generated joint (contact_pairing.h): the bore's surface nodes (or the
// block's top) against the rigid obstacle, and — the deformable journal meshed on the bearing's
// rays — each bore node with the journal node on its ray. Both choose their candidates by the
// rigid obstacle's gap at the full push.
#include "fe_stage/contact/contact_pairing.h"
#include "fe_stage/core/face_dofs.h"

#include "common/error.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace clearjoint::fe::detail
{
  namespace
  {
    /// A point's ray and axial position, exact to round-off: the journal's surface nodes lie
    /// on the same rays as the bearing's (RayChart), so pairing is an exact lookup.
    using RayKey = std::pair<long, long>;
    RayKey ray_key(const Point<dim> &p)
    {
      return std::make_pair(std::lround(std::atan2(p[0], -p[1]) / 1e-9), std::lround(p[2] / 1e-11));
    }

    struct JournalNode
    {
      std::array<types::global_dof_index, dim> dofs;
      Point<dim> X;
      bool driven_y = false;
    };

    /// Every journal surface node on every rank (a few thousand): with several ranks the
    /// journal cell facing a bearing node is often neither owned nor a ghost, so the owner of
    /// each journal node contributes it (DoFs, position, whether its y-DoF is driven).
    std::map<RayKey, JournalNode> gather_journal_surface(
      const DofSpace &dofs, const std::map<types::global_dof_index, Point<dim>> &support,
      MPI_Comm comm)
    {
      std::vector<types::global_dof_index> face_dofs(dofs.fe().n_dofs_per_face());
      std::vector<double> mine;  // per node: key φ, key z, 3 DoFs, X, driven flag
      std::set<types::global_dof_index> seen;
      for (const auto &cell : dofs.handler().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_journal_surface)
              for (const auto &node : face_node_dofs(cell, f, face_dofs))
                if (dofs.owned().is_element(node[0]) && seen.insert(node[0]).second)
                  {
                    const Point<dim> &X = support.at(node[0]);
                    const auto key = ray_key(X);
                    mine.insert(mine.end(), {double(key.first), double(key.second), double(node[0]),
                                             double(node[1]), double(node[2]), X[0], X[1], X[2],
                                             dofs.is_loaded_y_dof(node[1]) ? 1.0 : 0.0});
                  }
      std::map<RayKey, JournalNode> journal_nodes;
      for (const auto &part : Utilities::MPI::all_gather(comm, mine))
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
      return journal_nodes;
    }

    /// The bore's (or the block top's) surface nodes against the rigid obstacle: a node whose
    /// gap at δ_max is more than twice the push is only watched (after every solve all
    /// surface nodes are checked for penetration, so a window that was too small is an
    /// error, not a silent miss); hanging and supported nodes are left out (they follow their
    /// masters).
    class ObstaclePairing : public ContactPairing
    {
    public:
      explicit ObstaclePairing(const PairingContext &context)
        : c_(context)
      {}

      Nodes find(const std::map<types::global_dof_index, Point<dim>> &support,
                 const TrilinosWrappers::MPI::Vector *u) const override
      {
        require_reference_search(u);
        return surface_nodes(support, [](ContactNode &) {});
      }

    protected:
      /// Only mortar searches between deformed surfaces (scene.cc admits contact.sliding
      /// finite only with it).
      static void require_reference_search(const TrilinosWrappers::MPI::Vector *u)
      {
        if (u)
          throw std::logic_error("fe_stage: finite sliding needs the mortar pairing");
      }

      /// The surface's nodes; `pair(cn)` gives each candidate its partner on the other body.
      template <typename Pair>
      Nodes surface_nodes(const std::map<types::global_dof_index, Point<dim>> &support,
                          const Pair &pair) const
      {
        const double delta_max = c_.scene.loading.delta_max;
        const double window_gap = 2.0 * delta_max;  // a factor 2 margin on the push
        Nodes by_x_dof;
        std::vector<types::global_dof_index> face_dofs(c_.dofs.fe().n_dofs_per_face());
        for (const auto &cell : c_.dofs.handler().active_cell_iterators())
          if (cell->is_locally_owned() || cell->is_ghost())
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_contact)
                for (const auto &dofs : face_node_dofs(cell, f, face_dofs))
                  {
                    if (by_x_dof.count(dofs[0]))
                      continue;
                    ContactNode cn;
                    cn.dofs = dofs;
                    cn.X = support.at(dofs[0]);
                    double g0;
                    Tensor<1, dim> n;
                    if (!obstacle_gap(cn.X, delta_max, g0, n))
                      continue;
                    if (c_.plan.rolling)
                      rolling_gap_on_path(c_.scene, c_.obstacle, cn.X, g0, n);
                    cn.owned = c_.dofs.owned().is_element(dofs[0]);
                    if (g0 > window_gap)
                      {
                        cn.candidate = false;  // watched only
                        by_x_dof.emplace(dofs[0], cn);
                        continue;
                      }
                    if (!c_.contact.choose_constrained_component(cn, n))
                      continue;
                    pair(cn);
                    by_x_dof.emplace(dofs[0], cn);
                  }
        return by_x_dof;
      }

      const PairingContext c_;

    private:
      /// The rigid obstacle's gap at a reference point (deal.II types around
      /// RigidObstacle::gap); false where X can never touch it.
      bool obstacle_gap(const Point<dim> &X, const double delta, double &g0,
                        Tensor<1, dim> &n) const
      {
        Vec3 normal;
        if (!c_.obstacle.gap({X[0], X[1], X[2]}, delta, g0, normal))
          return false;
        n = Tensor<1, dim>({normal[0], normal[1], normal[2]});
        return true;
      }
    };

    /// The deformable journal meshed on the bearing's rays: each candidate bore node is paired
    /// with the journal node on its ray (weight 1), its normal radial and its gap the radii's
    /// difference along the common ray.
    class CommonRayPairing : public ObstaclePairing
    {
    public:
      using ObstaclePairing::ObstaclePairing;

      Nodes find(const std::map<types::global_dof_index, Point<dim>> &support,
                 const TrilinosWrappers::MPI::Vector *u) const override
      {
        require_reference_search(u);
        const std::map<RayKey, JournalNode> journal_nodes =
          gather_journal_surface(c_.dofs, support, c_.comm);
        return surface_nodes(support, [&](ContactNode &cn) {
          const auto it = journal_nodes.find(ray_key(cn.X));
          if (it == journal_nodes.end())
            throw NumericalError("fe_stage: no journal node faces the bearing node at (" +
                                 format_value(cn.X[0]) + ", " + format_value(cn.X[1]) + ", " +
                                 format_value(cn.X[2]) + ") m: the contact meshes do not match");
          cn.two_body = true;
          cn.partners = {{it->second.dofs, 1.0, it->second.driven_y}};
          const Point<dim> &XJ = it->second.X;
          const double rB = std::hypot(cn.X[0], cn.X[1]);
          cn.n = Tensor<1, dim>({cn.X[0] / rB, cn.X[1] / rB, 0.0});
          cn.g0 = rB - std::hypot(XJ[0], XJ[1]);  // along the common ray
        });
      }
    };
  }  // namespace

  std::unique_ptr<ContactPairing> make_obstacle_pairing(const PairingContext &context)
  {
    return std::make_unique<ObstaclePairing>(context);
  }

  std::unique_ptr<ContactPairing> make_common_ray_pairing(const PairingContext &context)
  {
    return std::make_unique<CommonRayPairing>(context);
  }
}  // namespace clearjoint::fe::detail
