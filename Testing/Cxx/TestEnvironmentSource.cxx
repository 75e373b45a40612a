// vtkCatadioptricEnvironmentSource in PANORAMA mode: a panorama image file (written here as a
// PNG) seen in the mirror with the backdrop around it; the generated room panorama; missing and
// unreadable files; a real panorama from the shared data when present; the scene key.
#include "Environment.h"
#include "Projector.h"
#include "SphereMirror.h"
#include "TestUtilities.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricEnvironmentSource.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageReader2Factory.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;

// The demo's layout at 160x120: world z up, the camera at world (0, -0.2, 1) looks along +y at
// a mirror 20 cm away whose image is a disc of about 52 pixels radius in the middle.
catar::CameraModel SmallModel()
{
  catar::CameraModel m;
  m.intrinsics.width = 160;
  m.intrinsics.height = 120;
  m.intrinsics.fx = m.intrinsics.fy = 200.0;
  m.intrinsics.cx = 79.5;
  m.intrinsics.cy = 59.5;
  m.mirror = catar::SphereMirror{ catar::Vec3(0.0, 0.0, 0.2), 0.05 };
  m.worldToCamera << 1, 0, 0, 0, 0, 0, -1, 1.0, 0, 1, 0, 0.2, 0, 0, 0, 1;
  return m;
}

vtkSmartPointer<vtkCatadioptricCamera> SmallCamera()
{
  auto camera = vtkSmartPointer<vtkCatadioptricCamera>::New();
  camera->SetModel(SmallModel());
  return camera;
}

// A 96x48 RGB panorama (Core layout, row 0 at the top): sky-blue top half, brown bottom half, with
// a colour ramp in longitude and latitude so that a flipped or mirrored image shows.
catar::EquirectangularPanorama TestPanorama()
{
  catar::EquirectangularPanorama p;
  p.width = 96;
  p.height = 48;
  p.channels = 3;
  p.pixels.resize(static_cast<std::size_t>(p.width) * p.height * 3);
  for (int j = 0; j < p.height; ++j)
  {
    for (int i = 0; i < p.width; ++i)
    {
      std::uint8_t* t = p.texel(i, j);
      const bool sky = j < p.height / 2;
      t[0] = static_cast<std::uint8_t>(sky ? 40 + i : 150 + i);
      t[1] = static_cast<std::uint8_t>(sky ? 120 + 2 * j : 80 + j);
      t[2] = static_cast<std::uint8_t>(sky ? 230 : 30 + ((i / 8 + j / 8) % 2) * 60);
    }
  }
  return p;
}

// Writes a Core panorama as a PNG (vtkImageData rows from the bottom).
void WritePNG(const catar::EquirectangularPanorama& p, const std::string& path)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(p.width, p.height, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* out = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < p.height; ++y)
  {
    std::copy_n(
      p.texel(0, p.height - 1 - y), 3 * p.width, out + 3 * static_cast<std::size_t>(y) * p.width);
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}

std::string TempDir()
{
  const std::string dir = std::string(CATAR_TEST_OUTPUT_DIR) + "/EnvironmentSource";
  vtksys::SystemTools::MakeDirectory(dir);
  return dir;
}

// RGBA of pixel (x, y) in the camera's convention (y down) of a VTK-ordered image.
const unsigned char* At(vtkImageData* image, int x, int y)
{
  const int h = image->GetDimensions()[1];
  return static_cast<unsigned char*>(image->GetScalarPointer(x, h - 1 - y, 0));
}

int MaxDifference(const unsigned char* a, const catar::Vec3& c)
{
  int d = 0;
  for (int k = 0; k < 3; ++k)
  {
    d = std::max(d, std::abs(int(a[k]) - int(std::lround(255.0 * c[k]))));
  }
  return d;
}

std::string SharedData(const std::string& name)
{
  const char* folder = std::getenv("CATAR_SHARED_DATA");
  const std::string base =
    folder && *folder ? folder : std::string(CATAR_SOURCE_DIR) + "/../shared/data";
  return base + "/" + name;
}
} // namespace

TEST(EnvironmentSource, PanoramaFromPNG)
{
  const catar::EquirectangularPanorama pano = TestPanorama();
  const std::string file = TempDir() + "/panorama.png";
  WritePNG(pano, file);

  auto camera = SmallCamera();
  vtkNew<vtkCatadioptricEnvironmentSource> source;
  EXPECT_EQ(source->GetMode(), vtkCatadioptricEnvironmentSource::ROOM);
  source->SetCamera(camera);
  source->SetModeToPanorama();
  source->SetPanoramaFileName(file.c_str());
  source->SetPanoramaRotation(20.0);
  source->SetBackdropColor(0.1, 0.2, 0.3);
  source->SetSamples(1);
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(source);
  source->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  vtkImageData* image = source->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  ASSERT_EQ(dims[0], 160);
  ASSERT_EQ(dims[1], 120);
  ASSERT_EQ(image->GetNumberOfScalarComponents(), 4);

  // The corners do not see the mirror: backdrop.
  const int corners[2][2] = { { 0, 0 }, { 159, 119 } };
  for (const auto& p : corners)
  {
    const unsigned char* c = At(image, p[0], p[1]);
    EXPECT_EQ(int(c[0]), 26);
    EXPECT_EQ(int(c[1]), 51);
    EXPECT_EQ(int(c[2]), 77);
    EXPECT_EQ(int(c[3]), 255);
  }
  // Pixels in the mirror: the panorama along the reflected direction, turned by -20 degrees.
  const double a = -20.0 * kPi / 180.0;
  int checked = 0, sky = 0, ground = 0;
  for (int y = 12; y < 110; y += 7)
  {
    for (int x = 30; x < 130; x += 7)
    {
      const double pixel[2] = { double(x), double(y) };
      double origin[3], d[3];
      if (camera->BackProjectPixel(pixel, origin, d) != vtkCatadioptricCamera::VALID)
      {
        continue;
      }
      const catar::Vec3 r(
        std::cos(a) * d[0] - std::sin(a) * d[1], std::sin(a) * d[0] + std::cos(a) * d[1], d[2]);
      const catar::Vec3 expected = catar::PanoramaColor(pano, r);
      EXPECT_LE(MaxDifference(At(image, x, y), expected), 1) << "pixel " << x << ", " << y;
      ++checked;
      sky += d[2] > 0.1;
      ground += d[2] < -0.1;
    }
  }
  EXPECT_GT(checked, 100);
  // Upward reflected rays see the sky, downward ones the ground (rows were not flipped).
  EXPECT_GT(sky, 20);
  EXPECT_GT(ground, 20);
  const double up[2] = { 79.5, 25.0 }; // top of the disc reflects the zenith side
  double o[3], d[3];
  ASSERT_EQ(camera->BackProjectPixel(up, o, d), vtkCatadioptricCamera::VALID);
  ASSERT_GT(d[2], 0.3);
  EXPECT_EQ(int(At(image, 79, 25)[2]), 230); // sky blue

  // Parameters re-execute the source.
  vtkNew<vtkImageData> before;
  before->DeepCopy(image);
  source->SetPanoramaRotation(200.0);
  source->Update();
  int changed = 0;
  for (int y = 0; y < 120; ++y)
  {
    for (int x = 0; x < 160; ++x)
    {
      changed += std::abs(int(At(before, x, y)[0]) - int(At(image, x, y)[0])) > 5;
    }
  }
  EXPECT_GT(changed, 1000);
  source->SetBackdropColor(1, 1, 1);
  source->Update();
  EXPECT_EQ(int(At(image, 0, 0)[0]), 255);

  // The file rewritten under the same name (a newer modification time) is read again.
  catar::EquirectangularPanorama inverted = pano;
  for (std::uint8_t& v : inverted.pixels)
  {
    v = static_cast<std::uint8_t>(255 - v);
  }
  WritePNG(inverted, file);
  std::filesystem::last_write_time(
    file, std::filesystem::last_write_time(file) + std::chrono::seconds(2));
  source->Modified();
  source->Update();
  EXPECT_EQ(int(At(image, 79, 25)[2]), 255 - 230);
  EXPECT_EQ(errors->Count, 0) << errors->Last;
}

TEST(EnvironmentSource, GeneratedRoomPanorama)
{
  auto camera = SmallCamera();
  vtkNew<vtkCatadioptricEnvironmentSource> room;
  room->SetCamera(camera);
  room->SetSamples(1);
  room->Update();
  vtkNew<vtkCatadioptricEnvironmentSource> pano;
  pano->SetCamera(camera);
  pano->SetSamples(1);
  pano->SetModeToPanorama(); // no file: the room seen from the mirror centre
  pano->Update();
  vtkImageData* a = room->GetOutput();
  vtkImageData* b = pano->GetOutput();
  int mirror = 0, agree = 0;
  for (int y = 0; y < 120; ++y)
  {
    for (int x = 0; x < 160; ++x)
    {
      const double pixel[2] = { double(x), double(y) };
      double o[3], d[3];
      const unsigned char* pb = At(b, x, y);
      if (camera->BackProjectPixel(pixel, o, d) != vtkCatadioptricCamera::VALID)
      {
        ASSERT_EQ(int(pb[0]), 128); // mid grey backdrop
        ASSERT_EQ(int(pb[1]), 128);
        ASSERT_EQ(int(pb[2]), 128);
        continue;
      }
      ++mirror;
      // The room mode's mirror reflects 92% and from the mirror point rather than its centre.
      const unsigned char* pa = At(a, x, y);
      int diff = 0;
      for (int k = 0; k < 3; ++k)
      {
        diff = std::max(diff, std::abs(int(pa[k]) - int(std::lround(0.92 * pb[k]))));
      }
      agree += diff <= 6;
    }
  }
  EXPECT_GT(mirror, 7000);
  EXPECT_GT(agree, 0.8 * mirror);
}

TEST(EnvironmentSource, MissingOrUnreadablePanorama)
{
  auto camera = SmallCamera();
  vtkNew<vtkCatadioptricEnvironmentSource> source;
  source->SetCamera(camera);
  source->SetModeToPanorama();
  source->SetSamples(1);
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(source);
  const std::string missing = TempDir() + "/no-such-panorama.png";
  source->SetPanoramaFileName(missing.c_str());
  EXPECT_EQ(source->GetExecutive()->Update(), 0);
  EXPECT_GE(errors->Count, 1);
  EXPECT_NE(errors->Last.find("PanoramaFileName"), std::string::npos) << errors->Last;
  EXPECT_NE(errors->Last.find("no-such-panorama.png"), std::string::npos) << errors->Last;

  const std::string garbage = TempDir() + "/not-an-image.png";
  std::ofstream(garbage) << "this is not a PNG file\n";
  errors->Count = 0;
  source->SetPanoramaFileName(garbage.c_str());
  EXPECT_EQ(source->GetExecutive()->Update(), 0);
  EXPECT_GE(errors->Count, 1);
  EXPECT_NE(errors->Last.find("not-an-image.png"), std::string::npos) << errors->Last;

  // A good file afterwards works.
  const std::string good = TempDir() + "/panorama-good.png";
  WritePNG(TestPanorama(), good);
  errors->Count = 0;
  source->SetPanoramaFileName(good.c_str());
  EXPECT_EQ(source->GetExecutive()->Update(), 1);
  EXPECT_EQ(errors->Count, 0) << errors->Last;
  // The file name is ignored in ROOM mode.
  source->SetModeToRoom();
  source->SetPanoramaFileName(missing.c_str());
  EXPECT_EQ(source->GetExecutive()->Update(), 1);
  EXPECT_EQ(errors->Count, 0) << errors->Last;
}

TEST(EnvironmentSource, RealPanoramaFromSharedData)
{
  const std::string file = SharedData("env/spruit_sunrise_2k.jpg");
  if (!vtksys::SystemTools::FileExists(file, true))
  {
    GTEST_SKIP() << "shared data absent: " << file;
  }
  auto camera = SmallCamera();
  vtkNew<vtkCatadioptricEnvironmentSource> source;
  source->SetCamera(camera);
  source->SetModeToPanorama();
  source->SetPanoramaFileName(file.c_str());
  source->SetBackdropColor(1.0, 0.0, 1.0); // magenta: not in a sunrise over a field
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(source);
  source->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  vtkImageData* image = source->GetOutput();
  int mirror = 0, notBackdrop = 0;
  double sum = 0.0, sum2 = 0.0;
  for (int y = 0; y < 120; ++y)
  {
    for (int x = 0; x < 160; ++x)
    {
      const double pixel[2] = { double(x), double(y) };
      double o[3], d[3];
      if (camera->BackProjectPixel(pixel, o, d) != vtkCatadioptricCamera::VALID)
      {
        continue;
      }
      const unsigned char* c = At(image, x, y);
      ++mirror;
      notBackdrop += MaxDifference(c, catar::Vec3(1.0, 0.0, 1.0)) > 30;
      const double luma = 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];
      sum += luma;
      sum2 += luma * luma;
    }
  }
  ASSERT_GT(mirror, 7000);
  EXPECT_GT(notBackdrop, 0.95 * mirror);
  // A real place: the reflection is not a flat colour.
  const double mean = sum / mirror;
  EXPECT_GT(std::sqrt(std::max(0.0, sum2 / mirror - mean * mean)), 10.0);
  // Brighter sky above the horizon than ground below: the zenith side of the disc (top) against
  // the nadir side (bottom).
  double top = 0.0, bottom = 0.0;
  for (int x = 70; x < 90; ++x)
  {
    top += At(image, x, 14)[0] + At(image, x, 14)[1] + At(image, x, 14)[2];
    bottom += At(image, x, 105)[0] + At(image, x, 105)[1] + At(image, x, 105)[2];
  }
  EXPECT_GT(top, bottom);

  // A Radiance .hdr (float) panorama, tone-mapped, when VTK's factory reads it.
  const std::string hdr = SharedData("env/royal_esplanade_1k.hdr");
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(hdr.c_str()));
  if (reader && vtksys::SystemTools::FileExists(hdr, true))
  {
    source->SetPanoramaFileName(hdr.c_str());
    source->Update();
    EXPECT_EQ(errors->Count, 0) << errors->Last;
    int lit = 0;
    for (int x = 40; x < 120; ++x)
    {
      lit += MaxDifference(At(image, x, 60), catar::Vec3(1.0, 0.0, 1.0)) > 30;
    }
    EXPECT_GT(lit, 40);
  }
}

TEST(EnvironmentSource, SceneBackgroundPanorama)
{
  const std::string dir = TempDir();
  WritePNG(TestPanorama(), dir + "/scene-panorama.png");
  const std::string scene = dir + "/panorama-scene.yaml";
  std::ofstream(scene) << "%YAML:1.0\n---\ncamera: " << CATAR_SOURCE_DIR
                       << "/Data/calibration/demo-camera.yaml\n"
                          "output: { width: 166, height: 131 }\n"
                          "background: { type: panorama, file: scene-panorama.png, rotation: 10,"
                          " backdrop: [0, 1, 0], samples: 1 }\n"
                          "objects:\n"
                          "  - { type: sphere, radius: 0.03, translate: [0.06, -0.32, 0.92] }\n";
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(scene.c_str());
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  vtkImageData* image = renderer->GetOutput();
  const unsigned char* corner = At(image, 0, 0);
  EXPECT_EQ(int(corner[0]), 0);
  EXPECT_EQ(int(corner[1]), 255);
  EXPECT_EQ(int(corner[2]), 0);
  // The middle of the mirror (the demo's mirror is centred) shows the panorama, not the backdrop.
  const unsigned char* middle = At(image, 83, 65);
  EXPECT_FALSE(middle[0] == 0 && middle[1] == 255 && middle[2] == 0);

  // A missing panorama file: the error names the key.
  const std::string broken = dir + "/panorama-missing.yaml";
  std::ofstream(broken) << "%YAML:1.0\n---\ncamera: " << CATAR_SOURCE_DIR
                        << "/Data/calibration/demo-camera.yaml\n"
                           "output: { width: 166, height: 131 }\n"
                           "background: { type: panorama, file: nowhere.jpg }\n"
                           "objects: []\n";
  vtkNew<vtkCatadioptricSceneRenderer> bad;
  bad->SetSceneFileName(broken.c_str());
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(bad);
  EXPECT_FALSE(bad->Render());
  EXPECT_NE(std::string(bad->GetLastError()).find("file"), std::string::npos)
    << bad->GetLastError();
  EXPECT_NE(std::string(bad->GetLastError()).find("nowhere.jpg"), std::string::npos)
    << bad->GetLastError();
}

// The frame is kept while the camera and the source's parameters are unchanged (the camera
// marked modified with nothing changed: the same pixels, not traced again) and made anew when
// either changes: a new pose gives the frame a fresh source makes at that pose; back at the first
// pose, the first frame; other samples, other pixels (those of a fresh source with them). In ROOM
// and PANORAMA modes.
TEST(EnvironmentSource, FrameKeptUntilTheCameraOrTheSettingsChange)
{
  auto bytes = [](vtkImageData* image) {
    const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
    return std::vector<unsigned char>(p, p + 4 * image->GetNumberOfPoints());
  };
  for (const bool panorama : { false, true })
  {
    SCOPED_TRACE(panorama ? "panorama" : "room");
    auto camera = SmallCamera();
    vtkNew<vtkCatadioptricEnvironmentSource> env;
    env->SetCamera(camera);
    env->SetSamples(1);
    env->SetMode(panorama ? vtkCatadioptricEnvironmentSource::PANORAMA
                          : vtkCatadioptricEnvironmentSource::ROOM);
    auto fresh = [&](const catar::CameraModel& model, int samples) {
      auto other = vtkSmartPointer<vtkCatadioptricCamera>::New();
      other->SetModel(model);
      vtkNew<vtkCatadioptricEnvironmentSource> source;
      source->SetCamera(other);
      source->SetSamples(samples);
      source->SetMode(env->GetMode());
      source->Update();
      return bytes(source->GetOutput());
    };
    env->Update();
    vtkDataArray* pixels = env->GetOutput()->GetPointData()->GetScalars();
    ASSERT_NE(pixels, nullptr);
    const vtkMTimeType traced = pixels->GetMTime();
    const std::vector<unsigned char> first = bytes(env->GetOutput());
    EXPECT_EQ(first, fresh(camera->GetModel(), 1));

    camera->Modified(); // nothing changed: kept
    env->Update();
    EXPECT_EQ(env->GetOutput()->GetPointData()->GetScalars(), pixels);
    EXPECT_EQ(pixels->GetMTime(), traced);
    EXPECT_EQ(bytes(env->GetOutput()), first);
    int dims[3];
    env->GetOutput()->GetDimensions(dims);
    EXPECT_EQ(dims[0], 160);
    EXPECT_EQ(dims[1], 120);

    // The camera 3 cm to the side and turned 5 degrees: a new frame, as a fresh source's.
    catar::CameraModel moved = SmallModel();
    const double a = 5.0 * kPi / 180.0;
    catar::Mat4 turn = catar::Mat4::Identity();
    turn(0, 0) = turn(1, 1) = std::cos(a);
    turn(0, 1) = -std::sin(a);
    turn(1, 0) = std::sin(a);
    turn(0, 3) = 0.03;
    moved.worldToCamera = moved.worldToCamera * turn;
    camera->SetModel(moved);
    env->Update();
    const std::vector<unsigned char> second = bytes(env->GetOutput());
    EXPECT_NE(second, first);
    EXPECT_EQ(second, fresh(moved, 1));

    camera->SetModel(SmallModel()); // back: the first frame again
    env->Update();
    EXPECT_EQ(bytes(env->GetOutput()), first);

    env->SetSamples(2); // the source's own parameter
    env->Update();
    const std::vector<unsigned char> supersampled = bytes(env->GetOutput());
    EXPECT_NE(supersampled, first);
    EXPECT_EQ(supersampled, fresh(SmallModel(), 2));
  }
}
