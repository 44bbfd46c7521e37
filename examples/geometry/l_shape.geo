// A non-convex L-shaped domain, [0,1]^2 without the upper-right quarter (0.5,1]^2, meshed with
// unstructured quadrilaterals. h = target edge length (default 0.08). Boundaries, counter-
// clockwise from the origin: bottom (y = 0), right (x = 1), inner_horizontal (y = 0.5),
// inner_vertical (x = 0.5), top (y = 1), left (x = 0); domain: "domain".
//   gmsh -2 l_shape.geo -o l_shape.msh
If (!Exists(h))
  h = 0.08;
EndIf
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 0.5, 0, h};
Point(4) = {0.5, 0.5, 0, h};
Point(5) = {0.5, 1, 0, h};
Point(6) = {0, 1, 0, h};
For i In {1:6}
  Line(i) = {i, i % 6 + 1};
EndFor
Curve Loop(1) = {1:6};
Plane Surface(1) = {1};
Mesh.Algorithm = 6;  // Frontal-Delaunay (8, "for quads", crashes in Gmsh 4.8.4)
Mesh.RecombinationAlgorithm = 3;
Mesh.RecombineAll = 1;
Physical Curve("bottom", 1) = {1};
Physical Curve("right", 2) = {2};
Physical Curve("inner_horizontal", 3) = {3};
Physical Curve("inner_vertical", 4) = {4};
Physical Curve("top", 5) = {5};
Physical Curve("left", 6) = {6};
Physical Surface("domain", 7) = {1};
