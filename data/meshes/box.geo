// A 1 x 0.5 x 0.25 box, coarse tetrahedra (regenerate: see README.md).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 0.25};
Mesh.MeshSizeMax = 0.2;
