// Forward-projection cost per point of each solver (and from a nearby point's reflection),
// back-projection cost per pixel, and raster cost per triangle, single-threaded. Run:
//   build/bin/BenchmarkProjection [--benchmark_out=projection.csv --benchmark_out_format=csv]
// The counter ns_per_item is the cost of one point / pixel / triangle.
#include "../Cxx/TestCameras.h"
#include "PoseEstimation.h"
#include "Projector.h"
#include "Rasterizer.h"
#include "SceneDescription.h"

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

using namespace catar;

namespace
{
// World points around the demo scene's objects: behind and beside the camera, 0.1-0.6 m away.
std::vector<Vec3> ScenePoints(const CameraModel& model, size_t n)
{
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Projector proj(model);
  std::vector<Vec3> pts;
  while (pts.size() < n)
  {
    const Vec3 p(0.35 * u(rng), -0.14 - 0.3 * (u(rng) + 1.0), 1.0 + 0.3 * u(rng));
    if (proj.ProjectWorld(p).status == ProjectionStatus::Valid)
    {
      pts.push_back(p);
    }
  }
  return pts;
}

void SetPerItem(benchmark::State& state, size_t itemsPerIteration)
{
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * itemsPerIteration));
  state.counters["ns_per_item"] =
    benchmark::Counter(static_cast<double>(state.iterations() * itemsPerIteration),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

void BM_ForwardProjection(benchmark::State& state)
{
  const SolverType solver = state.range(0) == 0 ? SolverType::Quartic : SolverType::Iterative;
  state.SetLabel(solver == SolverType::Quartic ? "quartic" : "iterative");
  const CameraModel model = DemoScene().camera;
  const Projector proj(model);
  const std::vector<Vec3> pts = ScenePoints(model, 4096);
  for (auto _ : state)
  {
    for (const Vec3& p : pts)
    {
      benchmark::DoNotOptimize(proj.ProjectWorld(p, solver));
    }
  }
  SetPerItem(state, pts.size());
}
BENCHMARK(BM_ForwardProjection)->Arg(0)->Arg(1);

// The same through a hyperbolic mirror tilted 4 degrees (the general quadric solver): from its own
// start (0), from the reflection point of a point 1 mm away (1), and from there through the
// many-points call (2: points solved side by side).
void BM_ForwardProjectionQuadric(benchmark::State& state)
{
  const bool near = state.range(0) >= 1;
  const bool batch = state.range(0) == 2;
  state.SetLabel(batch ? "tilted hyperboloid, start 1 mm away, batch"
      : near           ? "tilted hyperboloid, start 1 mm away"
                       : "tilted hyperboloid");
  const CameraModel model = catar_test::TiltedHyperboloidCameraModel();
  const Projector proj(model);
  const std::vector<Vec3> pts = ScenePoints(model, 4096);
  std::vector<Vec3> guesses;
  for (const Vec3& p : pts)
  {
    guesses.push_back(proj.ProjectWorld(p + Vec3(1e-3, -1e-3, 1e-3)).mirrorPoint);
  }
  std::vector<ProjectedPoint> out(pts.size());
  for (auto _ : state)
  {
    if (batch)
    {
      proj.ProjectWorldNear(pts.size(), pts.data(), guesses.data(), out.data());
      benchmark::DoNotOptimize(out.data());
      continue;
    }
    for (std::size_t i = 0; i < pts.size(); ++i)
    {
      benchmark::DoNotOptimize(
        near ? proj.ProjectWorldNear(pts[i], guesses[i]) : proj.ProjectWorld(pts[i]));
    }
  }
  SetPerItem(state, pts.size());
}
BENCHMARK(BM_ForwardProjectionQuadric)->Arg(0)->Arg(1)->Arg(2);

// An axial hyperboloid (the same, untilted: the camera on its axis) with the quartic solver: the
// planar reduction, every root bracketed (0); and the iterative solver from its own start (1).
void BM_ForwardProjectionAxialQuadric(benchmark::State& state)
{
  const SolverType solver = state.range(0) == 0 ? SolverType::Quartic : SolverType::Iterative;
  state.SetLabel(solver == SolverType::Quartic ? "axial hyperboloid, planar reduction"
                                               : "axial hyperboloid, Newton");
  CameraModel model = catar_test::TiltedHyperboloidCameraModel();
  std::vector<double>& p = model.mirror.parameters; // a, b, then mirror_to_camera (row-major)
  const double untilted[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, p[2 + 11], 0, 0, 0, 1 };
  std::copy(untilted, untilted + 16, p.begin() + 2);
  const Projector proj(model);
  const std::vector<Vec3> pts = ScenePoints(model, 1024);
  for (auto _ : state)
  {
    for (const Vec3& q : pts)
    {
      benchmark::DoNotOptimize(proj.ProjectWorld(q, solver));
    }
  }
  SetPerItem(state, pts.size());
}
BENCHMARK(BM_ForwardProjectionAxialQuadric)->Arg(0)->Arg(1);

// Projection started from a nearby reflection point (what vtkCatadioptricProjection does for the
// cells' centroids and, with the iterative solver, for each vertex after the first): the guess
// is the reflection point of a point `range(0)` tenths of a millimetre away.
struct NearInput
{
  Projector proj;
  std::vector<Vec3> points;
  std::vector<Vec3> guesses;
};

NearInput MakeNearInput(benchmark::State& state)
{
  const double offset = 1e-4 * static_cast<double>(state.range(0));
  state.SetLabel("start " + std::to_string(offset * 1e3) + " mm away");
  const CameraModel model = DemoScene().camera;
  NearInput in{ Projector(model), ScenePoints(model, 4096), {} };
  for (const Vec3& p : in.points)
  {
    in.guesses.push_back(in.proj.ProjectWorld(p + Vec3(offset, -offset, offset)).mirrorPoint);
  }
  return in;
}

// One point at a time.
void BM_ForwardProjectionNear(benchmark::State& state)
{
  const NearInput in = MakeNearInput(state);
  for (auto _ : state)
  {
    for (size_t i = 0; i < in.points.size(); ++i)
    {
      benchmark::DoNotOptimize(in.proj.ProjectWorldNear(in.points[i], in.guesses[i]));
    }
  }
  SetPerItem(state, in.points.size());
}
BENCHMARK(BM_ForwardProjectionNear)->Arg(10)->Arg(100);

// The same points and guesses through the many-points call (points solved side by side).
void BM_ForwardProjectionNearBatch(benchmark::State& state)
{
  const NearInput in = MakeNearInput(state);
  std::vector<ProjectedPoint> out(in.points.size());
  for (auto _ : state)
  {
    in.proj.ProjectWorldNear(in.points.size(), in.points.data(), in.guesses.data(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
  SetPerItem(state, in.points.size());
}
BENCHMARK(BM_ForwardProjectionNearBatch)->Arg(10)->Arg(100);

// Every 16th pixel of every 16th row.
std::vector<Vec2> GridPixels(const CameraModel& model)
{
  std::vector<Vec2> pixels;
  for (int y = 0; y < model.intrinsics.height; y += 16)
  {
    for (int x = 0; x < model.intrinsics.width; x += 16)
    {
      pixels.emplace_back(x, y);
    }
  }
  return pixels;
}

void BM_BackProjection(benchmark::State& state)
{
  const CameraModel model = DemoScene().camera;
  const Projector proj(model);
  const std::vector<Vec2> pixels = GridPixels(model);
  for (auto _ : state)
  {
    for (const Vec2& px : pixels)
    {
      benchmark::DoNotOptimize(proj.BackProjectWorld(px));
    }
  }
  SetPerItem(state, pixels.size());
}
BENCHMARK(BM_BackProjection);

// The same pixels through the batched call (what the environment source and the ray tracer use).
void BM_BackProjectionBatch(benchmark::State& state)
{
  const CameraModel model = DemoScene().camera;
  const Projector proj(model);
  const std::vector<Vec2> pixels = GridPixels(model);
  std::vector<BackProjectedRay> rays(pixels.size());
  for (auto _ : state)
  {
    proj.BackProjectWorld(pixels.size(), pixels.data(), rays.data());
    benchmark::DoNotOptimize(rays.data());
    benchmark::ClobberMemory();
  }
  SetPerItem(state, pixels.size());
}
BENCHMARK(BM_BackProjectionBatch);

void BM_RasterizeTriangle(benchmark::State& state)
{
  // Triangles of about `area` pixels at random places of a 1328x1048 image.
  const double area = static_cast<double>(state.range(0));
  const int w = 1328, h = 1048;
  std::vector<std::uint8_t> buffer(4 * static_cast<size_t>(w) * h, 0);
  ImageView view;
  view.data = buffer.data();
  view.width = w;
  view.height = h;
  view.rowStride = 4 * w;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(0, w - 1), uy(0, h - 1), ua(0, 6.2831853);
  const double side = std::sqrt(2.0 * area);
  std::vector<RasterVertex> tris;
  for (int i = 0; i < 4096; ++i)
  {
    const double x = ux(rng), y = uy(rng), a = ua(rng);
    RasterVertex v0, v1, v2;
    v0.x = x;
    v0.y = y;
    v1.x = x + side * std::cos(a);
    v1.y = y + side * std::sin(a);
    v2.x = x + side * std::cos(a + 1.5707963);
    v2.y = y + side * std::sin(a + 1.5707963);
    v0.r = v1.g = v2.b = 1.0f;
    tris.insert(tris.end(), { v0, v1, v2 });
  }
  for (auto _ : state)
  {
    for (size_t i = 0; i < tris.size(); i += 3)
    {
      rasterizeTriangle(view, tris[i], tris[i + 1], tris[i + 2]);
    }
  }
  SetPerItem(state, tris.size() / 3);
}
BENCHMARK(BM_RasterizeTriangle)->Arg(2)->Arg(20)->Arg(200);
// The pose from 50 pixels of world points about a metre away (PoseEstimation.h: RANSAC, then the
// refinement), with 0.5 px noise; range(0) percent of them outliers; range(1): 0 the sphere, 1 the
// tilted hyperboloid. The time of one estimate (a frame's).
void BM_PoseEstimation(benchmark::State& state)
{
  const bool hyperboloid = state.range(1) == 1;
  const CameraModel model =
    hyperboloid ? catar_test::TiltedHyperboloidCameraModel() : DemoScene().camera;
  state.SetLabel(std::string(hyperboloid ? "tilted hyperboloid" : "sphere") + ", 50 points, " +
    std::to_string(state.range(0)) + " % outliers");
  const Projector proj(model);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<PoseObservation> observations;
  for (const Vec3& p : ScenePoints(model, 50))
  {
    Vec2 pixel = proj.ProjectWorld(p).pixel + Vec2(noise(rng), noise(rng));
    if (observations.size() * 100 < static_cast<std::size_t>(state.range(0)) * 50)
    {
      pixel += Vec2(40.0 * u(rng) + 30.0, 40.0 * u(rng)); // an outlier
    }
    observations.push_back({ pixel, p });
  }
  for (auto _ : state)
  {
    const PoseResult r = EstimatePose(model, observations);
    if (!r.ok)
    {
      state.SkipWithError(r.error.c_str());
      break;
    }
    benchmark::DoNotOptimize(r.worldToCamera.data());
  }
  SetPerItem(state, 1);
}
BENCHMARK(BM_PoseEstimation)
  ->Args({ 0, 0 })
  ->Args({ 30, 0 })
  ->Args({ 30, 1 })
  ->Unit(benchmark::kMillisecond);
} // namespace

BENCHMARK_MAIN();
