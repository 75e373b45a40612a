// The per-frame path the speed benchmarks time: projection -> lighting -> painter sort ->
// compositing onto a fixed camera frame, with spotlights that move every frame. Each stage is
// updated on its own so that its time can be read; the camera is marked modified every frame so
// that projection runs again (the full path, as when the object or the camera moves).
#ifndef catarFramePipeline_h
#define catarFramePipeline_h

#include "Csv.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricEnvironmentSource.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h> // malloc_trim
#endif

namespace catar_benchmark
{
using Clock = std::chrono::steady_clock;

inline double Ms(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// Resident memory of this process in MiB (Linux /proc/self/statm; 0 elsewhere), after the C
/// library has given its free heap memory back (glibc's malloc_trim), so that what is counted is
/// what is in use rather than where the allocator last left its arenas.
inline double ResidentMiB()
{
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096.0 / (1024.0 * 1024.0);
}

/// Median of a copy of `v` (0 when empty).
inline double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

using catar::CsvField;

/// The synthetic camera frame the objects are composited onto (the procedural room seen in the
/// mirror), made once.
inline vtkSmartPointer<vtkImageData> CameraFrame(vtkCatadioptricCamera* camera)
{
  vtkNew<vtkCatadioptricEnvironmentSource> env;
  env->SetCamera(camera);
  env->SetSamples(1);
  env->Update();
  vtkSmartPointer<vtkImageData> frame = vtkSmartPointer<vtkImageData>::New();
  frame->DeepCopy(env->GetOutput());
  return frame;
}

struct FrameOptions
{
  int solver = vtkCatadioptricProjection::QUARTIC;
  int shading = vtkCatadioptricLighting::GOURAUD;
  int lights = 1;
  bool shadows = false;
  int visibility = vtkCatadioptricCompositor::PAINTER;
  bool cullBackFaces = false;
  int antialias = 0;     ///< samples per edge pixel side (0: off)
  double adaptive = 0.0; ///< per-frame adaptive tessellation, pixels (0: off)
};

/// Times of one frame's stages in milliseconds.
struct StageTimes
{
  static constexpr int N = 4;
  std::array<double, N> ms{};
  double Total() const { return ms[0] + ms[1] + ms[2] + ms[3]; }
  static const char* Name(int i)
  {
    static const char* const names[N] = { "projection", "lighting", "sort", "composite" };
    return names[i];
  }
};

class FramePipeline
{
public:
  FramePipeline(vtkPolyData* mesh, vtkCatadioptricCamera* camera, vtkImageData* frame,
    const FrameOptions& options)
    : Camera(camera)
  {
    this->Projection->SetInputData(mesh);
    this->Projection->SetCamera(camera);
    this->Projection->SetSolver(options.solver);
    this->Projection->SetBackFaceCulling(options.cullBackFaces);
    this->Projection->SetAdaptiveTolerance(options.adaptive);
    this->Lighting->SetInputConnection(this->Projection->GetOutputPort());
    this->Lighting->SetShadingMode(options.shading);
    this->Lighting->SetShadows(options.shadows);
    this->Lighting->SetSpecular(0.3);
    this->Lighting->SetDiffuseColor(0.9, 0.85, 0.75);
    const double colors[3][3] = { { 1, 0.9, 0.8 }, { 0.5, 0.7, 1 }, { 1, 0.5, 0.5 } };
    for (int k = 0; k < options.lights; ++k)
    {
      this->Lighting->AddSpotLight(
        0, 0, 1.3, 0.0, -0.25, 0.9, 40, colors[k % 3][0], colors[k % 3][1], colors[k % 3][2]);
    }
    this->Sort->SetInputConnection(this->Lighting->GetOutputPort());
    this->Sort->DropInvisibleCellsOn();
    this->Compositor->SetFrameData(frame);
    this->Compositor->AddMeshConnection(this->Sort->GetOutputPort());
    this->Compositor->SetVisibility(options.visibility);
    this->Compositor->SetAntialias(options.antialias > 1);
    this->Compositor->SetAntialiasSamples(std::max(2, options.antialias));
    this->Compositor->SetColorArrayName("Colors");
    this->MoveLights(0);
  }

  /// Moves the spotlights to their places for frame `f`: each circles above the object once
  /// every 120 frames, a third of a turn apart.
  void MoveLights(int f)
  {
    vtkLightCollection* lights = this->Lighting->GetLights();
    const int n = lights->GetNumberOfItems();
    for (int k = 0; k < n; ++k)
    {
      auto* light = vtkLight::SafeDownCast(lights->GetItemAsObject(k));
      const double a = 2.0 * 3.14159265358979 * (f / 120.0 + k / 3.0);
      light->SetPosition(0.35 * std::cos(a), -0.25 + 0.35 * std::sin(a), 1.3);
    }
    this->Lighting->Modified();
  }

  /// Renders frame `f` and returns the time of each stage.
  StageTimes Frame(int f)
  {
    this->MoveLights(f);
    this->Camera->Modified(); // projection runs again, as when anything moves
    StageTimes t;
    auto t0 = Clock::now();
    this->Projection->Update();
    auto t1 = Clock::now();
    this->Lighting->Update();
    auto t2 = Clock::now();
    this->Sort->Update();
    auto t3 = Clock::now();
    this->Compositor->Update();
    auto t4 = Clock::now();
    t.ms = { Ms(t0, t1), Ms(t1, t2), Ms(t2, t3), Ms(t3, t4) };
    return t;
  }

  vtkImageData* GetOutput() { return this->Compositor->GetOutput(); }
  vtkCatadioptricCompositor* GetCompositor() { return this->Compositor; }
  vtkCatadioptricLighting* GetLighting() { return this->Lighting; }
  vtkCatadioptricProjection* GetProjection() { return this->Projection; }

private:
  vtkCatadioptricCamera* Camera;
  vtkNew<vtkCatadioptricProjection> Projection;
  vtkNew<vtkCatadioptricLighting> Lighting;
  vtkNew<vtkCatadioptricPainterSort> Sort;
  vtkNew<vtkCatadioptricCompositor> Compositor;
};

/// Median stage times over `frames` frames (after one warm-up frame), or over as many as fit in
/// `maxSeconds` (at least 5) when the frames are slow; `measured` (optional) receives the count.
inline StageTimes MedianFrame(FramePipeline& pipeline, int frames, double* medianTotal,
  double maxSeconds = 1e300, int* measured = nullptr)
{
  const auto start = Clock::now();
  pipeline.Frame(0);
  std::array<std::vector<double>, StageTimes::N> stages;
  std::vector<double> totals;
  for (int f = 1; f <= frames; ++f)
  {
    const StageTimes t = pipeline.Frame(f);
    for (int s = 0; s < StageTimes::N; ++s)
    {
      stages[s].push_back(t.ms[s]);
    }
    totals.push_back(t.Total());
    if (f >= 5 && Ms(start, Clock::now()) > 1e3 * maxSeconds)
    {
      break;
    }
  }
  StageTimes m;
  for (int s = 0; s < StageTimes::N; ++s)
  {
    m.ms[s] = Median(stages[s]);
  }
  *medianTotal = Median(totals);
  if (measured)
  {
    *measured = static_cast<int>(totals.size());
  }
  return m;
}
} // namespace catar_benchmark

#endif
