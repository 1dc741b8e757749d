// Contact candidates: bearing nodes against the rigid journal (or obstacle), or paired with the
// deformable journal's node on the same ray; partner ghosts across ranks; the cells whose
// condensed matrices change with the active set.
#include "fe_stage/contact_model.h"
#include "fe_stage/core/face_dofs.h"

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

    /// Partner DoFs this rank does not see yet become ghosts (solution values, constraint
    /// lines), and then the masters of partners that hang (a journal face refined on one
    /// side): closed lines have no chains, so two rounds suffice. After each round the fixed
    /// constraints are rebuilt on the enlarged set and made consistent across ranks.
    void ghost_partners(DofSpace &dofs, const std::vector<ContactNode> &nodes, MPI_Comm comm)
    {
      auto add_ghosts = [&](const auto &dofs_of_partner) {
        IndexSet extra(dofs.handler().n_dofs());
        for (const auto &cn : nodes)
          for (const auto &partner : cn.partners)
            for (const auto p : partner.dofs)
              for (const auto d : dofs_of_partner(p))
                if (!dofs.relevant().is_element(d))
                  extra.add_index(d);
        extra.compress();
        if (Utilities::MPI::max(extra.n_elements(), comm) == 0)
          return;  // collective: every rank takes the same branch
        dofs.add_relevant(extra);
      };
      add_ghosts(
        [](const types::global_dof_index p) { return std::vector<types::global_dof_index>{p}; });
      add_ghosts([&](const types::global_dof_index p) {
        std::vector<types::global_dof_index> masters;
        if (const auto *e = dofs.fixed().get_constraint_entries(p))
          for (const auto &entry : *e)
            masters.push_back(entry.first);
        return masters;
      });
    }

    /// Cells that hold a candidate DoF, or a hanging DoF that hangs from one: their condensed
    /// contributions change with the active set (a hanging node's share moves on through the
    /// contact line of its master); all other cells go into the static part once. Per active
    /// cell its index among them or −1; returns their number.
    unsigned int mark_contact_cells(const DofSpace &dofs, const std::vector<ContactNode> &nodes,
                                    const unsigned int n_active_cells,
                                    std::vector<int> &contact_cell_of)
    {
      IndexSet candidate_dofs(dofs.handler().n_dofs());
      for (const auto &cn : nodes)
        if (cn.candidate)
          for (const auto d : cn.dofs)
            candidate_dofs.add_index(d);
      candidate_dofs.compress();
      IndexSet hanging_on_candidates(dofs.handler().n_dofs());
      for (const auto &line : dofs.fixed().get_lines())
        for (const auto &entry : line.entries)
          if (candidate_dofs.is_element(entry.first))
            {
              hanging_on_candidates.add_index(line.index);
              break;
            }
      candidate_dofs.add_indices(hanging_on_candidates);
      candidate_dofs.compress();
      contact_cell_of.assign(n_active_cells, -1);
      std::vector<types::global_dof_index> cell_dofs(dofs.fe().n_dofs_per_cell());
      unsigned int n = 0;
      for (const auto &cell : dofs.handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(cell_dofs);
            for (const auto d : cell_dofs)
              if (candidate_dofs.is_element(d))
                {
                  contact_cell_of[cell->active_cell_index()] = n++;
                  break;
                }
          }
      return n;
    }
  }  // namespace
  /// The rolling study: the journal passes under a bore point X when the frame angle −φ
  /// reaches it; its gap then, at δ_max, decides whether X is a contact candidate (off the
  /// arc the journal travels, at the arc's nearer end).
  void ContactModel::rolling_gap_on_path(const Point<dim> &X, double &g0, Tensor<1, dim> &n) const
  {
    const double a = std::atan2(X[0], -X[1]);
    const double sweep = scene_.rolling.omega_B * rolling_end_time(scene_);
    RigidObstacle o = obstacle_;
    o.frame_angle = rolling_path_distance(scene_, a) == 0.0 ?
                      -a :
                      (std::abs(std::remainder(a, 2.0 * units::pi)) <
                           std::abs(std::remainder(a + sweep, 2.0 * units::pi)) ?
                         0.0 :
                         sweep);
    Vec3 normal;
    o.gap({X[0], X[1], X[2]}, scene_.loading.delta_max, g0, normal);
    n = Tensor<1, dim>({normal[0], normal[1], normal[2]});
  }

  void ContactModel::find_contact_nodes()
  {
    std::map<types::global_dof_index, Point<dim>> support;
    DoFTools::map_dofs_to_support_points(bodies_.mapping(), dofs_.handler(), support);

    // Candidates: surface nodes that could touch within the push (gap at δ_max below the
    // push itself, with a factor 2 margin). After every solve all surface nodes are checked
    // for penetration, so a window that was too small is an error, not a silent miss.
    const double window_gap = 2.0 * scene_.loading.delta_max;
    std::map<types::global_dof_index, ContactNode> by_x_dof;
    std::vector<types::global_dof_index> face_dofs(dofs_.fe().n_dofs_per_face());

    // Two bodies on common rays: the journal's surface nodes, keyed by (φ, z)
    const bool mortar = plan_.pairing == StudyPlan::Pairing::mortar;
    std::map<RayKey, JournalNode> journal_nodes;
    if (plan_.deformable_partner && !mortar)
      journal_nodes = gather_journal_surface(dofs_, support, comm_);
    if (mortar)
      find_mortar_contact_nodes(support, by_x_dof, search_displacement_);
    else
      for (const auto &cell : dofs_.handler().active_cell_iterators())
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
                    if (!obstacle_gap(cn.X, scene_.loading.delta_max, g0, n))
                      continue;
                    if (plan_.rolling)
                      rolling_gap_on_path(cn.X, g0, n);
                    cn.owned = dofs_.owned().is_element(dofs[0]);
                    if (g0 > window_gap)
                      {
                        cn.candidate = false;  // watched only
                        by_x_dof.emplace(dofs[0], cn);
                        continue;
                      }
                    // Hanging or supported nodes are skipped: they follow their masters.
                    if (!contact_.choose_constrained_component(cn, n))
                      continue;
                    if (plan_.deformable_partner)
                      {
                        const auto it = journal_nodes.find(ray_key(cn.X));
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
    contact_.nodes().clear();
    for (auto &[d, cn] : by_x_dof)
      contact_.nodes().push_back(cn);

    if (plan_.deformable_partner && n_ranks_ > 1)
      ghost_partners(dofs_, contact_.nodes(), comm_);
    std::vector<int> contact_cell_of;
    const unsigned int n =
      mark_contact_cells(dofs_, contact_.nodes(), bodies_.triangulation().n_active_cells(),
                         contact_cell_of);
    system_.set_contact_cells(std::move(contact_cell_of), n);
  }
}  // namespace clearjoint::fe::detail
