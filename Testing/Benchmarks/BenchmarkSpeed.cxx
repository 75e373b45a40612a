// The paper's figure 8 redone, and the real-time targets: frames per second of the full per-frame
// path (projection, Gouraud lighting with a moving spotlight, painter sort, compositing onto a
// 1328x1048 camera frame) against triangle count, median over --frames frames (default 300),
// with the time of each stage. Objects: the box remeshed to several sizes and spheres up to a
// million triangles (always), and the bunny, buddha and dragon when CATAR_SHARED_DATA names the
// shared data folder. Then, on the bunny (or a sphere of about 70k triangles without it): three
// spotlights with shadows, the depth buffer, the exact reference renderer, and resident memory
// over --memory-frames frames (default 1000). Run:
//   CATAR_SHARED_DATA=../shared/data build/bin/BenchmarkSpeed [--frames N] [--memory-frames N]
//     [--csv FILE] [--object NAME] [--max-seconds S] [--threads N] [--quick] [--no-variants]
//     [--tilted-hyperboloid] [--reference]
// --object NAME keeps only the objects of that name (box, sphere, bunny, happy-buddha-67k, ...).
// --max-seconds S (default 30) stops a row after S seconds (at least 5 frames; the table
// gives the count). --threads N runs vtkSMPTools on N threads (default: all cores).
// --quick (CI smoke) renders 3 frames of a few small objects. --no-variants stops after the first
// table (no variants, reference renderer or memory). --tilted-hyperboloid puts a hyperbolic mirror
// tilted 4 degrees in place of the sphere (Testing/Cxx/TestCameras.h; the general quadric solver).
// --reference measures only the exact reference renderer (one ray per pixel, Gouraud, one
// spotlight) on the bunny (or the sphere of the same size), frame by frame interleaved with the
// fast path's frame in the same process: with only the light moving, with only the camera's pose
// moving a little, with the mesh's points moving (the ray scene refitted) and with its cells
// marked modified (the ray scene built again) every frame.
#include "BenchmarkScene.h"
#include "FramePipeline.h"

#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCellArray.h"
#include "vtkMatrix4x4.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include <cstdlib>
#include <cstring>
#include <functional>

namespace
{
using namespace catar_benchmark;

// The paper's box remeshed to triangles of about `targetArea` square metres (0: as is).
vtkSmartPointer<vtkPolyData> Box(double targetArea)
{
  vtkSmartPointer<vtkPolyData> box = PaperBox();
  if (targetArea <= 0)
  {
    return box;
  }
  vtkNew<vtkCatadioptricRemesher> remesher;
  remesher->SetInputData(box);
  remesher->SetModeToTargetArea();
  remesher->SetTargetArea(targetArea);
  remesher->Update();
  return remesher->GetOutput();
}

// A shared PLY model, scaled to about 15 cm, z up, placed in view; null when absent.
vtkSmartPointer<vtkPolyData> SharedPly(const char* file)
{
  const char* shared = std::getenv("CATAR_SHARED_DATA");
  const std::string path = shared ? std::string(shared) + "/" + file : "";
  if (path.empty() || !vtksys::SystemTools::FileExists(path, true))
  {
    return nullptr;
  }
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* in = reader->GetOutput();
  double b[6];
  in->GetBounds(b);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  vtkNew<vtkTransform> centre;
  centre->PostMultiply();
  centre->Translate(-0.5 * (b[0] + b[1]), -0.5 * (b[2] + b[3]), -0.5 * (b[4] + b[5]));
  centre->Scale(0.15 / size, 0.15 / size, 0.15 / size);
  centre->RotateX(90); // the Stanford scans stand along +y
  return PlaceInView(in, centre);
}

struct Result
{
  std::string object, variant;
  vtkIdType triangles;
  StageTimes stages;
  double frameMs;
  int frames = 0; // frames measured
};

bool WriteCsv(const std::string& file, const std::vector<Result>& results)
{
  if (file.empty())
  {
    return true;
  }
  std::ofstream out(file);
  out << "object,variant,triangles,frames,projection_ms,lighting_ms,sort_ms,composite_ms,frame_ms,"
         "fps\n";
  for (const Result& r : results)
  {
    out << CsvField(r.object) << "," << CsvField(r.variant) << "," << r.triangles << ","
        << r.frames;
    for (double ms : r.stages.ms)
    {
      out << "," << ms;
    }
    out << "," << r.frameMs << "," << (r.frameMs > 0 ? 1e3 / r.frameMs : 0.0) << "\n";
  }
  if (!out)
  {
    std::fprintf(stderr, "cannot write %s\n", file.c_str());
    return false;
  }
  return true;
}

// The exact reference renderer against the fast path, frame by frame in turn (the machine's speed
// drifts): the fast path's full frame (moving spotlight); the reference with only the spotlight
// moving; with only the camera's pose moving (a fraction of a millimetre and of a degree); with
// the mesh's points moving (the ray scene refitted every frame); with its cells marked modified
// (the ray scene built again every frame). Median times.
int ReferenceTable(vtkPolyData* target, const std::string& name, vtkCatadioptricCamera* camera,
  vtkImageData* frame, int frames, double maxSeconds, const std::string& csv)
{
  FrameOptions options;
  options.solver = vtkCatadioptricProjection::ITERATIVE;
  FramePipeline pipeline(target, camera, frame, options);

  // Light moving: lit by the pipeline's own (moving) spotlight.
  vtkNew<vtkCatadioptricRayTracer> lightTracer;
  lightTracer->SetCamera(camera);
  lightTracer->SetFrameData(frame);
  lightTracer->AddMeshData(target);
  lightTracer->SetMeshLighting(0, pipeline.GetLighting());

  // Pose moving: a camera of its own and a still spotlight.
  vtkNew<vtkCatadioptricCamera> movingCamera;
  movingCamera->SetModel(camera->GetModel());
  double start[16];
  movingCamera->GetWorldToCameraElements(start);
  vtkNew<vtkCatadioptricLighting> stillLight;
  stillLight->SetShadingMode(vtkCatadioptricLighting::GOURAUD);
  stillLight->SetSpecular(0.3);
  stillLight->SetDiffuseColor(0.9, 0.85, 0.75);
  stillLight->AddSpotLight(0, 0, 1.3, 0.0, -0.25, 0.9, 40, 1, 0.9, 0.8);
  vtkNew<vtkCatadioptricRayTracer> poseTracer;
  poseTracer->SetCamera(movingCamera);
  poseTracer->SetFrameData(frame);
  poseTracer->AddMeshData(target);
  poseTracer->SetMeshLighting(0, stillLight);

  // Mesh moved: a copy of the mesh whose points move (by up to 1 mm) every frame, marked modified
  // (the ray scene refitted); mesh rebuilt: a copy whose cells change every frame, all of them and
  // all but the last in turn (the ray scene built again).
  vtkNew<vtkPolyData> copy;
  copy->DeepCopy(target);
  vtkNew<vtkCatadioptricRayTracer> meshTracer;
  meshTracer->SetCamera(camera);
  meshTracer->SetFrameData(frame);
  meshTracer->AddMeshData(copy);
  meshTracer->SetMeshLighting(0, stillLight);
  vtkNew<vtkPolyData> copy2;
  copy2->DeepCopy(target);
  vtkNew<vtkCatadioptricRayTracer> cellsTracer;
  cellsTracer->SetCamera(camera);
  cellsTracer->SetFrameData(frame);
  cellsTracer->AddMeshData(copy2);
  cellsTracer->SetMeshLighting(0, stillLight);
  vtkSmartPointer<vtkCellArray> allCells = copy2->GetPolys();
  vtkNew<vtkCellArray> fewerCells;
  fewerCells->DeepCopy(allCells);
  fewerCells->ResizeExact(
    allCells->GetNumberOfCells() - 1, allCells->GetNumberOfConnectivityIds() - 3);
  double previousShift = 0.0;
  auto movePoints = [&](int f) {
    const double shift = 0.001 * std::sin(0.3 * f);
    vtkPoints* points = copy->GetPoints();
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      double p[3];
      points->GetPoint(i, p);
      p[0] += shift - previousShift;
      points->SetPoint(i, p);
    }
    previousShift = shift;
    points->Modified();
  };

  // A small camera motion for frame f: world-to-camera = (rotation about the camera's y axis by up
  // to 0.3 degrees, translation by up to 0.5 mm) * the start.
  auto movePose = [&](int f) {
    const double a = 0.3 * std::sin(0.37 * f) * 3.14159265358979 / 180.0;
    const double d = 0.0005 * std::cos(0.23 * f);
    const double delta[16] = { std::cos(a), 0, std::sin(a), d, 0, 1, 0, 0.5 * d, -std::sin(a), 0,
      std::cos(a), 0, 0, 0, 0, 1 };
    double m[16];
    vtkMatrix4x4::Multiply4x4(delta, start, m);
    movingCamera->SetWorldToCameraElements(m);
  };

  constexpr int kRows = 5;
  const char* labels[kRows] = { "fast path (1 spot, gouraud, painter, iterative)",
    "reference, light moving", "reference, camera pose moving",
    "reference, mesh points moving (scene refitted)",
    "reference, mesh cells modified (scene built)" };
  std::vector<double> times[kRows];
  const auto begin = Clock::now();
  for (int f = 0; f <= frames; ++f) // frame 0: warm-up (rays and ray scene made)
  {
    double ms[kRows];
    ms[0] = pipeline.Frame(f).Total();
    auto t0 = Clock::now();
    lightTracer->Update();
    ms[1] = Ms(t0, Clock::now());
    movePose(f);
    t0 = Clock::now();
    poseTracer->Update();
    ms[2] = Ms(t0, Clock::now());
    movePoints(f);
    t0 = Clock::now();
    meshTracer->Update();
    ms[3] = Ms(t0, Clock::now());
    copy2->SetPolys(f % 2 ? fewerCells.Get() : allCells.Get());
    t0 = Clock::now();
    cellsTracer->Update();
    ms[4] = Ms(t0, Clock::now());
    if (f > 0)
    {
      for (int k = 0; k < kRows; ++k)
      {
        times[k].push_back(ms[k]);
      }
    }
    if (f >= 5 && Ms(begin, Clock::now()) > 1e3 * maxSeconds)
    {
      break;
    }
  }
  std::printf("Exact reference renderer (1 ray per pixel, gouraud, 1 spotlight) against the fast "
              "path on the %s, 1328x1048, frames in turn, median (ms):\n\n",
    name.c_str());
  std::printf("| object | renderer | triangles | frames | frame | fps | x fast path |\n"
              "|---|---|---|---|---|---|---|\n");
  std::vector<Result> results;
  const double fast = Median(times[0]);
  for (int k = 0; k < kRows; ++k)
  {
    Result r{ name, labels[k], target->GetNumberOfPolys(), {}, Median(times[k]) };
    r.stages.ms = { 0, 0, 0, r.frameMs };
    r.frames = static_cast<int>(times[k].size());
    std::printf("| %s | %s | %lld | %d | %.2f | %.1f | %.2f |\n", r.object.c_str(),
      r.variant.c_str(), static_cast<long long>(r.triangles), r.frames, r.frameMs,
      r.frameMs > 0 ? 1e3 / r.frameMs : 0.0, fast > 0 ? r.frameMs / fast : 0.0);
    results.push_back(r);
  }
  std::fflush(stdout);
  return WriteCsv(csv, results) ? 0 : 1;
}

void PrintRow(const Result& r)
{
  std::printf("| %s | %s | %lld | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f |\n",
    r.object.c_str(), r.variant.c_str(), static_cast<long long>(r.triangles), r.frames,
    r.stages.ms[0], r.stages.ms[1], r.stages.ms[2], r.stages.ms[3], r.frameMs,
    r.frameMs > 0 ? 1e3 / r.frameMs : 0.0);
  std::fflush(stdout);
}
} // namespace

int main(int argc, char* argv[])
{
  vtkCatadioptricParallel::EnableThreads();
  int frames = 300;
  int memoryFrames = 1000;
  double maxSeconds = 30.0;
  bool quick = false;
  bool variants = true;
  std::string csv;
  std::string only;         // --object NAME: only the objects of that name
  bool hyperboloid = false; // --tilted-hyperboloid: the demo rig's mirror replaced
  bool reference = false;   // --reference: the reference renderer's table only
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--memory-frames") && i + 1 < argc)
    {
      memoryFrames = std::max(0, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--max-seconds") && i + 1 < argc)
    {
      maxSeconds = std::max(0.0, std::atof(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
    {
      vtkSMPTools::Initialize(std::max(1, std::atoi(argv[++i])));
    }
    else if (!std::strcmp(argv[i], "--object") && i + 1 < argc)
    {
      only = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else if (!std::strcmp(argv[i], "--no-variants"))
    {
      variants = false;
    }
    else if (!std::strcmp(argv[i], "--tilted-hyperboloid"))
    {
      hyperboloid = true;
    }
    else if (!std::strcmp(argv[i], "--reference"))
    {
      reference = true;
    }
    else
    {
      std::fprintf(stderr,
        "usage: BenchmarkSpeed [--frames N] [--memory-frames N] [--csv FILE] [--object NAME] "
        "[--threads N] [--max-seconds S] [--quick] [--no-variants] [--tilted-hyperboloid] "
        "[--reference]\n");
      return 2;
    }
  }
  if (quick)
  {
    frames = 3;
    memoryFrames = 10;
  }
  vtkNew<vtkCatadioptricCamera> camera;
  DemoCamera(camera);
  if (hyperboloid)
  {
    camera->SetModel(catar_test::TiltedHyperboloidCameraModel());
  }
  vtkSmartPointer<vtkImageData> frame = CameraFrame(camera);
  if (reference)
  {
    std::string name;
    vtkSmartPointer<vtkPolyData> target = BunnyOrSphere(name);
    return ReferenceTable(
      target, name, camera, frame, quick ? 3 : std::min(frames, 100), maxSeconds, csv);
  }

  // The objects, made only when they are measured (remeshing the largest box takes seconds).
  std::vector<std::pair<std::string, std::function<vtkSmartPointer<vtkPolyData>()>>> objects;
  objects.emplace_back("box", [] { return Box(0); });
  for (double area : quick ? std::vector<double>{ 1e-4 } : std::vector<double>{ 1e-4, 1e-5, 1e-6 })
  {
    objects.emplace_back("box", [area] { return Box(area); });
  }
  const std::vector<std::pair<int, int>> spheres = quick
    ? std::vector<std::pair<int, int>>{ { 64, 34 } }
    : std::vector<std::pair<int, int>>{ { 64, 34 }, { 264, 134 }, { 512, 258 }, { 1000, 502 } };
  for (const auto& s : spheres)
  {
    objects.emplace_back("sphere", [s] { return Sphere(s.first, s.second); });
  }
  vtkSmartPointer<vtkPolyData> bunny = SharedBunny();
  objects.emplace_back("bunny", [bunny] { return bunny; });
  if (!quick)
  {
    for (const char* f : { "happy-buddha-16k.ply", "happy-buddha-67k.ply", "dragon-11k.ply",
           "dragon-48k.ply", "dragon-203k.ply" })
    {
      objects.emplace_back(
        std::string(f).substr(0, std::strlen(f) - 4), [f] { return SharedPly(f); });
    }
  }
  std::vector<Result> results;
  std::printf("Full per-frame path, 1328x1048, median of up to %d frames (ms):\n\n", frames);
  std::printf("| object | variant | triangles | frames | projection | lighting | sort | "
              "composite | frame | fps |\n|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& o : objects)
  {
    if (!only.empty() && o.first != only)
    {
      continue;
    }
    vtkSmartPointer<vtkPolyData> mesh = o.second();
    if (!mesh)
    {
      continue; // a shared model that is not there
    }
    FrameOptions options;
    options.solver = vtkCatadioptricProjection::ITERATIVE;
    FramePipeline pipeline(mesh, camera, frame, options);
    Result r{ o.first, "1 spot, gouraud, painter, iterative", mesh->GetNumberOfPolys(), {}, 0.0 };
    r.stages = MedianFrame(pipeline, frames, &r.frameMs, maxSeconds, &r.frames);
    PrintRow(r);
    results.push_back(r);
  }

  // The targets, on the bunny (or, without the shared data, a sphere of the same size).
  std::string name = "bunny";
  vtkSmartPointer<vtkPolyData> target = bunny ? bunny : nullptr;
  if (!target)
  {
    name = "sphere";
    target = Sphere(264, 134);
  }
  if ((!only.empty() && only != name) || !variants)
  {
    return WriteCsv(csv, results) ? 0 : 1;
  }
  std::printf("\nVariants on the %s (%lld triangles), median of up to %d frames (ms):\n\n",
    name.c_str(), static_cast<long long>(target->GetNumberOfPolys()), frames);
  std::printf("| object | variant | triangles | frames | projection | lighting | sort | "
              "composite | frame | fps |\n|---|---|---|---|---|---|---|---|---|---|\n");
  struct Variant
  {
    const char* label;
    FrameOptions options;
  };
  std::vector<Variant> variantList(11);
  variantList[0].label = "1 spot, gouraud, painter, quartic";
  variantList[1].label = "1 spot, gouraud, painter, iterative";
  variantList[1].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[2].label = "3 spots, shadows, gouraud, painter, iterative";
  variantList[2].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[2].options.lights = 3;
  variantList[2].options.shadows = true;
  variantList[3].label = "1 spot, flat, painter, iterative";
  variantList[3].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[3].options.shading = vtkCatadioptricLighting::FLAT;
  variantList[4].label = "1 spot, gouraud, depth buffer, iterative";
  variantList[4].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[4].options.visibility = vtkCatadioptricCompositor::DEPTH_BUFFER;
  variantList[5].label = "1 spot, gouraud, painter, iterative, back faces culled";
  variantList[5].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[5].options.cullBackFaces = true;
  variantList[6].label = "3 spots, shadows, gouraud, painter, iterative, back faces culled";
  variantList[6].options = variantList[2].options;
  variantList[6].options.cullBackFaces = true;
  variantList[7].label = "1 spot, gouraud, painter, quartic, back faces culled";
  variantList[7].options.cullBackFaces = true;
  variantList[8].label = "1 spot, gouraud, painter, iterative, antialiased 4 x 4";
  variantList[8].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[8].options.antialias = 4;
  variantList[9].label = "1 spot, gouraud, painter, iterative, antialiased 2 x 2";
  variantList[9].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[9].options.antialias = 2;
  variantList[10].label = "1 spot, gouraud, painter, iterative, adaptive 0.25 px";
  variantList[10].options.solver = vtkCatadioptricProjection::ITERATIVE;
  variantList[10].options.adaptive = 0.25;
  for (const Variant& v : variantList)
  {
    FramePipeline pipeline(target, camera, frame, v.options);
    Result r{ name, v.label, target->GetNumberOfPolys(), {}, 0.0 };
    r.stages = MedianFrame(pipeline, frames, &r.frameMs, maxSeconds, &r.frames);
    PrintRow(r);
    results.push_back(r);
  }

  // The exact reference renderer on the same scene (one ray per pixel), a moving spotlight.
  {
    FramePipeline pipeline(target, camera, frame, FrameOptions());
    vtkNew<vtkCatadioptricRayTracer> tracer;
    tracer->SetCamera(camera);
    tracer->SetFrameData(frame);
    tracer->AddMeshData(target);
    tracer->SetMeshLighting(0, pipeline.GetLighting());
    tracer->Update(); // rays and the ray scene are built once
    const int tracerFrames = std::max(1, std::min(frames, quick ? 2 : 30));
    std::vector<double> times;
    for (int f = 1; f <= tracerFrames; ++f)
    {
      pipeline.MoveLights(f);
      tracer->Modified();
      const auto t0 = Clock::now();
      tracer->Update();
      times.push_back(Ms(t0, Clock::now()));
    }
    Result r{ name, "exact reference renderer (1 ray per pixel)", target->GetNumberOfPolys(), {},
      Median(times) };
    r.stages.ms = { 0, 0, 0, r.frameMs };
    r.frames = tracerFrames;
    std::printf("| %s | %s | %lld | %d | | | | | %.2f | %.1f |\n", r.object.c_str(),
      r.variant.c_str(), static_cast<long long>(r.triangles), r.frames, r.frameMs, 1e3 / r.frameMs);
    results.push_back(r);
  }

  // Memory: resident size after a warm-up and after memoryFrames more frames.
  if (memoryFrames > 0)
  {
    FrameOptions options;
    options.solver = vtkCatadioptricProjection::ITERATIVE;
    FramePipeline pipeline(target, camera, frame, options);
    for (int f = 0; f < 20; ++f)
    {
      pipeline.Frame(f);
    }
    // Three readings: a step in the first half is the allocator settling; growth per frame shows
    // in the second half as well.
    const double before = ResidentMiB();
    const int half = memoryFrames / 2;
    for (int f = 0; f < half; ++f)
    {
      pipeline.Frame(20 + f);
    }
    const double middle = ResidentMiB();
    for (int f = half; f < memoryFrames; ++f)
    {
      pipeline.Frame(20 + f);
    }
    const double after = ResidentMiB();
    const int second = std::max(1, memoryFrames - half);
    std::printf("\nResident memory: %.1f MiB after 20 frames, %.1f MiB after %d more, %.1f MiB "
                "after %d more (%+.1f MiB over the last %d frames, %+.2f KiB per frame)\n",
      before, middle, half, after, memoryFrames - half, after - middle, second,
      1024.0 * (after - middle) / second);
  }
  return WriteCsv(csv, results) ? 0 : 1;
}
