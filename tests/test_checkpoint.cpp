// Saving and resuming: a Simulation's state taken after some frames and
// restored, into the same simulation or a new one built from the same inputs
// (through the checkpoint file), continues bit for bit as the original did;
// damaged files and checkpoints of another mesh are refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>

#include "snh/checkpoint.h"
#include "snh/error.h"
#include "snh/simulation.h"
#include "support/plane_selection.h"

namespace snh::test {
namespace {

std::string temp_path(const std::string& name) { return ::testing::TempDir() + "snh_checkpoint_" + name; }

// Everything a solve reports that does not depend on wall time.
void expect_same_solve(const SolveResult& a, const SolveResult& b, const std::string& what) {
  EXPECT_EQ(a.positions, b.positions) << what;
  EXPECT_EQ(a.converged, b.converged) << what;
  EXPECT_EQ(a.final_residual_norm, b.final_residual_norm) << what;
  ASSERT_EQ(a.steps.size(), b.steps.size()) << what;
  for (size_t s = 0; s < a.steps.size(); ++s) {
    const StepResult &x = a.steps[s], &y = b.steps[s];
    EXPECT_EQ(x.newton_iterations, y.newton_iterations) << what << " step " << s;
    EXPECT_EQ(x.cg_iterations, y.cg_iterations) << what << " step " << s;
    EXPECT_EQ(x.residual_norm, y.residual_norm) << what << " step " << s;
    EXPECT_EQ(x.status, y.status) << what << " step " << s;
    EXPECT_EQ(x.time, y.time) << what << " step " << s;
    EXPECT_EQ(x.contacts, y.contacts) << what << " step " << s;
    EXPECT_EQ(x.max_penetration, y.max_penetration) << what << " step " << s;
    EXPECT_EQ(x.preconditioner_builds, y.preconditioner_builds) << what << " step " << s;
  }
  ASSERT_EQ(a.history.size(), b.history.size()) << what;
  for (size_t i = 0; i < a.history.size(); ++i) {
    const NewtonIteration &x = a.history[i], &y = b.history[i];
    EXPECT_EQ(x.residual_norm, y.residual_norm) << what << " record " << i;
    EXPECT_EQ(x.energy, y.energy) << what << " record " << i;
    EXPECT_EQ(x.step_length, y.step_length) << what << " record " << i;
    EXPECT_EQ(x.cg_iterations, y.cg_iterations) << what << " record " << i;
    EXPECT_EQ(x.cg_stop, y.cg_stop) << what << " record " << i;
    EXPECT_EQ(x.recovery, y.recovery) << what << " record " << i;
  }
}

struct Frames {
  std::vector<SolveResult> results;
  Points positions, velocities;
  double time = 0.0;
};

// Runs frames `first` .. `first + count - 1` of a scene's driver.
using Frame = std::function<SolveResult(Simulation&, int frame)>;
Frames run_frames(Simulation& sim, const Frame& frame, int first, int count) {
  Frames r;
  for (int f = first; f < first + count; ++f) r.results.push_back(frame(sim, f));
  r.positions = sim.positions();
  r.velocities = sim.velocities();
  r.time = sim.time();
  return r;
}

void expect_same_run(const Frames& a, const Frames& b, const std::string& what) {
  ASSERT_EQ(a.results.size(), b.results.size());
  for (size_t f = 0; f < a.results.size(); ++f)
    expect_same_solve(a.results[f], b.results[f], what + " frame " + std::to_string(f));
  EXPECT_EQ(a.positions, b.positions) << what;
  EXPECT_EQ(a.velocities, b.velocities) << what;
  EXPECT_EQ(a.time, b.time) << what;
}

// N frames, a checkpoint, M more; then the checkpoint restored into the same
// simulation and into a new one (through the file) runs the same M frames.
Frames expect_resumes_exactly(const std::function<Simulation()>& make, const Frame& frame, int n, int m,
                              const std::string& name) {
  Simulation sim = make();
  run_frames(sim, frame, 0, n);
  const SimulationState state = sim.checkpoint();
  const Frames original = run_frames(sim, frame, n, m);
  for (const SolveResult& r : original.results) EXPECT_TRUE(r.converged) << name;

  sim.restore(state);
  expect_same_run(original, run_frames(sim, frame, n, m), name + ", restored in place");

  const std::string path = temp_path(name + ".bin");
  write_checkpoint(path, state);
  Simulation fresh = make();
  fresh.restore(read_checkpoint(path));
  expect_same_run(original, run_frames(fresh, frame, n, m), name + ", restored from the file into a new simulation");
  std::remove(path.c_str());
  return original;
}

// A block thrown sideways onto a plane with friction under gravity, a sphere
// pressing on its top, with multigrid (its hierarchy carried across time
// steps) and block-Jacobi.
TEST(Checkpoint, DynamicsWithObstaclesAndFrictionResumeBitForBit) {
  for (Preconditioner preconditioner : {Preconditioner::block_jacobi, Preconditioner::multigrid}) {
    auto make = [=] {
      const Mesh mesh = make_box_lattice(4, 4, 2, 0.025);
      SolveOptions o;
      o.dynamics = DynamicsOptions{};
      o.dynamics->time_step = 0.005;
      o.dynamics->density = 1000.0;
      o.dynamics->damping.stiffness = 1e-4;
      o.body_force = {0.0, 0.0, -9810.0};
      o.initial_velocities = Points(mesh.vertex_count());
      for (size_t v = 0; v < mesh.vertex_count(); ++v) o.initial_velocities(v, 0) = 0.5;
      o.obstacles = {Obstacle::plane({0, 0, -0.004}, {0, 0, 1}),
                     Obstacle::sphere({0.05, 0.05, 0.104}, 0.05).with_friction(0.1)};
      o.contact.stiffness = 1e3;
      o.contact.thickness = 0.005;
      o.contact.friction = 0.4;
      o.preconditioner = preconditioner;
      o.multigrid.coarsest_dofs = 60;
      return Simulation(mesh, StableNeoHookean::from_youngs_modulus(2e5, 0.4), {}, o);
    };
    const Frame frame = [](Simulation& sim, int) { return sim.solve(2); };
    const Frames run = expect_resumes_exactly(make, frame, 3, 3, std::string("dynamics ") + to_string(preconditioner));
    // The scene exercises what it is meant to: contact in every step, and
    // with multigrid a hierarchy reused across time steps.
    int newton = 0, builds = 0;
    for (const SolveResult& r : run.results)
      for (const StepResult& s : r.steps) {
        EXPECT_GT(s.contacts, 0);
        newton += s.newton_iterations;
        builds += s.preconditioner_builds;
      }
    if (preconditioner == Preconditioner::multigrid) {
      EXPECT_LT(builds, newton);
    }
  }
}

// A bar held at one end and twisted at the other by set_transform, its body
// force changed before the checkpoint (the load ramp's ends are state).
TEST(Checkpoint, QuasistaticTransformTargetsResumeBitForBit) {
  auto make = [] {
    const Mesh mesh = make_box_lattice(6, 2, 2, 0.1);
    SolveOptions o;
    o.preconditioner = Preconditioner::multigrid;
    o.multigrid.coarsest_dofs = 60;
    return Simulation(
        mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.45),
        {ConstraintSet::fixed("wall", on_plane(mesh, 0, 0.0)), ConstraintSet::fixed("end", on_plane(mesh, 0, 0.6))}, o);
  };
  const Frame frame = [](Simulation& sim, int f) {
    sim.set_transform("end", RigidTransform::rotation_about({1, 0, 0}, 0.3 * (f + 1), {0.6, 0.1, 0.1}));
    if (f == 2) sim.set_body_force({0.0, 0.0, -3000.0});
    return sim.solve(2);
  };
  expect_resumes_exactly(make, frame, 3, 3, "quasistatic");
}

class CheckpointFile : public ::testing::Test {
 protected:
  void SetUp() override {
    mesh = make_box_lattice(2, 1, 1, 0.1);
    Simulation sim(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.3),
                   {ConstraintSet::fixed("wall", on_plane(mesh, 0, 0.0))});
    sim.set_body_force({0.0, 0.0, -100.0});
    sim.solve();
    state = sim.checkpoint();
    path = temp_path("file.bin");
    write_checkpoint(path, state);
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  void TearDown() override { std::remove(path.c_str()); }
  std::string error_reading(const std::vector<char>& content) const {
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out.write(content.data(), static_cast<std::streamsize>(content.size()));
    }
    try {
      read_checkpoint(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  Mesh mesh;
  SimulationState state;
  std::string path;
  std::vector<char> bytes;
};

TEST_F(CheckpointFile, RoundTripIsExact) {
  const SimulationState back = read_checkpoint(path);
  EXPECT_EQ(back.vertex_count, state.vertex_count);
  EXPECT_EQ(back.mesh_fingerprint, state.mesh_fingerprint);
  EXPECT_EQ(back.positions, state.positions);
  EXPECT_EQ(back.force_to, state.force_to);
  EXPECT_EQ(back.force_applied, state.force_applied);
  EXPECT_EQ(back.body_force, state.body_force);
  ASSERT_EQ(back.targets.size(), 1u);
  EXPECT_EQ(back.targets[0].set, "wall");
  EXPECT_EQ(back.targets[0].kind, TargetKind::callbacks);
}

TEST_F(CheckpointFile, DamagedFilesAreRefusedNamingTheItem) {
  std::vector<char> truncated(bytes.begin(), bytes.begin() + 60);
  const std::string cut = error_reading(truncated);
  EXPECT_NE(cut.find(path), std::string::npos) << cut;
  EXPECT_NE(cut.find("positions"), std::string::npos) << cut;
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;

  std::vector<char> version = bytes;
  version[8] = 7;
  const std::string v = error_reading(version);
  EXPECT_NE(v.find("version 7"), std::string::npos) << v;

  std::vector<char> longer = bytes;
  longer.push_back(0);
  EXPECT_NE(error_reading(longer).find("1 bytes after the last item"), std::string::npos);

  // The vertex count one higher: the positions no longer fit it.
  std::vector<char> count = bytes;
  ++count[16];
  const std::string size = error_reading(count);
  EXPECT_NE(size.find("positions: 36 values, expected 39"), std::string::npos) << size;

  EXPECT_NE(error_reading({'n', 'o', 'p', 'e', 0, 0, 0, 0, 0, 0, 0, 0}).find("not an snh checkpoint"),
            std::string::npos);
}

TEST_F(CheckpointFile, AnotherMeshOrOtherSetsAreRefusedOnRestore) {
  Mesh moved = mesh;
  moved.positions(0, 0) += 1e-3;
  Simulation other(moved, StableNeoHookean::from_youngs_modulus(1e5, 0.3),
                   {ConstraintSet::fixed("wall", on_plane(moved, 0, 0.1))});
  try {
    other.restore(state);
    ADD_FAILURE() << "restored a checkpoint of another mesh";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another mesh"), std::string::npos) << e.what();
  }
  Simulation renamed(mesh, StableNeoHookean::from_youngs_modulus(1e5, 0.3),
                     {ConstraintSet::fixed("floor", on_plane(mesh, 0, 0.0))});
  try {
    renamed.restore(state);
    ADD_FAILURE() << "restored a checkpoint of other constraint sets";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'wall'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace snh::test
