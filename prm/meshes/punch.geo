// Plane-strain flat punch on a block (half model, symmetric about x = 0):
// block [0, 10] x [0, 5] mm, the punch covers x in [0, 1] of the top face.
// Quadrilaterals, finer under the punch. Lengths in mm.
// Regenerate with: gmsh -2 -format msh22 punch.geo -o punch.msh
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {10, 5, 0};
Point(4) = {1, 5, 0};
Point(5) = {0, 5, 0};
Point(6) = {1, 0, 0};
Line(1) = {1, 6};  // bottom under the punch
Line(2) = {6, 2};  // bottom, rest
Line(3) = {2, 3};  // right
Line(4) = {3, 4};  // top, free
Line(5) = {4, 5};  // punch
Line(6) = {5, 1};  // symmetry
Line(7) = {6, 4};  // internal, x = 1
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{1, 5} = 9;
Transfinite Curve{2, 4} = 37 Using Progression 1.06;
Transfinite Curve{3, 6, 7} = 21 Using Progression 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};
Physical Curve("punch") = {5};
Physical Curve("top") = {4};
Physical Curve("symmetry") = {6};
Physical Curve("bottom") = {1, 2};
Physical Curve("right") = {3};
Physical Surface("block") = {1, 2};
