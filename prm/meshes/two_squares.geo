// Two unit squares side by side, [0,1]x[0,1] (left_body) and [1,2]x[0,1]
// (right_body), sharing the curve x = 1 (a conforming, glued interface).
// Quadrilateral mesh (Recombine), 4 x 4 cells per square. Lengths in mm.
// Regenerate with: gmsh -2 -format msh22 two_squares.geo -o two_squares.msh
n = 5; // nodes per edge

Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {2, 0, 0};
Point(4) = {0, 1, 0};
Point(5) = {1, 1, 0};
Point(6) = {2, 1, 0};

Line(1) = {1, 2}; // bottom, left square
Line(2) = {2, 3}; // bottom, right square
Line(3) = {3, 6}; // right
Line(4) = {6, 5}; // top, right square
Line(5) = {5, 4}; // top, left square
Line(6) = {4, 1}; // left
Line(7) = {2, 5}; // interface x = 1

Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};

Transfinite Curve{1:7} = n;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

Physical Curve("left") = {6};
Physical Curve("right") = {3};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {4, 5};
Physical Surface("left_body") = {1};
Physical Surface("right_body") = {2};
