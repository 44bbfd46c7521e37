// The unit square with a circular hole of radius 0.2 at (0.5, 0.5), unstructured quads.
// h = target edge length (default 0.06). Boundaries: bottom, right, top, left, hole.
//   gmsh -2 square_with_hole.geo -o square_with_hole.msh
SetFactory("OpenCASCADE");
If (!Exists(h))
  h = 0.06;
EndIf
Rectangle(1) = {0, 0, 0, 1, 1};
Disk(2) = {0.5, 0.5, 0, 0.2};
BooleanDifference(3) = {Surface{1}; Delete;}{Surface{2}; Delete;};
MeshSize{PointsOf{Surface{3};}} = h;
Mesh.Algorithm = 6;  // Frontal-Delaunay (8, "for quads", crashes in Gmsh 4.8.4)
Mesh.RecombinationAlgorithm = 3;
Mesh.RecombineAll = 1;
eps = 1e-6;
Physical Curve("bottom", 1) = Curve In BoundingBox{-eps, -eps, -eps, 1 + eps, eps, eps};
Physical Curve("right", 2) = Curve In BoundingBox{1 - eps, -eps, -eps, 1 + eps, 1 + eps, eps};
Physical Curve("top", 3) = Curve In BoundingBox{-eps, 1 - eps, -eps, 1 + eps, 1 + eps, eps};
Physical Curve("left", 4) = Curve In BoundingBox{-eps, -eps, -eps, eps, 1 + eps, eps};
Physical Curve("hole", 5) = Curve In BoundingBox{0.3 - eps, 0.3 - eps, -eps, 0.7 + eps, 0.7 + eps, eps};
Physical Surface("domain", 6) = {3};
