// A pin: a cylinder of radius R = 1 and length 2 with a hemispherical end, the end's lowest
// point at the origin. Physical surfaces "tip" (the spherical end), "top" (the flat end) and
// "side"; the volume "pin". The mesh is graded from 0.012 at the lowest point to 0.3.
SetFactory("OpenCASCADE");
R = 1;
L = 2;
Sphere(1) = {0, 0, R, R};
Cylinder(2) = {0, 0, R, 0, 0, L, R};
BooleanUnion(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
eps = 1e-6;
tip() = Surface In BoundingBox{-R - eps, -R - eps, -eps, R + eps, R + eps, R + eps};
top() = Surface In BoundingBox{-R - eps, -R - eps, R + L - eps, R + eps, R + eps, R + L + eps};
side() = Surface In BoundingBox{-R - eps, -R - eps, R - eps, R + eps, R + eps, R + L + eps};
side() -= top();
Physical Surface("tip") = tip();
Physical Surface("top") = top();
Physical Surface("side") = side();
Physical Volume("pin") = {3};
Field[1] = MathEval;
Field[1].F = "Min(0.3, 0.012 + 0.3 * Sqrt(x * x + y * y + z * z))";
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
