// The 1 x 0.5 x 0.25 box as two volumes (x < 0.5 and x > 0.5) with Gmsh
// physical groups (regenerate: see README.md): volumes "left" (1), "right"
// (2) and "all" (3, overlapping both), the surface "fixed" (1, at x = 0)
// and an unnamed surface group 7 (at x = 1). Surface and volume groups
// share tag 1, as Gmsh numbers each dimension separately.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.5, 0.5, 0.25};
Box(2) = {0.5, 0, 0, 0.5, 0.5, 0.25};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.MeshSizeMax = 0.25;
Physical Volume("left", 1) = {1};
Physical Volume("right", 2) = {2};
Physical Volume("all", 3) = {1, 2};
Physical Surface("fixed", 1) = {Surface In BoundingBox{-0.1, -1, -1, 0.1, 2, 2}};
Physical Surface(7) = {Surface In BoundingBox{0.9, -1, -1, 1.1, 2, 2}};
