// IPE 100 hot-rolled I-section with its root fillets, in mm (the model
// file scales it by 1e-3): h = 100, b = 55, t_w = 4.1, t_f = 5.7, r = 7
// (EN 10365). gmsh (x, y) become the section's (x, z).
//
// Three surfaces: each flange with its two fillets, and the web between
// the fillets (cut where the fillets end, so no surface has a cusp where
// a fillet meets the flange tangentially); physical groups "flanges" and
// "web" become section regions.
// All-quadrilateral, second order (9-node quads, L9), the high-order nodes
// on the fillet arcs.
//
//   gmsh ipe100.geo -2 -o ipe100.msh    (gmsh 4.x; the .msh is committed)

h = 100; b = 55; tw = 4.1; tf = 5.7; r = 7;
lc = 3.0;

Point(1) = {-b/2, 0, 0, lc};
Point(2) = { b/2, 0, 0, lc};
Point(3) = { b/2, tf, 0, lc};
Point(4) = { tw/2 + r, tf, 0, lc};
Point(5) = { tw/2 + r, tf + r, 0, lc};     // fillet centre
Point(6) = { tw/2, tf + r, 0, lc};
Point(7) = { tw/2, h - tf - r, 0, lc};
Point(8) = { tw/2 + r, h - tf - r, 0, lc}; // fillet centre
Point(9) = { tw/2 + r, h - tf, 0, lc};
Point(10) = { b/2, h - tf, 0, lc};
Point(11) = { b/2, h, 0, lc};
Point(12) = {-b/2, h, 0, lc};
Point(13) = {-b/2, h - tf, 0, lc};
Point(14) = {-tw/2 - r, h - tf, 0, lc};
Point(15) = {-tw/2 - r, h - tf - r, 0, lc}; // fillet centre
Point(16) = {-tw/2, h - tf - r, 0, lc};
Point(17) = {-tw/2, tf + r, 0, lc};
Point(18) = {-tw/2 - r, tf + r, 0, lc};     // fillet centre
Point(19) = {-tw/2 - r, tf, 0, lc};
Point(20) = {-b/2, tf, 0, lc};

// bottom flange with its two fillets (counter-clockwise)
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Circle(4) = {4, 5, 6};
Line(5) = {6, 17};
Circle(6) = {17, 18, 19};
Line(7) = {19, 20};
Line(8) = {20, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8};
Plane Surface(1) = {1};

// web between the fillets
Line(9) = {6, 7};
Line(10) = {7, 16};
Line(11) = {16, 17};
Curve Loop(2) = {-5, 9, 10, 11};
Plane Surface(2) = {2};

// top flange with its two fillets
Circle(12) = {7, 8, 9};
Line(13) = {9, 10};
Line(14) = {10, 11};
Line(15) = {11, 12};
Line(16) = {12, 13};
Line(17) = {13, 14};
Circle(18) = {14, 15, 16};
Curve Loop(3) = {12, 13, 14, 15, 16, 17, 18, -10};
Plane Surface(3) = {3};

Physical Surface("flanges") = {1, 3};
Physical Surface("web") = {2};

Mesh.RecombineAll = 1;
Mesh.Algorithm = 8;              // frontal-Delaunay for quads
Mesh.RecombinationAlgorithm = 3; // blossom full-quad: all quadrilaterals
Mesh.SubdivisionAlgorithm = 0;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;  // 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
