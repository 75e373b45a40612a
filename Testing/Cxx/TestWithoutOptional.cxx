// What a build without the optional dependencies does where it would need them
// (Module/Trace/RaySceneWithoutEmbree.cxx, Module/Vision/PoseEstimationWithoutSolvers.cxx,
// Module/MeshPrep/MeshPrepWithoutLibraries.cxx, built here on their own): it refuses, with a
// sentence that names what is missing and how to get it, and never answers as if it had traced or
// posed.
#include "CameraModel.h"
#include "MeshMetrics.h"
#include "MeshRepair.h"
#include "PointSetSurface.h"
#include "PoseEstimation.h"
#include "RayScene.h"
#include "Remeshing.h"
#include "RigCalibration.h"
#include "ScreenSpaceRemeshing.h"

#include <gtest/gtest.h>

#include <cmath>

#include <stdexcept>
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

TEST(WithoutPoseSolvers, EveryCalibrationIsRefusedAndSaysWhy)
{
  const catar::CalibrationResult result =
    catar::CalibrateRig(catar::CameraModel(), std::vector<catar::CalibrationView>(4));
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("without OpenGV and Ceres"), std::string::npos) << result.error;
}

TEST(WithoutMeshPreparation, EveryPreparationIsRefusedAndSaysWhy)
{
  catar::mesh::TriangleMesh mesh;
  mesh.points = { catar::Vec3(0, 0, 0), catar::Vec3(1, 0, 0), catar::Vec3(0, 1, 0) };
  mesh.triangles = { { { 0, 1, 2 } } };
  const auto says = [](const std::string& error) {
    return error.find("without CGAL and OpenMesh") != std::string::npos &&
      error.find("libcgal-dev") != std::string::npos;
  };
  catar::mesh::RepairReport report;
  catar::mesh::Warnings warnings;
  std::string error;
  catar::mesh::TriangleMesh repaired = mesh;
  EXPECT_FALSE(catar::mesh::RepairMesh(repaired, report, warnings, error));
  EXPECT_TRUE(says(error)) << error;

  const catar::mesh::RemeshResult area = catar::mesh::RemeshToArea(mesh, {});
  EXPECT_FALSE(area.ok);
  EXPECT_TRUE(area.mesh.triangles.empty());
  EXPECT_TRUE(says(area.error)) << area.error;

  const catar::mesh::ScreenSpaceResult pixels = catar::mesh::RemeshToPixelTolerance(
    mesh, [](const catar::Vec3&, const catar::Vec3&) { return 0.0; }, {});
  EXPECT_FALSE(pixels.ok);
  EXPECT_TRUE(says(pixels.error)) << pixels.error;

  const catar::mesh::PointSetResult surface = catar::mesh::SurfaceFromPoints(mesh.points, {});
  EXPECT_FALSE(surface.ok);
  EXPECT_TRUE(says(surface.error)) << surface.error;

  // Measures cannot answer at all: they throw the sentence instead of returning a number.
  try
  {
    (void)catar::mesh::HausdorffDistance(mesh, mesh, 0.1);
    ADD_FAILURE() << "HausdorffDistance answered";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_TRUE(says(e.what())) << e.what();
  }
  EXPECT_THROW((void)catar::mesh::TriangleAreaStatistics(mesh), std::runtime_error);
  // The formulas that need no library still hold: an equilateral triangle of side 2.
  EXPECT_NEAR(catar::mesh::AreaForEdgeLength(2.0), std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(catar::mesh::EdgeLengthForArea(std::sqrt(3.0)), 2.0, 1e-15);
}
