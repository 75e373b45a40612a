// vtkCatadioptricSceneReader: a scene file as a VTK source. Its image is the scene renderer's
// (still scenes and every frame of a sequence); its objects are one named block per object of
// the scene, placed as the file says; a sequence's time steps are its trajectory file's times; a
// bad scene is one error with the parser's words, and empty outputs.
#include "vtkCatadioptricSceneReader.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
const std::string kScenes = std::string(CATAR_SOURCE_DIR) + "/Data/scenes/";

// The number of pixels whose RGBA differ (-1 when the images differ in size).
long long DifferentPixels(vtkImageData* a, vtkImageData* b)
{
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  auto* pa = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* pb = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  if (!pa || !pb || da[0] != db[0] || da[1] != db[1] || pa->GetNumberOfValues() == 0 ||
    pa->GetNumberOfValues() != pb->GetNumberOfValues())
  {
    return -1;
  }
  long long different = 0;
  for (vtkIdType i = 0; i < pa->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 4; ++c)
    {
      if (pa->GetValue(4 * i + c) != pb->GetValue(4 * i + c))
      {
        ++different;
        break;
      }
    }
  }
  return different;
}

// The timestamps of a TUM trajectory file (the first number of every line that is not a
// comment).
std::vector<double> Timestamps(const std::string& path)
{
  std::ifstream in(path);
  std::vector<double> times;
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream s(line);
    double t;
    if (!line.empty() && line[0] != '#' && (s >> t))
    {
      times.push_back(t);
    }
  }
  return times;
}
} // namespace

TEST(SceneReader, StillSceneIsTheRenderersImageAndItsObjects)
{
  const std::string path = kScenes + "two-objects.yaml";
  vtkNew<vtkCatadioptricSceneReader> reader;
  EXPECT_EQ(reader->CanReadFile(path.c_str()), 1);
  EXPECT_EQ(reader->CanReadFile(
              (std::string(CATAR_SOURCE_DIR) + "/Data/calibration/demo-camera.yaml").c_str()),
    0); // a calibration file is not a scene
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  EXPECT_FALSE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS())); // a still scene
  int extent[6];
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  EXPECT_EQ(extent[1], 663); // output: { width: 664, height: 524 }
  EXPECT_EQ(extent[3], 523);
  reader->Update();

  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(path.c_str());
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  EXPECT_EQ(DifferentPixels(reader->GetImageOutput(), renderer->GetOutput()), 0);

  vtkMultiBlockDataSet* objects = reader->GetObjectsOutput();
  ASSERT_EQ(objects->GetNumberOfBlocks(), 2u);
  const char* names[2] = { "ball", "post" };
  // The objects' positions in the scene file (the sphere and the cylinder are symmetric about
  // them).
  const double centres[2][3] = { { 0.15, -0.35, 0.95 }, { -0.15, -0.3, 1.0 } };
  for (unsigned int i = 0; i < 2; ++i)
  {
    auto* block = vtkPolyData::SafeDownCast(objects->GetBlock(i));
    ASSERT_NE(block, nullptr);
    EXPECT_STREQ(objects->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()), names[i]);
    EXPECT_GT(block->GetNumberOfPolys(), 0);
    EXPECT_NE(block->GetCellData()->GetArray("Colors"), nullptr);
    double b[6];
    block->GetBounds(b);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(0.5 * (b[2 * k] + b[2 * k + 1]), centres[i][k], 1e-6) << names[i] << " " << k;
    }
  }
  // The cylinder (height 0.3) stands along z (rotate 90 about x).
  double b[6];
  vtkPolyData::SafeDownCast(objects->GetBlock(1))->GetBounds(b);
  EXPECT_NEAR(b[5] - b[4], 0.3, 1e-6);
}

TEST(SceneReader, SequenceTimeStepsAndFrames)
{
  const std::string path = kScenes + "moving-camera.yaml";
  const std::vector<double> stamps = Timestamps(kScenes + "moving-camera.tum");
  ASSERT_EQ(stamps.size(), 60u);
  vtkNew<vtkCatadioptricSceneReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(1);
  ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 60);
  const double* steps = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  for (int k = 0; k < 60; ++k)
  {
    EXPECT_NEAR(steps[k], stamps[k], 1e-12) << k;
  }
  // Frame 30, asked for by its time and by a time a little after it: the renderer's frame 30.
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(path.c_str());
  ASSERT_TRUE(renderer->RenderFrame(30)) << renderer->GetLastError();
  for (double t : { stamps[30], 0.5 * (stamps[30] + stamps[31]) })
  {
    reader->UpdateTimeStep(t);
    EXPECT_EQ(reader->GetCurrentFrame(), 30) << t;
    EXPECT_EQ(DifferentPixels(reader->GetImageOutput(), renderer->GetOutput()), 0) << t;
    EXPECT_EQ(
      reader->GetImageOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), stamps[30]);
  }
  // Before the first time: the first frame.
  reader->UpdateTimeStep(-1.0);
  EXPECT_EQ(reader->GetCurrentFrame(), 0);
}

TEST(SceneReader, BadScenesAreOneErrorAndEmptyOutputs)
{
  const std::string dir = std::string(CATAR_TEST_OUTPUT_DIR) + "/scene-reader";
  mkdir(CATAR_TEST_OUTPUT_DIR, 0755);
  mkdir(dir.c_str(), 0755);
  const std::string bad = dir + "/bad.yaml";
  std::ofstream(bad) << "camera: " << CATAR_SOURCE_DIR
                     << "/Data/calibration/demo-camera.yaml\nobjetcs: []\n";
  const std::string mesh = dir + "/missing-mesh.yaml";
  std::ofstream(mesh) << "camera: " << CATAR_SOURCE_DIR
                      << "/Data/calibration/demo-camera.yaml\n"
                         "objects:\n  - { type: mesh, file: nowhere.ply }\n";
  const std::pair<std::string, std::string> cases[] = { { bad, "unknown key 'objetcs'" },
    { mesh, "nowhere.ply" }, { dir + "/none.yaml", "none.yaml" }, { "", "FileName" } };
  for (const auto& c : cases)
  {
    vtkNew<vtkCatadioptricSceneReader> reader;
    vtkNew<catar_test::ErrorCounter> own, executive;
    own->Watch(reader);
    executive->Watch(reader->GetExecutive()); // "returned failure for request"
    reader->SetFileName(c.first.c_str());
    EXPECT_EQ(reader->GetExecutive()->Update(), 0) << c.first;
    // The reader's own message, once (not again for the data request), with the parser's words.
    EXPECT_EQ(own->Count, 1) << c.first;
    EXPECT_NE(own->Last.find(c.second), std::string::npos) << own->Last;
    EXPECT_EQ(reader->GetImageOutput()->GetNumberOfPoints(), 0) << c.first;
    EXPECT_EQ(reader->GetObjectsOutput()->GetNumberOfBlocks(), 0u) << c.first;
  }
}
