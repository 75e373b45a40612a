// What a build without the optional dependencies does where it would need them
// (Module/Trace/RaySceneWithoutEmbree.cxx, Module/Vision/PoseEstimationWithoutSolvers.cxx, built
// here on their own): it refuses, with a sentence that names what is missing and how to get it,
// and never answers as if it had traced or posed.
#include "CameraModel.h"
#include "PoseEstimation.h"
#include "RayScene.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

TEST(WithoutEmbree, EveryBuildFailsAndSaysWhy)
{
  catar::RayScene scene;
  const std::vector<float> points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  const std::vector<std::uint32_t> triangles = { 0, 1, 2 };
  EXPECT_FALSE(scene.Build(points, triangles));
  EXPECT_NE(scene.GetError().find("without Embree"), std::string::npos) << scene.GetError();
  EXPECT_NE(scene.GetError().find("libembree-dev"), std::string::npos) << scene.GetError();
  EXPECT_FALSE(scene.Build(std::vector<catar::RayScene::MeshView>{}));
  EXPECT_FALSE(scene.Commit());
  EXPECT_FALSE(scene.Intersect(catar::Vec3(0.2, 0.2, -1), catar::Vec3(0, 0, 1), 0, 10).hit);
  EXPECT_FALSE(scene.Occluded(catar::Vec3(0.2, 0.2, -1), catar::Vec3(0.2, 0.2, 1)));
}

TEST(WithoutPoseSolvers, EveryPoseIsRefusedAndSaysWhy)
{
  const catar::CameraModel camera;
  std::vector<catar::PoseObservation> observations(6);
  for (int i = 0; i < 6; ++i)
  {
    observations[i].pixel = catar::Vec2(100 + 10 * i, 200 + 5 * i);
    observations[i].world = catar::Vec3(i % 2, i / 2, 1 + i);
  }
  const catar::PoseResult result = catar::EstimatePose(camera, observations);
  EXPECT_FALSE(result.ok);
  EXPECT_TRUE(result.inliers.empty());
  EXPECT_NE(result.error.find("without OpenGV and Ceres"), std::string::npos) << result.error;
}
