#include "mbd_stage/scene.h"

#include "common/error.h"
#include "common/log.h"
#include "common/strict_reader.h"
#include "laws/law_family.h"
#include "laws/law_file.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

namespace clearjoint::mbd
{
  namespace
  {
    Vector3 vec3(StrictObject &o, const std::string &key, const Range &range = Range::any())
    {
      const auto v = o.number_array(key, range, 3);
      if (v.size() != 3)
        o.fail(key, std::to_string(v.size()) + " numbers", "exactly 3 numbers");
      return {v[0], v[1], v[2]};
    }

    // Guards against absurd starting values (issue 16): each bound is far beyond any mechanism
    // this stage models, and close enough that nothing non-finite can arise from it (a norm of
    // [1e308, 1e308, 0] overflows to inf and the normalised axis becomes NaN).
    /// [m] positions and centres: a machine, not a geodesic; double precision still resolves
    /// 1e-13 m at this distance, far below any clearance.
    const Range position_range = Range::closed(-1e3, 1e3, "m");
    /// [m/s] speeds of a point (about three times the speed of sound in air).
    const Range speed_range = Range::closed(-1e3, 1e3, "m/s");
    /// [rad/s] about 10⁶ rpm, above the fastest turbomachinery.
    const Range spin_range = Range::closed(-1e5, 1e5, "rad/s");
    /// [m/s²] about 100 g per component.
    const Range gravity_range = Range::closed(-1e3, 1e3, "m/s^2");

    Vector3 unit_vec3(StrictObject &o, const std::string &key)
    {
      // Components of a direction: any scale, but bounded so that its norm stays finite.
      const Vector3 a = vec3(o, key, Range::closed(-1e6, 1e6));
      if (!(a.norm() > 1e-12))
        o.fail(key, "[0, 0, 0]", "a non-zero direction");
      return a.normalized();
    }

    int body_ref(StrictObject &o, const std::string &key, const MultibodySystem &sys)
    {
      const std::string name = o.string(key);
      const int b = sys.body_index(name);
      if (b == -2)
      {
        std::string names = "ground";
        for (const auto &p : sys.bodies())
          names += "|" + p.name;
        o.fail(key, name, "one of " + names, "no body of that name");
      }
      return b;
    }

    laws::DampingModel damping_of(StrictObject &o)
    {
      return laws::parse_damping_model(o.string("damping", laws::damping_model_names()));
    }

    std::string resolve(const std::string &base_dir, const std::string &p)
    {
      const std::filesystem::path path(p);
      return path.is_absolute() ? p : (std::filesystem::path(base_dir) / path).lexically_normal().string();
    }

    /// The damping keys every contact model shares: damping, restitution (c_e in (0, 1]) and
    /// min_impact_velocity (the floor of δ̇⁻, m/s).
    void read_damping(StrictObject &o, ContactForceModel &model)
    {
      const laws::DampingModel damping = damping_of(o);
      const double c_e = o.number("restitution", Range{.lo = 0.0, .hi = 1.0, .lo_open = true, .unit = "1"});
      // Default 1e-4 m/s (docs/mbd.md §4): the slowest real onsets of the paper scenes are
      // 2e-4 m/s (the end of a bouncing series), so the floor acts on grazing contact only.
      const double v_min = o.number_or("min_impact_velocity", 1e-4, Range::positive("m/s"));
      model.set_damping(damping, c_e, v_min);
    }

    ContactForceModel read_normal_model(StrictObject o, const ClearanceGeometry &G,
                                        const double E_star, const std::string &base_dir,
                                        std::vector<std::string> &inputs)
    {
      const std::string kind =
        o.string("model", {"fe_law", "law_family", "hertz", "johnson", "pereira"});
      const double scale = o.number_or("stiffness_scale", 1.0, Range::positive("1"));
      const laws::RangePolicy policy =
        laws::parse_range_policy(o.string_or("out_of_range", "extend", {"error", "clamp", "extend"}));
      ContactForceModel model;
      if (kind == "fe_law" || kind == "law_family")
      {
        const std::string path = resolve(base_dir, o.string("law_file"));
        inputs.push_back(path);
        std::optional<laws::LawFamily> family;
        try
        {
          if (kind == "fe_law")
          {
            laws::LawFile law = laws::read_law_file(path);
            law.law.K *= scale;
            model = ContactForceModel::law_file("fe_law", law, policy);
          }
          else
          {
            if (scale != 1.0)
              o.fail("stiffness_scale", format_value(scale), "1 for law families");
            family = laws::read_law_family(path);
            model = ContactForceModel::law_family("law_family", *family, policy);
          }
        }
        catch (const InputError &e)
        {
          o.fail("law_file", path, std::string("a readable ") +
                                     (kind == "fe_law" ? laws::law_schema : laws::law_family_schema) +
                                     " file",
                 e.what());
        }
        // The family is evaluated at the current tilt θ in rad (clearance_joint.cc): a family
        // over another parameter, or over θ in degrees, would be read at a wrong value silently.
        if (family && (family->parameter() != "theta" || family->unit() != "rad"))
          o.fail("law_file", path, "a law family over the tilt theta in rad",
                 "this family is over " + family->parameter() + " in " + family->unit() +
                   "; mbd_stage evaluates a law family at the current "
                   "misalignment theta [rad]");
      }
      else if (kind == "hertz")
      {
        laws::PowerLaw law = hertz_cylinder_law(G.R_B, G.R_J, E_star);
        law.K *= scale;
        model = ContactForceModel::power_law("hertz", law);
      }
      else if (kind == "pereira")
      {
        PereiraParameters p;
        if (o.has("pereira"))
        {
          StrictObject po = o.object("pereira");
          p.a = po.number("a", Range::any("1"));
          p.b = po.number("b", Range::any("mm"));
          po.finish();
        }
        else
          o.number_or("pereira", 0.0, Range::any());  // mark as known
        try
        {
          laws::PowerLaw law = pereira_law(G.R_B, G.R_J, G.L_J, E_star, p);
          law.K *= scale;
          model = ContactForceModel::power_law("pereira", law);
        }
        catch (const InputError &e)
        {
          o.fail("model", "pereira", "a clearance R_B − R_J in [0.005, 10.1] mm", e.what());
        }
      }
      else  // johnson
      {
        if (scale != 1.0)
          o.fail("stiffness_scale", format_value(scale), "1 for johnson");
        model = ContactForceModel::johnson("johnson", JohnsonLaw(G.c_r(), G.L_J, E_star), policy);
      }
      read_damping(o, model);
      o.finish();
      return model;
    }

    ContactForceModel read_axial_model(StrictObject o)
    {
      const double K = o.number("K", Range::positive("N/m^n"));
      const double n = o.number("n", Range::closed(1.0, 2.0, "1"));
      ContactForceModel model = ContactForceModel::power_law("axial", {K, n});
      read_damping(o, model);
      o.finish();
      return model;
    }
    /// An impossible start (issue 16): the journal must begin inside its bearing. A journal
    /// 2 mm off centre in a 0.5 mm clearance, or tilted 45°, would start with a penetration
    /// many times the clearance and an enormous force; the integrator then crawls for hours.
    /// Allowed overlap: 1 % of the clearance — hand-typed coordinates rounded to a few digits
    /// stay well inside it, and a run at θ = θ_max starts exactly touching (δ = 0).
    void check_starting_gaps(StrictObject &c, const ClearanceJoint &joint,
                             const KinematicsView &k0)
    {
      const std::array<double, 3> delta = joint.gaps(k0);
      const ClearanceGeometry &G = joint.geometry();
      const double allowed[3] = {0.01 * G.c_r(), 0.01 * G.c_a(), 0.01 * G.c_a()};
      const char *what[3] = {"radial", "axial (+axis wall)", "axial (-axis wall)"};
      for (int i = 0; i < 3; ++i)
        if (!std::isfinite(delta[i]) || delta[i] > allowed[i])
          c.fail("journal", "a starting " + std::string(what[i]) + " penetration of " +
                              format_value(delta[i]) + " m",
                 "a journal inside its bearing: penetration <= " + format_value(allowed[i]) +
                   " m (1 % of the " + (i == 0 ? "radial" : "axial") + " clearance)",
                 "move journal.center towards bearing.center, or align journal.axis with "
                 "bearing.axis");
    }

    /// Names of joints, drivers and clearance joints: one namespace, each name used once.
    class ElementNames
    {
    public:
      /// o's `name`, which no element read before may have.
      std::string read_unique(StrictObject &o)
      {
        const std::string name = o.string("name");
        if (!names_.insert(name).second)
          o.fail("name", name, "a name not used by another joint, driver or clearance joint");
        return name;
      }

    private:
      std::set<std::string> names_;
    };

    /// One entry of `bodies`: its properties and its initial kinematics (unit-norm e, ω' in
    /// the body frame).
    void read_body(StrictObject &b, std::set<std::string> &names, MultibodySystem &sys)
    {
      BodyProperties p;
      p.name = b.string("name");
      if (!names.insert(p.name).second)
        b.fail("name", p.name, "a unique name other than 'ground'");
      // 1e6 kg and kg·m²: a ship's engine, not a joint test rig; beyond this the stiff
      // contact and the tiny clearance make the problem meaningless in double precision.
      p.mass = b.number("mass", Range{.lo = 0.0, .hi = 1e6, .lo_open = true, .unit = "kg"});
      p.inertia =
        vec3(b, "inertia", Range{.lo = 0.0, .hi = 1e6, .lo_open = true, .unit = "kg*m^2"});
      BodyKinematics k;
      k.r = vec3(b, "position", position_range);
      const auto e = b.number_array("euler_parameters", Range::closed(-1.0 - 1e-3, 1.0 + 1e-3), 4);
      if (e.size() != 4)
        b.fail("euler_parameters", std::to_string(e.size()) + " numbers", "exactly 4 numbers");
      k.e = Vector4(e[0], e[1], e[2], e[3]);
      const double norm = k.e.norm();
      // 1e-6: tables quote e to 4–6 digits; anything further off is a typo, not rounding.
      if (std::abs(norm - 1.0) > 1e-6)
        b.fail("euler_parameters", "norm " + format_value(norm), "unit norm within 1e-6",
               "Euler parameters must satisfy e0² + e1² + e2² + e3² = 1");
      k.e /= norm;
      k.A = rotation_matrix(k.e);
      k.v = vec3(b, "velocity", speed_range);
      k.w_B = k.A.transpose() * vec3(b, "angular_velocity", spin_range);
      b.finish();
      sys.add_body(p, k);
    }

    void read_bodies(StrictObject &top, MultibodySystem &sys)
    {
      std::set<std::string> names{"ground"};
      for (StrictObject b : top.object_array("bodies"))
        read_body(b, names, sys);
      if (sys.n_bodies() == 0)
        top.fail("bodies", "[]", "at least one body");
    }

    /// `joints`; returns their names in order (drivers name their joint).
    std::vector<std::string> read_joints(StrictObject &top, MultibodySystem &sys,
                                         ElementNames &element_names)
    {
      std::vector<std::string> joint_names;
      for (StrictObject j : top.object_array("joints"))
      {
        const std::string name = element_names.read_unique(j);
        const JointType type = parse_joint_type(
          j.string("type", {"revolute", "translational", "spherical", "fixed"}));
        const int bi = body_ref(j, "body_i", sys), bj = body_ref(j, "body_j", sys);
        if (bi == bj)
          j.fail("body_j", j.raw("body_j").dump(), "a body other than body_i");
        const Vector3 point = vec3(j, "point", position_range);
        const Vector3 axis = type == JointType::spherical && !j.has("axis")
                               ? Vector3::UnitX()
                               : unit_vec3(j, "axis");
        j.finish();
        sys.add_joint(name, type, bi, bj, point, axis);
        joint_names.push_back(name);
      }
      return joint_names;
    }

    /// `drivers` (optional): each drives one revolute joint at a constant speed.
    void read_drivers(StrictObject &top, MultibodySystem &sys, ElementNames &element_names,
                      const std::vector<std::string> &joint_names)
    {
      if (!top.has("drivers"))
      {
        top.number_or("drivers", 0.0, Range::any());  // mark as known
        return;
      }
      for (StrictObject d : top.object_array("drivers"))
      {
        const std::string name = element_names.read_unique(d);
        const std::string jn = d.string("joint");
        int idx = -1;
        for (std::size_t i = 0; i < joint_names.size(); ++i)
          if (joint_names[i] == jn)
            idx = static_cast<int>(i);
        if (idx < 0)
          d.fail("joint", jn, "the name of a revolute joint of this scene");
        if (sys.joints()[idx].type() != JointType::revolute)
          d.fail("joint", jn, "a revolute joint");
        const double speed = d.number("speed", spin_range);
        d.finish();
        sys.add_driver(name, idx, speed);
      }
    }

    /// A clearance joint's `bearing` and `journal`: body, centre and axis of each, in ground.
    struct BearingAndJournal
    {
      int bearing_body, journal_body;
      Vector3 bearing_center, bearing_axis, journal_center, journal_axis;
    };

    BearingAndJournal read_bearing_and_journal(StrictObject &c, const MultibodySystem &sys)
    {
      BearingAndJournal e;
      StrictObject bo = c.object("bearing"), jo = c.object("journal");
      e.bearing_body = body_ref(bo, "body", sys);
      e.journal_body = body_ref(jo, "body", sys);
      if (e.bearing_body == e.journal_body)
        jo.fail("body", jo.raw("body").dump(), "a body other than the bearing's");
      e.bearing_center = vec3(bo, "center", position_range);
      e.bearing_axis = unit_vec3(bo, "axis");
      e.journal_center = vec3(jo, "center", position_range);
      e.journal_axis = unit_vec3(jo, "axis");
      bo.finish();
      jo.finish();
      return e;
    }

    /// `geometry`: R_B, R_J, L_B, L_J [m], with room between journal and bearing both ways.
    ClearanceGeometry read_clearance_geometry(StrictObject go)
    {
      ClearanceGeometry G;
      // 10 m: a bearing larger than that is not a journal bearing this model describes.
      const Range size_range{.lo = 0.0, .hi = 10.0, .lo_open = true, .unit = "m"};
      G.R_B = go.number("R_B", size_range);
      G.R_J = go.number("R_J", size_range);
      G.L_B = go.number("L_B", size_range);
      G.L_J = go.number("L_J", size_range);
      if (!(G.R_J < G.R_B))
        go.fail("R_J", format_value(G.R_J), "(0, R_B = " + format_value(G.R_B) + ") m",
                "the radial clearance c_r = R_B − R_J must be > 0");
      if (!(G.L_J < G.L_B))
        go.fail("L_J", format_value(G.L_J), "(0, L_B = " + format_value(G.L_B) + ") m",
                "the axial clearance c_a = (L_B − L_J)/2 must be > 0");
      go.finish();
      return G;
    }

    /// `material`: both bodies' E [Pa] and ν → the effective modulus E* [Pa].
    double read_effective_modulus(StrictObject mo)
    {
      // 1e13 Pa: ten times diamond's Young's modulus.
      const Range modulus_range{.lo = 0.0, .hi = 1e13, .lo_open = true, .unit = "Pa"};
      const double Eb = mo.number("E_bearing", modulus_range);
      const double nb = mo.number("nu_bearing", Range::open(-1.0, 0.5, "1"));
      const double Ej = mo.number("E_journal", modulus_range);
      const double nj = mo.number("nu_journal", Range::open(-1.0, 0.5, "1"));
      mo.finish();
      return effective_modulus(Eb, nb, Ej, nj);
    }

    /// `friction`: μ and the velocities v0 < v1 [m/s] of the Coulomb ramp.
    CoulombFriction read_friction(StrictObject fo)
    {
      CoulombFriction fr;
      fr.mu = fo.number("mu", Range::closed(0.0, 2.0, "1"));
      fr.v0 = fo.number("v0", Range::positive("m/s"));
      fr.v1 = fo.number("v1", Range::positive("m/s"));
      if (!(fr.v1 > fr.v0))
        fo.fail("v1", format_value(fr.v1), "> v0 = " + format_value(fr.v0) + " m/s");
      fo.finish();
      return fr;
    }

    /// One entry of `clearance_joints`, added to sys once its journal is found inside its
    /// bearing; the law files it reads join `inputs`.
    void read_clearance_joint(StrictObject &c, MultibodySystem &sys, ElementNames &element_names,
                              const std::string &base_dir, std::vector<std::string> &inputs)
    {
      const std::string name = element_names.read_unique(c);
      const BearingAndJournal e = read_bearing_and_journal(c, sys);
      const ClearanceGeometry G = read_clearance_geometry(c.object("geometry"));
      const double E_star = read_effective_modulus(c.object("material"));
      ContactForceModel normal = read_normal_model(c.object("normal"), G, E_star, base_dir, inputs);
      ContactForceModel axial = read_axial_model(c.object("axial"));
      const CoulombFriction fr = read_friction(c.object("friction"));
      c.finish();
      auto joint = std::make_unique<ClearanceJoint>(
        name, e.bearing_body, e.journal_body, e.bearing_center, e.bearing_axis, e.journal_center,
        e.journal_axis, G, std::move(normal), std::move(axial), fr, sys.initial_view());
      check_starting_gaps(c, *joint, sys.initial_view());
      sys.add_clearance_joint(std::move(joint));
    }

    /// `clearance_joints` (optional).
    void read_clearance_joints(StrictObject &top, MultibodySystem &sys,
                               ElementNames &element_names, const std::string &base_dir,
                               std::vector<std::string> &inputs)
    {
      if (!top.has("clearance_joints"))
      {
        top.number_or("clearance_joints", 0.0, Range::any());  // mark as known
        return;
      }
      for (StrictObject c : top.object_array("clearance_joints"))
        read_clearance_joint(c, sys, element_names, base_dir, inputs);
    }

    /// `integrator`: the settings and the output interval (at most the duration).
    void read_integrator(StrictObject &top, Scene &scene)
    {
      StrictObject io = top.object("integrator");
      IntegratorSettings &s = scene.integrator;
      s.method = parse_integrator_method(io.string("method", integrator_method_names()));
      s.rtol = io.number("rtol", Range::closed(1e-14, 1e-2, "1"));
      s.atol_position = io.number("atol_position", Range::positive("m"));
      s.atol_velocity = io.number("atol_velocity", Range::positive("m/s"));
      s.max_step = io.number("max_step", Range::non_negative("s (0: no limit)"));
      s.depth_guard = io.number_or("depth_guard", s.depth_guard,
                                   Range{.lo = 0.0, .hi = 1.0, .lo_open = true, .unit = "1 (fraction of c_r)"});
      scene.output_interval = io.number("output_interval", Range::positive("s"));
      io.finish();
      if (scene.output_interval > scene.duration)
        top.fail("integrator.output_interval", format_value(scene.output_interval),
                 "(0, duration] s");
    }

    /// `stabilization` (optional; default 50/s for α, β and the Euler-parameter gain).
    Stabilization read_stabilization(StrictObject &top)
    {
      Stabilization stab{.alpha = 50.0, .beta = 50.0, .euler_gain = 50.0};
      if (!top.has("stabilization"))
      {
        top.number_or("stabilization", 0.0, Range::any());  // mark as known
        return stab;
      }
      StrictObject so = top.object("stabilization");
      stab.alpha = so.number("alpha", Range::non_negative("1/s"));
      stab.beta = so.number("beta", Range::non_negative("1/s"));
      stab.euler_gain = so.number_or("euler_gain", stab.beta, Range::non_negative("1/s"));
      so.finish();
      return stab;
    }

    /// `outputs` (optional): the slider's and the crank's monitored axes.
    void read_outputs(StrictObject &top, const MultibodySystem &sys, Scene &scene)
    {
      if (!top.has("outputs"))
      {
        top.number_or("outputs", 0.0, Range::any());  // mark as known
        return;
      }
      StrictObject oo = top.object("outputs");
      for (const char *key : {"slider", "crank"})
        if (oo.has(key))
        {
          StrictObject ax = oo.object(key);
          MonitoredAxis m;
          m.body = ax.string("body");
          if (sys.body_index(m.body) < 0)
            ax.fail("body", m.body, "the name of a moving body");
          m.axis = unit_vec3(ax, "axis");
          ax.finish();
          (std::string(key) == "slider" ? scene.slider : scene.crank) = m;
        }
        else
          oo.number_or(key, 0.0, Range::any());
      oo.finish();
    }

    /// `budget` (optional): wall time, steps and output rows a run may take.
    void read_budget(StrictObject &top, Scene &scene)
    {
      if (!top.has("budget"))
      {
        top.number_or("budget", 0.0, Range::any());  // mark as known
        return;
      }
      StrictObject bo = top.object("budget");
      scene.max_wall_time = bo.number_or("wall_time", scene.max_wall_time, Range::positive("s"));
      scene.max_steps = bo.integer_or("steps", scene.max_steps, 1, 1'000'000'000'000L);
      scene.max_output_rows =
        bo.integer_or("output_rows", scene.max_output_rows, 1, 1'000'000'000'000L);
      bo.finish();
    }

    /// The time series has one row per output_interval (~0.5 kB each): a duration of 1e300 s,
    /// or an interval of 1e-12 s, would fill the disk long before any budget stops the run.
    void check_output_rows(StrictObject &top, const Scene &scene)
    {
      if (const double rows = std::floor(scene.duration / scene.output_interval) + 1.0;
          !(rows <= static_cast<double>(scene.max_output_rows)))
        top.fail("integrator.output_interval", format_value(scene.output_interval),
                 "at least duration / budget.output_rows = " +
                   format_value(scene.duration / static_cast<double>(scene.max_output_rows)) +
                   " s (duration " + format_value(scene.duration) + " s would give " +
                   format_value(rows) + " rows of timeseries.csv, ~0.5 kB each; raise "
                   "output_interval, shorten duration or raise budget.output_rows)");
    }
  } // namespace

  Scene read_scene(const std::string &path)
  {
    const nlohmann::json doc = read_structured_file(path);
    return scene_from_json(doc, path, std::filesystem::path(path).parent_path().string());
  }

  Scene scene_from_json(const nlohmann::json &doc, const std::string &file,
                        const std::string &base_dir)
  {
    Scene scene;
    scene.file = file;
    scene.raw = doc;
    StrictObject top(doc, file);
    top.expect_schema(scene_schema);
    scene.name = top.string("name");
    scene.description = top.string_or("description", "");
    scene.duration = top.number("duration", Range::positive("s"));
    auto sys = std::make_shared<MultibodySystem>();
    sys->set_gravity(vec3(top, "gravity", gravity_range));

    read_bodies(top, *sys);
    ElementNames element_names;
    const std::vector<std::string> joint_names = read_joints(top, *sys, element_names);
    read_drivers(top, *sys, element_names, joint_names);
    read_clearance_joints(top, *sys, element_names, base_dir, scene.input_files);
    read_integrator(top, scene);
    sys->set_stabilization(read_stabilization(top));
    read_outputs(top, *sys, scene);
    read_budget(top, scene);
    check_output_rows(top, scene);
    top.finish();

    sys->finalize(0.0);
    scene.system = sys;
    return scene;
  }
} // namespace clearjoint::mbd
