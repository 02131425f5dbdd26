// The paper's test scenes (Smith et al. 2018, sec. 6) at sizes a small
// machine can run: a mesh, a material, constraints and solve options that
// QuasistaticSolver runs as they are.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "snh/material.h"
#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh {

struct SceneParameters {
  std::optional<int> resolution;  // cells across the scene's thickness; unset: the scene's default
  double youngs_modulus = 1.0;
  double poisson_ratio = 0.49;
  std::optional<Barrier> barrier;  // unset: see Barrier
  std::optional<int> steps;        // load steps; unset: the scene's default
  unsigned seed = 1;
  // hex8 (the paper's lattices) or tet4 (each lattice hex split in six).
  ElementType element_type = ElementType::hex8;
  // Newton stops when the force residual is that of a strain error of this
  // size: |r| <= strain_tolerance * E * h^2 * sqrt(vertices), h the cell size
  // on the lattice scenes; drop (a Gmsh tet blob) passes it on as
  // SolveOptions::strain_tolerance (h its mean vertex spacing).
  double strain_tolerance = defaults::strain_tolerance_double;
};

struct Scene {
  std::string name;
  std::string description;
  Mesh mesh;
  StableNeoHookean material;
  std::vector<ConstraintSet> constraints;
  SolveOptions options;  // steps, tolerance and, for scramble, the initial positions
};

// "stretch": a voxelized hex cylinder (radius 0.5, length 2) stretched to 3.4x
//   its length by moving its end faces apart (paper: volume +4.3%, nu = 0.49).
// "twist": a unit cube of resolution^3 hexes (default 15), the bottom face
//   fixed, the top face rotated about the vertical axis by pi/2 per step,
//   twice (paper: 12 and 16 Newton, 3,278 and 4,956 CG iterations).
// "scramble": a cube whose vertices start at random inside a box of twice its
//   volume, four bottom corners pinned at rest; it must recover.
// "flex": a 4:1:1 limb-like hex lattice driven by two rigid bones (vertex sets
//   in its core); one bone fixed, the other bent 90 degrees about the joint.
// "elbow": a 6:1:1 limb flexed 140 degrees by two bones with self-contact on
//   (SolveOptions::contact.self), so the inner side folds without passing
//   through itself.
// "drop": the paper's octopus test (Fig. 11) in miniature, in SI units: a
//   soft Gmsh tet body (data/meshes/blob.msh: an ellipsoid of radii 5, 5, 4
//   cm, 6,117 tets; resolution 1: blob_coarse.msh, 700 tets) under gravity
//   and implicit Euler (density 1000 kg/m^3, 2 s in `steps` frames, default
//   60, 4 substeps each) falls onto three parallel horizontal cylinders
//   between two walls; a fourth, broad cylinder comes down and squashes it
//   against them (to 6 mm above the middle one), goes back up, and the body
//   must recover its shape. Its E and nu come from scene_defaults("drop")
//   (5e4 Pa, 0.46); element_type does not apply (the mesh is tet4).
// Throws snh::Error for an unknown name or out-of-range parameters.
Scene make_scene(const std::string& name, const SceneParameters& parameters);

std::vector<std::string> scene_names();

// The scenes built on the paper's lattices and run as load steps (all but
// "drop", a tet4 mesh under dynamics, and "elbow", with self-contact): those
// whose resolution, element type and E the benchmarks that sweep them
// (errtime, scale) can vary.
std::vector<std::string> lattice_scene_names();

// The parameters a scene is meant to run with: the struct's defaults, except
// "drop"'s SI material (E = 5e4 Pa, nu = 0.46).
SceneParameters scene_defaults(const std::string& name);

// Where scenes find their shipped files (drop's mesh): the environment
// variable SNH_DATA_DIR if set, else the source tree's data/ folder.
std::string scene_data_dir();

}  // namespace snh
