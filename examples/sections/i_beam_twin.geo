// The parametric section
//   shape = "i_beam", element = "L9", width = 0.1, height = 0.2,
//   web_thickness = 0.006, flange_thickness = 0.01,
//   along_flange = 2, along_web = 4, through = 1
// drawn in gmsh as seven transfinite rectangles (in m): the test
// tests/sections.rs checks that both give the same nodes, elements and
// results. gmsh (x, y) become the section's (x, z).
//
//   gmsh i_beam_twin.geo -2 -o i_beam_twin.msh

xs[] = {0, 0.047, 0.053, 0.1};
zs[] = {0, 0.01, 0.19, 0.2};
nx[] = {2, 1, 2};   // elements per column
nz[] = {1, 4, 1};   // elements per row
cells[] = {0,0, 1,0, 2,0, 1,1, 0,2, 1,2, 2,2};

For j In {0:3}
  For i In {0:3}
    p~{i}~{j} = newp; Point(p~{i}~{j}) = {xs[i], zs[j], 0};
  EndFor
EndFor
s = 0;
For c In {0:6}
  i = cells[2*c]; j = cells[2*c + 1];
  // edges shared by two cells are created once
  a = p~{i}~{j}; b = p~{i+1}~{j}; d = p~{i+1}~{j+1}; e = p~{i}~{j+1};
  l1 = newl; Line(l1) = {a, b}; l2 = newl; Line(l2) = {b, d};
  l3 = newl; Line(l3) = {d, e}; l4 = newl; Line(l4) = {e, a};
  Transfinite Curve{l1, l3} = nx[i] + 1;
  Transfinite Curve{l2, l4} = nz[j] + 1;
  cl = newcl; Curve Loop(cl) = {l1, l2, l3, l4};
  s = news; Plane Surface(s) = {cl};
  Transfinite Surface{s};
  Recombine Surface{s};
  surfaces[c] = s;
EndFor
Coherence;  // merge the duplicated points and lines of neighbouring cells

Physical Surface("flanges") = {surfaces[0], surfaces[1], surfaces[2], surfaces[4], surfaces[5], surfaces[6]};
Physical Surface("web") = {surfaces[3]};

Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
