// Lighting stage cost on a ~70k-triangle object: flat and Gouraud, 1 and 3 spotlights, shadows
// on and off (STDThread backend). The object is the Stanford bunny (69,451 triangles) when
// CATAR_SHARED_DATA names a folder holding stanford-bunny.obj, otherwise a sphere of 70,224
// triangles. Run:
//   CATAR_SHARED_DATA=../shared/data build/bin/BenchmarkLighting
//     [--benchmark_out=lighting.csv --benchmark_out_format=csv]
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricProjection.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtksys/SystemTools.hxx"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

namespace
{
// The demo camera: at world (0, -0.14, 1), looking along +y at a 5 cm mirror 14 cm away.
void DemoCamera(vtkCatadioptricCamera* cam)
{
  cam->SetImageWidth(1328);
  cam->SetImageHeight(1048);
  cam->SetFocalLength(1000, 1000);
  cam->SetPrincipalPoint(663.5, 523.5);
  cam->SetMirrorCenter(0, 0, 0.14);
  cam->SetMirrorRadius(0.05);
  const double pose[16] = { 1, 0, 0, 0, 0, 0, -1, 1.0, 0, 1, 0, 0.14, 0, 0, 0, 1 };
  cam->SetWorldToCameraElements(pose);
}

// The object, placed 25 cm behind the camera, about 15 cm across; name is set to its origin.
vtkSmartPointer<vtkPolyData> Object(std::string& name)
{
  vtkSmartPointer<vtkPolyData> mesh;
  const char* shared = std::getenv("CATAR_SHARED_DATA");
  const std::string bunny = shared ? std::string(shared) + "/stanford-bunny.obj" : "";
  vtkNew<vtkTransform> place;
  place->PostMultiply();
  if (!bunny.empty() && vtksys::SystemTools::FileExists(bunny, true))
  {
    vtkNew<vtkOBJReader> reader;
    reader->SetFileName(bunny.c_str());
    reader->Update();
    mesh = reader->GetOutput();
    name = "bunny";
    place->Translate(0.017, -0.11, -0.0016); // bounding-box centre to the origin
    place->RotateX(90);                      // y up -> z up
  }
  else
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(0.075);
    sphere->SetThetaResolution(264);
    sphere->SetPhiResolution(134);
    sphere->Update();
    mesh = sphere->GetOutput();
    name = "sphere";
  }
  place->Translate(0.0, -0.25, 0.9);
  vtkNew<vtkTransformPolyDataFilter> xf;
  xf->SetTransform(place);
  xf->SetInputData(mesh);
  xf->Update();
  return xf->GetOutput();
}

void BM_Lighting(benchmark::State& state)
{
  vtkSMPTools::SetBackend("STDThread");
  const int mode = static_cast<int>(state.range(0));
  const int nLights = static_cast<int>(state.range(1));
  const bool shadows = state.range(2) != 0;
  std::string name;
  vtkSmartPointer<vtkPolyData> mesh = Object(name);
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
    lighting->AddSpotLight(0.2 * (k - 1), 0.0, 1.3, 0.0, -0.25, 0.9, 35, colors[k][0],
      colors[k][1], colors[k][2]);
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
  ->ArgsProduct({ { vtkCatadioptricLighting::FLAT, vtkCatadioptricLighting::GOURAUD }, { 1, 3 },
    { 0, 1 } })
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();
} // namespace

BENCHMARK_MAIN();
