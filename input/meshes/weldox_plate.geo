// The quarter of a round plate for the blunt-projectile perforation
// (input/perforation_fine.yaml): radius R, thickness h, top face at z = 0, x >= 0,
// y >= 0 by symmetry. An O-grid: a square core of side a about the axis, a ring out
// to r1, the band r1..r2 where the plug is cut (the projectile's rim at 10 mm) in nb
// radial elements, and a ring out to R graded coarse. na elements around the quarter
// (na / 2 in each half of the core), nz through the thickness.
// Physical volume "plate"; physical surfaces "cut_x" (x = 0), "cut_y" (y = 0), "rim"
// (r = R), "top" (z = 0) and "back" (z = -h).
DefineConstant[ R = {50e-3, Name "radius, m"}, h = {12e-3, Name "thickness, m"},
                a = {6e-3, Name "core side, m"}, r1 = {8e-3, Name "band inner radius, m"},
                r2 = {12e-3, Name "band outer radius, m"},
                na = {24, Name "elements around the quarter (even)"},
                n1 = {3, Name "radial elements, core to r1"}, nb = {10, Name "radial elements in the band"},
                no = {16, Name "radial elements, r2 to R"}, grow = {1.17, Name "growth outside the band"},
                nz = {16, Name "elements through the thickness"} ];
s = Sqrt(0.5);
c = 0.8 * a;  // the core's corner on the diagonal
Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0}; Point(3) = {c, c, 0}; Point(4) = {0, a, 0};
radii[] = {r1, r2, R};
For k In {0 : 2}
  Point(10 + 3 * k) = {radii[k], 0, 0};
  Point(11 + 3 * k) = {s * radii[k], s * radii[k], 0};
  Point(12 + 3 * k) = {0, radii[k], 0};
EndFor
// The core.
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
// Arcs at r1, r2, R: 10 + 2 k on the x side, 11 + 2 k on the y side.
For k In {0 : 2}
  Circle(10 + 2 * k) = {10 + 3 * k, 1, 11 + 3 * k};
  Circle(11 + 2 * k) = {11 + 3 * k, 1, 12 + 3 * k};
EndFor
// Radial lines: on y = 0 (20 + k), on the diagonal (23 + k), on x = 0 (26 + k), k the ring.
Line(20) = {2, 10}; Line(21) = {10, 13}; Line(22) = {13, 16};
Line(23) = {3, 11}; Line(24) = {11, 14}; Line(25) = {14, 17};
Line(26) = {4, 12}; Line(27) = {12, 15}; Line(28) = {15, 18};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {20, 10, -23, -2};  Curve Loop(3) = {23, 11, -26, -3};
Curve Loop(4) = {21, 12, -24, -10}; Curve Loop(5) = {24, 13, -27, -11};
Curve Loop(6) = {22, 14, -25, -12}; Curve Loop(7) = {25, 15, -28, -13};
For k In {1 : 7}
  Plane Surface(k) = {k};
EndFor
half = na / 2;
Transfinite Curve{1, 2, 3, 4, 10, 11, 12, 13, 14, 15} = half + 1;
Transfinite Curve{20, 23, 26} = n1 + 1;
Transfinite Curve{21, 24, 27} = nb + 1;
Transfinite Curve{22, 25, 28} = no + 1 Using Progression grow;
Transfinite Surface{1} = {1, 2, 3, 4};
For k In {2 : 7}
  Transfinite Surface{k};
EndFor
Recombine Surface{1 : 7};
out[] = Extrude{0, 0, -h}{ Surface{1 : 7}; Layers{nz}; Recombine; };
volumes[] = {};
For k In {0 : 6}
  volumes[] += out[6 * k + 1];
EndFor
e = 1e-7;
Physical Volume("plate") = {volumes[]};
Physical Surface("top") = {1 : 7};
Physical Surface("back") = Surface In BoundingBox{-e, -e, -h - e, R + e, R + e, -h + e};
Physical Surface("cut_y") = Surface In BoundingBox{-e, -e, -h - e, R + e, e, e};
Physical Surface("cut_x") = Surface In BoundingBox{-e, -e, -h - e, e, R + e, e};
Physical Surface("rim") = {Surface In BoundingBox{s * R - e, -e, -h - e, R + e, s * R + e, e},
                           Surface In BoundingBox{-e, s * R - e, -h - e, s * R + e, R + e, e}};
