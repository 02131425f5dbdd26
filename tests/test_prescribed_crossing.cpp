// A prescribed motion that moves the surface through itself: barrier
// self-contact cannot stop it (the target is placed as given), so the step
// says so with a `surface_intersections` warning; a motion that stays clear,
// or comes close without crossing (where the conservative CCD does not
// clear the whole move), gives none (solver/contact/prescribed_crossing.h).
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "snh/mesh.h"
#include "snh/outcomes.h"
#include "snh/simulation.h"

namespace snh::test {
namespace {

// Two 1 x 1 x 1 cubes of 2^3 hexes, the second 1 to the side of the first.
Mesh two_cubes() {
  Mesh a = make_box_lattice(2, 2, 2, 0.5);
  const Mesh b = make_box_lattice(2, 2, 2, 0.5, {2.0, 0.0, 0.0});
  const int32_t offset = static_cast<int32_t>(a.vertex_count());
  for (size_t v = 0; v < b.vertex_count(); ++v) a.positions.push_back(b.vertex(v));
  for (int32_t v : b.elements) a.elements.push_back(v + offset);
  return a;
}

// The first cube carried by `offset` in one load step, the second held at
// its floor; barrier self-contact on.
SolveResult carry_first_cube(const std::array<double, 3>& offset) {
  const Mesh mesh = two_cubes();
  const int32_t half = static_cast<int32_t>(mesh.vertex_count() / 2);
  std::vector<int32_t> first, floor;
  for (int32_t v = 0; v < half; ++v) first.push_back(v);
  for (int32_t v = half; v < 2 * half; ++v)
    if (mesh.positions(static_cast<size_t>(v), 2) == 0.0) floor.push_back(v);
  std::vector<ConstraintSet> sets{
      ConstraintSet::moving("carried", first,
                            [offset](double t) {
                              return RigidTransform::translation_by({t * offset[0], t * offset[1], t * offset[2]});
                            }),
      ConstraintSet::fixed("floor", floor)};
  SolveOptions options;
  options.precision = Precision::double_;
  options.contact.self = true;
  options.contact.self_method = SelfContactMethod::barrier;
  Simulation sim(mesh, uniform_material(mesh, StableNeoHookean::from_youngs_modulus(10.0, 0.3)), sets, options);
  return sim.solve(1);
}

TEST(PrescribedCrossing, AMotionThroughTheSurfaceIsWarnedOfAndOneThatStaysClearIsNot) {
  // Into the second cube, off its faces' planes: the faces cross.
  const SolveResult through = carry_first_cube({2.5, 0.25, 0.25});
  ASSERT_EQ(through.steps.size(), 1u);
  EXPECT_TRUE(has_warning(through.steps[0].warnings, ResultWarning::surface_intersections));
  EXPECT_TRUE(has_warning(through.warnings, ResultWarning::surface_intersections));
  bool names_the_step = false;
  for (const std::string& w : through.warnings)
    names_the_step = names_the_step || w.rfind("surface_intersections: load step 1 ended with ", 0) == 0;
  EXPECT_TRUE(names_the_step);

  // Halfway to it: the CCD clears the move.
  const SolveResult clear = carry_first_cube({0.5, 0.25, 0.25});
  EXPECT_FALSE(has_warning(clear.warnings, ResultWarning::surface_intersections));
  // To 0.02 of it: the CCD stops short of the move (it keeps 10% of the
  // starting distance), the exact count finds no crossing.
  const SolveResult close = carry_first_cube({0.98, 0.25, 0.25});
  EXPECT_FALSE(has_warning(close.warnings, ResultWarning::surface_intersections));
}

}  // namespace
}  // namespace snh::test
