// RobotRun: the paper's moving camera (its section 3.4: "each time a new image is received, the
// pose must be recomputed"). A camera on a robot's mast drives through the room past ArUco
// markers on the floor. First its footage is rendered from the true trajectory (the room and the
// markers, as a real camera would film them); then each frame's pose is estimated from the
// markers alone, and an object (the Stanford bunny, or a generated one) is placed on the floor
// and drawn into the footage with that pose, written as a video. Prints how far the estimated
// poses are from the true ones, the pose time per frame and the throughput.
//
//   RobotRun [--frames N] [--mesh FILE] [--out DIR] [--samples S]
//
// Writes DIR/footage_%03d.png (the camera's frames), DIR/trajectory.tum (the true poses),
// DIR/board.yaml (the markers), DIR/augmented.yaml (the scene of the second pass),
// DIR/robot-run.mp4 and DIR/strip.png (four frames side by side).
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkImageData.h"
#include "vtkNew.h"

#include "Trajectory.h"
#include "VideoIO.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
const double kPi = 3.14159265358979323846;
const int kWidth = 1328, kHeight = 1048;

const char* const kCamera = R"(camera:
  image_width: 1328
  image_height: 1048
  camera_matrix: [ 1000.0, 0.0, 663.5, 0.0, 1000.0, 523.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
)";

// The markers: 20 cm, on the floor around the path.
struct Marker
{
  int id;
  double x, y, turn;
};
const Marker kMarkers[] = { { 0, -0.45, -0.45, 0 }, { 1, 0.0, -0.55, 10 }, { 2, 0.45, -0.45, 20 },
  { 3, -0.5, -1.0, 30 }, { 4, 0.05, -1.05, 40 }, { 5, 0.55, -0.95, 50 }, { 6, -0.55, 0.05, 60 },
  { 7, 0.6, 0.1, 70 }, { 8, -0.1, -1.5, 80 }, { 9, 0.5, -1.5, 5 } };

// The robot's path over the run (s from 0 to 1): forward 40 cm along +y with a gentle weave,
// heading turning with the weave; the mast 1 m high, bobbing a centimetre. Camera-to-world.
Eigen::Matrix4d MastPose(double s)
{
  const double x = 0.12 * std::sin(2.0 * kPi * s);
  const double y = -0.3 + 0.4 * s;
  const double heading = 8.0 * std::cos(2.0 * kPi * s) * kPi / 180.0;
  const Eigen::Matrix3d look = (Eigen::Matrix3d() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) * look;
  m.topRightCorner<3, 1>() = Eigen::Vector3d(x, y, 1.0 + 0.01 * std::sin(6.0 * kPi * s));
  return m;
}

std::string MarkerObjects()
{
  std::ostringstream s;
  for (const Marker& m : kMarkers)
  {
    s << "  - { type: marker, id: " << m.id << ", size: 0.2, translate: [ " << m.x << ", " << m.y
      << ", 0.002 ], rotate: [ 0, 0, " << m.turn << " ] }\n";
  }
  return s.str();
}

std::string BoardText()
{
  std::ostringstream s;
  s << "dictionary: DICT_4X4_50\nmarkers:\n";
  for (const Marker& m : kMarkers)
  {
    s << "  - { id: " << m.id << ", size: 0.2, translate: [ " << m.x << ", " << m.y
      << ", 0.002 ], rotate: [ 0, 0, " << m.turn << " ] }\n";
  }
  return s.str();
}

// The object anchored on the floor: the mesh turned z up, about 45 cm tall, standing at
// (0.25, -0.25), or a
// generated torus standing on its rim.
std::string AnchoredObject(const std::string& mesh)
{
  std::ostringstream s;
  if (!mesh.empty())
  {
    // Stanford bunny: y up, metres, its feet at y = 0.033.
    s << "  - { type: mesh, file: \"" << mesh << "\", rotate: [ 90, 0, 150 ], scale: 3.0,\n"
      << "      translate: [ 0.25, -0.25, -0.099 ], color: [ 0.85, 0.8, 0.72 ] }\n";
  }
  else
  {
    s << "  - { type: torus, radius: 0.14, tube_radius: 0.05, resolution: 48,\n"
      << "      translate: [ 0.25, -0.25, 0.19 ], rotate: [ 90, 0, 30 ], color: [ 0.95, 0.55, "
         "0.1 ] }\n";
  }
  return s.str();
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}

double Seconds(std::chrono::steady_clock::time_point a)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

int Fail(const std::string& what)
{
  std::fprintf(stderr, "RobotRun: %s\n", what.c_str());
  return 1;
}
} // namespace

int main(int argc, char* argv[])
{
  int frames = 100;
  int samples = 2;
  std::string mesh, out = "robot-run";
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc)
    {
      frames = std::max(2, std::atoi(argv[++i]));
    }
    else if (a == "--samples" && i + 1 < argc)
    {
      samples = std::min(8, std::max(1, std::atoi(argv[++i])));
    }
    else if (a == "--mesh" && i + 1 < argc)
    {
      mesh = argv[++i];
    }
    else if (a == "--out" && i + 1 < argc)
    {
      out = argv[++i];
    }
    else
    {
      std::fprintf(
        stderr, "usage: RobotRun [--frames N] [--mesh FILE] [--out DIR] [--samples S]\n");
      return 2;
    }
  }
  if (!mesh.empty() && !std::ifstream(mesh).good())
  {
    std::printf("RobotRun: %s not found: a generated object instead\n", mesh.c_str());
    mesh.clear();
  }
  mkdir(out.c_str(), 0755);
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkCatadioptricParallel::EnableThreads();
  }

  // The true trajectory, 25 frames a second.
  catar::Trajectory truth;
  for (int k = 0; k < frames; ++k)
  {
    truth.poses.push_back({ k / 25.0, MastPose(k / double(frames - 1)).inverse() });
  }
  std::string error;
  if (!catar::SaveTrajectory(out + "/trajectory.tum", truth, "tum", error))
  {
    return Fail(error);
  }
  WriteText(out + "/board.yaml", BoardText());

  // 1. The footage: the room and the markers filmed along the true trajectory.
  std::ostringstream footage;
  footage << kCamera
          << "trajectory: trajectory.tum\nbackground: { type: environment, samples: " << samples
          << " }\nobjects:\n"
          << MarkerObjects();
  WriteText(out + "/footage.yaml", footage.str());
  auto start = std::chrono::steady_clock::now();
  {
    vtkNew<vtkCatadioptricSceneRenderer> r;
    r->SetSceneFileName((out + "/footage.yaml").c_str());
    catar::FrameWriter writer;
    if (!r->LoadScene() || !writer.Open(out + "/footage_%03d.png", kWidth, kHeight, 0.0, error))
    {
      return Fail(error.empty() ? r->GetLastError() : error);
    }
    for (int k = 0; k < frames; ++k)
    {
      if (!r->RenderFrame(k) ||
        !writer.Write(k, vtkCatadioptricImageSupport::ToFrame(r->GetOutput()), error))
      {
        return Fail(error.empty() ? r->GetLastError() : error);
      }
    }
  }
  std::printf("footage: %d frames of %dx%d in %.1f s\n", frames, kWidth, kHeight, Seconds(start));

  // 2. The same frames, each pose from its markers, the object anchored on the floor, lit.
  std::ostringstream augmented;
  augmented << kCamera << "background: { type: video, file: footage_%03d.png, fps: 25 }\n"
            << "markers: board.yaml\n"
            << "lighting:\n  shading: gouraud\n  global_ambient: [ 0.35, 0.35, 0.35 ]\n"
            << "  lights:\n    - { type: spot, position: [ 0.3, -0.6, 2.4 ], focal_point: [ 0.25, "
               "-0.25, 0.0 ], cone_angle: 40, color: [ 1.0, 0.97, 0.9 ] }\n"
            << "objects:\n"
            << AnchoredObject(mesh);
  WriteText(out + "/augmented.yaml", augmented.str());
  vtkNew<vtkCatadioptricSceneRenderer> r;
  r->SetSceneFileName((out + "/augmented.yaml").c_str());
  catar::FrameWriter video;
  if (!r->LoadScene() || !video.Open(out + "/robot-run.mp4", kWidth, kHeight, 25.0, error))
  {
    return Fail(error.empty() ? r->GetLastError() : error);
  }
  double worstMetres = 0.0, worstDegrees = 0.0, sumMetres = 0.0, poseTime = 0.0, worstPose = 0.0;
  const int stripFrames[4] = { 0, frames / 3, 2 * frames / 3, frames - 1 };
  std::vector<catar::Frame> strip;
  start = std::chrono::steady_clock::now();
  for (int k = 0; k < frames; ++k)
  {
    if (!r->RenderFrame(k))
    {
      return Fail(r->GetLastError());
    }
    const catar::Frame frame = vtkCatadioptricImageSupport::ToFrame(r->GetOutput());
    if (!video.Write(k, frame, error))
    {
      return Fail(error);
    }
    if (std::count(stripFrames, stripFrames + 4, k))
    {
      strip.push_back(frame);
    }
    poseTime += r->GetPoseTime();
    worstPose = std::max(worstPose, r->GetPoseTime());
    double m[16];
    r->GetCamera()->GetWorldToCameraElements(m);
    const Eigen::Matrix4d estimated = Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(m);
    const Eigen::Matrix4d& t = truth.poses[k].worldToCamera;
    const Eigen::Matrix3d R = estimated.topLeftCorner<3, 3>(), T = t.topLeftCorner<3, 3>();
    const double metres = ((-R.transpose() * estimated.topRightCorner<3, 1>()) -
      (-T.transpose() * t.topRightCorner<3, 1>()))
                            .norm();
    const double degrees = Eigen::AngleAxisd(R * T.transpose()).angle() * 180.0 / kPi;
    worstMetres = std::max(worstMetres, metres);
    worstDegrees = std::max(worstDegrees, degrees);
    sumMetres += metres;
  }
  video.Close();
  const double total = Seconds(start);
  std::printf("augmented: %d frames in %.1f s (%.1f frames a second with decoding, pose and "
              "encoding)\n",
    frames, total, frames / total);
  std::printf("pose from the markers: %.2f ms a frame (%.2f worst); %d frames without a pose\n",
    1e3 * poseTime / frames, 1e3 * worstPose, r->GetNumberOfPoseFailures());
  std::printf("against the true trajectory: camera centre %.2f mm mean, %.2f mm worst; "
              "rotation %.3f degrees worst\n",
    1e3 * sumMetres / frames, 1e3 * worstMetres, worstDegrees);

  // Four frames side by side, the mirror's square (800 pixels about the image centre) at half
  // size.
  const int side = 800, x0 = kWidth / 2 - side / 2, y0 = kHeight / 2 - side / 2;
  catar::Frame s;
  s.width = 2 * side;
  s.height = side / 2;
  s.rgba.assign(static_cast<std::size_t>(s.width) * s.height * 4, 255);
  for (std::size_t i = 0; i < strip.size(); ++i)
  {
    for (int y = 0; y < s.height; ++y)
    {
      for (int x = 0; x < side / 2; ++x)
      {
        for (int c = 0; c < 4; ++c)
        {
          int sum = 0;
          for (int d = 0; d < 4; ++d)
          {
            const int sx = x0 + 2 * x + d % 2, sy = y0 + 2 * y + d / 2;
            sum += strip[i].rgba[(static_cast<std::size_t>(sy) * kWidth + sx) * 4 + c];
          }
          s.rgba[(static_cast<std::size_t>(y) * s.width + i * (side / 2) + x) * 4 + c] =
            static_cast<std::uint8_t>(sum / 4);
        }
      }
    }
  }
  catar::FrameWriter stripWriter;
  if (!stripWriter.Open(out + "/strip_%d.png", s.width, s.height, 0.0, error) ||
    !stripWriter.Write(0, s, error))
  {
    return Fail(error);
  }
  std::printf("wrote %s/robot-run.mp4 and %s/strip_0.png\n", out.c_str(), out.c_str());
  // A pose that drifted off would show: fail the run (it runs as a test).
  return r->GetNumberOfPoseFailures() == 0 && worstMetres < 0.02 && worstDegrees < 1.0 ? 0 : 1;
}
