// An elastic strip (layer) of length L and thickness h lying on a foundation at y = 0, with a
// punch of half-width w on the middle of its top. Physical curves: "bottom" (may touch),
// "punch", "top" (the rest of the top), "ends"; physical surface "strip".
L = 4.0;
h = 1.0;
w = 0.25;
size = 0.05;

Point(1) = {-L / 2, 0, 0, size};
Point(2) = {L / 2, 0, 0, size};
Point(3) = {L / 2, h, 0, size};
Point(4) = {w, h, 0, size};
Point(5) = {-w, h, 0, size};
Point(6) = {-L / 2, h, 0, size};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

Physical Curve("bottom") = {1};
Physical Curve("punch") = {4};
Physical Curve("top") = {3, 5};
Physical Curve("ends") = {2, 6};
Physical Surface("strip") = {1};
Mesh.Algorithm = 6;
