// A character's frames (snh/character.h): run_frames one frame at a time,
// so that a frame can start from the skinned guess, with the simulated
// surface compared against linear blend skinning.
#include <cmath>

#include "snh/character.h"
#include "snh/error.h"

namespace snh {

std::vector<CharacterFrame> run_character_frames(Simulation& simulation, const Character& character,
                                                 const CharacterRig& rig, const CharacterFrameOptions& options,
                                                 const CharacterFrameCallback& on_frame) {
  if (!character.has_clip) throw Error(character.file + ": no animation clip to run");
  const Animation& all = rig.bones.animation;
  if (all.frame_count() != character.clip.frame_count())
    throw Error(character.file + ": the bones' animation has " + std::to_string(all.frame_count()) +
                " frames, the clip " + std::to_string(character.clip.frame_count()));
  if (options.skinned_guess && rig.lattice_weights.vertex_count() != simulation.mesh().vertex_count())
    throw Error(character.file + ": the skinned guess has weights for " +
                std::to_string(rig.lattice_weights.vertex_count()) + " lattice vertices, the simulation has " +
                std::to_string(simulation.mesh().vertex_count()));
  std::vector<CharacterFrame> frames;
  // The lattice's skinned positions of the frame before (the rest shape
  // before the first frame, where the state starts).
  Points skinned_before = simulation.mesh().positions;
  for (size_t f = 0; f < all.frame_count(); ++f) {
    const std::vector<Matrix4>& skinning = character.clip.skinning[f];
    if (options.skinned_guess) {
      // The last state moved by the skinning's change since the last frame:
      // it keeps what the solve added to skinning (volume at the inside of
      // a bend, which skinning alone loses and a start from it would have
      // to restore through inverted elements).
      const Points skinned = linear_blend_skinning(simulation.mesh().positions, rig.lattice_weights, skinning);
      Points guess = simulation.positions();
      double* g = guess.data();
      const double *now = skinned.data(), *before = skinned_before.data();
      for (size_t i = 0; i < guess.xyz().size(); ++i) g[i] += now[i] - before[i];
      simulation.set_state(guess);
      skinned_before = skinned;
    }
    Animation one;
    one.bones = all.bones;
    one.times = {all.times[f]};
    one.transforms = {all.transforms[f]};
    CharacterFrame frame;
    Points lattice, surface;
    run_frames(simulation, one, &rig.embedding, options.frames,
               [&](const FrameRecord& r, const Points& x, const Points& s) {
                 frame.record = r;
                 lattice = x;
                 surface = s;
                 return true;
               });
    frame.record.frame = character.clip.first_frame + static_cast<int>(f);
    frame.record.time = all.times[f];
    const Points skinned = linear_blend_skinning(character.surface.positions, character.weights, skinning);
    const size_t n = skinned.size();
    double sum = 0.0;
    bool finite = true;
    for (size_t v = 0; v < n; ++v) {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) d2 += (surface(v, d) - skinned(v, d)) * (surface(v, d) - skinned(v, d));
      const double d = std::sqrt(d2);
      finite = finite && std::isfinite(d);
      frame.lbs.max_distance = std::max(frame.lbs.max_distance, d);
      sum += d;
    }
    frame.lbs.mean_distance = n ? sum / static_cast<double>(n) : 0.0;
    if (!finite) frame.lbs.max_distance = frame.lbs.mean_distance = std::nan("");
    frames.push_back(frame);
    const bool go_on = on_frame ? on_frame(frame, lattice, surface, skinned) : true;
    if (!go_on || (options.frames.stop_on_failure && !frame.record.converged)) break;
  }
  return frames;
}

}  // namespace snh
