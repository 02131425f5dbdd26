// snh::Points, the API's point arrays (docs/design.md, "Conventions of the
// public API"): a row-major n x 3 array whose size counts points.
#include <gtest/gtest.h>

#include <string>

#include "snh/mesh.h"
#include "snh/points.h"

namespace {

TEST(Points, SizeCountsPointsAndDataIsRowMajor) {
  snh::Points p{{1, 2, 3}, {4, 5, 6}};
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p.xyz(), (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(p[1], (snh::Vec3{4, 5, 6}));
  EXPECT_EQ(p(0, 2), 3.0);
  p(1, 0) = -4;
  EXPECT_EQ(p.data()[3], -4.0);
  p.set(0, {7, 8, 9});
  EXPECT_EQ(p[0], (snh::Vec3{7, 8, 9}));
}

TEST(Points, GrowsByWholePoints) {
  snh::Points p(2, {1, 1, 1});
  p.resize(3, {2, 2, 2});
  p.push_back({3, 3, 3});
  p.append(snh::Points{{4, 4, 4}});
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(p.xyz().size(), 15u);
  EXPECT_EQ(p[1], (snh::Vec3{1, 1, 1}));
  EXPECT_EQ(p[2], (snh::Vec3{2, 2, 2}));
  EXPECT_EQ(p[4], (snh::Vec3{4, 4, 4}));
  std::vector<double> flat = p.release();
  EXPECT_EQ(flat.size(), 15u);
  EXPECT_TRUE(p.empty());
}

TEST(Points, FlatValuesMustBeWholePoints) {
  const snh::Points p = snh::Points::from_xyz({0, 1, 2, 3, 4, 5});
  EXPECT_EQ(p.size(), 2u);
  try {
    snh::Points::from_xyz({0, 1, 2, 3}, "targets of 'lid'");
    FAIL() << "four values were taken as points";
  } catch (const snh::Error& e) {
    EXPECT_NE(std::string(e.what()).find("targets of 'lid': 4 values, not three per point"), std::string::npos)
        << e.what();
  }
}

TEST(Points, MeshCountsItsVerticesFromThem) {
  const snh::Mesh box = snh::make_box_lattice(2, 1, 1, 1.0);
  EXPECT_EQ(box.vertex_count(), box.positions.size());
  EXPECT_EQ(box.vertex(5), box.positions[5]);
}

}  // namespace
