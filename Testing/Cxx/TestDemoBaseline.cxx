// Image baseline of the demo scene, plus checks that do not depend on the baseline: the objects
// land where the camera projects them.
//
// Tolerance (Documentation/testing.md): the images match when at most 0.1% of the pixels differ by
// more than 24 levels in some channel and the mean absolute difference is at most 1 level. On
// failure the rendered image and a difference image (x4) are written to Testing/Temporary of the
// build tree. CATAR_UPDATE_BASELINES=1 rewrites the baseline instead.
#include "SceneDescription.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricEnvironmentSource.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace
{
// The demo scene at half resolution (keeps the baseline small and the test quick).
std::string WriteHalfSizeDemo()
{
  std::string text = catar::DemoSceneText();
  const std::string from = "output: { width: 1328, height: 1048 }";
  const size_t at = text.find(from);
  if (at == std::string::npos)
  {
    return "";
  }
  text.replace(at, from.size(), "output: { width: 664, height: 524 }");
  vtksys::SystemTools::MakeDirectory(CATAR_TEST_OUTPUT_DIR);
  const std::string path = std::string(CATAR_TEST_OUTPUT_DIR) + "/demo-half.yaml";
  std::ofstream(path) << text;
  return path;
}

void WritePNG(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkPNGWriter> w;
  w->SetInputData(image);
  w->SetFileName(path.c_str());
  w->Write();
}

const unsigned char* PixelOf(vtkImageData* img, double x, double y)
{
  const int h = img->GetDimensions()[1];
  return static_cast<unsigned char*>(img->GetScalarPointer(
    static_cast<int>(std::lround(x)), h - 1 - static_cast<int>(std::lround(y)), 0));
}

// Compares `image` with the baseline `name`.png (see the tolerance above); writes the baseline
// instead when CATAR_UPDATE_BASELINES=1.
void CompareWithBaseline(vtkImageData* image, const std::string& name)
{
  const std::string baseline = std::string(CATAR_BASELINE_DIR) + "/" + name + ".png";
  const char* update = std::getenv("CATAR_UPDATE_BASELINES");
  if (update && std::string(update) == "1")
  {
    WritePNG(image, baseline);
    GTEST_SKIP() << "baseline rewritten: " << baseline;
  }
  vtksys::SystemTools::MakeDirectory(CATAR_TEST_OUTPUT_DIR);
  const std::string rendered = std::string(CATAR_TEST_OUTPUT_DIR) + "/" + name + ".png";
  if (!vtksys::SystemTools::FileExists(baseline, true))
  {
    WritePNG(image, rendered);
    FAIL() << "no baseline " << baseline << "; the rendered image is " << rendered
           << " (run with CATAR_UPDATE_BASELINES=1 to make it the baseline)";
  }
  int dims[3];
  image->GetDimensions(dims);
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  reader->Update();
  vtkImageData* base = reader->GetOutput();
  int bdims[3];
  base->GetDimensions(bdims);
  ASSERT_EQ(bdims[0], dims[0]);
  ASSERT_EQ(bdims[1], dims[1]);
  ASSERT_EQ(base->GetNumberOfScalarComponents(), 4);

  vtkNew<vtkImageData> diff;
  diff->SetDimensions(dims);
  diff->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  const unsigned char* a = static_cast<unsigned char*>(image->GetScalarPointer());
  const unsigned char* b = static_cast<unsigned char*>(base->GetScalarPointer());
  unsigned char* d = static_cast<unsigned char*>(diff->GetScalarPointer());
  const long n = static_cast<long>(dims[0]) * dims[1];
  long bad = 0;
  double sum = 0;
  for (long i = 0; i < n; ++i)
  {
    int worst = 0;
    for (int k = 0; k < 4; ++k)
    {
      const int e = std::abs(int(a[4 * i + k]) - int(b[4 * i + k]));
      worst = std::max(worst, e);
      sum += e;
      d[4 * i + k] = static_cast<unsigned char>(std::min(255, 4 * e));
    }
    d[4 * i + 3] = 255;
    bad += worst > 24;
  }
  const double mean = sum / (4.0 * n);
  const double badFraction = static_cast<double>(bad) / n;
  if (badFraction > 0.001 || mean > 1.0)
  {
    WritePNG(image, rendered);
    WritePNG(diff, std::string(CATAR_TEST_OUTPUT_DIR) + "/" + name + "-diff.png");
  }
  EXPECT_LE(badFraction, 0.001) << name << ": " << bad
                                << " pixels differ by more than 24 levels; see "
                                << CATAR_TEST_OUTPUT_DIR;
  EXPECT_LE(mean, 1.0) << name << ": mean absolute difference " << mean;
}
} // namespace

TEST(DemoScene, MatchesTheBaseline)
{
  const std::string scene = WriteHalfSizeDemo();
  ASSERT_FALSE(scene.empty()) << "the demo scene text no longer has the expected output line";
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(scene.c_str());
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  int dims[3];
  renderer->GetOutput()->GetDimensions(dims);
  ASSERT_EQ(dims[0], 664);
  ASSERT_EQ(dims[1], 524);
  CompareWithBaseline(renderer->GetOutput(), "DemoScene");
}

namespace
{
// Small lit scenes on a plain background, one per baseline (names are the baselines' names).
const char* kBaselineCamera = R"(%YAML:1.0
---
camera:
  image_width: 1328
  image_height: 1048
  camera_matrix: [ 1000.0, 0.0, 663.5, 0.0, 1000.0, 523.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
  world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1.0,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
output: { width: 664, height: 524 }
background: { type: color, color: [ 0.1, 0.1, 0.12 ] }
)";

const char* kTorus = R"(objects:
  - { type: torus, radius: 0.08, tube_radius: 0.03, resolution: 48, translate: [ 0.0, -0.25, 0.9 ],
      rotate: [ 60, 0, 0 ], color: [ 0.9, 0.9, 0.9 ],
      material: { ambient: 0.2, diffuse: 0.8, specular: 0.5, specular_power: 30 } }
)";

const char* kOneSpot = R"(  lights:
    - { type: spot, position: [ 0.2, 0.0, 1.3 ], focal_point: [ 0.0, -0.25, 0.9 ], cone_angle: 40,
        color: [ 1, 1, 1 ] }
)";

const char* kBoxOnPlate = R"(objects:
  - { type: box, size: [ 0.08, 0.08, 0.12 ], resolution: 8, translate: [ 0.0, -0.25, 0.86 ],
      color: [ 0.9, 0.5, 0.2 ] }
  - { type: plane, size: [ 0.4, 0.4 ], resolution: 80, translate: [ 0.0, -0.25, 0.8 ],
      color: [ 0.8, 0.8, 0.8 ] }
)";

const char* kSlantSpot = R"(  lights:
    - { type: spot, position: [ 0.25, 0.0, 1.25 ], focal_point: [ 0.0, -0.25, 0.8 ],
        cone_angle: 45, color: [ 1, 1, 1 ] }
)";

struct BaselineScene
{
  const char* name;
  std::string text;
};

std::vector<BaselineScene> BaselineScenes()
{
  const std::string cam = kBaselineCamera;
  return {
    { "LitFlat", cam + "lighting:\n  shading: flat\n  shadows: 0\n" + kOneSpot + kTorus },
    { "LitGouraud", cam + "lighting:\n  shading: gouraud\n  shadows: 0\n" + kOneSpot + kTorus },
    { "ThreeSpotlights",
      cam +
        "lighting:\n  shading: gouraud\n  shadows: 1\n  global_ambient: [0.1, 0.1, 0.1]\n"
        "  lights:\n"
        "    - { type: spot, position: [ 0.3, -0.25, 1.2 ], focal_point: [ 0.0, -0.25, 0.9 ],"
        " cone_angle: 30, color: [ 1.0, 0.15, 0.15 ] }\n"
        "    - { type: spot, position: [ -0.15, 0.0, 1.2 ], focal_point: [ 0.0, -0.25, 0.9 ],"
        " cone_angle: 30, color: [ 0.15, 1.0, 0.15 ] }\n"
        "    - { type: spot, position: [ -0.15, -0.5, 1.2 ], focal_point: [ 0.0, -0.25, 0.9 ],"
        " cone_angle: 30, color: [ 0.2, 0.3, 1.0 ] }\n" +
        kTorus },
    { "ShadowsOff",
      cam + "lighting:\n  shading: gouraud\n  shadows: 0\n" + kSlantSpot + kBoxOnPlate },
    { "ShadowsOn",
      cam + "lighting:\n  shading: gouraud\n  shadows: 1\n" + kSlantSpot + kBoxOnPlate },
    { "TexturedBox",
      cam + "lighting:\n  shading: gouraud\n  shadows: 0\n  global_ambient: [0.4, 0.4, 0.4]\n" +
        kOneSpot +
        "objects:\n  - { type: box, size: [ 0.3, 0.2, 0.15 ], resolution: 16, texture: checker,\n"
        "      translate: [ 0.0, -0.22, 0.85 ], rotate: [ 0, 0, 25 ], color: [ 1, 1, 1 ] }\n" },
  };
}

class ImageBaseline : public ::testing::TestWithParam<int>
{
};
} // namespace

TEST_P(ImageBaseline, MatchesTheBaseline)
{
  const BaselineScene scene = BaselineScenes()[GetParam()];
  vtksys::SystemTools::MakeDirectory(CATAR_TEST_OUTPUT_DIR);
  const std::string path = std::string(CATAR_TEST_OUTPUT_DIR) + "/" + scene.name + ".yaml";
  std::ofstream(path) << scene.text;
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(path.c_str());
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  CompareWithBaseline(renderer->GetOutput(), scene.name);
}

INSTANTIATE_TEST_SUITE_P(
  Lighting, ImageBaseline, ::testing::Range(0, 6), [](const ::testing::TestParamInfo<int>& info) {
    return std::string(BaselineScenes()[info.param].name);
  });

TEST(DemoScene, ObjectsLandWhereTheCameraProjectsThem)
{
  const std::string scene = WriteHalfSizeDemo();
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(scene.c_str());
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  vtkImageData* image = renderer->GetOutput();
  vtkCatadioptricCamera* cam = renderer->GetCamera();
  // The background alone, from the same camera.
  vtkNew<vtkCatadioptricEnvironmentSource> env;
  env->SetCamera(cam);
  env->Update();
  vtkImageData* background = env->GetOutput();
  auto differs = [&](const double w[3]) {
    double px[2], mp[3];
    if (cam->ProjectWorldPoint(w, px, mp) != vtkCatadioptricCamera::VALID)
    {
      return -1;
    }
    const unsigned char* a = PixelOf(image, px[0], px[1]);
    const unsigned char* b = PixelOf(background, px[0], px[1]);
    return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) > 30 ? 1 : 0;
  };
  const catar::SceneDescription demo = catar::DemoScene();
  // The box surrounds its centre: the pixel where the centre projects shows the box.
  const catar::SceneObject& box = demo.objects[0];
  const double centre[3] = { box.translate.x(), box.translate.y(), box.translate.z() };
  EXPECT_EQ(differs(centre), 1);
  // Points on the torus ring (inside the tube) show the torus.
  const catar::SceneObject& torus = demo.objects[1];
  int shown = 0;
  int total = 0;
  for (int k = 0; k < 16; ++k)
  {
    // Ring points in object coordinates, rotated like the scene does (x, then y, then z).
    const double t = 2 * M_PI * k / 16;
    double q[3] = { torus.radius * std::cos(t), torus.radius * std::sin(t), 0.0 };
    auto rot = [](double v[3], int axis, double deg) {
      const double a = deg * M_PI / 180, c = std::cos(a), s = std::sin(a);
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      const double vi = c * v[i] - s * v[j], vj = s * v[i] + c * v[j];
      v[i] = vi;
      v[j] = vj;
    };
    rot(q, 0, torus.rotate.x());
    rot(q, 1, torus.rotate.y());
    rot(q, 2, torus.rotate.z());
    const double w[3] = { q[0] + torus.translate.x(), q[1] + torus.translate.y(),
      q[2] + torus.translate.z() };
    const int d = differs(w);
    if (d >= 0)
    {
      ++total;
      shown += d;
    }
  }
  EXPECT_GT(total, 12);
  EXPECT_EQ(shown, total);
  // Far from both objects (the mirror's centre reflects the camera's own surroundings) the
  // image is the background.
  const double away[3] = { 0.0, -1.5, 1.0 };
  EXPECT_EQ(differs(away), 0);
}

// A mesh that carries its own texture coordinates (OBJ) with an image texture: the textured cow
// 'spot' from the shared data, when present. Its texture's black patches must show: rendered
// with and without the texture, many pixels of the object differ strongly.
TEST(TexturedMesh, ObjTextureCoordinatesAndImage)
{
  const std::string scene = std::string(CATAR_SOURCE_DIR) + "/Data/scenes/spot-textured.yaml";
  const std::string shared = std::string(CATAR_SOURCE_DIR) + "/../shared/data";
  const std::string obj = shared + "/spot/spot_triangulated.obj";
  if (!vtksys::SystemTools::FileExists(obj))
  {
    GTEST_SKIP() << "shared data absent: " << obj;
  }
  // The scene names the mesh and its texture by their place in the data folder.
  vtksys::SystemTools::PutEnv("CATAR_DATA_PATH=" + shared);
  vtkNew<vtkCatadioptricSceneRenderer> textured;
  textured->SetSceneFileName(scene.c_str());
  ASSERT_TRUE(textured->Render()) << textured->GetLastError();
  // The same scene without the texture key.
  std::ifstream in(scene);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t key = text.find("texture: ");
  ASSERT_NE(key, std::string::npos);
  text.erase(key, text.find(',', key) - key + 1);
  // Written elsewhere, so relative paths become absolute.
  const std::string dir = std::string(CATAR_SOURCE_DIR) + "/Data/scenes/";
  for (std::size_t at = text.find(" ../"); at != std::string::npos; at = text.find(" ../", at + 4))
  {
    text.insert(at + 1, dir);
  }
  vtksys::SystemTools::MakeDirectory(CATAR_TEST_OUTPUT_DIR);
  const std::string plainPath = std::string(CATAR_TEST_OUTPUT_DIR) + "/spot-plain.yaml";
  std::ofstream(plainPath) << text;
  vtkNew<vtkCatadioptricSceneRenderer> plain;
  plain->SetSceneFileName(plainPath.c_str());
  ASSERT_TRUE(plain->Render()) << plain->GetLastError();
  vtksys::SystemTools::UnPutEnv("CATAR_DATA_PATH");
  vtkImageData* a = textured->GetOutput();
  vtkImageData* b = plain->GetOutput();
  const vtkIdType n = a->GetNumberOfPoints();
  ASSERT_EQ(n, b->GetNumberOfPoints());
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  vtkIdType changed = 0, darker = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    int d = 0;
    for (int k = 0; k < 3; ++k)
    {
      d = std::max(d, std::abs(int(pa[4 * i + k]) - int(pb[4 * i + k])));
    }
    changed += d > 40;
    darker += (pa[4 * i] + 100 < pb[4 * i]); // black patches on a white cow
  }
  EXPECT_GT(changed, 1000);
  EXPECT_GT(darker, 500);
}
