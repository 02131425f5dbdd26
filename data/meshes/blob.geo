// The drop scene's soft body (metres): an ellipsoid of radii 5, 5 and 4 cm
// centred at the origin, tetrahedra of size h (default 9 mm; gmsh
// -setnumber h 0.015 for the coarse test mesh).
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.009, Name "mesh size"} ];
Sphere(1) = {0, 0, 0, 1};
Dilate {{0, 0, 0}, {0.05, 0.05, 0.04}} { Volume{1}; }
Mesh.MeshSizeMax = h;
Mesh.MeshSizeMin = 0.5 * h;
Mesh.Optimize = 1;
