// A circular cylinder in a channel (docs/curved.md): the channel [-1.5, 3.5] x [-1.5, 1.5] minus
// the disk of radius 0.5 at the origin, unstructured quads of size h (default 0.25) graded to
// h/hc (default hc = 3) on the cylinder. Boundaries: inlet (x = -1.5), outlet (x = 3.5),
// walls (y = +-1.5), cylinder (the circle, one closed OpenCASCADE curve).
//   gmsh -2 -setnumber h 0.25 cylinder.geo -o cylinder.msh
// The geometry itself is what --geometry reads (lpcvt, bamgquad, refine, meshconvert).
SetFactory("OpenCASCADE");
If (!Exists(h))
  h = 0.25;
EndIf
If (!Exists(hc))
  hc = 3;
EndIf
Rectangle(1) = {-1.5, -1.5, 0, 5, 3};
Disk(2) = {0, 0, 0, 0.5};
BooleanDifference(3) = {Surface{1}; Delete;}{Surface{2}; Delete;};
MeshSize{PointsOf{Surface{3};}} = h;
cyl() = Curve In BoundingBox{-0.6, -0.6, -1, 0.6, 0.6, 1};
MeshSize{PointsOf{Curve{cyl()};}} = h / hc;
Mesh.MeshSizeFromCurvature = 12;
Mesh.Algorithm = 6;
Mesh.RecombinationAlgorithm = 3;
Mesh.RecombineAll = 1;
eps = 1e-6;
Physical Curve("inlet", 1) = Curve In BoundingBox{-1.5 - eps, -1.5 - eps, -eps, -1.5 + eps, 1.5 + eps, eps};
Physical Curve("outlet", 2) = Curve In BoundingBox{3.5 - eps, -1.5 - eps, -eps, 3.5 + eps, 1.5 + eps, eps};
Physical Curve("walls", 3) = Curve In BoundingBox{-1.5 - eps, -1.5 - eps, -eps, 3.5 + eps, -1.5 + eps, eps};
Physical Curve("walls", 3) += Curve In BoundingBox{-1.5 - eps, 1.5 - eps, -eps, 3.5 + eps, 1.5 + eps, eps};
Physical Curve("cylinder", 4) = {cyl()};
Physical Surface("domain", 5) = {3};
