// The scene renderer against the bare per-frame pipeline, on the same bunny: BenchmarkSpeed's
// bunny row ("1 spot, gouraud, painter, iterative": FramePipeline.h) and the same setup as a
// scene file (Testing/Benchmarks/bunny-speed.yaml) through vtkCatadioptricSceneRenderer, as
// `catadioptric-render --repeat` renders it, frame by frame in turn in one process (this machine's
// speed drifts over minutes: alternating frames compares the two under the same load). Every
// frame, both redo every per-frame stage (the camera marked modified, the spotlight set again);
// the scene's frame counts every stage, the background included. Prints the median of each stage
// and of the frame for both, their ratio, and how far the two images are apart. Run:
//   CATAR_SHARED_DATA=../shared/data build/bin/BenchmarkSceneFile [--frames N] [--scene FILE]
// (CATAR_DATA_PATH, where the scene finds stanford-bunny.obj, defaults to CATAR_SHARED_DATA.)
// Without the shared bunny it says so and stops (exit 0).
#include "BenchmarkScene.h"
#include "FramePipeline.h"

#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkPointData.h"

#include <cstdlib>
#include <cstring>

namespace
{
using namespace catar_benchmark;

struct Row
{
  std::vector<double> background, projection, lighting, sort, composite, frame;
  void Print(const char* name) const
  {
    const double ms = Median(this->frame);
    char background[32] = "(made once)";
    if (!this->background.empty())
    {
      std::snprintf(background, sizeof(background), "%.2f", Median(this->background));
    }
    std::printf("| %s | %zu | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f |\n", name,
      this->frame.size(), background, Median(this->projection), Median(this->lighting),
      Median(this->sort), Median(this->composite), ms, ms > 0 ? 1e3 / ms : 0.0);
  }
};
} // namespace

int main(int argc, char* argv[])
{
  vtkCatadioptricParallel::EnableThreads();
  int frames = 200;
  std::string scene = std::string(CATAR_SOURCE_DIR) + "/Testing/Benchmarks/bunny-speed.yaml";
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--scene") && i + 1 < argc)
    {
      scene = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      frames = 3;
    }
    else
    {
      std::fprintf(stderr, "usage: BenchmarkSceneFile [--frames N] [--scene FILE] [--quick]\n");
      return 2;
    }
  }
  vtkSmartPointer<vtkPolyData> bunny = SharedBunny();
  if (!bunny)
  {
    std::printf("BenchmarkSceneFile: no stanford-bunny.obj in CATAR_SHARED_DATA: nothing to "
                "compare\n");
    return 0;
  }
  if (!std::getenv("CATAR_DATA_PATH"))
  {
    setenv("CATAR_DATA_PATH", std::getenv("CATAR_SHARED_DATA"), 1);
  }

  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(scene.c_str());
  if (!renderer->Render())
  {
    std::fprintf(stderr, "BenchmarkSceneFile: %s\n", renderer->GetLastError());
    return 1;
  }
  vtkNew<vtkCatadioptricCamera> camera;
  DemoCamera(camera);
  FrameOptions options;
  options.solver = vtkCatadioptricProjection::ITERATIVE;
  FramePipeline pipeline(bunny, camera, CameraFrame(camera), options);
  pipeline.Frame(0); // warm-up; the spotlight where the scene has it (frame 0's place)

  Row direct, file;
  const int first = renderer->GetFirstPerFrameStage(); // background, then projection .. composite
  for (int f = 0; f < frames; ++f)
  {
    const StageTimes t = pipeline.Frame(0);
    direct.projection.push_back(t.ms[0]);
    direct.lighting.push_back(t.ms[1]);
    direct.sort.push_back(t.ms[2]);
    direct.composite.push_back(t.ms[3]);
    direct.frame.push_back(t.Total());

    renderer->GetCamera()->Modified(); // as catadioptric-render --repeat
    if (!renderer->Render())
    {
      std::fprintf(stderr, "BenchmarkSceneFile: %s\n", renderer->GetLastError());
      return 1;
    }
    std::vector<double>* stages[] = { &file.background, &file.projection, &file.lighting,
      &file.sort, &file.composite };
    for (int s = 0; s < 5; ++s)
    {
      stages[s]->push_back(1e3 * renderer->GetStageTime(first + s));
    }
    file.frame.push_back(1e3 * renderer->GetFrameTime());
  }

  std::printf("The bunny (%lld triangles, 1328x1048, 1 spot, gouraud, painter, iterative), frames "
              "in turn, median of %d (ms):\n\n",
    static_cast<long long>(bunny->GetNumberOfPolys()), frames);
  std::printf("| path | frames | background | projection | lighting | sort | composite | frame | "
              "fps |\n|---|---|---|---|---|---|---|---|---|\n");
  direct.Print("FramePipeline (BenchmarkSpeed)");
  file.Print("scene file (catadioptric-render --repeat)");
  const double ratio = Median(file.frame) / Median(direct.frame);
  std::printf("\nscene file / FramePipeline: %.3f (%+.1f %%)\n", ratio, 100.0 * (ratio - 1.0));

  // The two pictures: the same scene, the bunny placed by equal transforms written differently.
  vtkDataArray* a = pipeline.GetOutput()->GetPointData()->GetScalars();
  vtkDataArray* b = renderer->GetOutput()->GetPointData()->GetScalars();
  if (a && b && a->GetNumberOfValues() == b->GetNumberOfValues())
  {
    long long differ = 0;
    int largest = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      int d = 0;
      for (int c = 0; c < 4; ++c)
      {
        d = std::max(d, static_cast<int>(std::abs(a->GetComponent(i, c) - b->GetComponent(i, c))));
      }
      differ += d > 0;
      largest = std::max(largest, d);
    }
    std::printf("images: %lld of %lld pixels differ, by at most %d levels\n", differ,
      static_cast<long long>(a->GetNumberOfTuples()), largest);
  }
  return 0;
}
