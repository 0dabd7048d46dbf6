// [0, 2] x [0, 1] as 2 x 1 transfinite 16-node quadrilaterals (gmsh type 36)
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Transfinite Curve{1, 3} = 3; Transfinite Curve{2, 4} = 2;
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("plate") = {1};
Mesh.ElementOrder = 3; Mesh.SecondOrderIncomplete = 0;
Mesh.MshFileVersion = 4.1; Mesh.Binary = 0;
