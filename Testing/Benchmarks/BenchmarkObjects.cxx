// Frame time and memory against the number of objects in a scene: scenes of 10, 30, 100, 300 and
// 1000 small boxes (2 cm, 12 triangles each, on a lattice behind the demo camera, seen in its
// spherical mirror), rendered by vtkCatadioptricSceneRenderer (the path of catadioptric-render):
// unlit; lit by the demo's spotlight and fill light with shadows (every box casts shadows on the
// others), all boxes of one material; and lit the same way with a material per box. The renderer
// draws consecutive untextured objects as one mesh, their materials with it; --separate gives
// every object a pipeline of its own (vtkCatadioptricSceneRenderer::JoinObjects off). Per scene:
// the scene and meshes (load), the first frame (which builds what is kept between frames), the
// median per-frame time of up to --frames frames with the camera marked modified every frame
// (projection runs again, as when anything moves) and its stages, and the resident memory with
// the scene loaded (each scene is rendered in a child process of its own). The scenes use the
// scene files' default solver, quartic; --iterative sets the iterative one (with which the
// renderer gives every object a pipeline of its own). Run:
//   build/bin/BenchmarkObjects [--frames N] [--max-seconds S] [--counts 10,30,...]
//     [--variants unlit,lit,materials] [--iterative] [--separate] [--threads N] [--csv FILE]
//     [--quick]
//   build/bin/BenchmarkObjects [--iterative] --print-scene COUNT unlit|lit|materials > boxes.yaml
// (the scene, for catadioptric-render; --iterative before --print-scene). --max-seconds S (default
// 20) stops a row after S seconds (at least 3 frames). --quick (CI smoke) renders 2 frames of 10
// and 30 boxes.
#include "FramePipeline.h"

#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkSMPTools.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#if defined(__unix__) || defined(__APPLE__)
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace
{
using namespace catar_benchmark;

const char* const kVariants[] = { "unlit", "lit", "materials" };

const char* Label(const std::string& variant)
{
  return variant == "unlit" ? "unlit"
    : variant == "lit"      ? "lit, shadows"
                            : "lit, shadows, a material per box";
}

// A scene of `count` boxes of 2 cm (resolution 1: 12 triangles) on a lattice 6 cm apart across
// and 4 cm apart in depth, behind the demo camera (x in [-0.27, 0.27], z in [0.73, 1.27], rows of
// 10 x 10 going away from the mirror from y = -0.2), in colours that vary over the lattice.
// "unlit": no lighting section; "lit": the demo's lights, Gouraud shading, shadows;
// "materials": lit, each box with its own specular power (10 + i / 10).
std::string BoxesScene(int count, const std::string& variant, bool iterative)
{
  std::ostringstream s;
  s << "%YAML:1.0\n---\n"
       "camera:\n"
       "  image_width: 1328\n"
       "  image_height: 1048\n"
       "  camera_matrix: [ 1000.0, 0.0, 663.5, 0.0, 1000.0, 523.5, 0.0, 0.0, 1.0 ]\n"
       "  distortion_coefficients: [ 0.0, 0.0, 0.0, 0.0, 0.0 ]\n"
       "  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }\n"
       "  world_to_camera: [ 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 1.0, 0.0, 1.0, 0.0, 0.14,\n"
       "                     0.0, 0.0, 0.0, 1.0 ]\n"
       "background: { type: color, color: [ 0.1, 0.1, 0.1 ] }\n";
  if (iterative)
  {
    s << "solver: iterative\n";
  }
  if (variant != "unlit")
  {
    s << "lighting:\n"
         "  shading: gouraud\n"
         "  shadows: 1\n"
         "  global_ambient: [ 0.3, 0.3, 0.3 ]\n"
         "  lights:\n"
         "    - { type: spot, position: [ 0.25, 0.05, 1.35 ], focal_point: [ 0.0, -0.3, 1.0 ],\n"
         "        cone_angle: 45, exponent: 1, color: [ 1.0, 0.95, 0.85 ] }\n"
         "    - { type: directional, position: [ -0.6, 1.0, 0.8 ], focal_point: [ 0, 0, 0 ],\n"
         "        color: [ 0.3, 0.35, 0.45 ] }\n";
  }
  s << "objects:\n";
  constexpr int side = 10;
  for (int i = 0; i < count; ++i)
  {
    const int col = i % side;
    const int row = (i / side) % side;
    const int layer = i / (side * side);
    s << "  - { type: box, size: [ 0.02, 0.02, 0.02 ], resolution: 1, translate: [ "
      << -0.27 + 0.06 * col << ", " << -0.2 - 0.04 * layer << ", " << 0.73 + 0.06 * row
      << " ], rotate: [ 0, 0, " << 7 * (i % 13) << " ], color: [ " << 0.3 + 0.07 * col << ", "
      << 0.3 + 0.07 * row << ", " << 0.9 - 0.08 * (layer % 10) << " ]";
    if (variant == "materials")
    {
      s << ", material: { specular_power: " << 10 + 0.1 * i << " }";
    }
    s << " }\n";
  }
  return s.str();
}

struct Result
{
  int objects = 0;
  std::string variant;
  vtkIdType triangles = 0;
  int frames = 0;
  double loadMs = 0, firstMs = 0, frameMs = 0;
  StageTimes stages;
  double residentMiB = 0;
};

bool WriteCsv(const std::string& file, const std::vector<Result>& results)
{
  if (file.empty())
  {
    return true;
  }
  std::ofstream out(file);
  out << "objects,variant,triangles,frames,load_ms,first_frame_ms,projection_ms,lighting_ms,"
         "sort_ms,composite_ms,frame_ms,resident_mib\n";
  for (const Result& r : results)
  {
    out << r.objects << "," << r.variant << "," << r.triangles << "," << r.frames << "," << r.loadMs
        << "," << r.firstMs;
    for (double ms : r.stages.ms)
    {
      out << "," << ms;
    }
    out << "," << r.frameMs << "," << r.residentMiB << "\n";
  }
  if (!out)
  {
    std::fprintf(stderr, "cannot write %s\n", file.c_str());
    return false;
  }
  return true;
}

// Renders the scene of `count` boxes; false (with a message) on failure.
// --separate: every object a pipeline of its own.
bool separate = false;

bool Measure(
  int count, const std::string& variant, bool iterative, int frames, double maxSeconds, Result& r)
{
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
    ("catar-benchmark-objects-" + std::to_string(Clock::now().time_since_epoch().count()) +
      ".yaml");
  {
    std::ofstream out(file);
    out << BoxesScene(count, variant, iterative);
    if (!out)
    {
      std::fprintf(stderr, "cannot write %s\n", file.string().c_str());
      return false;
    }
  }
  r.objects = count;
  r.variant = variant;
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(file.string().c_str());
  renderer->SetJoinObjects(!separate);
  const auto t0 = Clock::now();
  const bool loaded = renderer->LoadScene();
  const auto t1 = Clock::now();
  std::filesystem::remove(file);
  if (!loaded || !renderer->Render())
  {
    std::fprintf(stderr, "BenchmarkObjects: %s\n", renderer->GetLastError());
    return false;
  }
  r.loadMs = Ms(t0, t1);
  r.firstMs = Ms(t1, Clock::now());
  r.triangles = renderer->GetNumberOfTriangles();
  // The fast path's stages, projection to composite (after the background).
  int first = renderer->GetFirstPerFrameStage();
  while (first < renderer->GetNumberOfStages() &&
    std::string(renderer->GetStageName(first)) != StageTimes::Name(0))
  {
    ++first;
  }
  std::vector<std::vector<double>> stages(StageTimes::N);
  std::vector<double> totals;
  const auto start = Clock::now();
  for (int f = 0; f < frames; ++f)
  {
    if (f >= 3 && Ms(start, Clock::now()) > 1e3 * maxSeconds)
    {
      break;
    }
    renderer->GetCamera()->Modified(); // the per-frame stages run again
    if (!renderer->Render())
    {
      std::fprintf(stderr, "BenchmarkObjects: %s\n", renderer->GetLastError());
      return false;
    }
    for (int s = 0; s < StageTimes::N; ++s)
    {
      stages[s].push_back(1e3 * renderer->GetStageTime(first + s));
    }
    totals.push_back(1e3 * renderer->GetFrameTime());
  }
  r.frames = static_cast<int>(totals.size());
  for (int s = 0; s < StageTimes::N; ++s)
  {
    r.stages.ms[s] = Median(stages[s]);
  }
  r.frameMs = Median(totals);
  r.residentMiB = ResidentMiB();
  return true;
}

// Measure() in a child process, so that each scene starts from a fresh heap (the resident size is
// then the scene's, not what earlier scenes left with the allocator); in this process where
// there is no fork().
bool MeasureApart(
  int count, const std::string& variant, bool iterative, int frames, double maxSeconds, Result& r)
{
#if defined(__unix__) || defined(__APPLE__)
  int fds[2];
  if (pipe(fds) != 0)
  {
    return Measure(count, variant, iterative, frames, maxSeconds, r);
  }
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t child = fork();
  if (child < 0)
  {
    close(fds[0]);
    close(fds[1]);
    return Measure(count, variant, iterative, frames, maxSeconds, r);
  }
  if (child == 0)
  {
    close(fds[0]);
    const bool ok = Measure(count, variant, iterative, frames, maxSeconds, r);
    std::ostringstream out;
    out.precision(17);
    out << r.triangles << " " << r.frames << " " << r.loadMs << " " << r.firstMs << " " << r.frameMs
        << " " << r.residentMiB;
    for (double ms : r.stages.ms)
    {
      out << " " << ms;
    }
    const std::string text = out.str();
    const bool written =
      ok && write(fds[1], text.data(), text.size()) == static_cast<ssize_t>(text.size());
    close(fds[1]);
    _exit(written ? 0 : 1);
  }
  close(fds[1]);
  std::string text;
  char buffer[512];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;)
  {
    text.append(buffer, static_cast<size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    return false;
  }
  r.objects = count;
  r.variant = variant;
  std::istringstream in(text);
  in >> r.triangles >> r.frames >> r.loadMs >> r.firstMs >> r.frameMs >> r.residentMiB;
  for (double& ms : r.stages.ms)
  {
    in >> ms;
  }
  return static_cast<bool>(in);
#else
  return Measure(count, variant, iterative, frames, maxSeconds, r);
#endif
}

// Splits "a,b,c".
std::vector<std::string> Split(const char* list)
{
  std::vector<std::string> items;
  std::istringstream in(list);
  std::string item;
  while (std::getline(in, item, ','))
  {
    items.push_back(item);
  }
  return items;
}

bool IsVariant(const std::string& v)
{
  return std::find(std::begin(kVariants), std::end(kVariants), v) != std::end(kVariants);
}
} // namespace

int main(int argc, char* argv[])
{
  vtkCatadioptricParallel::EnableThreads();
  int frames = 30;
  double maxSeconds = 20.0;
  std::vector<int> counts{ 10, 30, 100, 300, 1000 };
  std::vector<std::string> variants(std::begin(kVariants), std::end(kVariants));
  std::string csv;
  bool iterative = false;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--max-seconds") && i + 1 < argc)
    {
      maxSeconds = std::max(0.0, std::atof(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--counts") && i + 1 < argc)
    {
      counts.clear();
      for (const std::string& c : Split(argv[++i]))
      {
        counts.push_back(std::max(1, std::atoi(c.c_str())));
      }
    }
    else if (!std::strcmp(argv[i], "--variants") && i + 1 < argc)
    {
      variants = Split(argv[++i]);
      for (const std::string& v : variants)
      {
        if (!IsVariant(v))
        {
          std::fprintf(stderr, "BenchmarkObjects: unknown variant %s\n", v.c_str());
          return 2;
        }
      }
    }
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
    {
      vtkSMPTools::Initialize(std::max(1, std::atoi(argv[++i])));
    }
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--print-scene") && i + 2 < argc && IsVariant(argv[i + 2]))
    {
      std::fputs(
        BoxesScene(std::max(1, std::atoi(argv[i + 1])), argv[i + 2], iterative).c_str(), stdout);
      return 0;
    }
    else if (!std::strcmp(argv[i], "--iterative"))
    {
      iterative = true;
    }
    else if (!std::strcmp(argv[i], "--separate"))
    {
      separate = true;
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      frames = 2;
      counts = { 10, 30 };
    }
    else
    {
      std::fprintf(stderr,
        "usage: BenchmarkObjects [--frames N] [--max-seconds S] [--counts 10,30,...] "
        "[--variants unlit,lit,materials] [--iterative] [--separate] [--threads N] [--csv FILE] "
        "[--quick]\n"
        "       BenchmarkObjects [--iterative] --print-scene COUNT unlit|lit|materials\n");
      return 2;
    }
  }
  std::printf("Scenes of small boxes (12 triangles each), 1328x1048, %s solver, median of up to "
              "%d frames (ms), resident memory with the scene loaded (MiB; each scene rendered in "
              "a process of its own):\n\n",
    iterative ? "iterative" : "quartic", frames);
  std::printf("| objects | variant | triangles | frames | load | first frame | projection | "
              "lighting | sort | composite | frame | MiB resident |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Result> results;
  for (const std::string& variant : variants)
  {
    for (int count : counts)
    {
      Result r;
      if (!MeasureApart(count, variant, iterative, frames, maxSeconds, r))
      {
        return 1;
      }
      std::printf("| %d | %s | %lld | %d | %.1f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f "
                  "|\n",
        r.objects, Label(r.variant), static_cast<long long>(r.triangles), r.frames, r.loadMs,
        r.firstMs, r.stages.ms[0], r.stages.ms[1], r.stages.ms[2], r.stages.ms[3], r.frameMs,
        r.residentMiB);
      std::fflush(stdout);
      results.push_back(r);
    }
  }
  return WriteCsv(csv, results) ? 0 : 1;
}
