// catadioptric-render: renders a scene file (or the built-in demo) to a PNG and prints the time
// of each stage.
//
//   catadioptric-render [SCENE] [-o OUT.png] [--repeat N] [--target-area A | --pixel-tolerance P]
//                       [--print-demo-scene]
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkNew.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{
void Usage(FILE* out)
{
  std::fprintf(out,
    "usage: catadioptric-render [SCENE] [-o OUT.png] [--repeat N]\n"
    "                           [--target-area A | --pixel-tolerance P] [--print-demo-scene]\n"
    "\n"
    "Renders SCENE (YAML or JSON, see README \"Scene files\") to OUT.png (default\n"
    "catadioptric-render.png) and prints the time of each stage. Without SCENE it renders the\n"
    "built-in demo scene. --repeat N renders N frames and reports the per-frame stages of the\n"
    "last one. --target-area A remeshes every object to triangles of about A square metres;\n"
    "--pixel-tolerance P remeshes every object so that no visible edge bends more than P pixels\n"
    "in the image (both override the scene's 'remesh' settings). --print-demo-scene writes the\n"
    "demo scene's YAML to standard output.\n");
}
} // namespace

int main(int argc, char* argv[])
{
  std::string scene;
  std::string outName = "catadioptric-render.png";
  int repeat = 1;
  double targetArea = 0.0;
  double pixelTolerance = 0.0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help")
    {
      Usage(stdout);
      return 0;
    }
    if (arg == "--print-demo-scene")
    {
      std::fputs(vtkCatadioptricSceneRenderer::GetDemoSceneText(), stdout);
      return 0;
    }
    if (arg == "-o" && i + 1 < argc)
    {
      outName = argv[++i];
    }
    else if (arg == "--repeat" && i + 1 < argc)
    {
      repeat = std::atoi(argv[++i]);
      if (repeat < 1)
      {
        std::fprintf(stderr, "catadioptric-render: --repeat needs a positive number\n");
        return 2;
      }
    }
    else if ((arg == "--target-area" || arg == "--pixel-tolerance") && i + 1 < argc)
    {
      char* end = nullptr;
      const double value = std::strtod(argv[++i], &end);
      if (!end || *end != '\0' || !(value > 0.0) || !std::isfinite(value))
      {
        std::fprintf(stderr, "catadioptric-render: %s needs a positive number\n", arg.c_str());
        return 2;
      }
      (arg == "--target-area" ? targetArea : pixelTolerance) = value;
      if (targetArea > 0.0 && pixelTolerance > 0.0)
      {
        std::fprintf(
          stderr, "catadioptric-render: give --target-area or --pixel-tolerance, not both\n");
        return 2;
      }
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      std::fprintf(stderr, "catadioptric-render: unknown option %s\n", arg.c_str());
      Usage(stderr);
      return 2;
    }
    else if (scene.empty())
    {
      scene = arg;
    }
    else
    {
      std::fprintf(stderr, "catadioptric-render: more than one scene given\n");
      return 2;
    }
  }
  // Parallel loops: STDThread unless the environment chose a backend.
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkCatadioptricParallel::EnableThreads();
  }

  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(scene.empty() ? nullptr : scene.c_str());
  renderer->SetRemeshTargetArea(targetArea);
  renderer->SetRemeshPixelTolerance(pixelTolerance);
  for (int f = 0; f < repeat; ++f)
  {
    if (!renderer->Render())
    {
      std::fprintf(stderr, "catadioptric-render: %s\n", renderer->GetLastError());
      return 1;
    }
    if (f + 1 < repeat)
    {
      // Touch the camera so that the next frame redoes the per-frame stages.
      renderer->GetCamera()->Modified();
    }
  }
  if (renderer->GetNumberOfTriangles() == 0)
  {
    std::fprintf(stderr,
      "catadioptric-render: warning: nothing to draw: the scene has no objects with triangles "
      "(is 'objects' spelt right?); the image is the background alone\n");
  }
  if (!renderer->WritePNG(outName.c_str()))
  {
    std::fprintf(stderr, "catadioptric-render: %s\n", renderer->GetLastError());
    return 1;
  }
  vtkCatadioptricCamera* cam = renderer->GetCamera();
  std::printf("scene: %s\n", scene.empty() ? "(built-in demo)" : scene.c_str());
  std::printf("image: %d x %d, %lld triangles, SMP backend %s (%d threads)\n", cam->GetImageWidth(),
    cam->GetImageHeight(), static_cast<long long>(renderer->GetNumberOfTriangles()),
    vtkSMPTools::GetBackend(), vtkSMPTools::GetEstimatedNumberOfThreads());
  if (*renderer->GetMeshReport())
  {
    std::printf("remeshed:\n%s", renderer->GetMeshReport());
  }
  for (int s = 0; s < renderer->GetNumberOfStages(); ++s)
  {
    std::printf("  %-11s %9.2f ms\n", renderer->GetStageName(s), 1e3 * renderer->GetStageTime(s));
  }
  std::printf("  per frame   %9.2f ms (projection + lighting + sort + composite)\n",
    1e3 * renderer->GetFrameTime());
  std::printf("wrote %s\n", outName.c_str());
  return 0;
}
