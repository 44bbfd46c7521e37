// The unit square [0,1]^2 as N x N structured quads (N = 16 is the studies' start).
// Boundaries: physical curves bottom (y = 0), right (x = 1), top (y = 1), left (x = 0);
// domain: physical surface "domain".
//   gmsh -2 -setnumber N 32 unit_square.geo -o square32.msh
// OpenCASCADE's rectangle gives exact node coordinates (the built-in kernel is off by ~1e-12).
SetFactory("OpenCASCADE");
If (!Exists(N))
  N = 16;
EndIf
Rectangle(1) = {0, 0, 0, 1, 1};
Transfinite Curve{1, 2, 3, 4} = N + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("bottom", 1) = {1};
Physical Curve("right", 2) = {2};
Physical Curve("top", 3) = {3};
Physical Curve("left", 4) = {4};
Physical Surface("domain", 5) = {1};
