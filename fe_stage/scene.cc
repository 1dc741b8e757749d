#include "fe_stage/scene.h"

#include "common/error.h"
#include "common/strict_reader.h"
#include "common/units.h"
#include "geometry/joint_geometry.h"
#include "geometry/msh_check.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace clearjoint::fe
{
  std::string to_string(const Study s)
  {
    switch (s)
      {
        case Study::radial:
          return "radial";
        case Study::misalignment:
          return "misalignment";
        case Study::hertz:
          return "hertz";
        case Study::patch:
          return "patch";
        case Study::impact:
          return "impact";
        case Study::rolling:
          return "rolling";
      }
    return "?";
  }

  std::string to_string(const JournalLoading l)
  {
    switch (l)
      {
        case JournalLoading::end_faces:
          return "end_faces";
        case JournalLoading::axis_line:
          return "axis_line";
        case JournalLoading::core:
          return "core";
        case JournalLoading::rigid:
          return "rigid";
      }
    return "?";
  }

  std::string to_string(const Contact::Pairing p)
  {
    switch (p)
      {
        case Contact::Pairing::automatic:
          return "automatic";
        case Contact::Pairing::node_to_node:
          return "node_to_node";
        case Contact::Pairing::mortar:
          return "mortar";
      }
    return "?";
  }

  std::string to_string(const Contact::Sliding s)
  {
    return s == Contact::Sliding::finite ? "finite" : "small";
  }

  std::string to_string(const Contact::MortarSlave s)
  {
    switch (s)
      {
        case Contact::MortarSlave::automatic:
          return "automatic";
        case Contact::MortarSlave::bore:
          return "bore";
        case Contact::MortarSlave::journal:
          return "journal";
      }
    return "?";
  }

  namespace
  {
    unsigned int uint_or(StrictObject &o, const std::string &key, unsigned int fallback, long lo,
                         long hi)
    {
      return static_cast<unsigned int>(o.integer_or(key, fallback, lo, hi));
    }

    // --- reading: one reader per block of the scene -------------------------------------------
    // Each reads its block's keys into the block's struct (whose members hold the defaults) and
    // rejects the block's unknown keys (finish). Messages name the file and the key path.

    Study read_study(StrictObject &top)
    {
      const std::string study =
        top.string_or("study", "radial",
                      {"radial", "misalignment", "hertz", "patch", "impact", "rolling"});
      return study == "radial"       ? Study::radial :
             study == "misalignment" ? Study::misalignment :
             study == "hertz"        ? Study::hertz :
             study == "impact"       ? Study::impact :
             study == "rolling"      ? Study::rolling :
                                       Study::patch;
    }

    /// The defaults a study changes, set before the blocks are read (a block's key wins).
    void set_study_defaults(FeScene &s)
    {
      // The misalignment study's journal is rigid unless the scene says otherwise (SPEC §2: the
      // end-face loading drives the contact rim); validate_scene rejects any other choice.
      // The impact study's journal is rigid unless the scene says end_faces, axis_line or core: then it
      // is deformable, free in the time steps, and its quasi-static reference curve is pushed
      // that way (the thickness study's loading).
      if (s.study == Study::misalignment || s.study == Study::impact)
        s.loading.journal = JournalLoading::rigid;
      // The rolling study's defaults are the paper's §3.4 (SPEC §2): elastoplastic steel,
      // μ = 0.3, a push of 1 mm; its journal is rigid unless the scene sets loading.journal
      // core (deformable, in its own frame). Finite kinematics (issue 30): at the paper's push
      // the strains reach 0.5–1, where small strain is not the same problem (docs/fe.md
      // "Finite strain in the FE model"); material.kinematics small stays available.
      // Up to 10 cuts: the step size carries over, and a large step from rest may need
      // several (the paper's case at 16 steps on the coarsest ring: 5; at 32 or 64 steps, with
      // the line search: none; docs/benchmarks.md "The paper's rolling case at 1 mm").
      if (s.study == Study::rolling)
        {
          s.loading.journal = JournalLoading::rigid;
          s.loading.delta_max = 1.0e-3;
          s.loading.max_cuts = 10;
          s.contact.mu = 0.3;
          s.material.model = Material::Model::elastoplastic;
          s.material.kinematics = Material::Kinematics::finite;
        }
    }

    void read_geometry(StrictObject g, Geometry &G)
    {
      G.R_B = g.number_or("R_B", G.R_B, Range::positive("m"));
      G.t_B = g.number_or("t_B", G.t_B, Range::positive("m"));
      G.L_B = g.number_or("L_B", G.L_B, Range::positive("m"));
      G.c_r = g.number_or("c_r", G.c_r, Range::positive("m"));
      G.c_a = g.number_or("c_a", G.c_a, Range::positive("m"));
      if (g.has("mesh"))
        {
          G.mesh = g.string("mesh");
          // relative to the scene file's folder, like every other path in a scene
          const std::string &source = g.file();
          const std::filesystem::path p(G.mesh);
          if (p.is_relative() && !source.empty())
            G.mesh = (std::filesystem::path(source).parent_path() / p).lexically_normal().string();
          if (!std::filesystem::is_regular_file(G.mesh))
            g.fail("mesh", G.mesh, "an existing Gmsh MSH 2.2 file (.msh)",
                   "file not found (paths are relative to the scene file)");
        }
      // "Journal larger than bearing": R_J = R_B - c_r must stay positive, L_J = L_B - 2 c_a too.
      if (!(G.c_r < G.R_B))
        g.fail("c_r", format_value(G.c_r), "(0, R_B) m = (0, " + format_value(G.R_B) + ") m",
               "the journal radius R_J = R_B - c_r must be positive");
      if (!(2.0 * G.c_a < G.L_B))
        g.fail("c_a", format_value(G.c_a),
               "(0, L_B/2) m = (0, " + format_value(0.5 * G.L_B) + ") m",
               "the journal length L_J = L_B - 2 c_a must be positive and below L_B");
      g.finish();
    }

    /// material.hardening: a non-empty list of [eps_p, sigma_y] pairs, checked as a table.
    void read_hardening(StrictObject &m, Material &M)
    {
      const std::string key = m.path_of("hardening");
      const auto &raw = m.raw("hardening");
      if (!raw.is_array() || raw.empty())
        m.fail("hardening", raw.dump(),
               "a non-empty list of [eps_p, sigma_y] points (eps_p [-], sigma_y [Pa])");
      for (std::size_t i = 0; i < raw.size(); ++i)
        {
          const auto &pt = raw[i];
          if (!pt.is_array() || pt.size() != 2 || !pt[0].is_number() || !pt[1].is_number())
            throw InputError(m.file(), key + "[" + std::to_string(i) + "]", pt.dump(),
                             "a pair [eps_p, sigma_y] of numbers (eps_p [-], sigma_y [Pa])");
          M.hardening.push_back({pt[0].get<double>(), pt[1].get<double>()});
        }
      hardening_table(M, m.file(), key);  // the table's own checks
    }

    void read_material(StrictObject m, Material &M)
    {
      M.E = m.number_or("E", M.E, Range::positive("Pa"));
      M.nu = m.number_or("nu", M.nu, Range::open(-1.0, 0.5, ""));
      M.rho = m.number_or("rho", M.rho, Range::positive("kg/m^3"));
      M.yield_stress = m.number_or("yield_stress", M.yield_stress, Range::positive("Pa"));
      if (m.has("model"))
        M.model = m.string("model", {"elastic", "elastoplastic"}) == "elastoplastic" ?
                    Material::Model::elastoplastic :
                    Material::Model::elastic;
      if (m.has("kinematics"))
        M.kinematics = m.string("kinematics", {"small", "finite"}) == "finite" ?
                         Material::Kinematics::finite :
                         Material::Kinematics::small;
      if (m.has("hardening"))
        read_hardening(m, M);
      m.finish();
    }

    void read_contact(StrictObject c, Contact &C)
    {
      C.mu = c.number_or("mu", C.mu, Range::closed(0.0, 10.0, ""));
      C.active_set_scale =
        c.number_or("active_set_scale", C.active_set_scale, Range::open(0.0, 1.0e12, ""));
      C.tangential_scale =
        c.number_or("tangential_scale", C.tangential_scale, Range::open(0.0, 1.0e12, ""));
      C.max_iterations = uint_or(c, "max_iterations", C.max_iterations, 1, 10000);
      const std::string pairing =
        c.string_or("pairing", "automatic", {"automatic", "node_to_node", "mortar"});
      C.pairing = pairing == "node_to_node" ? Contact::Pairing::node_to_node :
                  pairing == "mortar"       ? Contact::Pairing::mortar :
                                              Contact::Pairing::automatic;
      const std::string slave =
        c.string_or("mortar_slave", "automatic", {"automatic", "bore", "journal"});
      C.mortar_slave = slave == "bore"    ? Contact::MortarSlave::bore :
                       slave == "journal" ? Contact::MortarSlave::journal :
                                            Contact::MortarSlave::automatic;
      C.sliding = c.string_or("sliding", "small", {"small", "finite"}) == "finite" ?
                    Contact::Sliding::finite :
                    Contact::Sliding::small;
      c.finish();
    }

    void read_loading(StrictObject l, Loading &L)
    {
      const std::string journal =
        l.string_or("journal", to_string(L.journal), {"end_faces", "axis_line", "core", "rigid"});
      L.journal = journal == "end_faces" ? JournalLoading::end_faces :
                  journal == "axis_line" ? JournalLoading::axis_line :
                  journal == "core"      ? JournalLoading::core :
                                           JournalLoading::rigid;
      L.delta_max = l.number_or("delta_max", L.delta_max, Range::positive("m"));
      L.n_increments = uint_or(l, "n_increments", L.n_increments, 1, 100000);
      L.max_cuts = uint_or(l, "max_cuts", L.max_cuts, 0, 20);
      L.axial_offset = l.number_or("axial_offset", L.axial_offset, Range::closed(-1.0, 1.0, "m"));
      L.axial_slide = l.number_or("axial_slide", L.axial_slide, Range::closed(-1.0, 1.0, "m"));
      l.finish();
    }

    void read_mesh(StrictObject m, Mesh &M)
    {
      M.degree = uint_or(m, "degree", M.degree, 1, 2);
      M.n_circumferential = uint_or(m, "n_circumferential", M.n_circumferential, 4, 4096);
      if (M.n_circumferential % 4 != 0)
        m.fail("n_circumferential", std::to_string(M.n_circumferential),
               "a multiple of 4 in [4, 4096]");
      M.n_radial = uint_or(m, "n_radial", M.n_radial, 0, 1024);
      M.n_axial = uint_or(m, "n_axial", M.n_axial, 1, 4096);
      M.global_refinements = uint_or(m, "global_refinements", M.global_refinements, 0, 6);
      M.contact_refinements = uint_or(m, "contact_refinements", M.contact_refinements, 0, 8);
      M.contact_window_deg =
        m.number_or("contact_window_deg", M.contact_window_deg, Range::open(0.0, 180.0, "deg"));
      M.adaptive_cycles = uint_or(m, "adaptive_cycles", M.adaptive_cycles, 0, 8);
      M.adaptive_fraction =
        m.number_or("adaptive_fraction", M.adaptive_fraction, Range::open(0.0, 1.0, ""));
      M.adaptive_increments = uint_or(m, "adaptive_increments", M.adaptive_increments, 1, 1000);
      M.adaptive_target_error =
        m.number_or("adaptive_target_error", M.adaptive_target_error,
                    Range{.lo = 0.0, .hi = 0.5, .hi_open = true, .unit = ""});
      // the estimate extrapolates through three meshes: a target needs two cycles at least
      if (M.adaptive_target_error > 0.0 && M.adaptive_cycles < 2)
        m.fail("adaptive_cycles", std::to_string(M.adaptive_cycles),
               "2..8 with mesh.adaptive_target_error > 0 (the most cycles allowed: the error "
               "is estimated by extrapolating through three meshes)");
      m.finish();
    }

    void read_solver(StrictObject o, Solver &S)
    {
      const std::string lin = o.string_or("linear", "automatic", {"automatic", "cg_amg", "direct"});
      S.linear = lin == "automatic" ? LinearSolver::automatic :
                 lin == "cg_amg"    ? LinearSolver::cg_amg :
                                      LinearSolver::direct;
      S.tolerance = o.number_or("tolerance", S.tolerance, Range::open(0.0, 1.0e-2, ""));
      S.max_linear_iterations =
        uint_or(o, "max_linear_iterations", S.max_linear_iterations, 1, 1000000);
      S.direct_below_dofs = uint_or(o, "direct_below_dofs", S.direct_below_dofs, 0, 100000000);
      S.max_newton_iterations =
        uint_or(o, "max_newton_iterations", S.max_newton_iterations, 1, 1000);
      S.line_search = o.boolean_or("line_search", S.line_search);
      o.finish();
    }

    void read_verification(StrictObject v, Verification &V)
    {
      V.sphere_radius = v.number_or("sphere_radius", V.sphere_radius, Range::positive("m"));
      V.block_width = v.number_or("block_width", V.block_width, Range::positive("m"));
      V.block_height = v.number_or("block_height", V.block_height, Range::positive("m"));
      V.n_cells = uint_or(v, "n_cells", V.n_cells, 1, 256);
      V.contact_refinements = uint_or(v, "contact_refinements", V.contact_refinements, 0, 10);
      V.refine_radius = v.number_or("refine_radius", V.refine_radius, Range::positive("m"));
      V.deformable_indenter =
        v.string_or("indenter", V.deformable_indenter ? "deformable" : "rigid",
                    {"rigid", "deformable"}) == "deformable";
      V.indenter_n_cells = uint_or(v, "indenter_n_cells", V.indenter_n_cells, 1, 256);
      V.indenter_height = v.number_or("indenter_height", V.indenter_height, Range::positive("m"));
      v.finish();
    }

    /// After the geometry: theta_max is paper Eq. 3 for this joint.
    void read_misalignment(StrictObject m, Misalignment &M, const Geometry &G)
    {
      // a number [deg], or the word theta_max: the largest tilt of paper Eq. 3 for this geometry
      if (m.has("theta_deg") && m.raw("theta_deg").is_string())
        {
          const std::string word = m.string("theta_deg");
          if (word != "theta_max")
            m.fail("theta_deg", word, "a number of degrees in [0, theta_max] or 'theta_max'");
          M.theta_deg = theta_max_deg(G, m.file(), m.path_of("theta_deg"));
        }
      else
        M.theta_deg = m.number_or("theta_deg", M.theta_deg, Range::closed(0.0, 90.0, "deg"));
      m.finish();
    }

    void read_output(StrictObject o, Output &O)
    {
      O.fields = o.boolean_or("fields", O.fields);
      o.finish();
    }

    void read_impact(StrictObject o, Impact &I)
    {
      I.velocity = o.number_or("velocity", I.velocity, Range::open(0.0, 100.0, "m/s"));
      {
        const std::string app =
          o.string_or("application", application_name(I.application),
                      {"transient_fidelity", "moderate_dissipation", "quasi_static"});
        I.application = app == "transient_fidelity" ? DynamicApplication::transient_fidelity :
                        app == "quasi_static"       ? DynamicApplication::quasi_static :
                                                      DynamicApplication::moderate_dissipation;
      }
      if (o.has("alpha"))
        I.alpha = o.number("alpha", Range::closed(HhtAlpha::alpha_min, HhtAlpha::alpha_max, ""));
      I.steps_per_period = uint_or(o, "steps_per_period", I.steps_per_period, 10, 100000);
      if (o.has("time_step"))
        I.time_step = o.number("time_step", Range::positive("s"));
      if (o.has("end_time"))
        I.end_time = o.number("end_time", Range::positive("s"));
      if (o.has("journal_mass"))
        I.journal_mass = o.number("journal_mass", Range::positive("kg"));
      I.max_steps = uint_or(o, "max_steps", I.max_steps, 1, 1000000);
      I.field_stride = uint_or(o, "field_stride", I.field_stride, 1, 1000000);
      const std::string mass =
        o.string_or("mass", "redistributed", {"redistributed", "lumped", "consistent"});
      I.mass = mass == "lumped"     ? Impact::Mass::lumped :
               mass == "consistent" ? Impact::Mass::consistent :
                                      Impact::Mass::redistributed;
      o.finish();
    }

    void read_rolling(StrictObject o, Rolling &R)
    {
      R.omega_B = o.number_or("omega_B", R.omega_B, Range::open(0.0, 1.0e4, "rad/s"));
      R.ramp_time = o.number_or("ramp_time", R.ramp_time, Range::open(0.0, 1.0e6, "s"));
      if (o.has("end_time"))
        R.end_time = o.number("end_time", Range::open(0.0, 1.0e6, "s"));
      R.n_steps = uint_or(o, "n_steps", R.n_steps, 4, 1000000);
      R.support =
        o.string_or("support", "outer_surface", {"outer_surface", "upper_half"}) == "upper_half" ?
          Rolling::Support::upper_half :
          Rolling::Support::outer_surface;
      if (o.has("journal_inertia"))
        R.journal_inertia = o.number("journal_inertia", Range::open(0.0, 1.0e6, "kg m^2"));
      {
        const std::string spin =
          o.string_or("spin_solver", "bordered", {"bordered", "coupled", "nested"});
        R.spin_solver = spin == "bordered" ? Rolling::SpinSolver::bordered :
                        spin == "nested"   ? Rolling::SpinSolver::nested :
                                             Rolling::SpinSolver::coupled;
      }
      R.max_spin_iterations = uint_or(o, "max_spin_iterations", R.max_spin_iterations, 1, 10000);
      R.max_newton_iterations =
        uint_or(o, "max_newton_iterations", R.max_newton_iterations, 1, 1000);
      R.field_stride = uint_or(o, "field_stride", R.field_stride, 1, 1000000);
      o.finish();
    }

    /// sweep.theta_deg: numbers [deg] and the word theta_max (paper Eq. 3 for this geometry).
    std::vector<double> read_theta_list(StrictObject &w, const Geometry &G)
    {
      std::vector<double> thetas;
      const auto &raw = w.raw("theta_deg");
      if (!raw.is_array() || raw.empty())
        w.fail("theta_deg", raw.dump(), "a non-empty list of angles in degrees");
      for (std::size_t i = 0; i < raw.size(); ++i)
        {
          const std::string key = "theta_deg." + std::to_string(i);
          if (raw[i].is_string() && raw[i].get<std::string>() == "theta_max")
            thetas.push_back(theta_max_deg(G, w.file(), w.path_of(key)));
          else if (raw[i].is_number())
            thetas.push_back(raw[i].get<double>());
          else
            w.fail(key, raw[i].dump(), "a number of degrees or 'theta_max'");
        }
      return thetas;
    }

    /// sweep.journal_mass: masses [kg] and the word `own` (the rigid journal's ρ π R_J² L_J
    /// from the geometry and material read before).
    std::vector<double> read_mass_list(StrictObject &w, const FeScene &s)
    {
      std::vector<double> masses;
      const auto &raw = w.raw("journal_mass");
      if (!raw.is_array() || raw.empty())
        w.fail("journal_mass", raw.dump(), "a non-empty list of masses in kg (or 'own')");
      for (std::size_t i = 0; i < raw.size(); ++i)
        {
          const std::string key = "journal_mass." + std::to_string(i);
          if (raw[i].is_string() && raw[i].get<std::string>() == "own")
            {
              FeScene own = s;
              own.impact.journal_mass = 0.0;
              masses.push_back(rigid_journal_mass(own));
            }
          else if (raw[i].is_number() && raw[i].get<double>() > 0.0 &&
                   std::isfinite(raw[i].get<double>()))
            masses.push_back(raw[i].get<double>());
          else
            w.fail(key, raw[i].dump(),
                   "(0, inf) kg or 'own' (the rigid journal's rho pi R_J^2 L_J)");
        }
      return masses;
    }

    /// After the study, the geometry, the material and the impact block: one swept parameter,
    /// the study's own — or, for study impact, the velocity and the journal mass together
    /// (every pair).
    void read_sweep(StrictObject w, FeScene &s)
    {
      if (w.has("velocity"))
        s.sweep_velocity = w.number_array("velocity", Range::open(0.0, 100.0, "m/s"), 1);
      if (w.has("journal_mass"))
        s.sweep_journal_mass = read_mass_list(w, s);
      if (w.has("t_B"))
        s.sweep_t_B = w.number_array("t_B", Range::positive("m"), 1);
      if (w.has("theta_deg"))
        s.sweep_theta_deg = read_theta_list(w, s.geometry);
      const bool impact_sweep = !s.sweep_velocity.empty() || !s.sweep_journal_mass.empty();
      if (s.sweep_t_B.empty() && s.sweep_theta_deg.empty() && !impact_sweep)
        w.fail("t_B", "(none)",
               "sweep needs t_B [m], theta_deg [deg], velocity [m/s] or journal_mass [kg]");
      if (int(!s.sweep_t_B.empty()) + int(!s.sweep_theta_deg.empty()) + int(impact_sweep) > 1)
        w.fail(impact_sweep ? (s.sweep_velocity.empty() ? "journal_mass" : "velocity") :
                              "theta_deg",
               "(given with another)",
               "one swept parameter per scene (velocity and journal_mass together: study impact)");
      if (!s.sweep_velocity.empty() && s.study != Study::impact)
        w.fail("velocity", "(list)", "study impact only");
      if (!s.sweep_journal_mass.empty() && s.study != Study::impact)
        w.fail("journal_mass", "(list)", "study impact only");
      if (!s.sweep_theta_deg.empty() && s.study != Study::misalignment)
        w.fail("theta_deg", "(list)", "study misalignment only");
      w.finish();
    }
  }  // namespace

  FeScene scene_from_json(const nlohmann::json &j, const std::string &source)
  {
    FeScene s;
    s.source_file = source;
    StrictObject top(j, source);
    top.expect_schema("clearjoint.fe/1");
    s.study = read_study(top);
    set_study_defaults(s);
    s.full_model = top.boolean_or("full_model", false);
    // in this order: misalignment and sweep read theta_max from the geometry
    if (top.has("geometry"))
      read_geometry(top.object("geometry"), s.geometry);
    if (top.has("material"))
      read_material(top.object("material"), s.material);
    if (top.has("contact"))
      read_contact(top.object("contact"), s.contact);
    if (top.has("loading"))
      read_loading(top.object("loading"), s.loading);
    if (top.has("mesh"))
      read_mesh(top.object("mesh"), s.mesh);
    if (top.has("solver"))
      read_solver(top.object("solver"), s.solver);
    if (top.has("verification"))
      read_verification(top.object("verification"), s.verification);
    if (top.has("misalignment"))
      read_misalignment(top.object("misalignment"), s.misalignment, s.geometry);
    if (top.has("output"))
      read_output(top.object("output"), s.output);
    if (top.has("impact"))
      read_impact(top.object("impact"), s.impact);
    if (top.has("rolling"))
      read_rolling(top.object("rolling"), s.rolling);
    if (top.has("sweep"))
      read_sweep(top.object("sweep"), s);
    top.finish();
    validate_scene(s);
    return s;
  }

  namespace
  {
    // --- validation: the constraints between keys, one validator per block --------------------
    // validate_scene also checks scenes made in code (tests, sweeps), so the blocks' own ranges
    // are checked again here.

    void validate_geometry(const FeScene &s)
    {
      const auto &G = s.geometry;
      const std::string &f = s.source_file;
      if (!(G.c_r > 0.0))
        throw InputError(f, "geometry.c_r", format_value(G.c_r), "(0, R_B) m");
      if (!(G.t_B > 0.0))
        throw InputError(f, "geometry.t_B", format_value(G.t_B), "(0, inf) m");
      if (!(G.c_r < G.R_B))
        throw InputError(f, "geometry.c_r", format_value(G.c_r), "(0, R_B) m",
                         "journal larger than the bearing");
      if (!(G.c_a > 0.0 && 2.0 * G.c_a < G.L_B))
        throw InputError(f, "geometry.c_a", format_value(G.c_a), "(0, L_B/2) m",
                         "L_J = L_B - 2 c_a must lie in (0, L_B)");
    }

    void validate_loading(const FeScene &s)
    {
      if (!(s.loading.delta_max > 0.0))
        throw InputError(s.source_file, "loading.delta_max", format_value(s.loading.delta_max),
                         "(0, inf) m");
    }

    void validate_mesh(const FeScene &s)
    {
      if (is_joint_study(s.study) && s.full_model && s.mesh.n_circumferential < 8)
        throw InputError(s.source_file, "mesh.n_circumferential",
                         std::to_string(s.mesh.n_circumferential), ">= 8 for the full model");
    }

    void validate_sweep_t_B(const FeScene &s)
    {
      for (const double t : s.sweep_t_B)
        if (!(t > 0.0))
          throw InputError(s.source_file, "sweep.t_B", format_value(t), "(0, inf) m");
    }

    void validate_sweep_velocity(const FeScene &s)
    {
      for (const double v : s.sweep_velocity)
        if (!(v > 0.0 && v < 100.0))
          throw InputError(s.source_file, "sweep.velocity", format_value(v), "(0, 100) m/s");
    }

    /// sweep.journal_mass: positive, the rigid journal only (a deformable journal's mass is its
    /// mesh's), and not together with impact.journal_mass (which would be overridden).
    void validate_sweep_journal_mass(const FeScene &s)
    {
      const std::string &f = s.source_file;
      for (std::size_t i = 0; i < s.sweep_journal_mass.size(); ++i)
        if (!(s.sweep_journal_mass[i] > 0.0 && std::isfinite(s.sweep_journal_mass[i])))
          throw InputError(f, "sweep.journal_mass." + std::to_string(i),
                           format_value(s.sweep_journal_mass[i]), "(0, inf) kg");
      if (s.sweep_journal_mass.empty())
        return;
      if (s.loading.journal != JournalLoading::rigid)
        throw InputError(f, "sweep.journal_mass", "(list)", "only with loading.journal: rigid",
                         "a deformable journal's mass is its mesh's (material.rho)");
      if (s.impact.journal_mass > 0.0)
        throw InputError(f, "impact.journal_mass", format_value(s.impact.journal_mass),
                         "absent when sweep.journal_mass is given",
                         "the sweep sets the journal mass of every case");
    }

    /// Study impact.
    void validate_impact(const FeScene &s)
    {
      const auto &I = s.impact;
      const std::string &f = s.source_file;
      if (!(I.velocity > 0.0 && I.velocity < 100.0))
        throw InputError(f, "impact.velocity", format_value(I.velocity), "(0, 100) m/s");
      if (I.alpha && !(*I.alpha >= HhtAlpha::alpha_min && *I.alpha <= HhtAlpha::alpha_max))
        throw InputError(f, "impact.alpha", format_value(*I.alpha), "[-1/2, 0]",
                         "Hilber-Hughes-Taylor alpha (Abaqus's range), overriding "
                         "impact.application's; 0 = trapezoidal rule, no numerical damping");
      if (I.alpha && I.application == DynamicApplication::quasi_static)
        throw InputError(f, "impact.alpha", format_value(*I.alpha),
                         "no value with impact.application quasi_static",
                         "quasi_static is backward Euler, which has no alpha; give alpha with "
                         "transient_fidelity or moderate_dissipation");
      if (I.steps_per_period < 10)
        throw InputError(f, "impact.steps_per_period", std::to_string(I.steps_per_period), ">= 10",
                         "the time step must resolve the contact period (dt/T <= 1/10)");
      if (!(I.time_step >= 0.0))
        throw InputError(f, "impact.time_step", format_value(I.time_step), "(0, inf) s");
      if (!(I.end_time >= 0.0))
        throw InputError(f, "impact.end_time", format_value(I.end_time), "(0, inf) s");
      if (!(I.journal_mass >= 0.0))
        throw InputError(f, "impact.journal_mass", format_value(I.journal_mass), "(0, inf) kg");
      if (I.journal_mass > 0.0 && s.loading.journal != JournalLoading::rigid)
        throw InputError(f, "impact.journal_mass", format_value(I.journal_mass),
                         "only with loading.journal: rigid",
                         "a deformable journal's mass is its mesh's (material.rho)");
    }

    /// Study rolling.
    void validate_rolling(const FeScene &s)
    {
      const auto &R = s.rolling;
      const std::string &f = s.source_file;
      if (!(R.omega_B > 0.0 && R.omega_B < 1.0e4))
        throw InputError(f, "rolling.omega_B", format_value(R.omega_B), "(0, 1e4) rad/s");
      if (!(R.ramp_time > 0.0))
        throw InputError(f, "rolling.ramp_time", format_value(R.ramp_time), "(0, inf) s");
      if (R.end_time != 0.0 && !(R.end_time >= R.ramp_time))
        throw InputError(f, "rolling.end_time", format_value(R.end_time),
                         "[ramp_time, inf) s = [" + format_value(R.ramp_time) + ", inf) s",
                         "the run holds delta_max after the ramp; it cannot stop inside it");
      // A step carries the contact patch along the bore by the bearing's turn in it. Beyond a
      // quarter turn a step no longer follows the patch (it lands on bore it never pressed),
      // and the run only cuts its way through: measured at omega_B 1e3 rad/s with 32 steps
      // over 0.25 s (7.8 rad a step), 173 steps after cuts and 6 min on the coarsest ring for
      // a result no finer step was checked against.
      const double turn = R.omega_B * rolling_end_time(s);  // [rad] over the run
      const double turn_per_step = turn / R.n_steps;
      if (turn_per_step > 0.5 * units::pi)
        {
          const auto needed = static_cast<unsigned long>(std::ceil(turn / (0.5 * units::pi)));
          throw InputError(f, "rolling.n_steps", std::to_string(R.n_steps),
                           ">= " + std::to_string(needed) + " at omega_B " +
                             format_value(R.omega_B) + " rad/s over " +
                             format_value(rolling_end_time(s)) + " s",
                           "a step may turn the bearing by a quarter turn at most (this one: " +
                             format_value(turn_per_step) +
                             " rad); raise rolling.n_steps or lower rolling.omega_B");
        }
      if (s.loading.journal != JournalLoading::rigid && s.loading.journal != JournalLoading::core)
        throw InputError(f, "loading.journal", to_string(s.loading.journal),
                         "rigid or core for study rolling",
                         "the deformable journal is computed in its own frame, which carries "
                         "the push and the spin; its core r <= R_J/2 is clamped there");
      if (s.loading.journal == JournalLoading::core &&
          s.contact.pairing == Contact::Pairing::node_to_node)
        throw InputError(f, "contact.pairing", "node_to_node",
                         "mortar or automatic for study rolling",
                         "the turning journal's nodes leave the bore's rays");
      if (s.loading.journal == JournalLoading::core &&
          s.contact.mortar_slave == Contact::MortarSlave::journal)
        throw InputError(f, "contact.mortar_slave", "journal",
                         "bore or automatic for study rolling",
                         "the rolling study's contact rows, outputs and strain profile are "
                         "on the bore's nodes");
      if (s.material.model != Material::Model::elastoplastic)
        throw InputError(f, "material.model", "elastic", "elastoplastic for study rolling");
      if (s.mesh.adaptive_cycles > 0)
        throw InputError(f, "mesh.adaptive_cycles", std::to_string(s.mesh.adaptive_cycles),
                         "0 for study rolling", "the rolling study runs on one mesh");
      if (!s.geometry.mesh.empty())
        throw InputError(f, "geometry.mesh", s.geometry.mesh, "no mesh file for study rolling",
                         "the rolling study generates the whole ring (the contact zone "
                         "travels half way round the bore)");
      if (s.full_model)
        throw InputError(f, "full_model", "true", "false for study rolling",
                         "the rolling study always models the whole ring and uses the axial "
                         "mid-plane");
    }

    /// Plasticity: the rolling study (validate_rolling insists on it) and the patch test's
    /// block under the rigid flat (the elastoplastic quasi-static push, checked against the
    /// point law); elsewhere the model stays elastic and reports where von Mises exceeds
    /// material.yield_stress. Finite kinematics: the J2 law in the patch test, so far.
    void validate_material(const FeScene &s)
    {
      const std::string &f = s.source_file;
      const bool elastoplastic = s.material.model == Material::Model::elastoplastic;
      const bool patch = s.study == Study::patch;
      if (elastoplastic && s.study != Study::rolling && !patch)
        throw InputError(f, "material.model", "elastoplastic",
                         "elastic for study " + to_string(s.study),
                         "only the rolling study and the patch test integrate plasticity; the "
                         "others report where von Mises exceeds material.yield_stress");
      if (elastoplastic && patch && s.verification.deformable_indenter)
        throw InputError(f, "verification.indenter", "deformable",
                         "rigid with material.model elastoplastic",
                         "the elastoplastic patch test presses the rigid flat");
      if (elastoplastic && patch && s.mesh.adaptive_cycles > 0)
        throw InputError(f, "mesh.adaptive_cycles", std::to_string(s.mesh.adaptive_cycles),
                         "0 with material.model elastoplastic",
                         "the quadrature-point history is not carried to a refined mesh");
      // (elastoplastic: the patch test and the rolling study, above)
      if (s.material.kinematics == Material::Kinematics::finite && !elastoplastic)
        throw InputError(f, "material.kinematics", "finite", "small with material.model elastic",
                         "finite strain is implemented for the J2 law "
                         "(material.model: elastoplastic)");
    }

    /// Study misalignment: the journal's loading and the tilt (with the swept tilts).
    void validate_misalignment(const FeScene &s)
    {
      const auto &G = s.geometry;
      const std::string &f = s.source_file;
      if (s.loading.journal != JournalLoading::rigid && s.loading.journal != JournalLoading::core)
        throw InputError(f, "loading.journal", to_string(s.loading.journal),
                         "rigid or core for study misalignment",
                         "SPEC §2: with end_faces or axis_line loading the rim that carries the "
                         "contact is itself driven (a line load whose force does not converge "
                         "with the mesh)");
      if (s.loading.journal == JournalLoading::core && !G.mesh.empty())
        throw InputError(f, "loading.journal", "core",
                         "rigid for study misalignment with geometry.mesh",
                         "the deformable tilted journal is generated (meshed aligned, then "
                         "turned by theta); a Gmsh journal is not tilted");
      if (s.loading.journal == JournalLoading::core &&
          s.contact.mortar_slave == Contact::MortarSlave::bore)
        throw InputError(f, "contact.mortar_slave", "bore",
                         "journal or automatic for study misalignment",
                         "the tilted journal bears on the bore with its rim: the bore faces "
                         "around the rim's trace are only partly covered by the journal, and "
                         "their nodes would drop out of the contact exactly where it is");
      const auto jg = joint_geometry(G);
      geometry::check_tilt(jg, geometry::radians(s.misalignment.theta_deg), f,
                           "misalignment.theta_deg");
      for (std::size_t i = 0; i < s.sweep_theta_deg.size(); ++i)
        geometry::check_tilt(jg, geometry::radians(s.sweep_theta_deg[i]), f,
                             "sweep.theta_deg." + std::to_string(i));
    }

    /// The other body is meshed: two deformable bodies, to which pairing, the mortar slave
    /// side and finite sliding apply.
    bool has_deformable_journal(const FeScene &s)
    {
      return is_joint_study(s.study) && s.loading.journal != JournalLoading::rigid;
    }
    bool has_deformable_indenter(const FeScene &s)
    {
      return !is_joint_study(s.study) && s.verification.deformable_indenter;
    }

    /// contact.pairing
    void validate_pairing(const FeScene &s)
    {
      using Pairing = Contact::Pairing;
      const std::string &f = s.source_file;
      const bool deformable_journal = has_deformable_journal(s);
      const bool deformable_indenter = has_deformable_indenter(s);
      if (s.contact.pairing == Pairing::automatic)
        return;
      if (!deformable_journal && !deformable_indenter)
        throw InputError(f, "contact.pairing", to_string(s.contact.pairing),
                         "automatic when the other body is rigid",
                         "pairing couples two deformable bodies: set loading.journal to "
                         "end_faces, axis_line or core (or verification.deformable_indenter)");
      if (deformable_journal && s.contact.pairing == Pairing::node_to_node &&
          s.mesh.adaptive_cycles > 0)
        throw InputError(f, "contact.pairing", "node_to_node",
                         "mortar or automatic with mesh.adaptive_cycles > 0",
                         "adaptive refinement refines the bore and the journal differently, "
                         "so their nodes no longer lie on common rays");
      if (deformable_journal && s.contact.pairing == Pairing::node_to_node &&
          s.study == Study::misalignment)
        throw InputError(f, "contact.pairing", "node_to_node",
                         "mortar or automatic for study misalignment",
                         "the tilted journal's nodes do not lie on the bore's rays");
      if (deformable_indenter && s.contact.pairing == Pairing::node_to_node)
        throw InputError(f, "contact.pairing", "node_to_node",
                         "mortar or automatic for the verification blocks",
                         "the block and its indenter are meshed independently: their "
                         "nodes do not face each other");
    }

    /// loading.axial_offset and axial_slide: an axially moved journal's ends no longer lie on
    /// the bore's mesh planes, so its surface must be the mortar slave (it lies wholly over the
    /// longer bore), and it must stay within the bore (beyond the bore's end its faces would
    /// have no partner).
    void validate_axial_motion(const FeScene &s)
    {
      const auto &G = s.geometry;
      const std::string &f = s.source_file;
      if (s.loading.axial_offset == 0.0 && s.loading.axial_slide == 0.0)
        return;
      const char *key =
        s.loading.axial_offset != 0.0 ? "loading.axial_offset" : "loading.axial_slide";
      const std::string value = format_value(
        s.loading.axial_offset != 0.0 ? s.loading.axial_offset : s.loading.axial_slide);
      if (s.study != Study::radial || s.loading.journal != JournalLoading::core || !G.mesh.empty())
        throw InputError(f, key, value, "0 unless study radial with loading.journal core",
                         "the journal is moved axially at its core; a generated mesh only");
      if (s.contact.mortar_slave == Contact::MortarSlave::bore ||
          s.contact.pairing == Contact::Pairing::node_to_node)
        throw InputError(f, key, value, "0 with contact.mortar_slave bore or node_to_node",
                         "the journal's ends leave the bore's mesh planes: the journal's "
                         "surface must be the mortar slave (contact.mortar_slave automatic)");
      const double c_a = G.c_a * (1.0 + 1e-12);
      if (std::abs(s.loading.axial_offset) > c_a)
        throw InputError(f, "loading.axial_offset", format_value(s.loading.axial_offset),
                         "[-c_a, c_a] = [-" + format_value(G.c_a) + ", " + format_value(G.c_a) +
                           "] m",
                         "the journal must stay within the bore");
      if (std::abs(s.loading.axial_offset + s.loading.axial_slide) > c_a)
        throw InputError(f, "loading.axial_slide", format_value(s.loading.axial_slide),
                         "axial_offset + axial_slide within [-c_a, c_a] = [-" +
                           format_value(G.c_a) + ", " + format_value(G.c_a) + "] m",
                         "the journal must stay within the bore");
    }

    /// contact.sliding
    void validate_sliding(const FeScene &s)
    {
      if (s.contact.sliding == Contact::Sliding::finite &&
          ((!has_deformable_journal(s) && !has_deformable_indenter(s)) ||
           s.contact.pairing == Contact::Pairing::node_to_node || s.study == Study::impact ||
           s.study == Study::rolling))
        throw InputError(s.source_file, "contact.sliding", "finite",
                         "small unless two deformable bodies meet by mortar (quasi-static)",
                         "finite sliding redoes the mortar search at the deformed surfaces after "
                         "each increment; a rigid obstacle's gap is exact already, common rays "
                         "cannot follow sliding, the impact study's time steps do not redo it, "
                         "and the rolling study redoes it at every time step anyway");
    }

    /// contact.mortar_slave
    void validate_mortar_slave(const FeScene &s)
    {
      const std::string &f = s.source_file;
      if (s.contact.mortar_slave == Contact::MortarSlave::automatic)
        return;
      if (!has_deformable_journal(s) || s.contact.pairing == Contact::Pairing::node_to_node)
        throw InputError(f, "contact.mortar_slave", to_string(s.contact.mortar_slave),
                         "automatic unless a deformable journal meets the bore by mortar",
                         "set loading.journal to end_faces, axis_line or core, and "
                         "contact.pairing to mortar or automatic");
      if (s.contact.mortar_slave == Contact::MortarSlave::journal &&
          s.loading.journal != JournalLoading::core)
        throw InputError(f, "contact.mortar_slave", "journal",
                         "bore or automatic with loading.journal " + to_string(s.loading.journal),
                         "the slave's nodes carry the contact constraints, and the journal's "
                         "surface nodes are driven by that loading: use loading.journal core");
    }

    /// loading.delta_max against the joint: the push stays inside the journal.
    void validate_push_depth(const FeScene &s)
    {
      if (is_joint_study(s.study) && s.loading.delta_max >= s.geometry.R_J())
        throw InputError(s.source_file, "loading.delta_max", format_value(s.loading.delta_max),
                         "(0, R_J) m", "the push must be smaller than the journal radius");
    }
  }  // namespace

  void validate_scene(const FeScene &s)
  {
    // in this order: with several faults, the first check that fails names its key
    validate_geometry(s);
    validate_loading(s);
    validate_mesh(s);
    validate_sweep_t_B(s);
    if (s.study == Study::impact)
      validate_impact(s);
    if (s.study == Study::rolling)
      validate_rolling(s);
    validate_material(s);
    validate_sweep_velocity(s);
    validate_sweep_journal_mass(s);
    if (s.study == Study::misalignment)
      validate_misalignment(s);
    validate_pairing(s);
    validate_axial_motion(s);
    validate_sliding(s);
    validate_mortar_slave(s);
    if (!s.geometry.mesh.empty())
      check_mesh_against_scene(s);
    validate_push_depth(s);
  }

  double rolling_journal_inertia(const FeScene &scene)
  {
    if (scene.rolling.journal_inertia > 0.0)
      return scene.rolling.journal_inertia;
    const double R = scene.geometry.R_J();
    const double m = scene.material.rho * units::pi * R * R * scene.geometry.L_J();
    return 0.5 * m * R * R;
  }

  double rolling_end_time(const FeScene &scene)
  {
    return scene.rolling.end_time > 0.0 ? scene.rolling.end_time : scene.rolling.ramp_time;
  }

  HardeningTable hardening_table(const Material &m, const std::string &file,
                                 const std::string &key_path)
  {
    if (m.hardening.empty())
      return HardeningTable::spec_default();
    std::vector<HardeningPoint> pts;
    for (const auto &p : m.hardening)
      pts.push_back({p[0], p[1]});
    return HardeningTable(std::move(pts), key_path, file);
  }

  geometry::JointGeometry joint_geometry(const Geometry &g)
  {
    geometry::JointGeometry j;
    j.R_B = g.R_B;
    j.t_B = g.t_B;
    j.L_B = g.L_B;
    j.c_r = g.c_r;
    j.c_a = g.c_a;
    return j;
  }

  double theta_max_deg(const Geometry &g, const std::string &file, const std::string &key)
  {
    const auto t = geometry::theta_max(joint_geometry(g));
    if (!t)
      throw InputError(file, key, "theta_max", "a number of degrees",
                       "paper Eq. 3 has no root for this geometry: the journal can turn over "
                       "inside the bearing, so there is no largest tilt");
    return geometry::degrees(*t);
  }

  /// A Gmsh mesh must be usable (geometry::read_joint_mesh: groups, hexahedra, no inverted
  /// cells) and describe the scene's joint, before any output is written.
  void check_mesh_against_scene(const FeScene &s)
  {
    const auto &G = s.geometry;
    const std::string &f = s.source_file;
    if (!is_joint_study(s.study))
      throw InputError(f, "geometry.mesh", G.mesh, "study radial, misalignment or impact",
                       "the verification problems generate their own block");
    const bool deformable_journal = s.loading.journal != JournalLoading::rigid;
    if (deformable_journal && s.contact.pairing == Contact::Pairing::node_to_node)
      throw InputError(f, "contact.pairing", "node_to_node",
                       "mortar or automatic when geometry.mesh has the deformable journal",
                       "a Gmsh mesh's journal and bore do not share rays: they are paired by "
                       "dual mortar");
    const geometry::MshMesh msh = geometry::read_joint_mesh(G.mesh);
    // The bore must be the scene's: the rigid journal is placed from R_B and c_r.
    const double tol = 1e-6 * G.R_B;  // Gmsh writes coordinates to ~16 digits
    double r_lo = std::numeric_limits<double>::max(), r_hi = 0.0;
    for (const std::size_t node : msh.nodes_of("bearing_contact"))
      {
        const double r = std::hypot(msh.nodes[node][0], msh.nodes[node][1]);
        r_lo = std::min(r_lo, r);
        r_hi = std::max(r_hi, r);
      }
    if (std::abs(r_lo - G.R_B) > tol || std::abs(r_hi - G.R_B) > tol)
      throw InputError(f, "geometry.R_B", format_value(G.R_B),
                       "the bore radius of " + G.mesh + " (its bearing_contact nodes lie at " +
                         format_value(r_lo) + " .. " + format_value(r_hi) + " m)",
                       "the scene's geometry numbers must describe the meshed joint");
    // A deformable journal is used as meshed, on the journal chart about (0, −c_r): its
    // surface must be the scene's journal at first touch.
    if (deformable_journal)
      {
        double d_lo = std::numeric_limits<double>::max(), d_hi = 0.0;
        for (const std::size_t node : msh.nodes_of("journal_contact"))
          {
            const double d = std::hypot(msh.nodes[node][0], msh.nodes[node][1] + G.c_r);
            d_lo = std::min(d_lo, d);
            d_hi = std::max(d_hi, d);
          }
        if (std::abs(d_lo - G.R_J()) > tol || std::abs(d_hi - G.R_J()) > tol)
          throw InputError(f, "geometry.c_r", format_value(G.c_r),
                           "the mesh's journal: its journal_contact nodes lie " +
                             format_value(d_lo) + " .. " + format_value(d_hi) +
                             " m from (0, -c_r), not at R_J = R_B - c_r",
                           "a deformable journal from " + G.mesh +
                             " must be meshed at first "
                             "touch (journal_offset = c_r in the .geo) with the scene's radius");
      }
    // The tilted journal breaks the z = 0 symmetry: the bearing must reach z < 0.
    double z_lo = std::numeric_limits<double>::max();
    for (const std::size_t node : msh.nodes_of("bearing"))
      z_lo = std::min(z_lo, msh.nodes[node][2]);
    if (s.study == Study::misalignment && z_lo > -tol)
      throw InputError(f, "geometry.mesh", G.mesh,
                       "a mesh of the whole length for study misalignment",
                       "the tilted journal breaks the z = 0 symmetry (mesh with quarter = 0)");
  }

  bool has_sweep(const FeScene &scene)
  {
    return !scene.sweep_t_B.empty() || !scene.sweep_theta_deg.empty() ||
           !scene.sweep_velocity.empty() || !scene.sweep_journal_mass.empty();
  }

  double rigid_journal_mass(const FeScene &scene)
  {
    if (scene.impact.journal_mass > 0.0)
      return scene.impact.journal_mass;
    const double R_J = scene.geometry.R_J(), L_J = scene.geometry.L_J();
    return scene.material.rho * 3.14159265358979323846 * R_J * R_J * L_J;
  }

  FeScene read_scene(const std::string &path)
  {
    return scene_from_json(read_structured_file(path), path);
  }

  namespace
  {
    // --- the annotated defaults: one block each, as read above ----------------------------------

    /// the header, study and full_model
    void write_top_defaults(std::ostream &o)
    {
      o << "# fe_stage scene, schema clearjoint.fe/1. SI units everywhere (m, Pa, kg/m^3).\n"
        << "# Every key is optional except schema; shown here with its default.\n"
        << "schema: clearjoint.fe/1\n"
        << "study: radial            # radial | misalignment | impact | rolling | hertz | patch\n"
        << "                         #   (verification); rolling changes the defaults of\n"
        << "                         #   material.model (elastoplastic), contact.mu (0.3),\n"
        << "                         #   loading.delta_max (1.0e-3) and loading.max_cuts (10)\n"
        << "full_model: false        # false: symmetry planes (radial: x = 0 and z = 0, quarter\n"
        << "                         #   model; misalignment: x = 0 only, half model)\n";
    }

    /// geometry:
    void write_geometry_defaults(std::ostream &o, const FeScene &d)
    {
      o << "geometry:\n"
        << "  R_B: " << d.geometry.R_B << "   # [m] bearing inner radius, (0, inf)\n"
        << "  t_B: " << d.geometry.t_B << "   # [m] bearing thickness, (0, inf)\n"
        << "  L_B: " << d.geometry.L_B << "   # [m] bearing length, (0, inf)\n"
        << "  c_r: " << d.geometry.c_r << "  # [m] radial clearance, (0, R_B); R_J = R_B - c_r\n"
        << "  c_a: " << d.geometry.c_a
        << "   # [m] axial clearance, (0, L_B/2); L_J = L_B - 2 c_a\n"
        << "  # mesh: bearing.msh  # optional Gmsh MSH 2.2 mesh with the physical groups of\n"
        << "                     #   docs/geometry.md (relative to the scene); the numbers above\n"
        << "                     #   must describe the same joint\n";
    }

    /// misalignment:
    void write_misalignment_defaults(std::ostream &o, const FeScene &d)
    {
      o << "misalignment:          # study misalignment (paper 3.3): journal tilted in the y-z "
           "plane\n"
        << "  theta_deg: " << d.misalignment.theta_deg
        << "        # [deg] in [0, theta_max] (Eq. 3: 3.2842 deg for the defaults), or theta_max\n";
    }

    /// material:
    void write_material_defaults(std::ostream &o, const FeScene &d)
    {
      o << "material:\n"
        << "  E: " << d.material.E << "    # [Pa] Young's modulus, (0, inf)\n"
        << "  nu: " << d.material.nu << "         # [1] Poisson's ratio, (-1, 0.5)\n"
        << "  rho: " << d.material.rho << "       # [kg/m^3] density (dynamic studies only)\n"
        << "  model: elastic      # elastic | elastoplastic (study rolling, and patch: von\n"
        << "                      #   Mises, isotropic hardening, radial return)\n"
        << "  kinematics: small   # small | finite (total Lagrangian, J2 in the logarithmic\n"
        << "                      #   strain space; elastoplastic: patch, rolling); the\n"
        << "                      #   rolling study's default is finite\n"
        << "  # hardening: [[0, 168.2e6], [0.1, 196.225e6], ...]  # [eps_p, sigma_y Pa] points,\n"
        << "                      #   linear between, extended beyond the last; default SPEC 2:\n"
        << "                      #   168.2 + 280.25 eps_p MPa at eps_p = 0, 0.1, ..., 1.0\n"
        << "  yield_stress: " << d.material.yield_stress
        << " # [Pa] (0, inf): the yield check reports where von Mises exceeds it\n";
    }

    /// contact:
    void write_contact_defaults(std::ostream &o, const FeScene &d)
    {
      o << "contact:\n"
        << "  mu: " << d.contact.mu
        << "          # [1] Coulomb friction coefficient, [0, 10] (0: frictionless)\n"
        << "  active_set_scale: " << d.contact.active_set_scale
        << "  # [1] complementarity constant c = scale*E*h; does not change the solution\n"
        << "  tangential_scale: " << d.contact.tangential_scale
        << "  # [1] friction's constant c_T = scale*c; does not change the solution\n"
        << "  max_iterations: " << d.contact.max_iterations
        << "   # active-set iterations per increment before the increment is cut\n"
        << "  pairing: automatic  # automatic | node_to_node | mortar: how a deformable journal\n"
        << "                      #   meets the bore (automatic = mortar; node_to_node: the\n"
        << "                      #   generated joint's nodes on common rays)\n"
        << "  mortar_slave: automatic  # automatic | bore | journal: the mortar surface that\n"
        << "                      #   carries the constraints (journal: loading.journal core\n"
        << "                      #   only); automatic = journal for the tilted journal of\n"
        << "                      #   study misalignment, bore otherwise\n"
        << "  sliding: small      # small | finite: the mortar search once in the reference\n"
        << "                      #   configuration, or again at the deformed surfaces after\n"
        << "                      #   every increment (for sliding of a contact cell or more)\n";
    }

    /// loading:
    void write_loading_defaults(std::ostream &o, const FeScene &d)
    {
      o << "loading:\n"
        << "  journal: end_faces  # end_faces | axis_line (the paper's) | core (the inner core\n"
        << "                      #   r <= R_J/2 moved rigidly) | rigid (rigid journal)\n"
        << "                      #   study misalignment: rigid (default) or core\n"
        << "                      #   study rolling: rigid (default) or core (clamped in the\n"
        << "                      #   journal's own turning frame, elastoplastic)\n"
        << "  delta_max: " << d.loading.delta_max << "  # [m] push beyond first touch, (0, R_J)\n"
        << "  n_increments: " << d.loading.n_increments << "   # equal increments of delta\n"
        << "  max_cuts: " << d.loading.max_cuts << "        # halvings of a failed increment\n"
        << "  axial_offset: 0     # [m] core journal placed off the axial centre, |.| <= c_a\n"
        << "  axial_slide: 0      # [m] the core also slides along z over the push (with\n"
        << "                      #   contact.sliding finite), |offset + slide| <= c_a\n";
    }

    /// mesh:
    void write_mesh_defaults(std::ostream &o, const FeScene &d)
    {
      o << "mesh:\n"
        << "  degree: " << d.mesh.degree
        << "            # 1 or 2 (Q1/Q2 hexahedra, curved mapping)\n"
        << "  n_circumferential: " << d.mesh.n_circumferential
        << "  # coarse cells over 180 degrees (multiple of 4)\n"
        << "  n_radial: " << d.mesh.n_radial
        << "          # coarse cells through t_B; 0: one per 2 mm\n"
        << "  n_axial: " << d.mesh.n_axial << "           # coarse cells over L_B/2\n"
        << "  global_refinements: " << d.mesh.global_refinements << "\n"
        << "  contact_refinements: " << d.mesh.contact_refinements
        << "  # extra refinements of the cells inside the contact window\n"
        << "  contact_window_deg: " << d.mesh.contact_window_deg
        << "  # [deg] half-angle of the refined zone about the bottom\n"
        << "  adaptive_cycles: " << d.mesh.adaptive_cycles
        << "   # 0..8 cycles of (curve, Kelly indicator, refine) before the recorded curve\n"
        << "  adaptive_fraction: " << d.mesh.adaptive_fraction
        << " # (0, 1) of the cells refined per cycle, those with the largest indicators\n"
        << "  adaptive_increments: " << d.mesh.adaptive_increments
        << "  # 1..1000 increments of the push on each marking mesh (the curve: n_increments)\n"
        << "  adaptive_target_error: " << d.mesh.adaptive_target_error
        << "  # [0, 0.5) > 0: refine until the estimated error of F(delta_max) is at most this\n";
    }

    /// solver:
    void write_solver_defaults(std::ostream &o, const FeScene &d)
    {
      o << "solver:\n"
        << "  linear: automatic   # automatic | cg_amg | direct\n"
        << "  tolerance: " << d.solver.tolerance << "   # relative residual of the linear solves\n"
        << "  max_linear_iterations: " << d.solver.max_linear_iterations << "\n"
        << "  direct_below_dofs: " << d.solver.direct_below_dofs
        << "  # automatic: MUMPS below this many DoFs, else CG + ML AMG\n"
        << "  max_newton_iterations: " << d.solver.max_newton_iterations
        << "  # [1, 1000] material Newton iterations per increment (elastoplastic)\n"
        << "  line_search: " << (d.solver.line_search ? "true" : "false")
        << "  # shorten a material Newton step that overshoots the energy's minimum along it\n";
    }

    /// verification:
    void write_verification_defaults(std::ostream &o, const FeScene &d)
    {
      o << "verification:         # study hertz / patch: block [0,W]x[-H,0]x[0,W] (quarter)\n"
        << "  sphere_radius: " << d.verification.sphere_radius << "  # [m] hertz sphere radius\n"
        << "  block_width: " << d.verification.block_width << "    # [m] W\n"
        << "  block_height: " << d.verification.block_height << "   # [m] H\n"
        << "  n_cells: " << d.verification.n_cells << "            # coarse cells per edge\n"
        << "  contact_refinements: " << d.verification.contact_refinements << "\n"
        << "  refine_radius: " << d.verification.refine_radius
        << "  # [m] hertz: cells within this distance of the contact point are refined\n"
        << "  indenter: " << (d.verification.deformable_indenter ? "deformable" : "rigid")
        << "      # rigid | deformable (same material, non-matching mesh, dual mortar)\n"
        << "  indenter_n_cells: " << d.verification.indenter_n_cells
        << "    # coarse cells per edge of a deformable indenter\n"
        << "  indenter_height: " << d.verification.indenter_height
        << "  # [m] height of a deformable indenter (its top is pushed by delta)\n";
    }

    /// impact:
    void write_impact_defaults(std::ostream &o, const FeScene &d)
    {
      o << "impact:               # study impact (paper 3.2): the journal (mass rho*pi*R_J^2*L_J; "
           "rigid\n"
        << "                      #   unless loading.journal is end_faces, axis_line or core: "
           "deformable and\n"
        << "                      #   free, its quasi-static curve pushed that way) starts at "
           "first\n"
        << "                      #   touch moving toward the bearing (-y)\n"
        << "  velocity: " << d.impact.velocity << "       # [m/s] speed at first touch, (0, 100)\n"
        << "  application: " << application_name(d.impact.application)
        << "  # Abaqus/Standard's *DYNAMIC, APPLICATION=:\n"
        << "                      #   transient_fidelity (HHT alpha -0.05, beta 0.275625, gamma "
           "0.55) |\n"
        << "                      #   moderate_dissipation (HHT alpha -0.41421, beta 0.5, gamma "
           "0.91421;\n"
        << "                      #   the paper's) | quasi_static (backward Euler)\n"
        << "  # alpha: -0.2         # HHT alpha in [-1/2, 0] overriding the application's (beta, "
           "gamma\n"
        << "                      #   follow); not with quasi_static\n"
        << "  steps_per_period: " << d.impact.steps_per_period
        << "  # >= 10: dt = T_c/this, T_c = 2 pi sqrt(m_J/k_c), k_c measured\n"
        << "  # time_step: 1.0e-6   # [s] > 0: a fixed dt instead\n"
        << "  # end_time: 1.0e-3    # [s] > 0: run to this time, past the separation (default:\n"
        << "                      #   stop once the journal has left, at the latest at 4 T_c)\n"
        << "  # journal_mass: 0.5     # [kg] > 0: the rigid journal's mass instead of "
           "rho*pi*R_J^2*L_J\n"
        << "  max_steps: " << d.impact.max_steps << "      # time steps at most\n"
        << "  field_stride: " << d.impact.field_stride
        << "       # VTU fields every this many steps\n"
        << "  mass: redistributed   # redistributed (contact nodes massless) | lumped | "
           "consistent\n";
    }

    /// rolling:
    void write_rolling_defaults(std::ostream &o, const FeScene &d)
    {
      o << "rolling:              # study rolling (paper 3.4): the bearing turns, the journal "
           "(rigid;\n"
        << "                      #   loading.journal core: deformable, its core clamped in its "
           "own\n"
        << "                      #   turning frame) is pushed to loading.delta_max and spun by\n"
        << "                      #   friction alone\n"
        << "  omega_B: " << d.rolling.omega_B << "       # [rad/s] the bearing's spin, (0, 1e4)\n"
        << "  ramp_time: " << d.rolling.ramp_time
        << "      # [s] the push reaches delta_max at this time\n"
        << "  # end_time: 0.3       # [s] >= ramp_time: hold delta_max until then (default "
           "ramp_time)\n"
        << "  n_steps: " << d.rolling.n_steps
        << "          # time steps over the run, >= 4 and at most a\n"
        << "                      #   quarter turn of the bearing each\n"
        << "  support: outer_surface  # outer_surface (turned by its housing) | upper_half (the\n"
        << "                      #   radial study's support, turning with the bearing)\n"
        << "  # journal_inertia: 1.8e-6  # [kg m^2] > 0: instead of 1/2 m R_J^2 of the journal\n"
        << "  spin_solver: bordered  # the journal's spin: bordered (an unknown of each material\n"
        << "                      #   Newton iteration) | coupled (a secant step in each) |\n"
        << "                      #   nested (a root finder around whole solves)\n"
        << "  max_spin_iterations: " << d.rolling.max_spin_iterations
        << "   # torque-balance evaluations per step at most (nested)\n"
        << "  max_newton_iterations: " << d.rolling.max_newton_iterations
        << " # material Newton iterations per solve at most\n"
        << "  field_stride: " << d.rolling.field_stride
        << "     # VTU fields every this many steps\n";
    }

    /// output, and the optional sweep block (commented out)
    void write_output_defaults(std::ostream &o)
    {
      o << "output:\n"
        << "  fields: true        # VTU/PVTU + PVD fields in DIR/fields\n"
        << "# sweep:              # optional: one run (and output folder) per value\n"
        << "#   t_B: [2.0e-3, 4.0e-3, 6.0e-3, 8.0e-3, 10.0e-3]   # [m]\n"
        << "#   theta_deg: [1.0, 1.5, 2.0, 2.5, theta_max]       # [deg] (study misalignment)\n"
        << "#   velocity: [0.05, 0.08, 0.10, 0.15, 0.20]         # [m/s] (study impact)\n"
        << "#   journal_mass: [own, 1.0, 25.0]   # [kg] (study impact, rigid journal; own: rho pi "
           "R_J^2 L_J;\n"
        << "#                                    # with velocity: every velocity at every mass)\n";
    }
  }  // namespace

  namespace
  {
    /// rolling.spin_solver as the scene writes it
    const char *spin_solver_name(const Rolling::SpinSolver s)
    {
      switch (s)
        {
          case Rolling::SpinSolver::coupled:
            return "coupled";
          case Rolling::SpinSolver::nested:
            return "nested";
          case Rolling::SpinSolver::bordered:
            break;
        }
      return "bordered";
    }
  }  // namespace

  std::string default_scene_yaml()
  {
    const FeScene d;
    std::ostringstream o;
    o.precision(10);
    write_top_defaults(o);
    write_geometry_defaults(o, d);
    write_misalignment_defaults(o, d);
    write_material_defaults(o, d);
    write_contact_defaults(o, d);
    write_loading_defaults(o, d);
    write_mesh_defaults(o, d);
    write_solver_defaults(o, d);
    write_verification_defaults(o, d);
    write_impact_defaults(o, d);
    write_rolling_defaults(o, d);
    write_output_defaults(o);
    return o.str();
  }

  nlohmann::json scene_to_json(const FeScene &s)
  {
    nlohmann::json j;
    j["schema"] = "clearjoint.fe/1";
    j["study"] = to_string(s.study);
    j["full_model"] = s.full_model;
    j["geometry"] = {{"R_B", s.geometry.R_B},
                     {"t_B", s.geometry.t_B},
                     {"L_B", s.geometry.L_B},
                     {"c_r", s.geometry.c_r},
                     {"c_a", s.geometry.c_a}};
    if (!s.geometry.mesh.empty())
      j["geometry"]["mesh"] = s.geometry.mesh;
    if (s.study == Study::misalignment)
      j["misalignment"] = {{"theta_deg", s.misalignment.theta_deg}};
    j["material"] = {
      {"E", s.material.E},
      {"nu", s.material.nu},
      {"rho", s.material.rho},
      {"yield_stress", s.material.yield_stress},
      {"model", s.material.model == Material::Model::elastoplastic ? "elastoplastic" : "elastic"},
      {"kinematics", s.material.kinematics == Material::Kinematics::finite ? "finite" : "small"}};
    if (s.material.model == Material::Model::elastoplastic)
      {
        nlohmann::json h = nlohmann::json::array();
        const HardeningTable table = hardening_table(s.material, s.source_file);
        for (const auto &p : table.points())  // (a named table: points() is a reference)
          h.push_back({p.eps_p, p.sigma_y});
        j["material"]["hardening"] = h;
      }
    if (s.study == Study::rolling)
      j["rolling"] = {{"omega_B", s.rolling.omega_B},
                      {"ramp_time", s.rolling.ramp_time},
                      {"end_time", rolling_end_time(s)},
                      {"n_steps", s.rolling.n_steps},
                      {"support", s.rolling.support == Rolling::Support::upper_half ?
                                    "upper_half" :
                                    "outer_surface"},
                      {"journal_inertia", rolling_journal_inertia(s)},
                      {"spin_solver", spin_solver_name(s.rolling.spin_solver)},
                      {"max_spin_iterations", s.rolling.max_spin_iterations},
                      {"max_newton_iterations", s.rolling.max_newton_iterations},
                      {"field_stride", s.rolling.field_stride}};
    j["contact"] = {{"mu", s.contact.mu},
                    {"active_set_scale", s.contact.active_set_scale},
                    {"max_iterations", s.contact.max_iterations},
                    {"tangential_scale", s.contact.tangential_scale},
                    {"pairing", to_string(s.contact.pairing)},
                    {"mortar_slave", to_string(s.contact.mortar_slave)},
                    {"sliding", to_string(s.contact.sliding)}};
    j["loading"] = {{"journal", to_string(s.loading.journal)},
                    {"delta_max", s.loading.delta_max},
                    {"n_increments", s.loading.n_increments},
                    {"max_cuts", s.loading.max_cuts},
                    {"axial_offset", s.loading.axial_offset},
                    {"axial_slide", s.loading.axial_slide}};
    j["mesh"] = {{"degree", s.mesh.degree},
                 {"n_circumferential", s.mesh.n_circumferential},
                 {"n_radial", s.mesh.n_radial},
                 {"n_axial", s.mesh.n_axial},
                 {"global_refinements", s.mesh.global_refinements},
                 {"contact_refinements", s.mesh.contact_refinements},
                 {"contact_window_deg", s.mesh.contact_window_deg},
                 {"adaptive_cycles", s.mesh.adaptive_cycles},
                 {"adaptive_fraction", s.mesh.adaptive_fraction},
                 {"adaptive_increments", s.mesh.adaptive_increments},
                 {"adaptive_target_error", s.mesh.adaptive_target_error}};
    const char *lin = s.solver.linear == LinearSolver::automatic ? "automatic" :
                      s.solver.linear == LinearSolver::cg_amg    ? "cg_amg" :
                                                                   "direct";
    j["solver"] = {{"linear", lin},
                   {"tolerance", s.solver.tolerance},
                   {"max_linear_iterations", s.solver.max_linear_iterations},
                   {"direct_below_dofs", s.solver.direct_below_dofs},
                   {"max_newton_iterations", s.solver.max_newton_iterations},
                   {"line_search", s.solver.line_search}};
    j["verification"] = {{"sphere_radius", s.verification.sphere_radius},
                         {"block_width", s.verification.block_width},
                         {"block_height", s.verification.block_height},
                         {"n_cells", s.verification.n_cells},
                         {"contact_refinements", s.verification.contact_refinements},
                         {"refine_radius", s.verification.refine_radius},
                         {"indenter", s.verification.deformable_indenter ? "deformable" : "rigid"},
                         {"indenter_n_cells", s.verification.indenter_n_cells},
                         {"indenter_height", s.verification.indenter_height}};
    j["output"] = {{"fields", s.output.fields}};
    if (s.study == Study::impact)
      {
        j["impact"] = {{"velocity", s.impact.velocity},
                       {"application", application_name(s.impact.application)},
                       {"steps_per_period", s.impact.steps_per_period},
                       {"max_steps", s.impact.max_steps},
                       {"field_stride", s.impact.field_stride},
                       {"mass", s.impact.mass == Impact::Mass::lumped     ? "lumped" :
                                s.impact.mass == Impact::Mass::consistent ? "consistent" :
                                                                            "redistributed"}};
        if (s.impact.time_step > 0.0)
          j["impact"]["time_step"] = s.impact.time_step;
        if (s.impact.end_time > 0.0)
          j["impact"]["end_time"] = s.impact.end_time;
        if (s.impact.journal_mass > 0.0)
          j["impact"]["journal_mass"] = s.impact.journal_mass;
        if (s.impact.alpha)
          j["impact"]["alpha"] = *s.impact.alpha;
      }
    return j;
  }
}  // namespace clearjoint::fe
