// The seed paper's two plates (input/plate_impact.yaml) as one Gmsh model: plate_a
// on -2.5 mm <= x <= 0, plate_b on 0 <= x <= 2.5 mm, 25 um thick in y (one element:
// plane strain), 2.5 mm in z (the half model above the symmetry plane z = 0).
// n x 1 x n hexahedra per plate (n = 100: h = 25 um). The plates share the surface
// x = 0 ("interface") and its nodes; exdyn gives each part nodes of its own.
//   gmsh -3 -setnumber n 100 plate_impact.geo -o plate_impact_hex8.msh
//   gmsh -3 -order 2 -setnumber n 50 -setnumber t 5e-5 -string "Mesh.SecondOrderIncomplete=1;" ...
// (scripts/make_meshes.sh makes the committed files).
DefineConstant[ n = {100, Name "elements along x and z of each plate"},
                t = {2.5e-5, Name "thickness in y, m"} ];
L = 2.5e-3;
Point(1) = {-L, 0, 0}; Point(2) = {0, 0, 0}; Point(3) = {L, 0, 0};
Point(4) = {-L, 0, L}; Point(5) = {0, 0, L}; Point(6) = {L, 0, L};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 5}; Line(4) = {5, 6};
Line(5) = {1, 4}; Line(6) = {2, 5}; Line(7) = {3, 6};
Curve Loop(1) = {1, 6, -3, -5}; Plane Surface(1) = {1};   // plate_a's face y = 0
Curve Loop(2) = {2, 7, -4, -6}; Plane Surface(2) = {2};   // plate_b's face y = 0
Transfinite Curve{1:7} = n + 1;
Transfinite Surface{1, 2}; Recombine Surface{1, 2};
a[] = Extrude{0, t, 0}{ Surface{1}; Layers{1}; Recombine; };
b[] = Extrude{0, t, 0}{ Surface{2}; Layers{1}; Recombine; };
// Extrude returns the top surface, the volume, then the sides along the loop's curves:
// a[2] on curve 1 (z = 0), a[3] on 6 (x = 0), a[4] on 3 (z = L), a[5] on 5 (x = -L).
Physical Volume("plate_a") = {a[1]};
Physical Volume("plate_b") = {b[1]};
Physical Surface("front") = {1, 2};          // y = 0
Physical Surface("back") = {a[0], b[0]};     // y = t
Physical Surface("bottom") = {a[2], b[2]};   // z = 0, the symmetry plane
Physical Surface("top") = {a[4], b[4]};      // z = L
Physical Surface("interface") = {a[3]};      // x = 0, shared by both plates
Physical Surface("left") = {a[5]};           // x = -L
Physical Surface("right") = {b[3]};          // x = L
