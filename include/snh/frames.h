// Running an animation: for each frame, every animated bone's transform set
// on its constraint set, a solve from the previous frame (warm start), and
// the embedded surface carried along. Running is separate from writing: the
// driver returns one record per frame and hands each frame's positions to a
// callback, which writes what it likes (snh/io.h, snh/surface.h).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "snh/animation.h"
#include "snh/simulation.h"
#include "snh/surface.h"

namespace snh {

struct FrameRecord {
  int frame = 0;
  double time = 0.0;
  bool converged = false;  // every load step's Newton solve met its tolerance (and none failed on inversion)
  // The last load step's (StepResult::status); StepStatus::inverted_elements
  // where FrameOptions::fail_on_inverted (or SolveOptions') failed the frame.
  StepStatus status = StepStatus::none;
  int newton_iterations = 0;
  int cg_iterations = 0;
  double residual_norm = 0.0;
  double seconds = 0.0;
  SolveProfile profile;  // where the frame's solve spent its time (SolveResult::profile)
  double volume_ratio = 0.0;
  double min_j = 0.0;
  int inverted_elements = 0;  // at the frame's end (J <= 0 at some quadrature point)
  // Barrier self-contact (ContactOptions::self): the pairs within d-hat and
  // their smallest distance at the frame's end, and the host time it took
  // (StepResult's fields of the same names, summed over the load steps).
  int self_contact_pairs = 0;
  double min_self_distance = 0.0;
  double self_contact_seconds = 0.0;
  // Damage the frame's solve or end state shows (StepResult::warnings of its
  // load steps; each begins with its ResultWarning's name, snh/outcomes.h).
  // Empty: a clean frame.
  std::vector<std::string> warnings;
  // Per constraint set, the force and torque it exerts on the body at the
  // frame's end (Simulation::reactions); empty where they are undefined (a
  // non-finite state: then a warning says so).
  std::vector<Reaction> reactions;
  std::vector<NewtonIteration> history;  // the frame's Newton iterations (SolveResult::history)
  // What the frame's solve ran, as SolveResult reports it (the fields of the
  // same names): unset choices resolved.
  ProductVariant product = ProductVariant::cached;
  Preconditioner preconditioner = Preconditioner::block_jacobi;
  Precision product_precision = Precision::double_;
  std::optional<int> multigrid_smoother_degree;  // empty without multigrid
  std::optional<ChebyshevKind> multigrid_chebyshev;
  bool multigrid_float_cycle = false;
  std::string kernel_specialization;
  size_t device_memory_bytes = 0;
};

struct FrameOptions {
  int load_steps = 1;  // per frame
  // Stop at the first frame that does not converge (its record is the last).
  bool stop_on_failure = false;
  // A frame that ends with inverted elements fails: its status becomes
  // StepStatus::inverted_elements, converged false, and it is the last frame
  // run (as SolveOptions::fail_on_inverted does per load step).
  bool fail_on_inverted = false;
};

// Called after each frame with its record, the lattice positions and the
// embedded surface's positions (empty without an embedding).
// Return false to stop after this frame.
using FrameCallback = std::function<bool(const FrameRecord&, const Points& lattice, const Points& surface)>;

// Runs every frame of `animation` on `simulation`: each animated bone's
// matrix goes to the constraint set of the same name through
// set_transform(to_rigid_transform(M, c)), c the centroid of the set's rest
// positions (rigid motions are interpolated about the bone itself); sets the
// animation does not name keep their targets. The surface follows
// `embedding` (null: no surface). Throws snh::Error naming an animated bone
// that is not a constraint set of the simulation, before any solve.
std::vector<FrameRecord> run_frames(Simulation& simulation, const Animation& animation, const Embedding* embedding,
                                    const FrameOptions& options = {}, const FrameCallback& on_frame = {});

}  // namespace snh
