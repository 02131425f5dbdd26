// A sphere of radius 0.5 at the origin, as a triangle surface (regenerate: see README.md).
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 0.5};
Mesh.MeshSizeMax = 0.15;
