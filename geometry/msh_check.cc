#include "geometry/msh_check.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

namespace clearjoint::geometry
{
  namespace
  {
    int n_nodes_of_type(const int type)
    {
      static const std::map<int, int> n{
        {1, 2},   {2, 3},   {3, 4},   {4, 4},   {5, 8},   {6, 6},   {7, 5},   {8, 3},
        {9, 6},   {10, 9},  {11, 10}, {12, 27}, {13, 18}, {14, 14}, {15, 1},  {16, 8},
        {17, 20}, {18, 15}, {19, 13}, {20, 9},  {21, 10}, {22, 12}, {23, 15}, {24, 15},
        {25, 21}, {26, 4},  {27, 5},  {28, 6},  {29, 20}, {30, 35}, {31, 56}, {92, 64},
        {93, 125}};
      const auto it = n.find(type);
      return it == n.end() ? -1 : it->second;
    }

    [[noreturn]] void malformed(const std::string &file, const std::string &what, long line)
    {
      throw InputError(file + (line > 0 ? ":" + std::to_string(line) : ""), "", "", "",
                       "not a valid MSH 2.2 ASCII file: " + what +
                         " (write it with gmsh -format msh22, ASCII)");
    }

    /// Reads the file line by line, counting lines for messages.
    struct LineReader
    {
      std::ifstream in;
      std::string file;
      long line_no = 0;
      bool next(std::string &line)
      {
        if (!std::getline(in, line))
          return false;
        ++line_no;
        if (!line.empty() && line.back() == '\r')
          line.pop_back();
        return true;
      }
      long expect_count(const std::string &what)
      {
        const std::string l = expect(what);
        try
        {
          std::size_t used = 0;
          const long n = std::stol(l, &used);
          if (n >= 0 && l.find_first_not_of(" \t", used) == std::string::npos)
            return n;
        }
        catch (const std::exception &)
        {}
        malformed(file, "expected " + what + ", found '" + l + "'", line_no);
      }
      std::string expect(const std::string &what)
      {
        std::string line;
        if (!next(line))
          malformed(file, "unexpected end of file, expected " + what, line_no);
        return line;
      }
    };

    using Mat3 = std::array<std::array<double, 3>, 3>;

    // Gmsh 8-node hexahedron reference corners.
    constexpr double hex_ref[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                      {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

    double hex_det_j(const MshMesh &mesh, const MshElement &hex, double xi, double eta,
                     double zeta)
    {
      Mat3 J{};  // J[a][b] = d x_a / d ref_b
      for (int i = 0; i < 8; ++i)
      {
        const double a = hex_ref[i][0], b = hex_ref[i][1], c = hex_ref[i][2];
        const double d[3] = {a * (1 + b * eta) * (1 + c * zeta) / 8,
                             b * (1 + a * xi) * (1 + c * zeta) / 8,
                             c * (1 + a * xi) * (1 + b * eta) / 8};
        const auto &x = mesh.nodes[hex.nodes[i]];
        for (int r = 0; r < 3; ++r)
          for (int s = 0; s < 3; ++s)
            J[r][s] += x[r] * d[s];
      }
      return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
             J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
             J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    }

    using FaceKey = std::array<std::size_t, 4>;
    FaceKey sorted_key(std::array<std::size_t, 4> k)
    {
      std::sort(k.begin(), k.end());
      return k;
    }

    std::string join(const std::vector<std::string> &v, const std::string &sep)
    {
      std::string s;
      for (std::size_t i = 0; i < v.size(); ++i)
        s += (i ? sep : "") + v[i];
      return s;
    }
  } // namespace

  int msh_element_dimension(const int type)
  {
    switch (type)
    {
      case 15: return 0;
      case 1: case 8: case 26: case 27: case 28: return 1;
      case 2: case 3: case 9: case 10: case 16: case 20: case 21: case 22: case 23: case 24:
      case 25: return 2;
      case 4: case 5: case 6: case 7: case 11: case 12: case 13: case 14: case 17: case 18:
      case 19: case 29: case 30: case 31: case 92: case 93: return 3;
      default: return -1;
    }
  }

  std::string msh_element_name(const int type)
  {
    switch (type)
    {
      case 15: return "point";
      case 1: return "line";
      case 2: return "triangle";
      case 3: return "quadrangle";
      case 4: return "tetrahedron";
      case 5: return "hexahedron";
      case 6: return "prism";
      case 7: return "pyramid";
      case 9: return "6-node triangle";
      case 10: return "9-node quadrangle";
      case 11: return "10-node tetrahedron";
      case 12: return "27-node hexahedron";
      case 16: return "8-node quadrangle";
      case 17: return "20-node hexahedron";
      default: return "element type " + std::to_string(type);
    }
  }

  const MshPhysicalGroup *MshMesh::group(const std::string &name) const
  {
    for (const auto &g : groups)
      if (g.name == name)
        return &g;
    return nullptr;
  }

  std::vector<const MshElement *> MshMesh::elements_of(const std::string &name) const
  {
    std::vector<const MshElement *> out;
    const auto *g = group(name);
    if (!g)
      return out;
    for (const auto &e : elements)
      if (e.physical == g->tag && msh_element_dimension(e.type) == g->dim)
        out.push_back(&e);
    return out;
  }

  std::vector<std::size_t> MshMesh::nodes_of(const std::string &name) const
  {
    std::vector<std::size_t> out;
    for (const auto *e : elements_of(name))
      out.insert(out.end(), e->nodes.begin(), e->nodes.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  MshMesh read_msh22(const std::string &path)
  {
    LineReader r{std::ifstream(path), path};
    if (!r.in)
      throw InputError(path, "", "", "", "cannot open the mesh file");
    MshMesh mesh;
    mesh.file = path;
    std::unordered_map<long, std::size_t> node_index;
    bool have_format = false, have_nodes = false, have_elements = false;
    std::vector<std::pair<long, std::vector<long>>> raw_elements;  // resolved after $Nodes

    std::string line;
    while (r.next(line))
    {
      if (line.empty())
        continue;
      if (line == "$MeshFormat")
      {
        std::istringstream s(r.expect("version line"));
        std::string version;
        int file_type = -1, data_size = 0;
        s >> version >> file_type >> data_size;
        if (version.rfind("2.2", 0) != 0 && version != "2")
          malformed(path, "MSH version " + version + " (only 2.2 is read)", r.line_no);
        if (file_type != 0)
          malformed(path, "binary MSH (only ASCII is read)", r.line_no);
        if (r.expect("$EndMeshFormat") != "$EndMeshFormat")
          malformed(path, "missing $EndMeshFormat", r.line_no);
        have_format = true;
      }
      else if (line == "$PhysicalNames")
      {
        const long n = r.expect_count("number of physical names");
        for (long i = 0; i < n; ++i)
        {
          const std::string l = r.expect("physical name");
          std::istringstream s(l);
          MshPhysicalGroup g;
          if (!(s >> g.dim >> g.tag))
            malformed(path, "bad $PhysicalNames line '" + l + "'", r.line_no);
          const auto q1 = l.find('"'), q2 = l.rfind('"');
          if (q1 == std::string::npos || q2 == q1)
            malformed(path, "physical name without quotes '" + l + "'", r.line_no);
          g.name = l.substr(q1 + 1, q2 - q1 - 1);
          mesh.groups.push_back(g);
        }
        if (r.expect("$EndPhysicalNames") != "$EndPhysicalNames")
          malformed(path, "missing $EndPhysicalNames", r.line_no);
      }
      else if (line == "$Nodes")
      {
        const long n = r.expect_count("number of nodes");
        mesh.nodes.reserve(n);
        for (long i = 0; i < n; ++i)
        {
          std::istringstream s(r.expect("node"));
          long id;
          std::array<double, 3> x;
          if (!(s >> id >> x[0] >> x[1] >> x[2]))
            malformed(path, "bad node line", r.line_no);
          node_index[id] = mesh.nodes.size();
          mesh.nodes.push_back(x);
        }
        if (r.expect("$EndNodes") != "$EndNodes")
          malformed(path, "missing $EndNodes (node count wrong?)", r.line_no);
        have_nodes = true;
      }
      else if (line == "$Elements")
      {
        const long n = r.expect_count("number of elements");
        for (long i = 0; i < n; ++i)
        {
          std::istringstream s(r.expect("element"));
          long id, type, n_tags;
          if (!(s >> id >> type >> n_tags) || n_tags < 0)
            malformed(path, "bad element line", r.line_no);
          std::vector<long> tags(n_tags);
          for (auto &t : tags)
            s >> t;
          const int nn = n_nodes_of_type(static_cast<int>(type));
          if (nn < 0)
            malformed(path, "unknown element type " + std::to_string(type), r.line_no);
          std::vector<long> v;
          v.push_back(type);
          v.push_back(n_tags > 0 ? tags[0] : 0);
          for (int k = 0; k < nn; ++k)
          {
            long node;
            if (!(s >> node))
              malformed(path, "element " + std::to_string(id) + " has too few nodes", r.line_no);
            v.push_back(node);
          }
          raw_elements.emplace_back(id, std::move(v));
        }
        if (r.expect("$EndElements") != "$EndElements")
          malformed(path, "missing $EndElements (element count wrong?)", r.line_no);
        have_elements = true;
      }
    }
    if (!have_format)
      malformed(path, "no $MeshFormat section", 0);
    if (!have_nodes || !have_elements)
      malformed(path, "no $Nodes or $Elements section", 0);

    mesh.elements.reserve(raw_elements.size());
    for (const auto &[id, v] : raw_elements)
    {
      MshElement e;
      e.id = static_cast<int>(id);
      e.type = static_cast<int>(v[0]);
      e.physical = static_cast<int>(v[1]);
      for (std::size_t k = 2; k < v.size(); ++k)
      {
        const auto it = node_index.find(v[k]);
        if (it == node_index.end())
          malformed(path, "element " + std::to_string(id) + " refers to missing node " +
                            std::to_string(v[k]), 0);
        e.nodes.push_back(it->second);
      }
      mesh.elements.push_back(std::move(e));
    }
    return mesh;
  }

  const std::vector<RequiredGroup> &required_joint_groups()
  {
    static const std::vector<RequiredGroup> groups{
      {"bearing", 3, ""},
      {"journal", 3, ""},
      {"bearing_fixed", 2, "bearing"},
      {"journal_loaded", 2, "journal"},
      {"bearing_contact", 2, "bearing"},
      {"journal_contact", 2, "journal"}};
    return groups;
  }

  std::string MeshCheckReport::message(const std::string &file) const
  {
    return file + ": " + join(problems, "; ");
  }

  std::array<double, 8> hex_corner_jacobians(const MshMesh &mesh, const MshElement &hex)
  {
    std::array<double, 8> det{};
    for (int i = 0; i < 8; ++i)
      det[i] = hex_det_j(mesh, hex, hex_ref[i][0], hex_ref[i][1], hex_ref[i][2]);
    return det;
  }

  double hex_volume(const MshMesh &mesh, const MshElement &hex)
  {
    const double g = 1.0 / std::sqrt(3.0);
    double v = 0.0;
    for (const double a : {-g, g})
      for (const double b : {-g, g})
        for (const double c : {-g, g})
          v += hex_det_j(mesh, hex, a, b, c);
    return v;
  }

  double group_volume(const MshMesh &mesh, const std::string &name)
  {
    double v = 0.0;
    for (const auto *e : mesh.elements_of(name))
      if (e->type == 5)
        v += hex_volume(mesh, *e);
    return v;
  }

  MeshCheckReport check_joint_mesh(const MshMesh &mesh)
  {
    MeshCheckReport rep;
    rep.n_nodes = mesh.nodes.size();

    // Units: a joint mesh spanning more than 1 m was most likely drawn in millimetres.
    if (!mesh.nodes.empty())
    {
      double extent = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        const auto [lo, hi] = std::minmax_element(
          mesh.nodes.begin(), mesh.nodes.end(),
          [k](const auto &a, const auto &b) { return a[k] < b[k]; });
        extent = std::max(extent, (*hi)[k] - (*lo)[k]);
      }
      if (extent > 1.0)
        rep.warnings.push_back("the mesh spans " + format_value(extent) +
                               " m: coordinates are read as metres (drawn in millimetres?)");
    }

    // Groups: all missing ones named at once; dimension must match.
    std::vector<std::string> missing;
    for (const auto &req : required_joint_groups())
    {
      const auto *g = mesh.group(req.name);
      if (!g)
        missing.push_back(req.name + " (" + (req.dim == 3 ? "volume" : "surface") + ")");
      else if (g->dim != req.dim)
        rep.problems.push_back("physical group '" + req.name + "' has dimension " +
                               std::to_string(g->dim) + ", needs " + std::to_string(req.dim));
    }
    if (!missing.empty())
      rep.problems.push_back("missing physical group(s): " + join(missing, ", "));

    // Volume elements: all hexahedra, all in bearing or journal, none inverted.
    std::set<int> body_tags;
    for (const char *b : {"bearing", "journal"})
      if (const auto *g = mesh.group(b); g && g->dim == 3)
        body_tags.insert(g->tag);
    std::map<std::string, std::size_t> non_hex;
    std::size_t outside_bodies = 0, n_non_quad = 0;
    std::vector<std::string> inverted_ids, degenerate_ids;
    for (const auto &e : mesh.elements)
    {
      const int dim = msh_element_dimension(e.type);
      if (dim == 2 && e.type != 3)
        ++n_non_quad;
      if (dim != 3)
        continue;
      if (!body_tags.count(e.physical))
        ++outside_bodies;
      if (e.type != 5)
      {
        ++non_hex[msh_element_name(e.type)];
        continue;
      }
      ++rep.n_hexahedra;
      const auto det = hex_corner_jacobians(mesh, e);
      const double lo = *std::min_element(det.begin(), det.end());
      if (lo < 0.0)
      {
        ++rep.n_inverted;
        if (inverted_ids.size() < 5)
          inverted_ids.push_back(std::to_string(e.id));
      }
      else if (lo == 0.0)
      {
        ++rep.n_inverted;
        if (degenerate_ids.size() < 5)
          degenerate_ids.push_back(std::to_string(e.id));
      }
    }
    for (const auto &[name, n] : non_hex)
    {
      rep.n_volume_non_hex += n;
      rep.problems.push_back(std::to_string(n) + " non-hexahedral volume element(s) (" + name +
                             "); the distributed triangulation needs all-hexahedral meshes "
                             "(transfinite volumes or Recombine + Mesh.SubdivisionAlgorithm = 2)");
    }
    if (rep.n_inverted > 0)
      rep.problems.push_back(
        std::to_string(rep.n_inverted) + " inverted or degenerate hexahedra (corner Jacobian " +
        "<= 0; elements " + join(inverted_ids.empty() ? degenerate_ids : inverted_ids, ", ") +
        (rep.n_inverted > 5 ? ", …" : "") + ")");
    if (outside_bodies > 0)
      rep.problems.push_back(std::to_string(outside_bodies) +
                             " volume element(s) in neither 'bearing' nor 'journal'");
    if (n_non_quad > 0)
      rep.problems.push_back(std::to_string(n_non_quad) +
                             " non-quadrilateral surface element(s) (faces of hexahedra are "
                             "quadrilaterals)");

    // Surface groups: boundary faces of their body.
    for (const char *body : {"bearing", "journal"})
    {
      std::map<FaceKey, int> face_count;
      static constexpr int hex_faces[6][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3},
                                              {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};
      for (const auto *e : mesh.elements_of(body))
        if (e->type == 5)
          for (const auto &f : hex_faces)
            ++face_count[sorted_key({e->nodes[f[0]], e->nodes[f[1]], e->nodes[f[2]],
                                     e->nodes[f[3]]})];
      for (const auto &req : required_joint_groups())
      {
        if (req.body != body || !mesh.group(req.name) || mesh.group(req.name)->dim != 2)
          continue;
        const auto faces = mesh.elements_of(req.name);
        if (faces.empty())
        {
          rep.problems.push_back("physical group '" + req.name + "' has no elements");
          continue;
        }
        std::size_t bad = 0;
        for (const auto *f : faces)
        {
          if (f->type != 3)
            continue;  // counted above
          const auto it = face_count.find(
            sorted_key({f->nodes[0], f->nodes[1], f->nodes[2], f->nodes[3]}));
          if (it == face_count.end() || it->second != 1)
            ++bad;
        }
        if (bad > 0)
          rep.problems.push_back(std::to_string(bad) + " of " + std::to_string(faces.size()) +
                                 " faces of '" + req.name + "' are not boundary faces of '" +
                                 body + "' cells");
      }
    }
    for (const char *body : {"bearing", "journal"})
      if (const auto *g = mesh.group(body); g && g->dim == 3 && mesh.elements_of(body).empty())
        rep.problems.push_back("physical group '" + std::string(body) + "' has no elements");

    // The bodies must not share nodes (that would weld them together).
    const auto nb = mesh.nodes_of("bearing"), nj = mesh.nodes_of("journal");
    std::vector<std::size_t> shared;
    std::set_intersection(nb.begin(), nb.end(), nj.begin(), nj.end(), std::back_inserter(shared));
    if (!shared.empty())
      rep.problems.push_back(std::to_string(shared.size()) +
                             " node(s) shared by 'bearing' and 'journal' (the bodies must be "
                             "meshed separately; do not call Coherence across them)");
    return rep;
  }

  MshMesh read_joint_mesh(const std::string &path)
  {
    MshMesh mesh = read_msh22(path);
    const auto rep = check_joint_mesh(mesh);
    if (!rep.ok())
      throw InputError(path, "", "", "", "unusable joint mesh: " + join(rep.problems, "; "));
    return mesh;
  }
} // namespace clearjoint::geometry
