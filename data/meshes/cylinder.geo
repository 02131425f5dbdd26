// A cylinder of radius 0.3 and length 1 along z, coarse tetrahedra.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 1, 0.3};
Mesh.MeshSizeMax = 0.2;
