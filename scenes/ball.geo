// A ball between two plates, for contactqp (ball-between-plates.json): the half x >= 0
// of the disc of radius R centred at (0, R), touching y = 0 at its lowest point and y = 2R at
// its highest. Triangles of size h_contact within |x| <= x_fine of both poles, growing by
// `grading` per unit distance up to h_far. Boundaries: "lower" and "upper" (the arcs below and
// above the centre's height), "symmetry" (the cut x = 0).
R = 1.0;
h_contact = 0.002;
h_far = 0.1;
grading = 0.1;
x_fine = 0.15;

phi = Asin(x_fine / R);
Point(1) = {0, R, 0};                              // centre
Point(2) = {0, 0, 0};                              // lowest point
Point(3) = {R * Sin(phi), R - R * Cos(phi), 0};
Point(4) = {R, R, 0};
Point(5) = {R * Sin(phi), R + R * Cos(phi), 0};
Point(6) = {0, 2 * R, 0};                          // highest point
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 6};
Line(5) = {6, 2};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

Physical Curve("lower") = {1, 2};
Physical Curve("upper") = {3, 4};
Physical Curve("symmetry") = {5};
Physical Surface("ball") = {1};

Field[1] = Distance;
Field[1].CurvesList = {1, 4};
Field[1].NumPointsPerCurve = 400;
Field[2] = MathEval;
Field[2].F = Sprintf("Min(%g, %g + %g * F1)", h_far, h_contact, grading);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;
