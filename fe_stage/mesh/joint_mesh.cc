// The joint's generated mesh: bearing ring and (deformable) journal on common rays, the rigid
// journal's placement (aligned or tilted), and the refinement toward the contact.
#include "fe_stage/mesh/append_body.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/mesh/boundary_ids.h"
#include "fe_stage/mesh/charts.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  namespace
  {
    /// The joint's vertices on common rays: φ is measured from −y toward +x, a point at radius
    /// r is (r sin φ, −r cos φ); vertex i sits at φ_i, and the full ring closes at φ = ±π
    /// (vertex index modulo n_phi_vertices).
    struct RayLayout
    {
      bool full = false;    // no x = 0 symmetry plane (φ over 360°)
      bool full_z = false;  // no z = 0 plane (the whole length)
      unsigned int n_phi = 0, n_phi_vertices = 0;
      double phi0 = 0.0, dphi = 0.0;
      double phi_of(const unsigned int i) const { return phi0 + (i % n_phi_vertices) * dphi; }
    };

    RayLayout ray_layout(const FeScene &scene, const StudyPlan &plan)
    {
      RayLayout l;
      // the rolling study: the whole ring (the contact travels round it), the mid-plane kept;
      // the tilted journal of the misalignment study breaks the axial symmetry
      l.full = scene.full_model || plan.rolling;
      l.full_z = scene.full_model || plan.full_length;
      const unsigned int n = scene.mesh.n_circumferential;
      l.n_phi = l.full ? 2 * n : n;
      l.n_phi_vertices = l.full ? l.n_phi : l.n_phi + 1;
      l.phi0 = l.full ? -units::pi : 0.0;
      l.dphi = (l.full ? 2.0 * units::pi : units::pi) / l.n_phi;
      return l;
    }

    /// The bearing's cross-section: a 2D (r, φ) grid of n_r layers from R_B to R_o, local x
    /// along r (outward), local y along φ.
    void make_bearing_section(const RayLayout &l, const unsigned int n_r, const double R_B,
                              const double R_o, Triangulation<2> &section)
    {
      std::vector<Point<2>> vertices;
      std::vector<CellData<2>> cells;
      auto bid = [&](unsigned int i, unsigned int j) {
        return (i % l.n_phi_vertices) * (n_r + 1) + j;
      };
      for (unsigned int i = 0; i < l.n_phi_vertices; ++i)
        for (unsigned int j = 0; j <= n_r; ++j)
          {
            const double r = R_B + (R_o - R_B) * j / n_r;
            vertices.emplace_back(r * std::sin(l.phi_of(i)), -r * std::cos(l.phi_of(i)));
          }
      for (unsigned int i = 0; i < l.n_phi; ++i)
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
      section.create_triangulation(vertices, cells, SubCellData());
    }

    /// The axial slices [m] of the bearing and of the deformable journal (as meshed).
    struct AxialSlices
    {
      std::vector<double> bearing, journal;
    };

    /// The journal's end L_J/2 is a mesh plane. The misalignment study's journal is rigid;
    /// there the plane goes through its first touch point P1 at z = −((L_J/2) cos θ − R_J sin θ)
    /// (and the mirrored plane through the diagonally opposite rim point, which touches at
    /// θ_max), so a node sits where contact starts. A placed deformable journal (tilted, or
    /// moved axially) is meshed aligned over its own length ±L_J/2 (the same number of
    /// slices) and then moved by its pose.
    AxialSlices axial_slices(const FeScene &scene, const StudyPlan &plan, const bool full_z,
                             const bool journal)
    {
      const auto &G = scene.geometry;
      const auto &M = scene.mesh;
      const double theta = plan.tilted ? scene.misalignment.theta_deg * units::deg : 0.0;
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
      std::vector<double> journal_half_slices = half_slices;
      if (!plan.journal_pose.identity() && journal)
        for (unsigned int k = 0; k <= n_in; ++k)
          journal_half_slices[k] = 0.5 * G.L_J() * k / n_in;
      AxialSlices slices;
      slices.journal = mirror(journal_half_slices);
      for (unsigned int k = 1; k <= n_out; ++k)
        half_slices.push_back(zJ + (zB - zJ) * k / n_out);
      slices.bearing = mirror(half_slices);
      return slices;
    }

    /// The deformable journal's cross-section: one ring layer s ∈ [s0, 1] on the rays of the
    /// bearing's vertices, and a structured core whose boundary lies on s = s0 (Coons patch).
    /// n: cells over 180°; the journal's axis at (0, −c_r).
    void make_journal_section(const RayLayout &l, const RayChart &journal_chart,
                              const unsigned int n, const double c_r, Triangulation<2> &section)
    {
      const double s0 = 0.6;
      const bool full = l.full;
      const unsigned int n_phi = l.n_phi, n_phi_vertices = l.n_phi_vertices;
      const unsigned int Nx = full ? n / 2 : n / 4, Ny = n / 2;
      std::vector<Point<2>> jv;
      std::vector<CellData<2>> jc;
      auto ring_point = [&](unsigned int i, double s) {
        const Point<dim> p = journal_chart.push_forward(Point<dim>(l.phi_of(i), s, 0.0));
        return Point<2>(p[0], p[1]);
      };
      // ring vertices: (i, l), l = 0 (s0), 1 (surface)
      auto rid = [&](unsigned int i, unsigned int k) { return (i % n_phi_vertices) * 2 + k; };
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
            if (b == 0)
              return int(n / 2 + a);
            if (a == Nx)
              return int(n / 2 + Nx + b);
            if (b == Ny)
              return int((n / 2 + Nx + Ny + (Nx - a)) % n_phi);
            if (a == 0)
              return int((n / 2 + 2 * Nx + Ny + (Ny - b)) % n_phi);
            return -1;
          }
        if (b == 0)
          return int(a);
        if (a == Nx)
          return int(Nx + b);
        if (b == Ny)
          return int(Nx + Ny + (Nx - a));
        return -1;
      };
      const Point<2> centre(0.0, -c_r);
      auto boundary_point = [&](unsigned int a, unsigned int b) -> Point<2> {
        const int i = ring_index(a, b);
        if (i >= 0)
          return ring_point(i, s0);
        // half model, a = 0: bottom → centre → top, linear in each half
        const Point<2> bot = ring_point(0, s0), top = ring_point(n, s0);
        const double t = double(b) / Ny;
        return t <= 0.5 ? bot + (centre - bot) * (2.0 * t) :
                          centre + (top - centre) * (2.0 * t - 1.0);
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
                p = Point<2>(
                  (1 - v) * B + v * T + (1 - u) * Lp + u * R -
                  ((1 - u) * (1 - v) * P00 + u * (1 - v) * P10 + (1 - u) * v * P01 + u * v * P11));
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
      GridTools::consistently_order_cells(jc);
      section.create_triangulation(jv, jc, SubCellData());
    }
  }  // namespace

  /// The bearing ring (and, unless the journal is rigid, the journal) as hexahedra on the
  /// RayChart manifolds (RayLayout: the rays both bodies share).
  void Bodies::make_radial_grid()
  {
    const auto &G = scene_.geometry;
    const auto &M = scene_.mesh;
    const RayLayout layout = ray_layout(scene_, plan_);
    const bool full = layout.full, full_z = layout.full_z;
    const bool journal = scene_.loading.journal != JournalLoading::rigid;
    const unsigned int n_r = M.n_radial > 0 ?
                               M.n_radial :
                               std::max(1u, static_cast<unsigned int>(std::lround(G.t_B / 2.0e-3)));
    const double R_o = G.R_B + G.t_B;
    const RayChart bearing_chart(G.c_r, G.R_J(), false), journal_chart(G.c_r, G.R_J(), true);
    const AxialSlices slices = axial_slices(scene_, plan_, full_z, journal);

    Triangulation<2> bearing2d;
    make_bearing_section(layout, n_r, G.R_B, R_o, bearing2d);
    Triangulation<dim> bearing3d;
    GridGenerator::extrude_triangulation(bearing2d, slices.bearing, bearing3d);
    auto [all_vertices, all_cells, subcells] = GridTools::get_coarse_mesh_description(bearing3d);
    for (auto &c : all_cells)
      {
        c.material_id = 0;
        c.manifold_id = 0;
      }
    if (journal)
      {
        Triangulation<2> journal2d;
        make_journal_section(layout, journal_chart, M.n_circumferential, G.c_r, journal2d);
        Triangulation<dim> journal3d;
        GridGenerator::extrude_triangulation(journal2d, slices.journal, journal3d, true);
        if (!plan_.journal_pose.identity())
          GridTools::transform([&](const Point<dim> &p) { return journal_world(p); }, journal3d);
        append_body(journal3d, 1, all_vertices, all_cells);
      }

    // One coarse mesh without vertex merging: the bodies touch at φ = 0 but stay separate.
    Triangulation<dim> serial;
    serial.create_triangulation(all_vertices, all_cells, SubCellData());
    set_joint_manifold_ids(serial, journal_chart);
    set_joint_boundary_ids(serial, full, full_z);

    tria_.copy_triangulation(serial);
    tria_.set_manifold(0, bearing_chart);
    if (plan_.journal_pose.identity())
      tria_.set_manifold(1, journal_chart);
    else
      tria_.set_manifold(1, PlacedChart(journal_chart, plan_.journal_pose));

    refine_joint_mesh();
    symmetry_factor_ = (full ? 1.0 : 2.0) * (full_z ? 1.0 : 2.0);
  }

  /// The bearing on its chart (0); the journal's ring layer on its chart (1), its core flat.
  void Bodies::set_joint_manifold_ids(Triangulation<dim> &serial,
                                      const RayChart &journal_chart) const
  {
    for (const auto &cell : serial.active_cell_iterators())
      {
        const bool is_journal = cell->material_id() == 1;
        if (is_journal)
          {
            // ring cells: all vertices at s ≥ s0 − tol on the journal chart
            bool ring = true;
            for (const auto v : cell->vertex_indices())
              ring =
                ring && journal_chart.pull_back(journal_local(cell->vertex(v)))[1] > 0.6 - 1e-6;
            cell->set_all_manifold_ids(ring ? 1 : numbers::flat_manifold_id);
          }
        else
          cell->set_all_manifold_ids(0);
      }
    // ring faces toward the core carry the chart too (set after the core so they stay curved)
    for (const auto &cell : serial.active_cell_iterators())
      if (cell->material_id() == 1 && cell->manifold_id() == 1)
        cell->set_all_manifold_ids(1);
  }

  /// The joint's boundary ids (mesh/boundary_ids.h): the bore (contact), the outer surface
  /// (supported on its upper half, or all round for the rolling study's outer support), the
  /// journal's surface and end faces, and the symmetry planes the model has.
  void Bodies::set_joint_boundary_ids(Triangulation<dim> &serial, const bool full,
                                      const bool full_z) const
  {
    const auto &G = scene_.geometry;
    const double R_o = G.R_B + G.t_B;
    const double tol = 1e-8 * G.R_B;
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
                const Point<dim> l = journal_local(p);  // the journal as meshed
                on_journal = on_journal && std::abs(std::hypot(l[0], l[1] + G.c_r) - G.R_J()) < tol;
              }
            types::boundary_id id = bid_free;
            if (cell->material_id() == 1)
              {
                const double z_end = 0.5 * G.L_J();  // as meshed (zJ when aligned)
                if (on_journal)
                  id = bid_journal_surface;
                else if (std::abs(std::abs(journal_local(c)[2]) - z_end) < tol)
                  id = bid_journal_end;
                else if (!full && on_x0)
                  id = bid_sym_x;
                else if (!full_z && std::abs(c[2]) < tol)
                  id = bid_sym_z;
              }
            else if (on_inner)
              id = bid_contact;
            else if (on_outer)
              id = (c[1] > 0.0 ||
                    (plan_.rolling && scene_.rolling.support == Rolling::Support::outer_surface)) ?
                     bid_fixed :
                     bid_free;
            else if (!full && on_x0)
              id = bid_sym_x;
            else if (!full_z && std::abs(c[2]) < tol)
              id = bid_sym_z;
            face->set_boundary_id(id);
          }
  }

  /// True if the bore (r = R_B) within the cell's angular and axial extent comes closer than
  /// `limit` to the journal pushed to δ_max. Sampled on a 16 × 16 grid of the extent, not at
  /// the vertices only: a rim contact patch can be much smaller than a coarse cell.
  template <typename CellIterator>
  bool Bodies::bore_gap_below(const CellIterator &cell, const double limit) const
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
          Vec3 normal;
          if (plan_.obstacle.gap({X[0], X[1], X[2]}, scene_.loading.delta_max, g0, normal) &&
              g0 < limit)
            return true;
        }
    return false;
  }

  double rolling_path_distance(const FeScene &scene, const double angle, const double body_sweep)
  {
    const double sweep =
      body_sweep >= 0.0 ? body_sweep : scene.rolling.omega_B * rolling_end_time(scene);
    if (sweep >= 2.0 * units::pi)
      return 0.0;
    // the frame angles the contact point passes: [−sweep, 0] (mod 2π)
    const double a = std::remainder(angle, 2.0 * units::pi);  // (−π, π]
    if ((a <= 0.0 && a >= -sweep) || a - 2.0 * units::pi >= -sweep)
      return 0.0;
    return std::min(std::abs(std::remainder(a, 2.0 * units::pi)),
                    std::abs(std::remainder(a + sweep, 2.0 * units::pi)));
  }

  /// Global refinements, then `contact_refinements` rounds near the contact: the radial study
  /// refines the cells within contact_window_deg of the bottom (the mean vertex angle is the
  /// same for a bearing cell and the journal cell on the same rays); the misalignment study,
  /// whose contact is a small patch under one rim, the cells that hold contact candidates
  /// (a vertex within 2 δ_max of the journal pushed to δ_max; hanging nodes in the contact
  /// zone pass their force to their masters, see DofSpace::condense_hanging); the rolling study, the
  /// cells within the window of the arc the contact point travels over in the frame.
  void Bodies::refine_joint_mesh()
  {
    const auto &M = scene_.mesh;
    for (unsigned int k = 0; k < M.global_refinements; ++k)
      tria_.refine_global(1);
    const double window = M.contact_window_deg * units::deg;
    const bool by_gap = plan_.tilted;
    for (unsigned int k = 0; k < M.contact_refinements; ++k)
      {
        for (const auto &cell : tria_.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              if (by_gap)
                {
                  // a deformable journal's cell only at its surface (its inner cells span
                  // wide angles about the bearing axis and would all be refined)
                  bool at_surface = cell->material_id() == 0;
                  for (const auto v : cell->vertex_indices())
                    {
                      const Point<dim> l = journal_local(cell->vertex(v));
                      at_surface = at_surface || std::hypot(l[0], l[1] + scene_.geometry.c_r) >
                                                   scene_.geometry.R_J() - 0.5 * cell->diameter();
                    }
                  if (at_surface && bore_gap_below(cell, 2.0 * scene_.loading.delta_max))
                    cell->set_refine_flag();
                  continue;
                }
              if (plan_.rolling)
                {
                  // the contact point travels from frame angle 0 to −ω_B t_end over the bore;
                  // over a deformable journal's surface (its frame) from 0 to −γ_end, γ_end at
                  // most the rolling rate at δ_max times the run's time
                  const Point<dim> c = cell->center();
                  if (cell->material_id() == 0)
                    {
                      if (rolling_path_distance(scene_, std::atan2(c[0], -c[1])) < window)
                        cell->set_refine_flag();
                      continue;
                    }
                  const double y = c[1] + scene_.geometry.c_r;  // from the journal's axis
                  const bool at_surface =
                    std::hypot(c[0], y) > scene_.geometry.R_J() - cell->diameter();
                  const double gamma_end = scene_.rolling.omega_B *
                                           (scene_.geometry.R_B + scene_.loading.delta_max) /
                                           scene_.geometry.R_J() * rolling_end_time(scene_);
                  if (at_surface &&
                      rolling_path_distance(scene_, std::atan2(c[0], -y), gamma_end) < window)
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
}  // namespace clearjoint::fe::detail
