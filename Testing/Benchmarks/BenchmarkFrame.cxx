// Per-frame cost of the demo scene with the STDThread SMP backend: each iteration moves nothing but
// marks the camera modified, so the background frame is synthesised again (background_ms) and
// projection, painter sort and compositing run again (per_frame_ms, the AR path). Run:
//   build/bin/BenchmarkFrame [--benchmark_out=frame.csv --benchmark_out_format=csv]
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkNew.h"
#include "vtkSMPTools.h"

#include <benchmark/benchmark.h>

namespace
{
void BM_DemoFrame(benchmark::State& state)
{
  vtkSMPTools::SetBackend("STDThread");
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  if (!renderer->Render())
  {
    state.SkipWithError(renderer->GetLastError());
    return;
  }
  double stage[6] = { 0, 0, 0, 0, 0, 0 };
  for (auto _ : state)
  {
    renderer->GetCamera()->Modified(); // a new frame: per-frame stages run again
    renderer->Render();
    for (int s = 2; s < 6; ++s)
    {
      stage[s] += renderer->GetStageTime(s);
    }
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["background_ms"] = 1e3 * stage[2] / n;
  state.counters["projection_ms"] = 1e3 * stage[3] / n;
  state.counters["sort_ms"] = 1e3 * stage[4] / n;
  state.counters["composite_ms"] = 1e3 * stage[5] / n;
  state.counters["triangles"] = static_cast<double>(renderer->GetNumberOfTriangles());
  const double perFrame = (stage[3] + stage[4] + stage[5]) / n;
  state.counters["per_frame_ms"] = 1e3 * perFrame;
  state.counters["ar_fps"] = perFrame > 0 ? 1.0 / perFrame : 0.0;
}
BENCHMARK(BM_DemoFrame)->Unit(benchmark::kMillisecond)->UseRealTime();
} // namespace

BENCHMARK_MAIN();
