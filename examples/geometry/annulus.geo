// The annulus 1 <= r <= 2 around the origin, structured quads: four transfinite quarter rings of
// N x N cells each (-setnumber N .., default 4; 4 N^2 cells). Boundaries: inner (r = 1),
// outer (r = 2). Curved cells of geometric order q with their edge nodes on the true circles:
//   gmsh -2 -order 3 -setnumber N 4 annulus.geo -o annulus.msh
// (docs/curved.md; a q = 1 mesh is the straight-sided polygonal annulus.)
If (!Exists(N))
  N = 4;
EndIf
r1 = 1;
r2 = 2;
Point(1) = {0, 0, 0};
Point(2) = {r1, 0, 0};
Point(3) = {0, r1, 0};
Point(4) = {-r1, 0, 0};
Point(5) = {0, -r1, 0};
Point(6) = {r2, 0, 0};
Point(7) = {0, r2, 0};
Point(8) = {-r2, 0, 0};
Point(9) = {0, -r2, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 8};
Circle(7) = {8, 1, 9};
Circle(8) = {9, 1, 6};
Line(9) = {2, 6};
Line(10) = {3, 7};
Line(11) = {4, 8};
Line(12) = {5, 9};
Curve Loop(1) = {9, 5, -10, -1};
Curve Loop(2) = {10, 6, -11, -2};
Curve Loop(3) = {11, 7, -12, -3};
Curve Loop(4) = {12, 8, -9, -4};
For s In {1:4}
  Plane Surface(s) = {s};
EndFor
Transfinite Curve{1:12} = N + 1;
Transfinite Surface{1:4};
Recombine Surface{1:4};
Physical Curve("inner", 1) = {1:4};
Physical Curve("outer", 2) = {5:8};
Physical Surface("domain", 3) = {1:4};
