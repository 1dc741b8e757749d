// flanged_bearing.geo — a flanged bearing (sleeve + flange at the z = +L_B/2 end) with the SPEC
// §2 journal, all-hexahedral. Units: metres. Frame: axes along z, push along −y.
// Model: x >= 0 half over the full length (the flange breaks the z = 0 symmetry; symmetry
// plane x = 0 only). The sleeve is R_B..R_B + t_B over z in [−L_B/2, L_B/2]; the flange
// R_B + t_B..R_F over the last t_F of the length. The flange is bolted to a housing wall: its
// inboard face (z = L_B/2 − t_F, R_B + t_B <= r <= R_F) is bearing_fixed, the sleeve is free.
// Journal: axially centred, axis at y = −journal_offset (default c_r: first touch at the
// bottom; 0: coaxial); a separate body (see journal.geo_inc).
//
//   scripts/make_mesh fe_stage/geometries/flanged_bearing.geo out.msh -setnumber h 1e-3
// Physical groups: bearing, journal (volumes); bearing_fixed (flange face), bearing_contact
// (bore r = R_B), journal_loaded (both journal end faces), journal_contact (journal surface).

// ---- parameters (edit here or override with gmsh -setnumber NAME VALUE) ----
DefineConstant[ R_B = 10e-3 ];      // bearing bore radius [m]
DefineConstant[ t_B = 4e-3 ];       // sleeve wall thickness [m]
DefineConstant[ L_B = 20e-3 ];      // bearing length including the flange [m]
DefineConstant[ R_F = 20e-3 ];      // flange outer radius [m] (> R_B + t_B)
DefineConstant[ t_F = 3e-3 ];       // flange thickness [m] (< L_B)
DefineConstant[ c_r = 0.5e-3 ];     // radial clearance [m]: R_J = R_B - c_r (Eq. 1)
DefineConstant[ c_a = 1e-3 ];       // axial clearance [m]: L_J = L_B - 2 c_a (Eq. 2)
DefineConstant[ journal_offset = c_r ]; // journal axis at y = -journal_offset [m]
DefineConstant[ h = 1e-3 ];         // target element size [m] (mesh-size / refinement parameter)
DefineConstant[ min_layers_t = 2 ]; // at least this many elements through the sleeve wall

R_J = R_B - c_r;
L_J = L_B - 2 * c_a;
z0J = -L_J / 2;                     // journal meshed over its full length
zF = L_B / 2 - t_F;                 // inboard face of the flange

nB = Ceil(0.5 * Pi * R_B / h);                  // per 90 deg
nT = Max(min_layers_t, Ceil(t_B / h));          // through the sleeve wall
nF = Max(1, Ceil((R_F - R_B - t_B) / h));       // radially across the flange
nZS = Max(1, Ceil((L_B - t_F) / h));            // along the sleeve
nZF = Max(1, Ceil(t_F / h));                    // through the flange

// ---- cross-section at z = zF: sleeve sectors and flange sectors, split at y = 0 ----
p0 = newp; Point(p0) = {0, 0, zF};
Point(p0 + 1) = {0, -R_B, zF};          Point(p0 + 2) = {R_B, 0, zF};
Point(p0 + 3) = {0, R_B, zF};           Point(p0 + 4) = {0, -R_B - t_B, zF};
Point(p0 + 5) = {R_B + t_B, 0, zF};     Point(p0 + 6) = {0, R_B + t_B, zF};
Point(p0 + 7) = {0, -R_F, zF};          Point(p0 + 8) = {R_F, 0, zF};
Point(p0 + 9) = {0, R_F, zF};
c0 = newc;
Circle(c0) = {p0 + 1, p0, p0 + 2};      Circle(c0 + 1) = {p0 + 2, p0, p0 + 3};  // bore
Circle(c0 + 2) = {p0 + 4, p0, p0 + 5};  Circle(c0 + 3) = {p0 + 5, p0, p0 + 6};  // sleeve outside
Circle(c0 + 4) = {p0 + 7, p0, p0 + 8};  Circle(c0 + 5) = {p0 + 8, p0, p0 + 9};  // flange rim
Line(c0 + 6) = {p0 + 1, p0 + 4};  Line(c0 + 7) = {p0 + 2, p0 + 5};  Line(c0 + 8) = {p0 + 3, p0 + 6};
Line(c0 + 9) = {p0 + 4, p0 + 7};  Line(c0 + 10) = {p0 + 5, p0 + 8}; Line(c0 + 11) = {p0 + 6, p0 + 9};
Transfinite Curve{c0:c0 + 5} = nB + 1;
Transfinite Curve{c0 + 6, c0 + 7, c0 + 8} = nT + 1;
Transfinite Curve{c0 + 9, c0 + 10, c0 + 11} = nF + 1;
l0 = newll;
Curve Loop(l0) = {c0, c0 + 7, -(c0 + 2), -(c0 + 6)};          s_low = news; Plane Surface(s_low) = {l0};
Curve Loop(l0 + 1) = {c0 + 1, c0 + 8, -(c0 + 3), -(c0 + 7)};  s_up = news;  Plane Surface(s_up) = {l0 + 1};
Curve Loop(l0 + 2) = {c0 + 2, c0 + 10, -(c0 + 4), -(c0 + 9)}; f_low = news; Plane Surface(f_low) = {l0 + 2};
Curve Loop(l0 + 3) = {c0 + 3, c0 + 11, -(c0 + 5), -(c0 + 10)}; f_up = news; Plane Surface(f_up) = {l0 + 3};
Transfinite Surface{s_low, s_up, f_low, f_up}; Recombine Surface{s_low, s_up, f_low, f_up};

// Sleeve below the flange (toward −z), then sleeve + flange through the flange thickness.
ex_s[] = Extrude {0, 0, -(L_B - t_F)} { Surface{s_low, s_up}; Layers{nZS}; Recombine; };
ex_f[] = Extrude {0, 0, t_F} { Surface{s_low, s_up, f_low, f_up}; Layers{nZF}; Recombine; };

// Extrude output per surface: [top, volume, laterals in curve-loop order] (6 entries).
Physical Volume("bearing") = {ex_s[1], ex_s[7], ex_f[1], ex_f[7], ex_f[13], ex_f[19]};
Physical Surface("bearing_fixed") = {f_low, f_up};                          // flange inboard face
Physical Surface("bearing_contact") = {ex_s[2], ex_s[8], ex_f[2], ex_f[8]}; // bore r = R_B

Include "journal.geo_inc";

Mesh.MshFileVersion = 2.2;
Mesh.SaveAll = 0;  // only elements of physical groups are written
