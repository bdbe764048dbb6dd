// A hollow steel tube (input/tube_impact.yaml; thinner, input/tube_crush.yaml), a
// shape no built-in block makes:
// inner radius ri, outer radius ro, length L along z from z0, a quarter (x >= 0,
// y >= 0) by symmetry. The quarter annulus is one transfinite patch: na elements
// around, nr across the wall; nz layers along the axis.
// Physical volume "tube"; physical surfaces "impact_end" (z = z0), "free_end"
// (z = z0 + L), "outer", "inner", "cut_x" (x = 0) and "cut_y" (y = 0).
DefineConstant[ ri = {8e-3, Name "inner radius, m"}, ro = {10e-3, Name "outer radius, m"},
                L = {50e-3, Name "length, m"}, z0 = {1e-5, Name "height of the impact end, m"},
                na = {8, Name "elements around a quarter"}, nr = {2, Name "elements across the wall"},
                nz = {50, Name "elements along the axis"} ];
Point(1) = {0, 0, z0};
Point(2) = {ri, 0, z0}; Point(3) = {ro, 0, z0};
Point(4) = {0, ri, z0}; Point(5) = {0, ro, z0};
Line(1) = {2, 3};            // on y = 0
Circle(2) = {3, 1, 5};       // outer arc
Line(3) = {5, 4};            // on x = 0
Circle(4) = {4, 1, 2};       // inner arc
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nr + 1;
Transfinite Curve{2, 4} = na + 1;
Transfinite Surface{1}; Recombine Surface{1};
t[] = Extrude{0, 0, L}{ Surface{1}; Layers{nz}; Recombine; };
// t[0] the far end, t[1] the volume, t[2..5] the sides along curves 1, 2, 3, 4.
Physical Volume("tube") = {t[1]};
Physical Surface("impact_end") = {1};
Physical Surface("free_end") = {t[0]};
Physical Surface("cut_y") = {t[2]};
Physical Surface("outer") = {t[3]};
Physical Surface("cut_x") = {t[4]};
Physical Surface("inner") = {t[5]};
