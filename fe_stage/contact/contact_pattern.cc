// ContactPattern (contact/contact_pattern.h), the contact nodes on the DoF space (core/
// dof_space.h): the pairing's nodes (contact/contact_pairing.h), their partners' ghosts and the
// cells whose condensed matrices change with the active set; then the sparsity pattern that
// every active set condenses into and the assembler's matrices on it.
#include "fe_stage/contact/contact_pattern.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <algorithm>
#include <map>
#include <vector>

namespace clearjoint::fe::detail
{
  namespace
  {
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

  ContactPattern::ContactPattern(MeshPreparation &mesh, const Parts &parts)
    : mesh_(mesh)
    , scene_(parts.scene)
    , plan_(parts.plan)
    , bodies_(parts.bodies)
    , dofs_(parts.dofs)
    , contact_(parts.contact)
    , pairing_(parts.pairing)
    , frame_(parts.frame)
    , system_(parts.system)
    , state_(parts.state)
    , evaluation_(parts.evaluation)
    , comm_(parts.comm)
    , n_ranks_(Utilities::MPI::n_mpi_processes(parts.comm))
  {}

  /// The pairing's contact nodes, searched between the reference surfaces or those displaced
  /// by `search_displacement` (ghosted; finite sliding's rebuild), then their partners' ghosts
  /// and the contact cells.
  void ContactPattern::find_contact_nodes(const TrilinosWrappers::MPI::Vector *search_displacement)
  {
    std::map<types::global_dof_index, Point<dim>> support;
    DoFTools::map_dofs_to_support_points(bodies_.mapping(), dofs_.handler(), support);
    contact_.nodes().clear();
    for (auto &[d, cn] : pairing_.find(support, search_displacement))
      contact_.nodes().push_back(cn);

    if (plan_.deformable_partner && n_ranks_ > 1)
      ghost_partners(dofs_, contact_.nodes(), comm_);
    std::vector<int> contact_cell_of;
    const unsigned int n =
      mark_contact_cells(dofs_, contact_.nodes(), bodies_.triangulation().n_active_cells(),
                         contact_cell_of);
    system_.set_contact_cells(std::move(contact_cell_of), n);
  }

  /// The matrices. The sparsity pattern is built with every candidate's contact line present,
  /// so any active set condenses into it (the two-body lines couple journal DoFs).
  void ContactPattern::make_matrices()
  {
    AffineConstraints<double> worst(dofs_.relevant());
    pattern_partners_.clear();
    for (const auto &cn : contact_.nodes())
      if (cn.candidate)
        {
          auto &entry = pattern_partners_[cn.dofs[0]];
          entry.component = cn.constrained_component;
          for (const auto &p : cn.partners)
            entry.partners.insert(p.dofs[0]);
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
          if (contact_.friction())
            for (unsigned int k = 0; k < dim; ++k)
              if (k != cn.constrained_component && !dofs_.fixed().is_constrained(cn.dofs[k]))
                {
                  worst.add_line(cn.dofs[k]);
                  // (the rolling study's turning journal: its partners' x and y mix)
                  for (const auto &p : cn.partners)
                    for (unsigned int m = 0; m < dim; ++m)
                      if (m == k || plan_.journal_turns_deformable())
                        worst.add_entry(cn.dofs[k], p.dofs[m], 1.0);
                }
        }
    worst.merge(dofs_.fixed(), AffineConstraints<double>::left_object_wins, true);
    worst.close();
    // The union of the patterns with and without the contact lines: a master of a hanging node
    // may be a contact DoF, whose line is active in some iterations and not in others.
    DynamicSparsityPattern dsp(dofs_.relevant());
    DoFTools::make_sparsity_pattern(dofs_.handler(), dsp, dofs_.fixed(), true);
    DoFTools::make_sparsity_pattern(dofs_.handler(), dsp, worst, true);
    // Any mix of active and inactive candidates must fit the pattern, not only "none" and
    // "all": condensing the contact line of a candidate d moves entries K(i, d) and K(d, j) of
    // every cell holding d — or holding a hanging DoF that hangs from d — to the DoFs of d's
    // line (its node's other components, the journal partner's components and their
    // masters). A free candidate's row in such a cell then couples to them too. Add these
    // couplings for every such cell explicitly.
    {
      std::map<types::global_dof_index, std::vector<types::global_dof_index>> line_dofs;
      for (const auto &cn : contact_.nodes())
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
              if (l == cn.constrained_component || contact_.friction())
                {
                  auto &target = line_dofs[cn.dofs[l]];
                  target.insert(target.end(), v.begin(), v.end());
                }
          }
      std::vector<types::global_dof_index> cell_dofs(dofs_.fe().n_dofs_per_cell());
      for (const auto &cell : dofs_.handler().active_cell_iterators())
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
                if (const auto *e = dofs_.fixed().get_constraint_entries(d))
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
              if (dofs_.relevant().is_element(i))
                for (const auto j : all)
                  dsp.add(i, j);
          }
    }
    SparsityTools::distribute_sparsity_pattern(dsp, dofs_.owned(), comm_, dofs_.relevant());
    system_.reinit(dsp);
  }
}  // namespace clearjoint::fe::detail
