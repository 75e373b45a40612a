// SpotlightSequence: the paper's moving-spotlight experiment (its figure 9). A spotlight circles
// above an object seen in the spherical mirror; every frame is written as PNG and, optionally,
// into a video through OpenCV.
//
//   SpotlightSequence [--mesh FILE] [--frames N] [--size W H] [--shading flat|gouraud]
//                     [--shadows 0|1] [--prefix OUT/frame] [--video OUT.avi]
//
// Without --mesh the object is the paper's parallelepiped (a box of 30 x 12 x 9 cm). With a
// Stanford mesh (e.g. ../shared/data/stanford-bunny.obj, y up, metres) the mesh is turned z up
// and scaled to about 20 cm. The paper's rows: box and bunny flat without shadows; buddha and
// dragon Gouraud with shadows.
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"

#include <vtksys/SystemTools.hxx>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
std::string SceneText(
  const std::string& mesh, int w, int h, const std::string& shading, bool shadows)
{
  std::ostringstream s;
  s << "---\n"
    << "camera:\n"
    << "  image_width: 1328\n  image_height: 1048\n"
    << "  camera_matrix: [ 1000.0, 0.0, 663.5, 0.0, 1000.0, 523.5, 0.0, 0.0, 1.0 ]\n"
    << "  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }\n"
    << "  world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1.0,  0, 1, 0, 0.14,  0, 0, 0, 1 ]\n"
    << "output: { width: " << w << ", height: " << h << " }\n"
    << "background: { type: environment, samples: 1 }\n"
    << "lighting:\n  shading: " << shading << "\n  shadows: " << (shadows ? 1 : 0) << "\n"
    << "  global_ambient: [ 0.25, 0.25, 0.25 ]\n"
    << "  lights:\n    - { type: spot, position: [ 0.0, 0.0, 1.4 ], focal_point: [ 0.0, -0.25, "
       "0.9 ], cone_angle: 35, exponent: 1, color: [ 1.0, 1.0, 1.0 ] }\n"
    << "objects:\n";
  if (mesh.empty())
  {
    s << "  - { type: box, size: [ 0.30, 0.12, 0.09 ], resolution: 24, translate: [ 0.0, -0.25, "
         "0.9 ], rotate: [ 0, 0, 20 ], color: [ 0.75, 0.75, 0.78 ], face_colors: 0,\n"
      << "      material: { ambient: 0.3, diffuse: 0.8, specular: 0.5, specular_power: 30 } }\n";
  }
  else
  {
    // Stanford meshes: y up, ~0.15-0.2 m; turn z up and make them ~0.2 m.
    s << "  - { type: mesh, file: \"" << mesh << "\", rotate: [ 90, 0, 0 ], scale: 1.2,\n"
      << "      translate: [ 0.0, -0.25, 0.75 ], color: [ 0.75, 0.75, 0.78 ],\n"
      << "      material: { ambient: 0.3, diffuse: 0.8, specular: 0.5, specular_power: 30 } }\n";
  }
  return s.str();
}
} // namespace

int main(int argc, char* argv[])
{
  std::string mesh, shading = "flat", prefix = "spotlight", video;
  int frames = 30, w = 664, h = 524;
  bool shadows = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--mesh" && i + 1 < argc)
      mesh = argv[++i];
    else if (a == "--frames" && i + 1 < argc)
      frames = std::atoi(argv[++i]);
    else if (a == "--size" && i + 2 < argc)
    {
      w = std::atoi(argv[++i]);
      h = std::atoi(argv[++i]);
    }
    else if (a == "--shading" && i + 1 < argc)
      shading = argv[++i];
    else if (a == "--shadows" && i + 1 < argc)
      shadows = std::atoi(argv[++i]) != 0;
    else if (a == "--prefix" && i + 1 < argc)
      prefix = argv[++i];
    else if (a == "--video" && i + 1 < argc)
      video = argv[++i];
    else
    {
      std::fprintf(stderr,
        "usage: %s [--mesh FILE] [--frames N] [--size W H] [--shading flat|gouraud] "
        "[--shadows 0|1] [--prefix OUT/frame] [--video OUT.avi]\n",
        argv[0]);
      return 2;
    }
  }
  if (frames < 1 || w < 16 || h < 16)
  {
    std::fprintf(stderr, "frames must be positive and the size at least 16x16\n");
    return 2;
  }
  vtkCatadioptricParallel::EnableThreads();
  const std::string scenePath = prefix + "-scene.yaml";
  // The scene file sits beside the frames: a mesh named relative to the working folder is named
  // by its full path there.
  const std::string meshPath = mesh.empty() ? mesh : vtksys::SystemTools::CollapseFullPath(mesh);
  std::ofstream(scenePath) << SceneText(meshPath, w, h, shading, shadows);
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(scenePath.c_str());
  if (!renderer->LoadScene())
  {
    std::fprintf(stderr, "%s\n", renderer->GetLastError());
    return 1;
  }
  vtkLight* spot = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  cv::VideoWriter writer;
  if (!video.empty() &&
    !writer.open(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25.0, cv::Size(w, h)))
  {
    std::fprintf(stderr, "cannot open the video %s\n", video.c_str());
    return 1;
  }
  double total = 0.0;
  for (int f = 0; f < frames; ++f)
  {
    // The spotlight circles 35 cm above the object, always aimed at it.
    const double a = 2.0 * M_PI * f / frames;
    spot->SetPosition(0.3 * std::cos(a), -0.25 + 0.3 * std::sin(a), 1.25);
    if (!renderer->Render())
    {
      std::fprintf(stderr, "%s\n", renderer->GetLastError());
      return 1;
    }
    total += renderer->GetFrameTime();
    char name[512];
    std::snprintf(name, sizeof(name), "%s_%03d.png", prefix.c_str(), f);
    if (!renderer->WritePNG(name))
    {
      return 1;
    }
    if (writer.isOpened())
    {
      vtkImageData* img = renderer->GetOutput();
      // VTK rows go bottom-up; OpenCV's top-down, in BGR.
      cv::Mat rgba(h, w, CV_8UC4, img->GetScalarPointer());
      cv::Mat flipped, bgr;
      cv::flip(rgba, flipped, 0);
      cv::cvtColor(flipped, bgr, cv::COLOR_RGBA2BGR);
      writer.write(bgr);
    }
  }
  std::printf("%d frames (%s, %s), %lld triangles: %.2f ms per frame for background + "
              "projection + lighting + sort + composite; frames %s_000.png ...%s%s\n",
    frames, shading.c_str(), shadows ? "shadows" : "no shadows",
    static_cast<long long>(renderer->GetNumberOfTriangles()), 1e3 * total / frames, prefix.c_str(),
    video.empty() ? "" : ", video ", video.c_str());
  return 0;
}
