// Hertz's half cylinder for contactqp, meshed by Gmsh: the lower half of the disc of radius
// R centred at (0, R), touching y = 0 at the origin. Triangles of size h_contact within
// |x| <= x_fine of the lowest point, growing by `grading` per unit distance up to h_far.
// contactqp meshes this file when it solves scenes/hertz-gmsh.json; to make a .msh instead:
//   gmsh scenes/hertz_disc.geo -2 -format msh41 -o hertz_disc.msh   (msh22 for version 2.2)
R = 1.0;
h_contact = 0.002;
h_far = 0.1;
grading = 0.1;
x_fine = 0.15;

phi = Asin(x_fine / R);
Point(1) = {0, R, 0};                                // centre
Point(2) = {-R, R, 0};
Point(3) = {-R * Sin(phi), R - R * Cos(phi), 0};
Point(4) = {0, 0, 0};                                // lowest point
Point(5) = {R * Sin(phi), R - R * Cos(phi), 0};
Point(6) = {R, R, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 6};
Line(5) = {6, 2};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

Physical Curve("arc") = {1, 2, 3, 4};
Physical Curve("top") = {5};
Physical Surface("body") = {1};

Field[1] = Distance;
Field[1].CurvesList = {2, 3};
Field[1].NumPointsPerCurve = 400;
Field[2] = MathEval;
Field[2].F = Sprintf("Min(%g, %g + %g * F1)", h_far, h_contact, grading);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;
