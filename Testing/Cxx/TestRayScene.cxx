// RayScene (Embree): occlusion and nearest hits on small scenes with known answers.
#include "RayScene.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace catar;

namespace
{
// A unit square at height z, as two triangles.
void AddSquare(std::vector<float>& pts, std::vector<std::uint32_t>& tris, float z)
{
  const std::uint32_t b = static_cast<std::uint32_t>(pts.size() / 3);
  const float xy[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  for (const auto& p : xy)
  {
    pts.insert(pts.end(), { p[0], p[1], z });
  }
  tris.insert(tris.end(), { b, b + 1, b + 2, b, b + 2, b + 3 });
}
} // namespace

TEST(RayScene, OcclusionAndHits)
{
  std::vector<float> pts;
  std::vector<std::uint32_t> tris;
  AddSquare(pts, tris, 1.0f);
  RayScene scene;
  ASSERT_TRUE(scene.Build(pts, tris)) << scene.GetError();
  EXPECT_EQ(scene.GetNumberOfTriangles(), 2u);
  EXPECT_NEAR(scene.GetSceneSize(), std::sqrt(2.0), 1e-6);
  // Through the square.
  EXPECT_TRUE(scene.Occluded(Vec3(0.5, 0.5, 0.0), Vec3(0.3, 0.6, 2.0)));
  // Beside it, and stopping short of it.
  EXPECT_FALSE(scene.Occluded(Vec3(1.5, 0.5, 0.0), Vec3(1.5, 0.5, 2.0)));
  EXPECT_FALSE(scene.Occluded(Vec3(0.5, 0.5, 0.0), Vec3(0.5, 0.5, 0.9)));
  // A segment starting on the square itself is not blocked by it (margin).
  EXPECT_FALSE(scene.Occluded(Vec3(0.5, 0.5, 1.0), Vec3(0.5, 0.5, 3.0)));
  // Watertight: rays exactly through the shared diagonal edge are blocked too.
  for (double t : { 0.25, 0.5, 0.75 })
  {
    EXPECT_TRUE(scene.Occluded(Vec3(t, t, 0.0), Vec3(t, t, 2.0))) << t;
  }
  // Nearest hit.
  const RayScene::Hit h = scene.Intersect(Vec3(0.25, 0.5, -1.0), Vec3(0, 0, 1), 0.0, 10.0);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 2.0, 1e-6);
  EXPECT_FALSE(scene.Intersect(Vec3(2, 2, -1), Vec3(0, 0, 1), 0.0, 10.0).hit);
  EXPECT_FALSE(scene.Intersect(Vec3(0.25, 0.5, -1.0), Vec3(0, 0, 1), 0.0, 1.5).hit);
}

TEST(RayScene, BadInputIsRefused)
{
  RayScene scene;
  EXPECT_FALSE(scene.Build({ 0, 0, 0, 1, 0, 0 }, { 0, 1, 2 }));
  EXPECT_FALSE(scene.GetError().empty());
  EXPECT_FALSE(scene.Build({ 0, 0 }, {}));
  EXPECT_FALSE(scene.Build({ 0, 0, std::nanf(""), 1, 0, 0, 0, 1, 0 }, { 0, 1, 2 }));
  // An empty scene blocks nothing.
  ASSERT_TRUE(scene.Build({}, {}));
  EXPECT_FALSE(scene.Occluded(Vec3(0, 0, 0), Vec3(1, 1, 1)));
}
