// A host application as it drives snh frame by frame: a limb of muscle
// (stiff core) wrapped in fat (soft layer) under gravity, held by two bones.
// The upper bone stays; the lower one bends about the elbow by a new
// absolute transform each frame. Each frame is solved from the previous one
// (warm start); the program prints the bones' reaction forces and torques
// and writes every frame's stress, strain and energy density to .vtu files
// indexed by a .pvd collection for ParaView.
//
// Usage: flex_frames [output-folder]   (default: flex_frames_out)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "snh/error.h"
#include "snh/fields.h"
#include "snh/io.h"
#include "snh/regions.h"
#include "snh/selection.h"
#include "snh/simulation.h"

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "flex_frames_out";
  try {
    std::filesystem::create_directories(out);
    // Lengths in m, forces in N, stresses in Pa: a 0.4 m limb, 0.1 m thick.
    const double h = 0.025;
    const snh::Mesh limb = snh::make_box_lattice(16, 4, 4, h);  // 0.4 x 0.1 x 0.1

    // Materials: muscle in the core, fat around it (E in Pa).
    const auto fat = snh::Material::from_youngs_modulus(snh::MaterialModel::stable_neo_hookean, 2e4, 0.47);
    const auto muscle = snh::Material::from_youngs_modulus(snh::MaterialModel::stable_neo_hookean, 1e5, 0.49);
    const snh::MaterialRegion core{"muscle", snh::elements_in_box(limb, {0.0, 0.025, 0.025}, {0.4, 0.075, 0.075}),
                                   muscle};
    const snh::MaterialMap materials = snh::make_material_map(limb, fat, {core});

    // Bones: the lattice vertices along the limb's axis near each end.
    const double e = 1e-6;  // boxes a hair wider than the lines they select
    const auto upper_bone = snh::vertices_in_box(limb, {-e, 0.05 - e, 0.05 - e}, {0.15 + e, 0.05 + e, 0.05 + e});
    const auto lower_bone = snh::vertices_in_box(limb, {0.25 - e, 0.05 - e, 0.05 - e}, {0.4 + e, 0.05 + e, 0.05 + e});
    const std::array<double, 3> elbow{0.2, 0.05, 0.05};

    snh::SolveOptions options;
    options.body_force = {0.0, 0.0, -1000.0 * 9.81};  // density 1000 kg/m^3 times gravity
    snh::Simulation sim(
        limb, materials,
        {snh::ConstraintSet::fixed("upper_bone", upper_bone), snh::ConstraintSet::fixed("lower_bone", lower_bone)},
        options);
    std::cout << "device: " << sim.device().name << ", " << limb.element_count() << " hexes, "
              << 3 * limb.vertex_count() << " DOF\n";

    std::vector<std::pair<double, std::string>> frames;
    const int frame_count = 6;
    bool all_converged = true, balanced = true;
    for (int frame = 0; frame <= frame_count; ++frame) {
      // The bone's absolute transform this frame: bent about the elbow.
      const double angle = (M_PI / 3) * frame / frame_count;
      sim.set_transform("lower_bone", snh::RigidTransform::rotation_about({0, 1, 0}, -angle, elbow));
      const snh::SolveResult r = sim.solve(frame == 0 ? 1 : 2);
      all_converged = all_converged && r.converged;

      const std::vector<snh::Reaction> reactions = sim.reactions();
      // The bones carry the limb's weight: their reactions balance gravity.
      double carried = 0.0, weight = 0.0;
      for (const snh::Reaction& b : reactions) carried += b.force[2];
      for (size_t v = 0; v < limb.vertex_count(); ++v) weight -= sim.applied_force()(v, 2);
      balanced = balanced && std::abs(carried - weight) <= 1e-3 * weight;
      std::printf("frame %d: %.0f deg, %zu Newton, %s, min J %.3f; bones carry %.3f N of %.3f N weight\n", frame,
                  angle * 180 / M_PI, r.history.size(), r.converged ? "converged" : to_string(r.steps.back().status),
                  r.min_j, carried, weight);
      for (const snh::Reaction& b : reactions)
        std::printf("  %-10s force (%8.3f %8.3f %8.3f) N  torque (%8.4f %8.4f %8.4f) N m\n", b.name.c_str(), b.force[0],
                    b.force[1], b.force[2], b.torque[0], b.torque[1], b.torque[2]);

      const snh::ElementFields fields = sim.fields();
      const std::string name = "frame_" + std::to_string(frame) + ".vtu";
      snh::write_vtu(out + "/" + name, limb, sim.positions(), {}, snh::element_fields_for_vtu(fields, materials));
      frames.emplace_back(frame, name);
    }
    snh::write_pvd(out + "/frames.pvd", frames);
    std::cout << "wrote " << out << "/frames.pvd\n";
    return all_converged && balanced ? 0 : 1;
  } catch (const snh::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  }
}
