// The unit square meshed with unstructured quadrilaterals (Frontal-Delaunay triangles,
// then Blossom full-quad recombination). h = target edge length (default 0.08).
// Boundaries: bottom, right, top, left; domain: "domain".
//   gmsh -2 -setnumber h 0.05 unstructured_square.geo -o unstructured.msh
SetFactory("OpenCASCADE");
If (!Exists(h))
  h = 0.08;
EndIf
Rectangle(1) = {0, 0, 0, 1, 1};
MeshSize{PointsOf{Surface{1};}} = h;
Mesh.Algorithm = 6;  // Frontal-Delaunay (8, "for quads", crashes in Gmsh 4.8.4)
Mesh.RecombinationAlgorithm = 3;
Mesh.RecombineAll = 1;
Physical Curve("bottom", 1) = {1};
Physical Curve("right", 2) = {2};
Physical Curve("top", 3) = {3};
Physical Curve("left", 4) = {4};
Physical Surface("domain", 5) = {1};
