// RayScene (Embree): occlusion and nearest hits on small scenes with known answers; several meshes
// and ray streams against single rays. RayTracer: the tiles it skips, and a new pose taken without
// back-projecting the rays again, change no pixel.
#include "RayScene.h"
#include "RayTracer.h"
#include "TestCameras.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

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

TEST(RayScene, SeveralMeshesAndStreams)
{
  // Mesh 0: the square at z = 1; mesh 1: empty; mesh 2: a square at z = 2, shifted by 0.5 in x.
  std::vector<float> a, c;
  std::vector<std::uint32_t> ta, tc;
  AddSquare(a, ta, 1.0f);
  AddSquare(c, tc, 2.0f);
  for (std::size_t i = 0; i < c.size(); i += 3)
  {
    c[i] += 0.5f;
  }
  std::vector<RayScene::MeshView> meshes(3);
  meshes[0] = { a.data(), a.size() / 3, ta.data(), ta.size() / 3 };
  meshes[2] = { c.data(), c.size() / 3, tc.data(), tc.size() / 3 };
  for (int threads : { 1, 0 })
  {
    RayScene scene;
    scene.SetBuildThreads(threads);
    ASSERT_TRUE(scene.Build(meshes)) << scene.GetError();
    EXPECT_EQ(scene.GetNumberOfTriangles(), 4u);
    const RayScene::Hit low = scene.Intersect(Vec3(0.25, 0.5, 0.0), Vec3(0, 0, 1), 0.0, 10.0);
    ASSERT_TRUE(low.hit);
    EXPECT_EQ(low.mesh, 0u);
    EXPECT_NEAR(low.t, 1.0, 1e-6);
    const RayScene::Hit high = scene.Intersect(Vec3(1.25, 0.5, 0.0), Vec3(0, 0, 1), 0.0, 10.0);
    ASSERT_TRUE(high.hit);
    EXPECT_EQ(high.mesh, 2u);
    EXPECT_NEAR(high.t, 2.0, 1e-6);

    // Streams: the answers of single rays, for rays that hit, miss and graze.
    std::mt19937 random(7);
    std::uniform_real_distribution<float> u(-0.5f, 2.0f);
    std::vector<RayScene::Ray> rays(300);
    for (RayScene::Ray& r : rays)
    {
      const Vec3 d = Vec3(u(random) * 0.2, u(random) * 0.2, 1.0).normalized();
      r = { { u(random), u(random), 0.0f },
        { static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z()) } };
    }
    std::vector<RayScene::Hit> hits(rays.size());
    scene.Intersect(rays.size(), rays.data(), hits.data());
    int hit = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
    {
      const RayScene::Ray& r = rays[i];
      const RayScene::Hit one = scene.Intersect(Vec3(r.origin[0], r.origin[1], r.origin[2]),
        Vec3(r.direction[0], r.direction[1], r.direction[2]), 0.0, HUGE_VAL);
      ASSERT_EQ(hits[i].hit, one.hit) << "ray " << i;
      hit += one.hit;
      if (one.hit)
      {
        EXPECT_EQ(hits[i].mesh, one.mesh) << "ray " << i;
        EXPECT_EQ(hits[i].triangle, one.triangle) << "ray " << i;
        EXPECT_EQ(hits[i].t, one.t) << "ray " << i;
        EXPECT_EQ(hits[i].u, one.u) << "ray " << i;
        EXPECT_EQ(hits[i].v, one.v) << "ray " << i;
      }
    }
    EXPECT_GT(hit, 50);
    EXPECT_LT(hit, 250);
  }
}

namespace
{
// A box of 12 triangles, one colour per face, where the demo camera sees it.
std::shared_ptr<TraceMesh> TraceBox(const Vec3& lo, const Vec3& hi)
{
  auto box = std::make_shared<TraceMesh>();
  for (int k = 0; k < 8; ++k)
  {
    box->points.emplace_back(
      k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  }
  const std::uint32_t faces[6][4] = { { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 },
    { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 } };
  for (int f = 0; f < 6; ++f)
  {
    box->triangles.push_back({ faces[f][0], faces[f][1], faces[f][2] });
    box->triangles.push_back({ faces[f][0], faces[f][2], faces[f][3] });
    for (int t = 0; t < 2; ++t)
    {
      box->colors.insert(box->colors.end(), { 0.2f + 0.15f * f, 0.9f - 0.1f * f, 0.5f, 1.0f });
    }
  }
  box->colorSource = TraceMesh::ColorSource::Cell;
  box->shading = TraceMesh::Shading::None;
  return box;
}

// Renders the whole image (in bands of 24 rows: not a multiple of the tile) with `tracer`.
std::vector<std::uint8_t> Render(
  const RayTracer& tracer, RayTraceStatistics& statistics, std::vector<RasterId>& ids)
{
  const int w = tracer.GetWidth(), h = tracer.GetHeight();
  std::vector<std::uint8_t> pixels(4 * static_cast<std::size_t>(w) * h, 30);
  ids.assign(static_cast<std::size_t>(w) * h, -2);
  ImageView view;
  view.data = pixels.data();
  view.width = w;
  view.height = h;
  view.rowStride = 4 * static_cast<std::ptrdiff_t>(w);
  for (int y = 0; y < h; y += 24)
  {
    tracer.RenderRows(view, ids.data(), w, y, y + 24, &statistics);
  }
  return pixels;
}
} // namespace

TEST(RayTracer, SkippedTilesAndNewPosesChangeNoPixel)
{
  CameraModel model = catar_test::SmallDemoCameraModel();
  model.intrinsics.width = 645; // edge tiles of 5 x 3 pixels
  model.intrinsics.height = 483;
  model.intrinsics.cx = 322.0;
  model.intrinsics.cy = 241.0;
  const std::vector<std::shared_ptr<const TraceMesh>> meshes = { TraceBox(
    Vec3(-0.01, -0.37, 0.82), Vec3(0.29, -0.25, 0.91)) };
  RayTracer tracer;
  ASSERT_TRUE(tracer.SetScene(meshes, {}, {}, Vec3::Zero(), false)) << tracer.GetError();
  ASSERT_TRUE(tracer.SetScene(meshes, {}, {}, Vec3::Zero(), false)) << tracer.GetError();
  EXPECT_EQ(tracer.GetNumberOfBuilds(), 1u); // the same mesh object: kept
  for (int pose = 0; pose < 3; ++pose)
  {
    if (pose > 0)
    {
      // The camera turned about its x and z axes and moved by a few millimetres.
      const Eigen::Matrix3d turn =
        (Eigen::AngleAxisd(0.01 * pose, Vec3::UnitX()) * Eigen::AngleAxisd(-0.02, Vec3::UnitZ()))
          .toRotationMatrix();
      Mat4 delta = Mat4::Identity();
      delta.topLeftCorner<3, 3>() = turn;
      delta.topRightCorner<3, 1>() = Vec3(0.003, -0.002, 0.001 * pose);
      model.worldToCamera = delta * model.worldToCamera;
    }
    const Projector projector(model);
    ASSERT_TRUE(tracer.PrepareRays(projector, 1)) << tracer.GetError();
    EXPECT_EQ(tracer.GetNumberOfRayPreparations(), 1u) << "pose " << pose;
    RayTracer fresh;
    ASSERT_TRUE(fresh.SetScene(meshes, {}, {}, Vec3::Zero(), false));
    ASSERT_TRUE(fresh.PrepareRays(projector, 1));
    fresh.SetTileCulling(false);

    RayTraceStatistics culled, all;
    std::vector<RasterId> culledIds, allIds;
    const std::vector<std::uint8_t> a = Render(tracer, culled, culledIds);
    const std::vector<std::uint8_t> b = Render(fresh, all, allIds);
    EXPECT_GT(culled.hits, 1000u) << "pose " << pose;
    EXPECT_EQ(culled.mirrorRays, all.mirrorRays) << "pose " << pose;
    EXPECT_EQ(culled.tracedRays, all.tracedRays) << "pose " << pose;
    EXPECT_EQ(culled.hits, all.hits) << "pose " << pose;
    EXPECT_TRUE(a == b) << "pose " << pose;
    EXPECT_TRUE(culledIds == allIds) << "pose " << pose;
    EXPECT_EQ(std::count(culledIds.begin(), culledIds.end(), RasterId(-2)), 0);
  }
  // Another sample count: the rays are back-projected again.
  ASSERT_TRUE(tracer.PrepareRays(Projector(model), 2));
  EXPECT_EQ(tracer.GetNumberOfRayPreparations(), 2u);
}

TEST(RayScene, DynamicScenesRefitMovedPoints)
{
  std::vector<float> a, c;
  std::vector<std::uint32_t> ta, tc;
  AddSquare(a, ta, 1.0f);
  AddSquare(c, tc, 3.0f);
  for (std::size_t i = 0; i < c.size(); i += 3)
  {
    c[i] += 2.0f; // beside the first
  }
  std::vector<RayScene::MeshView> meshes(2);
  meshes[0] = { a.data(), a.size() / 3, ta.data(), ta.size() / 3 };
  meshes[1] = { c.data(), c.size() / 3, tc.data(), tc.size() / 3 };
  RayScene scene;
  EXPECT_FALSE(scene.UpdatePoints(0, a.data())); // nothing built
  scene.SetDynamic(true);
  ASSERT_TRUE(scene.Build(meshes)) << scene.GetError();
  // The first square moved up to z = 1.5 and along x by 0.25.
  std::vector<float> moved = a;
  for (std::size_t i = 0; i < moved.size(); i += 3)
  {
    moved[i] += 0.25f;
    moved[i + 2] = 1.5f;
  }
  ASSERT_TRUE(scene.UpdatePoints(0, moved.data())) << scene.GetError();
  ASSERT_TRUE(scene.Commit()) << scene.GetError();
  const RayScene::Hit h = scene.Intersect(Vec3(1.1, 0.5, 0.0), Vec3(0, 0, 1), 0.0, 10.0);
  ASSERT_TRUE(h.hit); // x = 1.1: inside the moved square only
  EXPECT_EQ(h.mesh, 0u);
  EXPECT_NEAR(h.t, 1.5, 1e-6);
  EXPECT_FALSE(scene.Intersect(Vec3(0.1, 0.5, 0.0), Vec3(0, 0, 1), 0.0, 10.0).hit);
  const RayScene::Hit other = scene.Intersect(Vec3(2.5, 0.5, 0.0), Vec3(0, 0, 1), 0.0, 10.0);
  ASSERT_TRUE(other.hit);
  EXPECT_EQ(other.mesh, 1u);
  EXPECT_NEAR(other.t, 3.0, 1e-6);
  // The scene's size follows the points: from (0.25, 0, 1.5) to (3, 1, 3).
  EXPECT_NEAR(scene.GetSceneSize(), std::sqrt(2.75 * 2.75 + 1.0 + 1.5 * 1.5), 1e-6);
  // Bad points are refused and leave the scene as it was.
  std::vector<float> bad = moved;
  bad[4] = std::nanf("");
  EXPECT_FALSE(scene.UpdatePoints(0, bad.data()));
  EXPECT_FALSE(scene.GetError().empty());
  EXPECT_FALSE(scene.UpdatePoints(2, moved.data())); // no such mesh
  ASSERT_TRUE(scene.Commit());
  EXPECT_TRUE(scene.Intersect(Vec3(1.1, 0.5, 0.0), Vec3(0, 0, 1), 0.0, 10.0).hit);
}
