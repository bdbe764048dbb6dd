// A U-shaped block (input/u_shape.yaml, the self-contact tests): a base b high and
// W wide with two arms a wide and H high, one element thick in z (a plane problem);
// right = 0 leaves the right arm off: an L. Transfinite blocks of h = 0.5 mm bricks.
// Physical volume "u"; physical surfaces "inner_left", "inner_right" (the arms' facing
// faces), "inner_base" (the base between them), "tip_left", "tip_right" (the arms'
// outer faces over their top t), "front" (z = 0) and "back" (z = h), "rest".
DefineConstant[ a = {3e-3, Name "arm width, m"}, g = {4e-3, Name "gap between the arms, m"},
                b = {3e-3, Name "base height, m"}, H = {20e-3, Name "arm height, m"},
                t = {4e-3, Name "tip height pushed, m"}, h = {0.5e-3, Name "element size, m"},
                right = {1, Name "1: a U, 0: an L"} ];
W = 2 * a + g;
xs[] = {0, a, a + g, W};
ys[] = {0, b, b + H - t, b + H};
For i In {0:3}
  For j In {0:3}
    Point(1 + i + 4 * j) = {xs[i], ys[j], 0};
  EndFor
EndFor
// Horizontal lines: 100 + i + 4 j joins (i, j)-(i+1, j); vertical: 200 + i + 4 j joins (i, j)-(i, j+1).
For j In {0:3}
  For i In {0:2}
    Line(100 + i + 4 * j) = {1 + i + 4 * j, 2 + i + 4 * j};
    Transfinite Curve{100 + i + 4 * j} = Round((xs[i + 1] - xs[i]) / h) + 1;
  EndFor
EndFor
For j In {0:2}
  For i In {0:3}
    Line(200 + i + 4 * j) = {1 + i + 4 * j, 1 + i + 4 * (j + 1)};
    Transfinite Curve{200 + i + 4 * j} = Round((ys[j + 1] - ys[j]) / h) + 1;
  EndFor
EndFor
// The blocks (i, j): the base row j = 0, the left arm i = 0 and the right arm i = 2 above it.
blocks[] = {0, 0, 1, 0, 2, 0, 0, 1, 0, 2};
If (right == 1)
  blocks[] += {2, 1, 2, 2};
EndIf
surfaces[] = {};
For k In {0:#blocks[] / 2 - 1}
  i = blocks[2 * k]; j = blocks[2 * k + 1];
  Curve Loop(1000 + k) = {100 + i + 4 * j, 200 + i + 1 + 4 * j, -(100 + i + 4 * (j + 1)), -(200 + i + 4 * j)};
  Plane Surface(1000 + k) = {1000 + k};
  Transfinite Surface{1000 + k};
  Recombine Surface{1000 + k};
  surfaces[] += {1000 + k};
EndFor
out[] = Extrude {0, 0, h} { Surface{surfaces[]}; Layers{1}; Recombine; };
Physical Volume("u") = Volume{:};
// The faces by where they lie (bounding boxes of the extruded sides).
eps = 1e-6;
Physical Surface("inner_left") = Surface In BoundingBox{a - eps, b - eps, -eps, a + eps, b + H + eps, h + eps};
Physical Surface("inner_right") = Surface In BoundingBox{a + g - eps, b - eps, -eps, a + g + eps, b + H + eps, h + eps};
Physical Surface("inner_base") = Surface In BoundingBox{a - eps, b - eps, -eps, a + g + eps, b + eps, h + eps};
Physical Surface("tip_left") = Surface In BoundingBox{-eps, b + H - t - eps, -eps, eps, b + H + eps, h + eps};
Physical Surface("tip_right") = Surface In BoundingBox{W - eps, b + H - t - eps, -eps, W + eps, b + H + eps, h + eps};
Physical Surface("front") = Surface In BoundingBox{-eps, -eps, -eps, W + eps, b + H + eps, eps};
Physical Surface("back") = Surface In BoundingBox{-eps, -eps, h - eps, W + eps, b + H + eps, h + eps};
