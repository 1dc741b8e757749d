// The MSH 2.2 reader and joint-mesh checker on tiny hand-made meshes: one unit-cube hexahedron
// per body, one quadrilateral per surface group; each error test breaks exactly one thing.
#include "common/error.h"
#include "geometry/msh_check.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace clearjoint;
using namespace clearjoint::geometry;
using clearjoint::test_support::ScratchDir;
using clearjoint::test_support::write_text;

namespace
{
  struct Options
  {
    std::string skip_group;        // leave this group out (name and elements)
    std::string skip_group2;
    bool journal_as_tets = false;  // journal cube as 5 tetrahedra instead of a hexahedron
    bool invert_bearing = false;   // bearing hex with bottom and top faces swapped
    bool contact_on_wrong_body = false;  // bearing_contact = a journal face
    bool share_node = false;       // journal's first node = bearing's node 2
    std::string header = "2.2 0 8";
  };

  // Bearing cube [0,1]³ (nodes 1–8), journal cube [2,3]×[0,1]² (nodes 9–16).
  std::string tiny_msh(const Options &o)
  {
    std::ostringstream s;
    s << "$MeshFormat\n" << o.header << "\n$EndMeshFormat\n";
    const std::vector<std::tuple<int, int, std::string>> groups{
      {3, 1, "bearing"},         {3, 2, "journal"},         {2, 3, "bearing_fixed"},
      {2, 4, "bearing_contact"}, {2, 5, "journal_loaded"},  {2, 6, "journal_contact"}};
    std::vector<std::tuple<int, int, std::string>> kept;
    for (const auto &g : groups)
      if (std::get<2>(g) != o.skip_group && std::get<2>(g) != o.skip_group2)
        kept.push_back(g);
    s << "$PhysicalNames\n" << kept.size() << "\n";
    for (const auto &[d, t, n] : kept)
      s << d << " " << t << " \"" << n << "\"\n";
    s << "$EndPhysicalNames\n$Nodes\n16\n";
    const int c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (int body = 0; body < 2; ++body)
      for (int i = 0; i < 8; ++i)
        s << body * 8 + i + 1 << " " << c[i][0] + 2 * body << " " << c[i][1] << " " << c[i][2]
          << "\n";
    s << "$EndNodes\n";
    auto tag_of = [&](const std::string &n) {
      for (const auto &[d, t, name] : kept)
        if (name == n)
          return t;
      return -1;
    };
    std::vector<std::string> el;
    auto add = [&](int type, const std::string &group, std::vector<int> nodes) {
      const int t = tag_of(group);
      if (t < 0)
        return;
      std::ostringstream e;
      e << type << " 2 " << t << " " << t;
      for (int n : nodes)
        e << " " << n;
      el.push_back(e.str());
    };
    const int j0 = o.share_node ? 2 : 9;  // journal node 9 replaced by bearing node 2
    if (o.invert_bearing)
      add(5, "bearing", {5, 6, 7, 8, 1, 2, 3, 4});
    else
      add(5, "bearing", {1, 2, 3, 4, 5, 6, 7, 8});
    if (o.journal_as_tets)
      for (const auto &t : std::vector<std::vector<int>>{
             {9, 10, 11, 14}, {9, 11, 12, 16}, {9, 13, 14, 16}, {11, 14, 15, 16}, {9, 11, 14, 16}})
        add(4, "journal", t);
    else
      add(5, "journal", {j0, 10, 11, 12, 13, 14, 15, 16});
    add(3, "bearing_fixed", {5, 6, 7, 8});     // top of the bearing cube
    if (o.contact_on_wrong_body)
      add(3, "bearing_contact", {9, 10, 11, 12});
    else
      add(3, "bearing_contact", {1, 4, 3, 2});   // bottom of the bearing cube
    add(3, "journal_loaded", {13, 14, 15, 16});
    add(3, "journal_contact", {j0, 12, 11, 10});
    s << "$Elements\n" << el.size() << "\n";
    for (std::size_t i = 0; i < el.size(); ++i)
      s << i + 1 << " " << el[i] << "\n";
    s << "$EndElements\n";
    return s.str();
  }

  std::string written(const ScratchDir &dir, const Options &o, const std::string &name)
  {
    const auto path = dir.file(name);
    write_text(path, tiny_msh(o));
    return path;
  }

  std::string error_of(const std::string &path)
  {
    return test_support::input_error_of([&] { read_joint_mesh(path); });
  }

  bool has(const std::string &m, const std::string &s) { return m.find(s) != std::string::npos; }
} // namespace

TEST(MshCheck, TinyValidMeshPasses)
{
  ScratchDir dir("msh_valid");
  const auto path = written(dir, {}, "ok.msh");
  const MshMesh mesh = read_joint_mesh(path);
  EXPECT_EQ(mesh.groups.size(), 6u);
  EXPECT_EQ(mesh.group("bearing_contact")->dim, 2);
  EXPECT_EQ(mesh.group("journal")->tag, 2);
  const auto rep = check_joint_mesh(mesh);
  EXPECT_TRUE(rep.ok()) << rep.message(path);
  EXPECT_EQ(rep.n_hexahedra, 2u);
  // The tiny mesh spans 3 m: a joint that size was probably drawn in mm (warning only).
  ASSERT_EQ(rep.warnings.size(), 1u);
  EXPECT_TRUE(has(rep.warnings[0], "spans 3 m") && has(rep.warnings[0], "millimetres"));
  // Unit cube from the reference cube [-1,1]³: det J = (1/2)³ at every corner, volume 1
  // (exact arithmetic on small integers and halves: 1e-15).
  for (double d : hex_corner_jacobians(mesh, *mesh.elements_of("bearing")[0]))
    EXPECT_NEAR(d, 0.125, 1e-15);
  EXPECT_NEAR(group_volume(mesh, "bearing"), 1.0, 1e-15);
  EXPECT_EQ(mesh.nodes_of("journal_loaded").size(), 4u);
}

TEST(MshCheck, MissingGroupsAreNamedWithTheFile)
{
  ScratchDir dir("msh_missing");
  Options o;
  o.skip_group = "journal_contact";
  o.skip_group2 = "bearing_fixed";
  const auto path = written(dir, o, "missing.msh");
  const auto m = error_of(path);
  EXPECT_TRUE(has(m, path)) << m;
  EXPECT_TRUE(has(m, "missing physical group(s): bearing_fixed (surface), journal_contact (surface)"))
    << m;
}

TEST(MshCheck, TetrahedronIsReported)
{
  ScratchDir dir("msh_tet");
  Options o;
  o.journal_as_tets = true;
  const auto m = error_of(written(dir, o, "tets.msh"));
  EXPECT_TRUE(has(m, "5 non-hexahedral volume element(s) (tetrahedron)")) << m;
  // the journal's surface quads no longer match any hexahedron face
  EXPECT_TRUE(has(m, "faces of 'journal_loaded' are not boundary faces of 'journal'")) << m;
}

TEST(MshCheck, InvertedHexahedronIsReported)
{
  ScratchDir dir("msh_inverted");
  Options o;
  o.invert_bearing = true;
  const auto path = written(dir, o, "inverted.msh");
  const auto mesh = read_msh22(path);
  for (double d : hex_corner_jacobians(mesh, *mesh.elements_of("bearing")[0]))
    EXPECT_NEAR(d, -0.125, 1e-15);
  const auto m = error_of(path);
  EXPECT_TRUE(has(m, "1 inverted or degenerate hexahedra") && has(m, "elements 1)")) << m;
}

TEST(MshCheck, SurfaceGroupOnTheWrongBodyIsReported)
{
  ScratchDir dir("msh_wrong_body");
  Options o;
  o.contact_on_wrong_body = true;
  const auto m = error_of(written(dir, o, "wrong.msh"));
  EXPECT_TRUE(has(m, "1 of 1 faces of 'bearing_contact' are not boundary faces of 'bearing'")) << m;
}

TEST(MshCheck, BodiesSharingANodeAreReported)
{
  ScratchDir dir("msh_shared");
  Options o;
  o.share_node = true;
  const auto m = error_of(written(dir, o, "shared.msh"));
  EXPECT_TRUE(has(m, "1 node(s) shared by 'bearing' and 'journal'")) << m;
}

TEST(MshCheck, OtherFormatsAreRejected)
{
  ScratchDir dir("msh_format");
  Options v4;
  v4.header = "4.1 0 8";
  EXPECT_TRUE(has(error_of(written(dir, v4, "v4.msh")), "MSH version 4.1"));
  Options binary;
  binary.header = "2.2 1 8";
  EXPECT_TRUE(has(error_of(written(dir, binary, "bin.msh")), "binary MSH"));
  EXPECT_TRUE(has(error_of(dir.file("absent.msh")), "cannot open"));
  write_text(dir.file("cut.msh"), tiny_msh({}).substr(0, 400));
  EXPECT_TRUE(has(error_of(dir.file("cut.msh")), "not a valid MSH 2.2 ASCII file"));
  std::string bad_count = tiny_msh({});
  bad_count.replace(bad_count.find("$Nodes\n16"), 9, "$Nodes\nxx");
  write_text(dir.file("count.msh"), bad_count);
  const auto m = error_of(dir.file("count.msh"));
  EXPECT_TRUE(has(m, "count.msh:") && has(m, "expected number of nodes, found 'xx'")) << m;
}
