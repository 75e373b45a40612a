// Per-frame cost of the demo scene with the STDThread SMP backend: each iteration moves nothing but
// marks the camera modified, so the background frame is synthesised again (background_ms) and
// projection, lighting, painter sort and compositing run again (per_frame_ms, the AR path). The
// compositor runs in painter order (/0, the paper's method) and with the depth buffer (/1, the
// scene key `visibility: depth`); composite_ms compares the two. Run:
//   build/bin/BenchmarkFrame [--benchmark_out=frame.csv --benchmark_out_format=csv]
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkNew.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace
{
void BM_DemoFrame(benchmark::State& state)
{
  vtkCatadioptricParallel::EnableThreads();
  const bool depth = state.range(0) != 0;
  state.SetLabel(depth ? "depth buffer" : "painter");
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  // The demo scene, with `visibility: depth` appended for the depth-buffer run.
  std::string sceneFile;
  if (depth)
  {
    sceneFile =
      (std::filesystem::temp_directory_path() / "catar_benchmark_frame_depth.yaml").string();
    std::ofstream out(sceneFile);
    out << vtkCatadioptricSceneRenderer::GetDemoSceneText() << "visibility: depth\n";
    if (!out)
    {
      state.SkipWithError("cannot write the depth-buffer scene file");
      return;
    }
    renderer->SetSceneFileName(sceneFile.c_str());
  }
  const bool loaded = renderer->Render();
  if (!sceneFile.empty())
  {
    std::remove(sceneFile.c_str()); // read by LoadScene, no longer needed
  }
  if (!loaded)
  {
    state.SkipWithError(renderer->GetLastError());
    return;
  }
  std::vector<double> stage(renderer->GetNumberOfStages(), 0.0);
  double frame = 0.0;
  for (auto _ : state)
  {
    renderer->GetCamera()->Modified(); // a new frame: per-frame stages run again
    renderer->Render();
    for (size_t s = 2; s < stage.size(); ++s)
    {
      stage[s] += renderer->GetStageTime(static_cast<int>(s));
    }
    frame += renderer->GetFrameTime();
  }
  const double n = static_cast<double>(state.iterations());
  for (size_t s = 2; s < stage.size(); ++s)
  {
    state.counters[std::string(renderer->GetStageName(static_cast<int>(s))) + "_ms"] =
      1e3 * stage[s] / n;
  }
  state.counters["triangles"] = static_cast<double>(renderer->GetNumberOfTriangles());
  const double perFrame = frame / n;
  state.counters["per_frame_ms"] = 1e3 * perFrame;
  state.counters["ar_fps"] = perFrame > 0 ? 1.0 / perFrame : 0.0;
}
BENCHMARK(BM_DemoFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
} // namespace

BENCHMARK_MAIN();
