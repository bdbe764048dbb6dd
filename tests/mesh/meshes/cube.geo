// A unit cube, for the mesh import's bad-input tests: meshed with tetrahedra
// (tets), or with hexahedra of 27 nodes (hex27) by scripts/make_meshes.sh.
DefineConstant[ hexahedra = {0, Name "1: hexahedra (transfinite, recombined)"} ];
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1:4} = 3; Transfinite Surface{1};
If (hexahedra)
  Recombine Surface{1};
  v[] = Extrude{0, 0, 1}{ Surface{1}; Layers{2}; Recombine; };
Else
  v[] = Extrude{0, 0, 1}{ Surface{1}; Layers{2}; };
EndIf
Physical Volume("cube") = {v[1]};
Physical Surface("bottom") = {1};
