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
// marked modified (the ray scene built again) every frame; both renderers with three moving
// spotlights and shadows; then both, with one spotlight and with three and shadows, on a large
// object (a sphere around the rig that fills the mirror's whole image, a third of the frame's
// pixels), where the reference's cost (per pixel) meets the fast path's (per triangle).
#include "BenchmarkScene.h"
#include "FramePipeline.h"

#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCellArray.h"
#include "vtkMatrix4x4.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkReverseSense.h"
#include "vtkSMPTools.h"

#include <cstdlib>
#include <cstring>
#include <functional>
#include <utility>

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

// One row of a table measured frame by frame in turn: its label, the row it is compared with
// (the fast path with the same lighting), and what renders frame f (returns the stages' times in
// milliseconds; the reference's whole frame as its last stage).
struct Timed
{
  std::string label;
  int baseline;
  std::function<StageTimes(int)> frame;
  std::vector<double> times;
  std::array<std::vector<double>, StageTimes::N> stages;
};

void AddRow(std::vector<Timed>& rows, const std::string& label, int baseline,
  std::function<StageTimes(int)> frame)
{
  rows.emplace_back();
  rows.back().label = label;
  rows.back().baseline = baseline;
  rows.back().frame = std::move(frame);
}

// Renders every row's frame f in turn, f = 0 (warm-up, not kept) to `frames`, stopping after
// `maxSeconds` (at least 5 frames); prints the medians and appends them to `results`.
void RunInTurn(std::vector<Timed>& rows, const std::string& name, vtkIdType triangles, int frames,
  double maxSeconds, std::vector<Result>& results)
{
  const auto begin = Clock::now();
  for (int f = 0; f <= frames; ++f)
  {
    for (Timed& row : rows)
    {
      const StageTimes t = row.frame(f);
      if (f > 0)
      {
        row.times.push_back(t.Total());
        for (int k = 0; k < StageTimes::N; ++k)
        {
          row.stages[k].push_back(t.ms[k]);
        }
      }
    }
    if (f >= 5 && Ms(begin, Clock::now()) > 1e3 * maxSeconds)
    {
      break;
    }
  }
  std::printf("| object | renderer | triangles | frames | frame | fps | x fast path | "
              "projection | lighting | sort | composite |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Timed& row : rows)
  {
    Result r{ name, row.label, triangles, {}, Median(row.times) };
    for (int k = 0; k < StageTimes::N; ++k)
    {
      r.stages.ms[k] = Median(row.stages[k]);
    }
    r.frames = static_cast<int>(row.times.size());
    const double fast = Median(rows[row.baseline].times);
    std::printf("| %s | %s | %lld | %d | %.2f | %.1f | %.2f |", r.object.c_str(), r.variant.c_str(),
      static_cast<long long>(r.triangles), r.frames, r.frameMs,
      r.frameMs > 0 ? 1e3 / r.frameMs : 0.0, fast > 0 ? r.frameMs / fast : 0.0);
    if (r.stages.ms[0] > 0 || r.stages.ms[1] > 0 || r.stages.ms[2] > 0)
    {
      std::printf(" %.2f | %.2f | %.2f | %.2f |\n", r.stages.ms[0], r.stages.ms[1], r.stages.ms[2],
        r.stages.ms[3]);
    }
    else
    {
      std::printf(" | | | |\n");
    }
    results.push_back(r);
  }
  std::fflush(stdout);
}

// Times one Update of `tracer` (as the last stage).
StageTimes TimeUpdate(vtkCatadioptricRayTracer* tracer)
{
  const auto t0 = Clock::now();
  tracer->Update();
  StageTimes t;
  t.ms[3] = Ms(t0, Clock::now());
  return t;
}

vtkSmartPointer<vtkCatadioptricRayTracer> MakeTracer(vtkCatadioptricCamera* camera,
  vtkImageData* frame, vtkPolyData* mesh, vtkCatadioptricLighting* lighting)
{
  auto tracer = vtkSmartPointer<vtkCatadioptricRayTracer>::New();
  tracer->SetCamera(camera);
  tracer->SetFrameData(frame);
  tracer->AddMeshData(mesh);
  tracer->SetMeshLighting(0, lighting);
  return tracer;
}

// Both renderers of one mesh, as the interleaved tables time them: the fast path (iterative
// solver) with one moving spotlight and with three and shadows, and the exact tracer lit by each.
struct BothRenderers
{
  BothRenderers(vtkPolyData* mesh, vtkCatadioptricCamera* camera, vtkImageData* frame)
    : Fast(mesh, camera, frame, Options(1, false))
    , FastShadows(mesh, camera, frame, Options(3, true))
    , Exact(MakeTracer(camera, frame, mesh, Fast.GetLighting()))
    , ExactShadows(MakeTracer(camera, frame, mesh, FastShadows.GetLighting()))
  {
  }
  static FrameOptions Options(int lights, bool shadows)
  {
    FrameOptions options;
    options.solver = vtkCatadioptricProjection::ITERATIVE;
    options.lights = lights;
    options.shadows = shadows;
    return options;
  }
  FramePipeline Fast;
  FramePipeline FastShadows;
  vtkSmartPointer<vtkCatadioptricRayTracer> Exact;
  vtkSmartPointer<vtkCatadioptricRayTracer> ExactShadows;
};

// A sphere of 69,696 triangles, 0.8 m in radius, around the camera and the mirror (centred 10 cm
// behind the mirror's centre, towards the camera), its triangles turned to face inwards: an
// object that fills every pixel of the mirror's image (a third of the frame). The spotlights
// circle inside it.
vtkSmartPointer<vtkPolyData> SurroundingSphere()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.8);
  sphere->SetCenter(0.0, -0.1, 1.0);
  sphere->SetThetaResolution(264);
  sphere->SetPhiResolution(134);
  vtkNew<vtkReverseSense> inwards;
  inwards->SetInputConnection(sphere->GetOutputPort());
  inwards->ReverseCellsOn();
  inwards->ReverseNormalsOn();
  inwards->Update();
  return inwards->GetOutput();
}

// The exact reference renderer against the fast path, frame by frame in turn (the machine's speed
// drifts): the fast path's full frame (moving spotlight); the reference with only the spotlight
// moving; with only the camera's pose moving (a fraction of a millimetre and of a degree); with
// the mesh's points moving (the ray scene refitted every frame); with its cells marked modified
// (the ray scene built again every frame); then the fast path and the reference with three moving
// spotlights and shadows. Median times.
void ReferenceTable(vtkPolyData* target, const std::string& name, vtkCatadioptricCamera* camera,
  vtkImageData* frame, int frames, double maxSeconds, std::vector<Result>& results)
{
  // Light moving: the tracers are lit by the pipelines' own (moving) spotlight(s).
  BothRenderers both(target, camera, frame);
  FramePipeline& pipeline = both.Fast;
  FramePipeline& shadowPipeline = both.FastShadows;
  vtkCatadioptricRayTracer* lightTracer = both.Exact;
  vtkCatadioptricRayTracer* shadowTracer = both.ExactShadows;

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
  vtkSmartPointer<vtkCatadioptricRayTracer> poseTracer =
    MakeTracer(movingCamera, frame, target, stillLight);

  // Mesh moved: a copy of the mesh whose points move (by up to 1 mm) every frame, marked modified
  // (the ray scene refitted); mesh rebuilt: a copy whose cells change every frame, all of them and
  // all but the last in turn (the ray scene built again).
  vtkNew<vtkPolyData> copy;
  copy->DeepCopy(target);
  vtkSmartPointer<vtkCatadioptricRayTracer> meshTracer =
    MakeTracer(camera, frame, copy, stillLight);
  vtkNew<vtkPolyData> copy2;
  copy2->DeepCopy(target);
  vtkSmartPointer<vtkCatadioptricRayTracer> cellsTracer =
    MakeTracer(camera, frame, copy2, stillLight);
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

  // Frame 0 is the warm-up: rays and ray scenes made.
  std::vector<Timed> rows;
  AddRow(rows, "fast path (1 spot, gouraud, painter, iterative)", 0,
    [&](int f) { return pipeline.Frame(f); });
  AddRow(rows, "reference, light moving", 0, [&](int) { return TimeUpdate(lightTracer); });
  AddRow(rows, "reference, camera pose moving", 0, [&](int f) {
    movePose(f);
    return TimeUpdate(poseTracer);
  });
  AddRow(rows, "reference, mesh points moving (scene refitted)", 0, [&](int f) {
    movePoints(f);
    return TimeUpdate(meshTracer);
  });
  AddRow(rows, "reference, mesh cells modified (scene built)", 0, [&](int f) {
    copy2->SetPolys(f % 2 ? fewerCells.Get() : allCells.Get());
    return TimeUpdate(cellsTracer);
  });
  AddRow(rows, "fast path (3 spots, shadows, gouraud, painter, iterative)", 5,
    [&](int f) { return shadowPipeline.Frame(f); });
  AddRow(rows, "reference, 3 spots with shadows, lights moving", 5,
    [&](int) { return TimeUpdate(shadowTracer); });
  std::printf("Exact reference renderer (1 ray per pixel, gouraud) against the fast path on the "
              "%s, 1328x1048, frames in turn, median (ms; x fast path: against the fast path "
              "with the same lights):\n\n",
    name.c_str());
  RunInTurn(rows, name, target->GetNumberOfPolys(), frames, maxSeconds, results);
}

// An object that fills a large part of the mirror (SurroundingSphere): the fast path and the
// reference with one moving spotlight, and with three and shadows, frames in turn; the share of
// the frame's pixels the object covers (the reference's hits, one ray per pixel).
void LargeObjectTable(vtkCatadioptricCamera* camera, vtkImageData* frame, int frames,
  double maxSeconds, std::vector<Result>& results)
{
  const std::string name = "surrounding sphere";
  vtkSmartPointer<vtkPolyData> mesh = SurroundingSphere();
  BothRenderers both(mesh, camera, frame);
  FramePipeline& pipeline = both.Fast;
  FramePipeline& shadowPipeline = both.FastShadows;
  vtkCatadioptricRayTracer* tracer = both.Exact;
  vtkCatadioptricRayTracer* shadowTracer = both.ExactShadows;
  std::vector<Timed> rows;
  AddRow(rows, "fast path (1 spot, gouraud, painter, iterative)", 0,
    [&](int f) { return pipeline.Frame(f); });
  AddRow(rows, "reference, light moving", 0, [&](int) { return TimeUpdate(tracer); });
  AddRow(rows, "fast path (3 spots, shadows, gouraud, painter, iterative)", 2,
    [&](int f) { return shadowPipeline.Frame(f); });
  AddRow(rows, "reference, 3 spots with shadows, lights moving", 2,
    [&](int) { return TimeUpdate(shadowTracer); });
  tracer->Update();
  pipeline.Frame(0);
  int dims[3];
  frame->GetDimensions(dims);
  const double pixels = static_cast<double>(dims[0]) * dims[1];
  std::printf("\nA large object: a sphere of %lld triangles, 0.8 m in radius, around the camera "
              "and the mirror, seen inside; it covers %lld of the frame's %.0f pixels (%.1f %%; "
              "the mirror's whole image is about a third of the frame); %lld of its triangles "
              "cross the mirror's visibility boundary and are split there every frame. Frames in "
              "turn, median (ms):\n\n",
    static_cast<long long>(mesh->GetNumberOfPolys()),
    static_cast<long long>(tracer->GetNumberOfHits()), pixels,
    100.0 * tracer->GetNumberOfHits() / pixels,
    static_cast<long long>(pipeline.GetProjection()->GetNumberOfSplitTriangles()));
  RunInTurn(rows, name, mesh->GetNumberOfPolys(), frames, maxSeconds, results);
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
    const int referenceFrames = quick ? 3 : std::min(frames, 100);
    std::vector<Result> results;
    ReferenceTable(target, name, camera, frame, referenceFrames, maxSeconds, results);
    LargeObjectTable(camera, frame, referenceFrames, maxSeconds, results);
    return WriteCsv(csv, results) ? 0 : 1;
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
