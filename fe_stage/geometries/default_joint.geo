// default_joint.geo — bearing ring + journal of SPEC §2 (paper §2.2), all-hexahedral.
// Units: metres. Frame: axes along z, axial mid-plane z = 0, push along −y.
// Model: x >= 0 half (symmetry plane x = 0). With quarter = 1 (default) only z >= 0 is meshed
// as well (symmetry plane z = 0: the aligned radial study); quarter = 0 meshes the full length
// (misalignment study, which keeps only the x = 0 plane).
// Journal: axis at y = −journal_offset; the default offset c_r puts it at first touch with the
// bearing's inner surface at the bottom (0, −R_B); journal_offset = 0 makes it coaxial.
// The two bodies are separate volumes with their own nodes (the touch line has two coincident
// node rows, one per body; they are not merged).
//
// Generate (MSH 2.2 ASCII, what deal.II 9.4 GridIn reads):
//   scripts/make_mesh fe_stage/geometries/default_joint.geo out.msh -setnumber h 1e-3
// Physical groups: bearing, journal (volumes); bearing_fixed (outer surface, y >= 0),
// bearing_contact (inner surface), journal_loaded (journal end face(s) z = ±L_J/2, not the
// symmetry plane), journal_contact (journal cylindrical surface).


// ---- parameters (edit here or override with gmsh -setnumber NAME VALUE) ----
DefineConstant[ R_B = 10e-3 ];      // bearing inner radius [m]
DefineConstant[ t_B = 4e-3 ];       // bearing wall thickness [m]
DefineConstant[ L_B = 20e-3 ];      // bearing length [m]
DefineConstant[ c_r = 0.5e-3 ];     // radial clearance [m]: R_J = R_B - c_r (Eq. 1)
DefineConstant[ c_a = 1e-3 ];       // axial clearance [m]: L_J = L_B - 2 c_a (Eq. 2)
DefineConstant[ journal_offset = c_r ]; // journal axis at y = -journal_offset [m]
DefineConstant[ h = 1e-3 ];         // target element size [m] (mesh-size / refinement parameter)
DefineConstant[ quarter = 1 ];      // 1: z >= 0 only; 0: full length
DefineConstant[ min_layers_t = 2 ]; // at least this many elements through the bearing wall

R_J = R_B - c_r;
L_J = L_B - 2 * c_a;

// element counts from h (arcs use the arc length on the curved surface)
nB = Ceil(0.5 * Pi * R_B / h);                // per 90 deg of the bearing
nT = Max(min_layers_t, Ceil(t_B / h));        // through the wall
z0B = (quarter == 1) ? 0 : -L_B / 2;
z0J = (quarter == 1) ? 0 : -L_J / 2;
nZB = Max(1, Ceil((L_B / 2 - z0B) / h));

// ---- bearing cross-section (x >= 0), two annular sectors split at y = 0 ----
p0 = newp; Point(p0) = {0, 0, z0B};
Point(p0 + 1) = {0, -R_B, z0B};         Point(p0 + 2) = {R_B, 0, z0B};
Point(p0 + 3) = {0, R_B, z0B};          Point(p0 + 4) = {0, -R_B - t_B, z0B};
Point(p0 + 5) = {R_B + t_B, 0, z0B};    Point(p0 + 6) = {0, R_B + t_B, z0B};
c0 = newc;
Circle(c0) = {p0 + 1, p0, p0 + 2};      Circle(c0 + 1) = {p0 + 2, p0, p0 + 3};  // inner
Circle(c0 + 2) = {p0 + 4, p0, p0 + 5};  Circle(c0 + 3) = {p0 + 5, p0, p0 + 6};  // outer
Line(c0 + 4) = {p0 + 1, p0 + 4};  Line(c0 + 5) = {p0 + 2, p0 + 5};  Line(c0 + 6) = {p0 + 3, p0 + 6};
Transfinite Curve{c0, c0 + 1, c0 + 2, c0 + 3} = nB + 1;
Transfinite Curve{c0 + 4, c0 + 5, c0 + 6} = nT + 1;
// Loop order: inner arc first, so the extrusion's lateral surfaces come out as
// [inner, radial, outer, radial].
l0 = newll; Curve Loop(l0) = {c0, c0 + 5, -(c0 + 2), -(c0 + 4)};
s_low = news; Plane Surface(s_low) = {l0};
Curve Loop(l0 + 1) = {c0 + 1, c0 + 6, -(c0 + 3), -(c0 + 5)};
s_up = news; Plane Surface(s_up) = {l0 + 1};
Transfinite Surface{s_low, s_up}; Recombine Surface{s_low, s_up};

ex_b[] = Extrude {0, 0, L_B / 2 - z0B} { Surface{s_low, s_up}; Layers{nZB}; Recombine; };

// ---- physical groups of the bearing (the contract with fe_stage; see docs/geometry.md) ----
// Extrude output per surface: [top, volume, laterals in curve-loop order] (6 entries).
Physical Volume("bearing") = {ex_b[1], ex_b[7]};
Physical Surface("bearing_fixed") = {ex_b[10]};                  // outer surface, y >= 0
Physical Surface("bearing_contact") = {ex_b[2], ex_b[8]};        // inner surface r = R_B

Include "journal.geo_inc";

Mesh.MshFileVersion = 2.2;
Mesh.SaveAll = 0;  // only elements of physical groups are written
