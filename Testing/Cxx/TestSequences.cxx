// Sequences (Documentation/file-formats.md): frame k of a scene with a trajectory is the still
// scene at pose k; keyframed objects are where the still scene puts them; a frame recomputes only
// what moved; video backgrounds and outputs round-trip through OpenCV; catadioptric-render writes
// every frame; a synthesised background is traced again only when the camera moves.
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "TestUtilities.h"
#include "Trajectory.h"
#include "VideoIO.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
const double kPi = 3.14159265358979323846;

std::string Folder(const std::string& name)
{
  const std::string dir = std::string(CATAR_TEST_OUTPUT_DIR) + "/sequences-" + name;
  mkdir(CATAR_TEST_OUTPUT_DIR, 0755);
  mkdir(dir.c_str(), 0755);
  return dir;
}

void Write(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}

// The demo camera (looking along world +y from (0, -0.14, 1)), moved sideways by dx and turned
// by yaw degrees about world z: world-to-camera.
catar::Mat4 Pose(double dx, double yaw)
{
  catar::Mat4 cameraToWorld = catar::Mat4::Identity();
  const catar::Mat3 base = (catar::Mat3() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
  cameraToWorld.topLeftCorner<3, 3>() =
    Eigen::AngleAxisd(yaw * kPi / 180.0, catar::Vec3::UnitZ()).toRotationMatrix() * base;
  cameraToWorld.topRightCorner<3, 1>() = catar::Vec3(dx, -0.14, 1.0);
  return cameraToWorld.inverse();
}

std::string Matrix(const catar::Mat4& m)
{
  std::ostringstream s;
  s << std::setprecision(17) << "[ ";
  for (int i = 0; i < 16; ++i)
  {
    s << m(i / 4, i % 4) << (i < 15 ? ", " : " ]");
  }
  return s.str();
}

// A small lit scene; `extra` goes at the top level, `object` is the second object's extra keys.
std::string Scene(const catar::Mat4& pose, const std::string& extra, const std::string& rotate,
  const std::string& torusKeys = "", const std::string& lightKeys = "")
{
  std::ostringstream s;
  s << R"(camera:
  image_width: 240
  image_height: 190
  camera_matrix: [ 180.0, 0.0, 119.5, 0.0, 180.0, 94.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
  world_to_camera: )"
    << Matrix(pose) << R"(
background: { type: color, color: [ 0.1, 0.1, 0.1 ] }
lighting:
  shading: gouraud
  lights:
    - { type: spot, position: [ 0.25, 0.05, 1.35 ], focal_point: [ 0.0, -0.22, 0.95 ],
        cone_angle: 45 )"
    << lightKeys << R"( }
objects:
  - { type: box, size: [ 0.12, 0.08, 0.06 ], resolution: 6, translate: [ 0.12, -0.22, 0.9 ],
      rotate: [ 0, 0, 30 ], face_colors: true }
  - { type: torus, radius: 0.06, tube_radius: 0.02, resolution: 24,
      translate: [ -0.12, -0.22, 1.05 ], rotate: )"
    << rotate << R"(, color: [ 0.9, 0.5, 0.1 ] )" << torusKeys << R"( }
)" << extra;
  return s.str();
}

// The rendered frame's bytes (RGBA, VTK's row order).
std::vector<unsigned char> Bytes(vtkCatadioptricSceneRenderer* r)
{
  vtkImageData* image = r->GetOutput();
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  return std::vector<unsigned char>(p, p + image->GetNumberOfPoints() * 4);
}

std::vector<unsigned char> RenderStill(const std::string& path, const std::string& text)
{
  Write(path, text);
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName(path.c_str());
  EXPECT_TRUE(r->Render()) << r->GetLastError();
  EXPECT_EQ(r->GetNumberOfFrames(), 1);
  return Bytes(r);
}

// The share of pixels that differ by more than `tolerance` in any channel.
double DifferingShare(
  const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, int tolerance)
{
  EXPECT_EQ(a.size(), b.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
  {
    for (int c = 0; c < 4; ++c)
    {
      if (std::abs(int(a[i + c]) - int(b[i + c])) > tolerance)
      {
        ++differ;
        break;
      }
    }
  }
  return static_cast<double>(differ) / static_cast<double>(a.size() / 4);
}

// Poses of a camera sliding and turning (0.3 s apart), written as a TUM file.
catar::Trajectory SlidingCamera(int n)
{
  catar::Trajectory t;
  for (int k = 0; k < n; ++k)
  {
    t.poses.push_back({ 0.3 * k, Pose(-0.03 + 0.015 * k, -4.0 + 2.0 * k) });
  }
  return t;
}
} // namespace

// Frame k of a sequence is, byte for byte, the still scene whose world_to_camera is pose k (the
// trajectory read from a TUM file, camera-to-world, turned into world-to-camera).
TEST(Sequence, FrameKIsTheStillSceneAtPoseK)
{
  const std::string dir = Folder("trajectory");
  const catar::Trajectory written = SlidingCamera(5);
  std::string error;
  ASSERT_TRUE(catar::SaveTrajectory(dir + "/poses.tum", written, "tum", error)) << error;
  catar::Trajectory read;
  ASSERT_TRUE(catar::LoadTrajectory(dir + "/poses.tum", read, error)) << error;
  Write(dir + "/sequence.yaml",
    Scene(catar::Mat4::Identity(), "trajectory: poses.tum\n", "[ 70, 0, 20 ]"));
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/sequence.yaml").c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  ASSERT_EQ(r->GetNumberOfFrames(), 5);
  std::vector<std::vector<unsigned char>> frames;
  for (int k = 0; k < 5; ++k)
  {
    ASSERT_TRUE(r->RenderFrame(k)) << r->GetLastError();
    EXPECT_DOUBLE_EQ(r->GetFrameTime(k), 0.3 * k);
    frames.push_back(Bytes(r));
  }
  EXPECT_NEAR(r->GetFrameRate(), 1.0 / 0.3, 1e-9);
  for (int k = 0; k < 5; ++k)
  {
    // The pose read back is the pose written (to the quaternion's rounding).
    EXPECT_LT((read.poses[k].worldToCamera - written.poses[k].worldToCamera).norm(), 1e-12);
    const std::vector<unsigned char> still =
      RenderStill(dir + "/still-" + std::to_string(k) + ".yaml",
        Scene(read.poses[k].worldToCamera, "", "[ 70, 0, 20 ]"));
    EXPECT_TRUE(still == frames[k]) << "frame " << k;
    if (k > 0)
    {
      EXPECT_GT(DifferingShare(frames[k], frames[k - 1], 0), 0.01) << "the camera moved";
    }
  }
  // Out of range.
  EXPECT_FALSE(r->RenderFrame(5));
  EXPECT_NE(std::string(r->GetLastError()).find("0 to 4"), std::string::npos);
}

// A keyframed object at a keyframe's time stands where the still scene with that keyframe's
// translate and rotate puts it (the same mesh moved instead of built there: the same picture to
// rounding); between keyframes, at the slerp of the two rotations.
TEST(Sequence, KeyframedObjectsStandWhereTheStillSceneHasThem)
{
  const std::string dir = Folder("keyframes");
  const std::string keys = R"(, keyframes: [ { time: 0, rotate: [ 70, 0, 20 ] },
      { time: 1, translate: [ -0.10, -0.2, 1.0 ], rotate: [ 70, 0, 100 ] } ])";
  const std::string text =
    Scene(Pose(0, 0), "sequence: { frames: 3, fps: 2 }\n", "[ 70, 0, 20 ]", keys);
  Write(dir + "/sequence.yaml", text);
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/sequence.yaml").c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  ASSERT_EQ(r->GetNumberOfFrames(), 3);
  ASSERT_TRUE(r->RenderFrame(2)); // t = 1: the second keyframe
  const std::vector<unsigned char> last = Bytes(r);
  std::string moved = Scene(Pose(0, 0), "", "[ 70, 0, 100 ]");
  moved.replace(moved.find("[ -0.12, -0.22, 1.05 ]"), 22, "[ -0.10, -0.2, 1.0 ]");
  const std::vector<unsigned char> still = RenderStill(dir + "/still-1.yaml", moved);
  const double share = DifferingShare(last, still, 2);
  std::cout << "[ sequence ] keyframe 1 against the still scene: " << 100.0 * share
            << " % of pixels differ by more than 2" << std::endl;
  EXPECT_LT(share, 0.002);
  // t = 0.5: halfway, the rotation about z by 60 degrees (slerp of two rotations about the same
  // axis is that axis at the mean angle) and the mean position.
  ASSERT_TRUE(r->RenderFrame(1));
  const std::vector<unsigned char> half = Bytes(r);
  std::string halfway = Scene(Pose(0, 0), "", "[ 70, 0, 60 ]");
  halfway.replace(halfway.find("[ -0.12, -0.22, 1.05 ]"), 22, "[ -0.11, -0.21, 1.025 ]");
  EXPECT_LT(DifferingShare(half, RenderStill(dir + "/still-half.yaml", halfway), 2), 0.002);
  EXPECT_GT(DifferingShare(half, last, 2), 0.005) << "the object moved";
}

// Keyframes and no `sequence` key: the frames the keyframes span, at 30 a second, and a note
// that says so (one frame before, and nothing said).
TEST(Sequence, KeyframesWithoutASequenceKeySpanTheirTime)
{
  const std::string dir = Folder("keyframes-span");
  const std::string keys = R"(, keyframes: [ { time: 0, rotate: [ 70, 0, 20 ] },
      { time: 2, rotate: [ 70, 0, 100 ] } ])";
  Write(dir + "/span.yaml", Scene(Pose(0, 0), "", "[ 70, 0, 20 ]", keys));
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/span.yaml").c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  EXPECT_EQ(r->GetNumberOfFrames(), 61);
  EXPECT_NE(std::string(r->GetSequenceNote()).find("keyframes run to 2 s"), std::string::npos)
    << r->GetSequenceNote();
  // With the key, the key decides, and nothing is said.
  Write(dir + "/given.yaml",
    Scene(Pose(0, 0), "sequence: { frames: 3, fps: 2 }\n", "[ 70, 0, 20 ]", keys));
  r->SetSceneFileName((dir + "/given.yaml").c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  EXPECT_EQ(r->GetNumberOfFrames(), 3);
  EXPECT_STREQ(r->GetSequenceNote(), "");
}

// Numbered background frames with a gap: the sequence stops at the gap, and a note says so.
TEST(Sequence, AGapInNumberedFramesIsSaid)
{
  const std::string dir = Folder("gap");
  for (const int k : { 1, 2, 3, 5, 6 })
  {
    catar::Frame f;
    f.width = 240;
    f.height = 190;
    f.rgba.assign(static_cast<std::size_t>(240) * 190 * 4, 128);
    catar::FrameWriter writer;
    std::string error;
    ASSERT_TRUE(writer.Open(dir + "/bg_%03d.png", 240, 190, 0.0, error)) << error;
    ASSERT_TRUE(writer.Write(k, f, error)) << error;
  }
  std::string text = Scene(Pose(0, 0), "", "[ 70, 0, 20 ]");
  text.replace(text.find("background: { type: color, color: [ 0.1, 0.1, 0.1 ] }"), 53,
    "background: { type: video, file: bg_%03d.png, fps: 5 }");
  Write(dir + "/scene.yaml", text);
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/scene.yaml").c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  EXPECT_EQ(r->GetNumberOfFrames(), 3);
  const std::string note = r->GetSequenceNote();
  EXPECT_NE(note.find("bg_004.png is missing"), std::string::npos) << note;
  EXPECT_NE(note.find("bg_005.png exists"), std::string::npos) << note;
}

// Frame to frame, a still camera keeps the projection of still objects; a moving light redoes
// the lighting only; a moving object redoes its own projection only; a moving camera all of them.
TEST(Sequence, OnlyWhatMovedIsRecomputed)
{
  const std::string dir = Folder("recompute");
  catar::Trajectory t;
  t.poses = { { 0.0, Pose(0, 0) }, { 1.0, Pose(0, 0) }, { 2.0, Pose(0, 0) },
    { 3.0, Pose(0.02, 0) } };
  std::string error;
  ASSERT_TRUE(catar::SaveTrajectory(dir + "/poses.txt", t, "matrix", error)) << error;
  const std::string torusKeys = R"(, keyframes: [ { time: 1, rotate: [ 70, 0, 20 ] },
      { time: 2, rotate: [ 70, 0, 50 ] } ])";
  const std::string lightKeys = R"(, keyframes: [ { time: 0, position: [ 0.25, 0.05, 1.35 ] },
      { time: 1, position: [ 0.2, 0.05, 1.35 ] } ])";
  Write(dir + "/scene.yaml",
    Scene(Pose(0, 0), "trajectory: poses.txt\n", "[ 70, 0, 20 ]", torusKeys, lightKeys));
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/scene.yaml").c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  ASSERT_EQ(r->GetNumberOfPipelines(), 2); // the keyframed torus is not joined with the box
  auto times = [&]() {
    std::vector<vtkMTimeType> m;
    for (int p = 0; p < 2; ++p)
    {
      m.push_back(r->GetProjection(p)->GetOutput()->GetMTime());
      m.push_back(r->GetLighting(p)->GetOutput()->GetMTime());
    }
    return m; // box projection, box lighting, torus projection, torus lighting
  };
  ASSERT_TRUE(r->RenderFrame(0));
  const auto f0 = times();
  ASSERT_TRUE(r->RenderFrame(1)); // the light moved
  const auto f1 = times();
  EXPECT_EQ(f1[0], f0[0]);
  EXPECT_EQ(f1[2], f0[2]);
  EXPECT_GT(f1[1], f0[1]);
  EXPECT_GT(f1[3], f0[3]);
  ASSERT_TRUE(r->RenderFrame(2)); // the torus turned (its shadow on the box: both lightings)
  const auto f2 = times();
  EXPECT_EQ(f2[0], f1[0]);
  EXPECT_GT(f2[2], f1[2]);
  ASSERT_TRUE(r->RenderFrame(3)); // the camera moved
  const auto f3 = times();
  EXPECT_GT(f3[0], f2[0]);
  EXPECT_GT(f3[2], f2[2]);
  ASSERT_TRUE(r->RenderFrame(3)); // nothing moved
  EXPECT_EQ(times(), f3);
}

// A background given as numbered frames: frame k of the sequence shows background frame k; the
// frames written as a video (.avi and .mp4) read back with their count and size.
TEST(Sequence, VideoBackgroundAndVideoOutput)
{
  const std::string dir = Folder("video");
  const int n = 6, w = 240, h = 190;
  for (int k = 0; k < n; ++k)
  {
    catar::Frame f;
    f.width = w;
    f.height = h;
    f.rgba.assign(static_cast<std::size_t>(w) * h * 4, 255);
    for (std::size_t i = 0; i < f.rgba.size(); i += 4)
    {
      f.rgba[i] = static_cast<unsigned char>(40 * k); // red: the frame number
      f.rgba[i + 1] = 10;
      f.rgba[i + 2] = 200;
    }
    catar::FrameWriter writer;
    std::string error;
    ASSERT_TRUE(writer.Open(dir + "/bg_%03d.png", w, h, 0.0, error)) << error;
    ASSERT_TRUE(writer.Write(k + 1, f, error)) << error; // numbered from 1
  }
  std::string text = Scene(Pose(0, 0), "", "[ 70, 0, 20 ]");
  text.replace(text.find("background: { type: color, color: [ 0.1, 0.1, 0.1 ] }"), 53,
    "background: { type: video, file: bg_%03d.png, fps: 5 }");
  Write(dir + "/scene.yaml", text);
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/scene.yaml").c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  ASSERT_EQ(r->GetNumberOfFrames(), n);
  EXPECT_DOUBLE_EQ(r->GetFrameRate(), 5.0);
  for (const char* name : { "/out.avi", "/out.mp4" })
  {
    catar::FrameWriter video;
    std::string error;
    ASSERT_TRUE(video.Open(dir + name, w, h, r->GetFrameRate(), error)) << error;
    for (int k = 0; k < n; ++k)
    {
      ASSERT_TRUE(r->RenderFrame(k)) << r->GetLastError();
      const auto* corner = static_cast<unsigned char*>(r->GetOutput()->GetScalarPointer(0, 0, 0));
      EXPECT_EQ(int(corner[0]), 40 * k);
      EXPECT_EQ(int(corner[1]), 10);
      EXPECT_EQ(int(corner[2]), 200);
      ASSERT_TRUE(video.Write(k, vtkCatadioptricImageSupport::ToFrame(r->GetOutput()), error))
        << error;
    }
    video.Close();
    catar::FrameReader back;
    ASSERT_TRUE(back.Open(dir + name, error)) << error;
    EXPECT_EQ(back.GetNumberOfFrames(), n) << name;
    EXPECT_NEAR(back.GetFrameRate(), 5.0, 1e-6) << name;
    catar::Frame f;
    ASSERT_TRUE(back.Read(n - 1, f, error)) << error;
    EXPECT_EQ(f.width, w);
    EXPECT_EQ(f.height, h);
    EXPECT_NEAR(int(f.rgba[0]), 40 * (n - 1), 12) << name << ": a lossy codec, the same colour";
    EXPECT_FALSE(back.Read(n, f, error));
  }
}

// A background matched to the trajectory by time: frame k is at start_time + k / fps and the
// camera at the trajectory's pose then (interpolated between poses); matched by index, frame k
// takes pose k and the shorter of the two sets the count (a note says so).
TEST(Sequence, BackgroundFramesMatchedByTimeOrIndex)
{
  const std::string dir = Folder("match");
  const int w = 240, h = 190;
  for (int k = 0; k < 6; ++k)
  {
    catar::Frame f;
    f.width = w;
    f.height = h;
    f.rgba.assign(static_cast<std::size_t>(w) * h * 4, static_cast<unsigned char>(40 * k));
    catar::FrameWriter writer;
    std::string error;
    ASSERT_TRUE(writer.Open(dir + "/bg_%02d.png", w, h, 0.0, error)) << error;
    ASSERT_TRUE(writer.Write(k, f, error)) << error;
  }
  std::string error;
  const catar::Trajectory trajectory = SlidingCamera(3); // poses at 0, 0.3 and 0.6 s
  ASSERT_TRUE(catar::SaveTrajectory(dir + "/poses.txt", trajectory, "matrix", error)) << error;
  for (const std::string match : { "time", "index" })
  {
    std::string text = Scene(Pose(0, 0), "trajectory: poses.txt\n", "[ 70, 0, 20 ]");
    const std::string bg = "background: { type: color, color: [ 0.1, 0.1, 0.1 ] }";
    text.replace(text.find(bg), bg.size(),
      "background: { type: video, file: bg_%02d.png, fps: 10, start_time: 0.05, match: " + match +
        " }");
    Write(dir + "/scene.yaml", text);
    vtkNew<vtkCatadioptricSceneRenderer> r;
    r->SetSceneFileName((dir + "/scene.yaml").c_str());
    ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
    const bool byTime = match == "time";
    ASSERT_EQ(r->GetNumberOfFrames(), byTime ? 6 : 3);
    EXPECT_EQ(std::string(r->GetSequenceNote()).empty(), byTime) << r->GetSequenceNote();
    for (int k = 0; k < r->GetNumberOfFrames(); ++k)
    {
      ASSERT_TRUE(r->RenderFrame(k)) << r->GetLastError();
      const double t = byTime ? 0.05 + k / 10.0 : 0.3 * k;
      EXPECT_NEAR(r->GetFrameTime(k), t, 1e-12);
      const catar::Mat4 expected =
        byTime ? trajectory.PoseAt(t) : trajectory.poses[k].worldToCamera;
      double m[16];
      r->GetCamera()->GetWorldToCameraElements(m);
      for (int i = 0; i < 16; ++i)
      {
        EXPECT_NEAR(m[i], expected(i / 4, i % 4), 1e-15) << match << " frame " << k;
      }
      const auto* corner = static_cast<unsigned char*>(r->GetOutput()->GetScalarPointer(0, 0, 0));
      EXPECT_EQ(int(corner[0]), 40 * k) << "background frame " << k;
    }
  }
}

// The program: every frame of the range written, frame k the renderer's frame k; a video with
// the range's frame count.
TEST(Sequence, RenderProgramWritesEveryFrame)
{
  const std::string dir = Folder("program");
  std::string error;
  ASSERT_TRUE(catar::SaveTrajectory(dir + "/poses.tum", SlidingCamera(4), "tum", error)) << error;
  Write(dir + "/scene.yaml",
    Scene(catar::Mat4::Identity(), "trajectory: poses.tum\n", "[ 70, 0, 20 ]"));
  const std::string program = CATAR_RENDER_PROGRAM;
  const std::string command = "\"" + program + "\" \"" + dir + "/scene.yaml\" -o \"" + dir +
    "/frame_%02d.png\" --frames 1:4 > \"" + dir + "/log.txt\" 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/scene.yaml").c_str());
  ASSERT_TRUE(r->LoadScene());
  for (int k = 0; k < 4; ++k)
  {
    catar::FrameReader png;
    const std::string name = catar::FrameFileName(dir + "/frame_%02d.png", k);
    if (k == 0)
    {
      EXPECT_FALSE(std::ifstream(name).good()) << "frame 0 is not in 1:4";
      continue;
    }
    catar::Frame f;
    ASSERT_TRUE(png.Open(name, error)) << error;
    ASSERT_TRUE(png.Read(0, f, error)) << error;
    ASSERT_TRUE(r->RenderFrame(k));
    EXPECT_TRUE(f.rgba == vtkCatadioptricImageSupport::ToFrame(r->GetOutput()).rgba)
      << "frame " << k;
  }
  const std::string video = "\"" + program + "\" \"" + dir + "/scene.yaml\" -o \"" + dir +
    "/out.mp4\" --frames 0:3 --fps 12 > \"" + dir + "/log2.txt\" 2>&1";
  ASSERT_EQ(std::system(video.c_str()), 0) << video;
  catar::FrameReader back;
  ASSERT_TRUE(back.Open(dir + "/out.mp4", error)) << error;
  EXPECT_EQ(back.GetNumberOfFrames(), 3);
  EXPECT_NEAR(back.GetFrameRate(), 12.0, 1e-6);
  std::ifstream log(dir + "/log2.txt");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("frames: 3 (0 to 2)"), std::string::npos) << text;
  EXPECT_NE(text.find("encode"), std::string::npos) << text;
}

// The scene text refused by LoadScene with a sentence holding `expected`.
void ExpectRefused(const std::string& path, const std::string& text, const std::string& expected)
{
  Write(path, text);
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName(path.c_str());
  vtkObject::GlobalWarningDisplayOff(); // a global switch: on again below
  EXPECT_FALSE(r->LoadScene()) << text;
  vtkObject::GlobalWarningDisplayOn();
  EXPECT_NE(std::string(r->GetLastError()).find(expected), std::string::npos)
    << expected << ": " << r->GetLastError();
}

// The renderer names every file the loaded scene reads (what catadioptric-render compares its
// outputs with): the scene itself and its trajectory here; none before a load.
TEST(Sequence, TheRendererNamesItsInputFiles)
{
  const std::string dir = Folder("input-files");
  std::string error;
  ASSERT_TRUE(catar::SaveTrajectory(dir + "/poses.txt", SlidingCamera(3), "matrix", error))
    << error;
  Write(dir + "/scene.yaml", Scene(Pose(0, 0), "trajectory: poses.txt\n", "[ 70, 0, 20 ]"));
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((dir + "/scene.yaml").c_str());
  EXPECT_EQ(r->GetNumberOfInputFiles(), 0);
  EXPECT_EQ(r->GetInputFile(0), nullptr);
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  std::set<std::string> files;
  for (int i = 0; i < r->GetNumberOfInputFiles(); ++i)
  {
    files.insert(r->GetInputFile(i));
  }
  EXPECT_TRUE(files.count(dir + "/scene.yaml")) << files.size();
  EXPECT_TRUE(files.count(dir + "/poses.txt")) << files.size();
  EXPECT_EQ(r->GetInputFile(-1), nullptr);
  EXPECT_EQ(r->GetInputFile(r->GetNumberOfInputFiles()), nullptr);
}

// Bad sequence input ends in a sentence naming the key.
TEST(Sequence, BadSequencesAreRefusedWithASentence)
{
  const std::string dir = Folder("bad");
  Write(dir + "/bad.tum", "0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0\n");
  struct Case
  {
    std::string extra, expect;
  };
  const Case cases[] = { { "trajectory: missing.tum\n", "trajectory" },
    { "trajectory: bad.tum\n", "line 2" }, { "trajectory: [ 1, 2 ]\n", "'trajectory'" },
    { "sequence: { frames: 0 }\n", "sequence" }, { "sequence: { fps: -1 }\n", "sequence" },
    { "sequence: { frame: 3 }\n", "frame" } };
  for (const Case& c : cases)
  {
    ExpectRefused(dir + "/scene.yaml", Scene(Pose(0, 0), c.extra, "[ 70, 0, 20 ]"), c.expect);
  }
  const Case keyframes[] = {
    { ", keyframes: [ { time: 1 }, { time: 1 } ]", "keyframes[1]" },
    { ", keyframes: [ { time: 0, rotate: [ 1, 2 ] } ]", "rotate" },
    { ", keyframes: { time: 0 }", "sequence" },
    { ", keyframes: [ { time: 0, scale: 2 } ]", "scale" },
  };
  for (const Case& c : keyframes)
  {
    ExpectRefused(dir + "/scene.yaml", Scene(Pose(0, 0), "", "[ 70, 0, 20 ]", c.extra), c.expect);
  }
  std::string text = Scene(Pose(0, 0), "", "[ 70, 0, 20 ]");
  Write(dir + "/bg.avi", ""); // named below; found, so that the key after it is checked
  const std::string bg = "background: { type: color, color: [ 0.1, 0.1, 0.1 ] }";
  const Case backgrounds[] = { { "background: { type: video }", "needs 'file'" },
    { "background: { type: video, file: none_%03d.png, fps: 5 }", "no frames" },
    { "background: { type: video, file: x%q.png }", "'%'" },
    { "background: { type: video, file: bg.avi, match: pose }", "'match'" } };
  for (const Case& c : backgrounds)
  {
    std::string t = text;
    t.replace(t.find(bg), bg.size(), c.extra);
    ExpectRefused(dir + "/scene.yaml", t, c.expect);
  }
}

// The projection filter with a trajectory: the poses' times as TIME_STEPS; an update at a time
// takes the trajectory's pose there (between poses: PoseAt's interpolation), written to the
// output's field data; an unreadable trajectory is an error naming the property.
TEST(Sequence, ProjectionFollowsATrajectoryInTime)
{
  const std::string dir = Folder("filter");
  std::string error;
  const catar::Trajectory trajectory = SlidingCamera(3);
  ASSERT_TRUE(catar::SaveTrajectory(dir + "/poses.txt", trajectory, "matrix", error)) << error;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.0, -0.3, 0.95);
  sphere->SetRadius(0.03);
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputConnection(sphere->GetOutputPort());
  projection->SetCamera(catar_test::DemoCamera());
  projection->SetTrajectoryFileName((dir + "/poses.txt").c_str());
  projection->UpdateInformation();
  vtkInformation* info = projection->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 3);
  EXPECT_DOUBLE_EQ(info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[2], 0.6);
  for (double t : { 0.0, 0.3, 0.45, 0.6, 2.0 })
  {
    ASSERT_TRUE(projection->UpdateTimeStep(t));
    vtkNew<vtkCatadioptricCamera> used;
    ASSERT_TRUE(used->ReadFromFieldData(projection->GetOutput()->GetFieldData()));
    double m[16];
    used->GetWorldToCameraElements(m);
    const catar::Mat4 expected = trajectory.PoseAt(t);
    for (int i = 0; i < 16; ++i)
    {
      EXPECT_NEAR(m[i], expected(i / 4, i % 4), 1e-15) << "t " << t << " element " << i;
    }
  }
  // No trajectory: no time steps, the camera's own pose.
  projection->SetTrajectoryFileName(nullptr);
  projection->UpdateInformation();
  EXPECT_FALSE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  // An unreadable one.
  Write(dir + "/bad.txt", "0 1 2\n");
  projection->SetTrajectoryFileName((dir + "/bad.txt").c_str());
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(projection);
  EXPECT_FALSE(projection->UpdateTimeStep(0.0));
  EXPECT_GE(errors->Count, 1);
  EXPECT_NE(errors->Last.find("TrajectoryFileName"), std::string::npos) << errors->Last;
}

// A synthesised background is traced again only when the camera changes: not when only an object
// moves, nor when the camera is merely marked modified (as catadioptric-render --repeat does);
// after the camera moved, the frame is, byte for byte, what a fresh renderer makes at that frame.
// The per-frame time includes the background.
TEST(Sequence, EnvironmentBackgroundKeptUntilTheCameraMoves)
{
  const std::string dir = Folder("environment");
  catar::Trajectory t;
  t.poses = { { 0.0, Pose(0, 0) }, { 1.0, Pose(0, 0) }, { 2.0, Pose(0.02, 3) } };
  std::string error;
  ASSERT_TRUE(catar::SaveTrajectory(dir + "/poses.txt", t, "matrix", error)) << error;
  const std::string torusKeys = R"(, keyframes: [ { time: 0, rotate: [ 70, 0, 20 ] },
      { time: 1, translate: [ -0.1, -0.2, 1.0 ], rotate: [ 70, 0, 60 ] } ])";
  std::string text = Scene(Pose(0, 0), "trajectory: poses.txt\n", "[ 70, 0, 20 ]", torusKeys);
  const std::string color = "background: { type: color, color: [ 0.1, 0.1, 0.1 ] }";
  ASSERT_NE(text.find(color), std::string::npos);
  text.replace(text.find(color), color.size(), "background: { type: environment, samples: 1 }");
  const std::string path = dir + "/scene.yaml";
  Write(path, text);
  auto freshFrame = [&](int k) {
    vtkNew<vtkCatadioptricSceneRenderer> fresh;
    fresh->SetSceneFileName(path.c_str());
    EXPECT_TRUE(fresh->RenderFrame(k)) << fresh->GetLastError();
    return Bytes(fresh);
  };
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName(path.c_str());
  ASSERT_TRUE(r->LoadScene()) << r->GetLastError();
  ASSERT_EQ(r->GetNumberOfFrames(), 3);
  // The background's pixels: the compositor's frame input.
  auto background = [&]() {
    auto* image = vtkImageData::SafeDownCast(r->GetCompositor()->GetInputDataObject(0, 0));
    return image ? image->GetPointData()->GetScalars() : nullptr;
  };
  ASSERT_TRUE(r->RenderFrame(0)) << r->GetLastError();
  vtkDataArray* pixels = background();
  ASSERT_NE(pixels, nullptr);
  const vtkMTimeType traced = pixels->GetMTime();
  // The frame's time is its stages', the background's included.
  EXPECT_STREQ(r->GetStageName(r->GetFirstPerFrameStage()), "background");
  double stages = r->GetFramePoseTime();
  for (int s = r->GetFirstPerFrameStage(); s < r->GetNumberOfStages(); ++s)
  {
    stages += r->GetStageTime(s);
  }
  EXPECT_DOUBLE_EQ(r->GetFrameTime(), stages);
  EXPECT_GT(r->GetStageTime(r->GetFirstPerFrameStage()), 0.0);

  ASSERT_TRUE(r->RenderFrame(1)); // only the torus moved
  EXPECT_EQ(background(), pixels);
  EXPECT_EQ(pixels->GetMTime(), traced);
  const std::vector<unsigned char> frame1 = Bytes(r);
  EXPECT_EQ(frame1, freshFrame(1));

  r->GetCamera()->Modified(); // marked modified, unchanged: every per-frame stage runs again
  const vtkMTimeType projected = r->GetProjection(0)->GetOutput()->GetMTime();
  ASSERT_TRUE(r->Render());
  EXPECT_GT(r->GetProjection(0)->GetOutput()->GetMTime(), projected);
  EXPECT_EQ(background(), pixels);
  EXPECT_EQ(pixels->GetMTime(), traced);
  EXPECT_EQ(Bytes(r), frame1);

  ASSERT_TRUE(r->RenderFrame(2)); // the camera moved: traced again
  ASSERT_NE(background(), nullptr);
  EXPECT_GT(background()->GetMTime(), traced);
  const std::vector<unsigned char> frame2 = Bytes(r);
  EXPECT_GT(DifferingShare(frame2, frame1, 0), 0.1);
  EXPECT_EQ(frame2, freshFrame(2));
}
