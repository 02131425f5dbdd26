// A host application rigging a character's surface: it voxelizes the shipped
// arm (data/arm/arm.obj) into a hex lattice, embeds the surface in it, makes
// two capsule bones into constraint sets, and steps the first frames of the
// shipped elbow flexion (data/arm/arm_flexion.json), setting the forearm's
// transform each frame and reading the deformed surface back. It checks that
// the hand follows the elbow's rotation and writes the last frame's surface
// as OBJ.
//
// Usage: arm_rig DATA_ARM_FOLDER [frames=6] [output-folder=arm_rig_out]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "snh/animation.h"
#include "snh/error.h"
#include "snh/rig.h"
#include "snh/simulation.h"
#include "snh/surface.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: arm_rig DATA_ARM_FOLDER [frames] [output-folder]\n";
    return 2;
  }
  const std::string data = argv[1];
  const int frames = argc > 2 ? std::stoi(argv[2]) : 6;
  const std::string out = argc > 3 ? argv[3] : "arm_rig_out";
  try {
    // The surface, its lattice and the surface's place in the lattice.
    const snh::TriangleSurface arm = snh::read_surface(data + "/arm.obj");
    const snh::Voxelization voxels = snh::voxelize(arm, 0.125);
    const snh::Embedding embedding = snh::embed(voxels, arm);

    // Bones in rest coordinates (those of data/scenes/arm.json): the upper
    // arm listed first, so it would win a vertex both bones contain.
    const std::vector<snh::Bone> bones = {
        {"upper_arm", snh::Capsule{{0.35, 0.0, 0.0}, {1.6, 0.0, 0.0}, 0.25}},
        {"forearm", snh::Capsule{{2.4, 0.0, 0.0}, {3.55, 0.0, 0.0}, 0.24}},
    };
    const std::vector<snh::ConstraintSet> sets = snh::bone_constraints(voxels.lattice, bones);
    const auto flesh = snh::StableNeoHookean::from_youngs_modulus(1.0, 0.45);
    snh::Simulation sim(voxels.lattice, flesh, sets);
    std::cout << "device: " << sim.device().name << "; " << voxels.lattice.element_count() << " hexes, "
              << arm.vertex_count() << " surface vertices; bones hold " << sets[0].vertices.size() << " and "
              << sets[1].vertices.size() << " lattice vertices\n";

    // The forearm rotates about its own centroid between frames (the centre
    // Simulation interpolates rotations about); the upper arm stays at rest.
    std::array<double, 3> centroid{0, 0, 0};
    for (int32_t v : sets[1].vertices)
      for (int d = 0; d < 3; ++d) centroid[d] += voxels.lattice.positions(size_t(v), d) / sets[1].vertices.size();
    const snh::Animation flexion = snh::read_animation(data + "/arm_flexion.json");
    const auto named = std::find(flexion.bones.begin(), flexion.bones.end(), "forearm");
    if (named == flexion.bones.end()) throw snh::Error("arm_flexion.json does not animate the forearm");
    const size_t forearm = static_cast<size_t>(named - flexion.bones.begin());

    const size_t hand = arm.vertex_count() - 1;  // make_arm.py: the hand's tip (4, 0, 0) comes last
    snh::Points surface;
    snh::Matrix4 m = snh::identity_matrix4();
    bool converged = true;
    for (int f = 0; f < frames && f < static_cast<int>(flexion.frame_count()); ++f) {
      m = flexion.transforms[f][forearm];
      sim.set_transform("forearm", snh::to_rigid_transform(m, centroid));
      const snh::SolveResult r = sim.solve(1);
      converged = converged && r.converged;
      surface = snh::embedded_positions(embedding, voxels.lattice, sim.positions());
      std::printf("frame %d: %s, %zu Newton, min J %.3f; hand at (%.3f, %.3f, %.3f)\n", f,
                  r.converged ? "converged" : to_string(r.steps.back().status), r.history.size(), r.min_j,
                  surface(hand, 0), surface(hand, 1), surface(hand, 2));
    }
    // The hand follows the forearm bone's transform closely.
    const double* p = arm.positions.data() + 3 * hand;
    double miss = 0.0;
    for (int r = 0; r < 3; ++r) {
      const double target = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
      miss = std::max(miss, std::abs(surface(hand, r) - target));
    }
    std::filesystem::create_directories(out);
    snh::write_obj(out + "/arm_last_frame.obj", arm, surface);
    std::cout << "hand off its bone's transform by " << miss << "; wrote " << out << "/arm_last_frame.obj\n";
    return converged && miss < 0.05 ? 0 : 1;
  } catch (const snh::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  }
}
