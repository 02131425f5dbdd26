// A 1 x 0.6 x 1 box with a slot 0.04 wide (x in [0.48, 0.52]) cut from its top
// face down to z = 0.5, through its whole depth in y: two prongs joined at the
// bottom (regenerate: see README.md).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.6, 1};
Box(2) = {0.48, -0.1, 0.5, 0.04, 0.8, 0.6};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
Mesh.MeshSizeMax = 0.15;
