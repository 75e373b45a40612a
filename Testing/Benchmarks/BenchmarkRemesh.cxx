// The speed/size trade of mesh preparation: for each target triangle area (and each pixel
// tolerance), the triangle count, the remesh time, the achieved largest edge bend in pixels, and
// the per-frame time of projection + painter sort + compositing (median of --frames frames) at
// the demo camera's 1328 x 1048. Objects: the paper's parallelepiped (30 x 12 x 9 cm) and, when
// CATAR_SHARED_DATA names a folder holding stanford-bunny.obj, the Stanford bunny.
//
//   CATAR_SHARED_DATA=../shared/data build/bin/BenchmarkRemesh [--frames N] [--quick]
//     [--csv remesh.csv]
//
// --quick (CI smoke) runs one target per object and 2 frames.
#include "BenchmarkScene.h"
#include "EdgeBend.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;
double Ms(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

using catar_benchmark::DemoCamera;

// Largest edge bend (pixels) over the mesh's visible edges.
double MaximumBend(vtkPolyData* mesh, const catar::Projector& projector)
{
  std::set<std::pair<vtkIdType, vtkIdType>> edges;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      const vtkIdType a = ids->GetId(k), b = ids->GetId((k + 1) % ids->GetNumberOfIds());
      edges.insert({ std::min(a, b), std::max(a, b) });
    }
  }
  double worst = 0.0;
  for (const auto& e : edges)
  {
    catar::Vec3 a, b;
    mesh->GetPoint(e.first, a.data());
    mesh->GetPoint(e.second, b.data());
    worst = std::max(worst, catar::EdgeBendPixels(projector, a, b));
  }
  return worst;
}

// Median per-frame time (ms) of projection + sort + compositing.
double FrameTime(vtkPolyData* mesh, vtkCatadioptricCamera* camera, int frames)
{
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputData(mesh);
  projection->SetCamera(camera);
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(projection->GetOutputPort());
  sort->DropInvisibleCellsOn();
  vtkNew<vtkCatadioptricCompositor> compositor;
  compositor->AddMeshConnection(sort->GetOutputPort());
  compositor->Update(); // warm up: allocations
  std::vector<double> times;
  for (int f = 0; f < frames; ++f)
  {
    camera->Modified();
    const auto t0 = Clock::now();
    compositor->Update();
    times.push_back(Ms(t0, Clock::now()));
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2];
}

struct Row
{
  std::string object, mode;
  double parameter;
  vtkIdType triangles;
  double meanArea, remeshMs, bend, frameMs;
  double boundMm = 0.0; ///< pixel mode: the geometric error bound used, mm
};
} // namespace

int main(int argc, char* argv[])
{
  int frames = 20;
  bool quick = false;
  std::string csv;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else
    {
      std::fprintf(stderr, "usage: BenchmarkRemesh [--frames N] [--quick] [--csv FILE]\n");
      return 2;
    }
  }
  if (quick)
  {
    frames = 2;
  }
  vtkCatadioptricParallel::EnableThreads();
  // The bunny's repairs (unused points, open holes) would repeat on every row.
  vtkObject::GlobalWarningDisplayOff();
  vtkNew<vtkCatadioptricCamera> camera;
  DemoCamera(camera);
  const catar::Projector projector(camera->GetModel());

  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> objects;
  objects.emplace_back("box", catar_benchmark::PaperBox());
  if (vtkSmartPointer<vtkPolyData> bunny = catar_benchmark::SharedBunny())
  {
    objects.emplace_back("bunny", bunny);
  }
  else
  {
    std::printf("(no CATAR_SHARED_DATA/stanford-bunny.obj: box only)\n");
  }
  const std::vector<double> areas =
    quick ? std::vector<double>{ 4e-5 } : std::vector<double>{ 1e-4, 4e-5, 1.2e-5, 4e-6, 1e-6 };
  const std::vector<double> tolerances =
    quick ? std::vector<double>{ 1.0 } : std::vector<double>{ 2.0, 1.0, 0.5, 0.25 };

  std::vector<Row> rows;
  std::printf(
    "| object | mode | target | triangles | mean area (m^2) | remesh (ms) | max bend (px) "
    "| geometric bound (mm) | frame (ms) |\n|---|---|---|---|---|---|---|---|---|\n");
  auto print = [](const Row& r) {
    const std::string bound = r.boundMm > 0.0 ? std::to_string(r.boundMm).substr(0, 5) : "";
    std::printf("| %s | %s | %g | %lld | %.3g | %.1f | %.3f | %s | %.2f |\n", r.object.c_str(),
      r.mode.c_str(), r.parameter, static_cast<long long>(r.triangles), r.meanArea, r.remeshMs,
      r.bend, bound.c_str(), r.frameMs);
    std::fflush(stdout);
  };
  for (const auto& object : objects)
  {
    vtkPolyData* input = object.second;
    // The input as it is.
    Row in{ object.first, "input", 0.0, input->GetNumberOfPolys(), 0.0, 0.0,
      MaximumBend(input, projector), FrameTime(input, camera, frames) };
    print(in);
    rows.push_back(in);
    for (int mode = 0; mode < 2; ++mode)
    {
      for (double p : mode == 0 ? areas : tolerances)
      {
        vtkNew<vtkCatadioptricRemesher> remesher;
        remesher->SetInputData(input);
        if (mode == 0)
        {
          remesher->SetTargetArea(p);
        }
        else
        {
          remesher->SetModeToPixelTolerance();
          remesher->SetPixelTolerance(p);
          remesher->SetCamera(camera);
        }
        const auto t0 = Clock::now();
        remesher->Update();
        const double remeshMs = Ms(t0, Clock::now());
        vtkPolyData* out = remesher->GetOutput();
        if (out->GetNumberOfPolys() == 0)
        {
          std::fprintf(stderr, "remeshing %s failed\n", object.first.c_str());
          return 1;
        }
        vtkDataArray* mean = out->GetFieldData()->GetArray("MeanTriangleArea");
        Row r{ object.first, mode == 0 ? "area" : "pixels", p, out->GetNumberOfPolys(),
          mean ? mean->GetComponent(0, 0) : 0.0, remeshMs, MaximumBend(out, projector),
          FrameTime(out, camera, frames) };
        if (vtkDataArray* bound = out->GetFieldData()->GetArray("GeometricErrorBound"))
        {
          r.boundMm = 1e3 * bound->GetComponent(0, 0);
        }
        print(r);
        rows.push_back(r);
      }
    }
  }
  if (!csv.empty())
  {
    std::ofstream f(csv);
    f << "object,mode,target,triangles,mean_area_m2,remesh_ms,max_bend_px,geometric_bound_mm,"
         "frame_ms\n";
    for (const Row& r : rows)
    {
      f << r.object << "," << r.mode << "," << r.parameter << "," << r.triangles << ","
        << r.meanArea << "," << r.remeshMs << "," << r.bend << "," << r.boundMm << "," << r.frameMs
        << "\n";
    }
    std::printf("wrote %s\n", csv.c_str());
  }
  return 0;
}
