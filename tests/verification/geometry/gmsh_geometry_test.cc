// The shipped Gmsh geometries (fe_stage/geometries/*.geo), meshed by scripts/make_mesh at a
// coarse size: groups, all-hexahedral, none inverted, volumes against the exact solids, the
// contact surfaces on their radii, first touch at the bottom; and make_mesh's error paths.
#include "geometry/msh_check.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace clearjoint::geometry;
using namespace clearjoint::test_support;

namespace
{
  constexpr double pi = 3.14159265358979323846;
  // SPEC §2 defaults [m], the values at the top of both .geo files.
  constexpr double R_B = 10e-3, t_B = 4e-3, L_B = 20e-3, c_r = 0.5e-3, c_a = 1e-3;
  constexpr double R_J = R_B - c_r, L_J = L_B - 2 * c_a;
  constexpr double R_F = 20e-3, t_F = 3e-3;  // flanged_bearing.geo
  // Nodes are computed by Gmsh on the exact circles and written with 16 digits: positions are
  // exact to round-off. 1e-12 m is 1e-10 of the lengths here and far below any modelling
  // difference (c_r = 5e-4 m).
  constexpr double tol_x = 1e-12;

  std::string geo(const std::string &name)
  {
    return std::string(CLEARJOINT_SOURCE_DIR) + "/fe_stage/geometries/" + name;
  }

  /// Runs scripts/make_mesh; returns the exit code, the log in `log`.
  int make_mesh(const ScratchDir &dir, const std::string &geo_path, const std::string &out,
                const std::string &args, std::string &log)
  {
    const std::string cmd = "MSH_CHECK='" + std::string(MSH_CHECK_EXE) + "' '" +
                            CLEARJOINT_SOURCE_DIR + "/scripts/make_mesh' '" + geo_path + "' '" +
                            out + "' " + args;
    const int rc = run_command(cmd, dir.file("make_mesh.log"));
    log = read_text(dir.file("make_mesh.log"));
    return rc;
  }

  MshMesh generate(const ScratchDir &dir, const std::string &geo_name, double h,
                   const std::string &extra = "")
  {
    std::string log;
    const auto out = dir.file(geo_name + std::to_string(h) + ".msh");
    const int rc = make_mesh(dir, geo(geo_name), out,
                             "-setnumber h " + std::to_string(h) + " " + extra, log);
    EXPECT_EQ(rc, 0) << log;
    return read_joint_mesh(out);  // throws (fails the test) on any check problem
  }

  double radius(const std::array<double, 3> &x, double y0 = 0.0)
  {
    return std::hypot(x[0], x[1] - y0);
  }

  /// Min and max of f over the nodes of a group.
  template <class F>
  std::pair<double, double> range(const MshMesh &m, const std::string &group, F f)
  {
    double lo = 1e300, hi = -1e300;
    for (auto n : m.nodes_of(group))
    {
      lo = std::min(lo, f(m.nodes[n]));
      hi = std::max(hi, f(m.nodes[n]));
    }
    return {lo, hi};
  }

  /// Linear hexahedra with straight edges inscribe the circles: with arc nodes uniformly spaced
  /// by Δ ≤ h/R (the .geo files use Ceil(arc length / h) elements), every circular sector is
  /// replaced by a triangle of area fraction sin Δ/Δ ∈ [1 − Δ²/6, 1]. So the meshed volume lies in
  /// V·[1 − (h/R_min)²/6, 1] with R_min the smallest radius meshed with that Δ; 1e-12 relative
  /// slack on the upper side for round-off.
  void expect_inscribed_volume(double v_mesh, double v_exact, double h, double r_min,
                               const std::string &what)
  {
    const double deficit = (h / r_min) * (h / r_min) / 6.0;
    EXPECT_LE(v_mesh, v_exact * (1.0 + 1e-12)) << what;
    EXPECT_GE(v_mesh, v_exact * (1.0 - deficit)) << what;
    std::printf("%s: mesh %.9g m^3, exact %.9g m^3, rel. diff %.3e (bound %.3e)\n", what.c_str(),
                v_mesh, v_exact, v_mesh / v_exact - 1.0, -deficit);
  }
} // namespace

class GmshGeometry : public ::testing::Test
{
protected:
  void SetUp() override
  {
    if (std::string(GMSH_EXECUTABLE).empty())
      GTEST_SKIP() << "gmsh not installed (Debian package gmsh)";
  }
};

// Quarter model (x >= 0, z >= 0), journal at first touch.
TEST_F(GmshGeometry, DefaultJointQuarterModel)
{
  ScratchDir dir("geo_default");
  const double h = 1e-3;
  const MshMesh m = generate(dir, "default_joint.geo", h);
  const auto rep = check_joint_mesh(m);
  EXPECT_TRUE(rep.ok()) << rep.message(m.file);
  EXPECT_EQ(rep.n_volume_non_hex, 0u);
  EXPECT_EQ(rep.n_inverted, 0u);
  EXPECT_TRUE(rep.warnings.empty());  // metres: spans 28 mm
  std::printf("default_joint h = %g m: %zu nodes, %zu hexahedra\n", h, rep.n_nodes,
              rep.n_hexahedra);

  // Modelled fraction: half the circumference (x >= 0) times half the length (z >= 0).
  expect_inscribed_volume(group_volume(m, "bearing"),
                          pi * (std::pow(R_B + t_B, 2) - R_B * R_B) * L_B / 4, h, R_B,
                          "bearing (quarter)");
  expect_inscribed_volume(group_volume(m, "journal"), pi * R_J * R_J * L_J / 4, h, R_J,
                          "journal (quarter)");

  // Contact surfaces on their radii; the journal axis at y = -c_r.
  auto [b_lo, b_hi] = range(m, "bearing_contact", [](auto x) { return radius(x); });
  EXPECT_NEAR(b_lo, R_B, tol_x);
  EXPECT_NEAR(b_hi, R_B, tol_x);
  auto [j_lo, j_hi] = range(m, "journal_contact", [](auto x) { return radius(x, -c_r); });
  EXPECT_NEAR(j_lo, R_J, tol_x);
  EXPECT_NEAR(j_hi, R_J, tol_x);
  // First touch: the journal reaches y = -R_B and nowhere leaves the bore.
  auto [jy_lo, jy_hi] = range(m, "journal", [](auto x) { return x[1]; });
  EXPECT_NEAR(jy_lo, -R_B, tol_x);
  EXPECT_NEAR(jy_hi, R_J - c_r, tol_x);
  auto [jr_lo, jr_hi] = range(m, "journal", [](auto x) { return radius(x); });
  EXPECT_LE(jr_hi, R_B + tol_x);
  (void)jr_lo;
  // Fixed set: the outer surface on y >= 0 (the y = 0 row included).
  auto [fr_lo, fr_hi] = range(m, "bearing_fixed", [](auto x) { return radius(x); });
  EXPECT_NEAR(fr_lo, R_B + t_B, tol_x);
  EXPECT_NEAR(fr_hi, R_B + t_B, tol_x);
  auto [fy_lo, fy_hi] = range(m, "bearing_fixed", [](auto x) { return x[1]; });
  EXPECT_NEAR(fy_lo, 0.0, tol_x);
  EXPECT_NEAR(fy_hi, R_B + t_B, tol_x);
  // Loaded set: the journal end face z = L_J/2 (the z = 0 face is the symmetry plane).
  auto [lz_lo, lz_hi] = range(m, "journal_loaded", [](auto x) { return x[2]; });
  EXPECT_NEAR(lz_lo, L_J / 2, tol_x);
  EXPECT_NEAR(lz_hi, L_J / 2, tol_x);
  // The model: x >= 0 and z >= 0 everywhere.
  for (const auto &x : m.nodes)
  {
    ASSERT_GE(x[0], -tol_x);
    ASSERT_GE(x[2], -tol_x);
  }
}

// Half model (quarter = 0), coaxial journal; refining h moves the volume toward the exact one.
TEST_F(GmshGeometry, DefaultJointHalfModelCoaxialAndRefinement)
{
  ScratchDir dir("geo_default_half");
  const double v_b = pi * (std::pow(R_B + t_B, 2) - R_B * R_B) * L_B / 2;
  double previous_error = 1.0;
  std::size_t previous_cells = 0;
  for (const double h : {2e-3, 1e-3})
  {
    const MshMesh m =
      generate(dir, "default_joint.geo", h, "-setnumber quarter 0 -setnumber journal_offset 0");
    const auto rep = check_joint_mesh(m);
    EXPECT_TRUE(rep.ok()) << rep.message(m.file);
    const double v = group_volume(m, "bearing");
    expect_inscribed_volume(v, v_b, h, R_B, "bearing (half), h = " + std::to_string(h));
    const double error = std::abs(v / v_b - 1.0);
    EXPECT_LT(error, previous_error);
    EXPECT_GT(rep.n_hexahedra, 4 * previous_cells);  // halving h in 3D: ~8x the cells
    previous_error = error;
    previous_cells = rep.n_hexahedra;
    auto [j_lo, j_hi] = range(m, "journal_contact", [](auto x) { return radius(x); });
    EXPECT_NEAR(j_lo, R_J, tol_x);
    EXPECT_NEAR(j_hi, R_J, tol_x);
    auto [lz_lo, lz_hi] = range(m, "journal_loaded", [](auto x) { return std::abs(x[2]); });
    EXPECT_NEAR(lz_lo, L_J / 2, tol_x);  // both end faces z = ±L_J/2
    EXPECT_NEAR(lz_hi, L_J / 2, tol_x);
    auto [z_lo, z_hi] = range(m, "journal_loaded", [](auto x) { return x[2]; });
    EXPECT_LT(z_lo, 0.0);
    EXPECT_GT(z_hi, 0.0);
  }
}

TEST_F(GmshGeometry, FlangedBearing)
{
  ScratchDir dir("geo_flanged");
  const double h = 1e-3;
  const MshMesh m = generate(dir, "flanged_bearing.geo", h);
  const auto rep = check_joint_mesh(m);
  EXPECT_TRUE(rep.ok()) << rep.message(m.file);
  std::printf("flanged_bearing h = %g m: %zu nodes, %zu hexahedra\n", h, rep.n_nodes,
              rep.n_hexahedra);
  // Half model x >= 0 over the full length: sleeve plus flange.
  const double v_exact =
    pi * ((std::pow(R_B + t_B, 2) - R_B * R_B) * L_B + (R_F * R_F - std::pow(R_B + t_B, 2)) * t_F) / 2;
  expect_inscribed_volume(group_volume(m, "bearing"), v_exact, h, R_B, "flanged bearing (half)");
  expect_inscribed_volume(group_volume(m, "journal"), pi * R_J * R_J * L_J / 2, h, R_J,
                          "journal (half)");
  auto [b_lo, b_hi] = range(m, "bearing_contact", [](auto x) { return radius(x); });
  EXPECT_NEAR(b_lo, R_B, tol_x);
  EXPECT_NEAR(b_hi, R_B, tol_x);
  auto [bz_lo, bz_hi] = range(m, "bearing_contact", [](auto x) { return x[2]; });
  EXPECT_NEAR(bz_lo, -L_B / 2, tol_x);  // the bore runs the full length
  EXPECT_NEAR(bz_hi, L_B / 2, tol_x);
  auto [j_lo, j_hi] = range(m, "journal_contact", [](auto x) { return radius(x, -c_r); });
  EXPECT_NEAR(j_lo, R_J, tol_x);
  EXPECT_NEAR(j_hi, R_J, tol_x);
  // Fixed set: the flange's inboard face z = L_B/2 - t_F, R_B + t_B <= r <= R_F.
  auto [fz_lo, fz_hi] = range(m, "bearing_fixed", [](auto x) { return x[2]; });
  EXPECT_NEAR(fz_lo, L_B / 2 - t_F, tol_x);
  EXPECT_NEAR(fz_hi, L_B / 2 - t_F, tol_x);
  auto [fr_lo, fr_hi] = range(m, "bearing_fixed", [](auto x) { return radius(x); });
  EXPECT_NEAR(fr_lo, R_B + t_B, tol_x);
  EXPECT_NEAR(fr_hi, R_F, tol_x);
  auto [jy_lo, jy_hi] = range(m, "journal", [](auto x) { return x[1]; });
  EXPECT_NEAR(jy_lo, -R_B, tol_x);  // first touch at the bottom
  (void)jy_hi;
}

// make_mesh refuses a .geo whose mesh misses groups, or is not all-hexahedral, and writes no
// output file.
TEST_F(GmshGeometry, MakeMeshReportsMissingGroupsAndTetrahedra)
{
  ScratchDir dir("geo_errors");
  const std::string box =
    "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1e-2, 1e-2, 1e-2};\n"
    "Mesh.CharacteristicLengthMax = 5e-3;\n";
  write_text(dir.file("only_bearing.geo"),
             box + "Transfinite Curve{:} = 3;\nTransfinite Surface{:};\nRecombine Surface{:};\n"
                   "Transfinite Volume{1};\nPhysical Volume(\"bearing\") = {1};\n");
  std::string log;
  EXPECT_NE(make_mesh(dir, dir.file("only_bearing.geo"), dir.file("a.msh"), "", log), 0);
  EXPECT_NE(log.find("missing physical group(s): journal (volume), bearing_fixed (surface), "
                     "journal_loaded (surface), bearing_contact (surface), journal_contact "
                     "(surface)"),
            std::string::npos)
    << log;
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.msh")));

  write_text(dir.file("tets.geo"),
             box + "Physical Volume(\"bearing\") = {1};\nPhysical Volume(\"journal\") = {};\n");
  EXPECT_NE(make_mesh(dir, dir.file("tets.geo"), dir.file("b.msh"), "", log), 0);
  EXPECT_NE(log.find("non-hexahedral volume element(s) (tetrahedron)"), std::string::npos) << log;
  EXPECT_FALSE(std::filesystem::exists(dir.file("b.msh")));

  write_text(dir.file("broken.geo"), "Point(1) = {0, 0, 0;\n");
  EXPECT_NE(make_mesh(dir, dir.file("broken.geo"), dir.file("c.msh"), "", log), 0);
  EXPECT_NE(log.find("gmsh failed"), std::string::npos) << log;
}
