// Lighting stage cost on a ~70k-triangle object: flat and Gouraud, 1 and 3 spotlights, shadows
// on and off (STDThread backend). The object is the Stanford bunny (69,451 triangles) when
// CATAR_SHARED_DATA names a folder holding stanford-bunny.obj, otherwise a sphere of 70,224
// triangles. Run:
//   CATAR_SHARED_DATA=../shared/data build/bin/BenchmarkLighting
//     [--benchmark_out=lighting.csv --benchmark_out_format=csv]
#include "BenchmarkScene.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricProjection.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <benchmark/benchmark.h>

#include <string>

namespace
{
using catar_benchmark::DemoCamera;

void BM_Lighting(benchmark::State& state)
{
  vtkCatadioptricParallel::EnableThreads();
  const int mode = static_cast<int>(state.range(0));
  const int nLights = static_cast<int>(state.range(1));
  const bool shadows = state.range(2) != 0;
  std::string name;
  vtkSmartPointer<vtkPolyData> mesh = catar_benchmark::BunnyOrSphere(name);
  vtkNew<vtkCatadioptricCamera> cam;
  DemoCamera(cam);
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputData(mesh);
  proj->Update();
  vtkNew<vtkCatadioptricLighting> lighting;
  lighting->SetInputConnection(proj->GetOutputPort());
  const double colors[3][3] = { { 1, 0.3, 0.3 }, { 0.3, 1, 0.3 }, { 0.3, 0.3, 1 } };
  for (int k = 0; k < nLights; ++k)
  {
    lighting->AddSpotLight(
      0.2 * (k - 1), 0.0, 1.3, 0.0, -0.25, 0.9, 35, colors[k][0], colors[k][1], colors[k][2]);
  }
  lighting->SetShadingMode(mode);
  lighting->SetShadows(shadows);
  lighting->SetSpecular(0.4);
  lighting->Update(); // builds the shadow ray scene once (kept while the mesh does not change)
  for (auto _ : state)
  {
    lighting->Modified();
    lighting->Update();
  }
  state.SetLabel(name + (mode == vtkCatadioptricLighting::FLAT ? " flat" : " gouraud") + ", " +
    std::to_string(nLights) + (nLights == 1 ? " light" : " lights") +
    (shadows ? ", shadows" : ", no shadows"));
  state.counters["triangles"] = static_cast<double>(mesh->GetNumberOfPolys());
}
BENCHMARK(BM_Lighting)
  ->ArgsProduct(
    { { vtkCatadioptricLighting::FLAT, vtkCatadioptricLighting::GOURAUD }, { 1, 3 }, { 0, 1 } })
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();
} // namespace

BENCHMARK_MAIN();
