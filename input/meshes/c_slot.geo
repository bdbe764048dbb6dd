// A C-shaped block (input/c_slot.yaml, the single-surface tests): a back a wide joins
// two arms L long and b high, a slot s between them (0.16 of a brick: the back of the
// slot is one thin brick tall), one element thick in z (a plane problem). Transfinite
// blocks of h = 0.5 mm bricks, but the slot's back brick, s tall.
// Physical volume "c"; physical surfaces "slot_lower" and "slot_upper" (the arms' facing
// faces), "slot_back" (the thin brick's face between them), "lower_base" (y = 0),
// "upper_tip" (the upper arm's end), "front" (z = 0) and "back" (z = h).
DefineConstant[ a = {3e-3, Name "back width, m"}, L = {12e-3, Name "arm length, m"},
                b = {3e-3, Name "arm height, m"}, s = {0.08e-3, Name "slot width, m"},
                h = {0.5e-3, Name "element size, m"} ];
xs[] = {0, a, a + L};
ys[] = {0, b, b + s, 2 * b + s};
For i In {0:2}
  For j In {0:3}
    Point(1 + i + 3 * j) = {xs[i], ys[j], 0};
  EndFor
EndFor
// Horizontal lines: 100 + i + 3 j joins (i, j)-(i+1, j); vertical: 200 + i + 3 j joins (i, j)-(i, j+1).
For j In {0:3}
  For i In {0:1}
    Line(100 + i + 3 * j) = {1 + i + 3 * j, 2 + i + 3 * j};
    Transfinite Curve{100 + i + 3 * j} = Round((xs[i + 1] - xs[i]) / h) + 1;
  EndFor
EndFor
For j In {0:2}
  For i In {0:2}
    Line(200 + i + 3 * j) = {1 + i + 3 * j, 1 + i + 3 * (j + 1)};
    Transfinite Curve{200 + i + 3 * j} = Max(Round((ys[j + 1] - ys[j]) / h), 1) + 1;
  EndFor
EndFor
// The blocks (i, j): the back i = 0 in every row, the arms i = 1 in rows 0 and 2.
blocks[] = {0, 0, 0, 1, 0, 2, 1, 0, 1, 2};
surfaces[] = {};
For k In {0:#blocks[] / 2 - 1}
  i = blocks[2 * k]; j = blocks[2 * k + 1];
  Curve Loop(1000 + k) = {100 + i + 3 * j, 200 + i + 1 + 3 * j, -(100 + i + 3 * (j + 1)), -(200 + i + 3 * j)};
  Plane Surface(1000 + k) = {1000 + k};
  Transfinite Surface{1000 + k};
  Recombine Surface{1000 + k};
  surfaces[] += {1000 + k};
EndFor
out[] = Extrude {0, 0, h} { Surface{surfaces[]}; Layers{1}; Recombine; };
Physical Volume("c") = Volume{:};
// The faces by where they lie (bounding boxes of the extruded sides).
eps = 1e-7;
Physical Surface("slot_lower") = Surface In BoundingBox{a - eps, b - eps, -eps, a + L + eps, b + eps, h + eps};
Physical Surface("slot_upper") = Surface In BoundingBox{a - eps, b + s - eps, -eps, a + L + eps, b + s + eps, h + eps};
Physical Surface("slot_back") = Surface In BoundingBox{a - eps, b - eps, -eps, a + eps, b + s + eps, h + eps};
Physical Surface("lower_base") = Surface In BoundingBox{-eps, -eps, -eps, a + L + eps, eps, h + eps};
Physical Surface("upper_tip") = Surface In BoundingBox{a + L - eps, b + s - eps, -eps, a + L + eps, 2 * b + s + eps, h + eps};
Physical Surface("front") = Surface In BoundingBox{-eps, -eps, -eps, a + L + eps, 2 * b + s + eps, eps};
Physical Surface("back") = Surface In BoundingBox{-eps, -eps, h - eps, a + L + eps, 2 * b + s + eps, h + eps};
