// Reading and checking a Gmsh MSH 2.2 ASCII mesh of a joint without deal.II: the physical
// groups (dimension, tag, name), the element types, inverted hexahedra, and that the surface
// groups are boundary faces of the right body. deal.II 9.4's GridIn reads the same format; this
// check lets a user (and scripts/make_mesh) find a bad mesh before the FE stage starts.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace clearjoint::geometry
{
  struct MshPhysicalGroup
  {
    int dim = 0;
    int tag = 0;
    std::string name;
  };

  struct MshElement
  {
    int type = 0;      ///< Gmsh element type (5 = 8-node hexahedron, 3 = 4-node quadrangle, …)
    int physical = 0;  ///< first tag: physical group (0 if none)
    int id = 0;        ///< element number in the file
    std::vector<std::size_t> nodes;  ///< indices into MshMesh::nodes
  };

  struct MshMesh
  {
    std::string file;
    std::vector<MshPhysicalGroup> groups;
    std::vector<std::array<double, 3>> nodes;
    std::vector<MshElement> elements;

    /// The group with this name (nullptr if none).
    const MshPhysicalGroup *group(const std::string &name) const;
    /// Elements of the group with this name and dimension (empty if none).
    std::vector<const MshElement *> elements_of(const std::string &name) const;
    /// Sorted, unique node indices used by the group's elements.
    std::vector<std::size_t> nodes_of(const std::string &name) const;
  };

  /// Dimension of a Gmsh element type (0–3), or −1 if the type is unknown.
  int msh_element_dimension(int type);
  /// Human name of a Gmsh element type ("hexahedron", "tetrahedron", …).
  std::string msh_element_name(int type);

  /// Reads MSH 2.2 ASCII. Throws InputError naming the file (and line) for a missing file, a
  /// different version or binary format, a malformed section, unknown element types or
  /// elements that refer to missing nodes.
  MshMesh read_msh22(const std::string &path);

  /// The groups every joint mesh needs: volumes bearing, journal; surfaces bearing_fixed,
  /// bearing_contact (faces of bearing cells), journal_loaded, journal_contact (faces of journal
  /// cells).
  struct RequiredGroup
  {
    std::string name;
    int dim;
    std::string body;  ///< for surfaces: the volume group whose boundary faces they must be
  };
  const std::vector<RequiredGroup> &required_joint_groups();

  struct MeshCheckReport
  {
    std::size_t n_nodes = 0, n_hexahedra = 0, n_volume_non_hex = 0, n_inverted = 0;
    std::vector<std::string> problems;  ///< empty: the mesh is usable
    /// Not errors, but likely mistakes: e.g. a mesh larger than 1 m (drawn in mm?).
    std::vector<std::string> warnings;
    bool ok() const { return problems.empty(); }
    /// Problems joined as "file: problem; problem".
    std::string message(const std::string &file) const;
  };

  /// Every problem found (not only the first): missing groups (all named), wrong group
  /// dimensions, non-hexahedral volume elements (counted by type), volume elements outside the
  /// bearing/journal groups, non-quadrilateral surface elements, hexahedra with a corner Jacobian
  /// ≤ 0 (inverted or degenerate, first few element numbers listed), surface-group faces that are
  /// not boundary faces of their body, and nodes shared by bearing and journal. Warns (does not
  /// fail) when the mesh extends over more than 1 m: coordinates are metres, and a joint that
  /// size was most likely drawn in millimetres.
  MeshCheckReport check_joint_mesh(const MshMesh &mesh);

  /// read_msh22 + check_joint_mesh; throws InputError listing the problems and naming the file.
  MshMesh read_joint_mesh(const std::string &path);

  /// The 8 corner Jacobian determinants of an 8-node hexahedron in Gmsh node order.
  std::array<double, 8> hex_corner_jacobians(const MshMesh &mesh, const MshElement &hex);
  /// Volume of a trilinear hexahedron (2×2×2 Gauss: exact for the trilinear map's det J).
  double hex_volume(const MshMesh &mesh, const MshElement &hex);
  /// Sum of hex_volume over the hexahedra of a volume group [m³].
  double group_volume(const MshMesh &mesh, const std::string &name);
} // namespace clearjoint::geometry
