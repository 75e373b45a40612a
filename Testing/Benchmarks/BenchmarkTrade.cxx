// The speed/accuracy trade: frames per second of the full per-frame path (FramePipeline:
// projection, lighting with a moving spotlight, painter sort, compositing onto the 1328x1048
// camera frame; median of --frames frames, default 100) against the accuracy of its image of one
// fixed frame, measured against the exact reference renderer (vtkCatadioptricRayTracer) rendering
// the ORIGINAL mesh with the same lights at the same frame position, the same shading and shadow
// settings, onto the same camera frame. Rows:
//  1. the input mesh and the mesh remeshed by vtkCatadioptricRemesher (target areas 1e-4, 1e-5,
//     2e-6 m^2 and pixel tolerances 2, 0.5 px), each with the quartic and the iterative solver
//     (painter, Gouraud, no shadows);
//  2. on the input mesh (quartic solver): painter or depth buffer x flat or Gouraud x shadows off
//     or on;
//  3. the reference renderer's own frame time (median of --frames frames, at most 30, its rays and
//     ray scene kept from frame to frame: only the lights move), shown with error 0 by definition
//     (it is what every row is measured against), and its 1-ray-per-pixel image measured against
//     its own 8 x 8 rays per pixel (the anti-aliasing rows' reference).
// Accuracy (Core catar::CompareImages, Module/Metrics/ImageMetrics.h): silhouette IoU, mean and max
// (Hausdorff) distance between the silhouette boundaries in pixels, PSNR of RGB over the union of
// the silhouettes (dB), SSIM of the luminance over the object's box, and, on the input mesh,
// the pixels whose visible triangle differs from the reference's. The object is the Stanford
// bunny when CATAR_SHARED_DATA names a folder holding stanford-bunny.obj, otherwise a sphere of
// 69,696 triangles. Run:
//   CATAR_SHARED_DATA=../shared/data xvfb-run -a build/bin/BenchmarkTrade [--frames N]
//     [--samples N] [--csv FILE] [--chart FILE.png] [--quick]
// --chart writes a 1000x500 PNG (VTK charts, off screen: needs a display, e.g. xvfb-run): fps
// against the boundary error and against 1 - SSIM, one series per solver, the reference ray
// tracer as points on the same fps axis. --samples N: the
// reference's supersampling (default 1: one ray through each pixel centre, as the rasteriser
// covers pixel centres). --quick (CI smoke) runs one remesh target, 2 frames and fewer
// variants. Speed is never asserted; a failing stage ends the program with status 1.
#include "BenchmarkErrors.h"
#include "BenchmarkScene.h"
#include "BenchmarkTable.h"
#include "FramePipeline.h"

#include "ImageMetrics.h"

#include "vtkAxis.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkChartLegend.h"
#include "vtkChartMatrix.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkFloatArray.h"
#include "vtkLogger.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPNGWriter.h"
#include "vtkPlotPoints.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVector.h"
#include "vtkWindowToImageFilter.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace
{
using namespace catar_benchmark;

/// The frame whose image is compared with the reference (lights a sixth of a turn on).
constexpr int kAccuracyFrame = 20;

/// One rendering kept for comparison: RGBA colours and visible-triangle ids, VTK row order.
struct Rendering
{
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::vector<catar::RasterId> ids;

  catar::ImageInput Input() const
  {
    catar::ImageInput in;
    in.color = catar::ConstImageView{ this->rgba.data(), this->width, this->height,
      static_cast<std::ptrdiff_t>(4) * this->width };
    in.triangleIds = catar::TriangleIdView{ this->ids.data(), this->width, this->height,
      static_cast<std::ptrdiff_t>(this->width) };
    return in;
  }
};

// Copies an RGBA output of the compositor or the ray tracer with its "VisibleTriangle" ids.
Rendering Keep(vtkImageData* image, const std::string& what)
{
  Rendering r;
  int dims[3];
  image->GetDimensions(dims);
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  auto* ids = vtkTypeInt64Array::SafeDownCast(image->GetPointData()->GetArray("VisibleTriangle"));
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1];
  if (dims[0] < 1 || dims[1] < 1 || !rgba || rgba->GetNumberOfComponents() != 4 ||
    rgba->GetNumberOfTuples() != n || !ids || ids->GetNumberOfTuples() != n)
  {
    throw std::runtime_error(what + ": no RGBA image with VisibleTriangle ids");
  }
  r.width = dims[0];
  r.height = dims[1];
  r.rgba.assign(rgba->GetPointer(0), rgba->GetPointer(0) + 4 * n);
  r.ids.resize(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    r.ids[i] = ids->GetValue(i);
  }
  return r;
}

struct Accuracy
{
  double iou = 0, meanBoundary = 0, maxBoundary = 0, psnr = 0, ssim = 0;
  /// Mean |fast - exact| (levels, R G B) over the reference's silhouette edge: the pixels whose
  /// 3 x 3 neighbourhood holds both object and background in the reference's ids.
  double edgeError = 0;
  long long differingTriangles = -1; ///< -1: not comparable (remeshed)
};

double EdgeError(const catar::ImageInput& fast, const catar::ImageInput& exact)
{
  const int w = exact.color.width, h = exact.color.height;
  double sum = 0;
  long long n = 0;
  for (int y = 1; y + 1 < h; ++y)
  {
    for (int x = 1; x + 1 < w; ++x)
    {
      bool object = false, background = false;
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          (exact.triangleIds.at(x + dx, y + dy) >= 0 ? object : background) = true;
        }
      }
      if (!(object && background))
      {
        continue;
      }
      const std::uint8_t* a = fast.color.pixel(x, y);
      const std::uint8_t* b = exact.color.pixel(x, y);
      for (int k = 0; k < 3; ++k)
      {
        sum += std::abs(int(a[k]) - int(b[k]));
      }
      ++n;
    }
  }
  return n ? sum / (3.0 * static_cast<double>(n)) : 0.0;
}

// Silhouettes come from the VisibleTriangle id buffers (id >= 0: the object), so they are the
// virtual object's only, whatever the camera frame under it; both images are composited onto the
// same camera frame, so the pixels outside both silhouettes are identical. The PSNR is therefore
// taken over the union of the silhouettes, and the SSIM over the box of that union grown by 8 px
// (over the whole 1328x1048 image it would be ~1 for every row).
Accuracy Compare(const Rendering& fast, const Rendering& exact, bool trianglesComparable)
{
  catar::CompareOptions options;
  options.psnrOverSilhouette = true;
  const catar::ImageInput a = fast.Input(), b = exact.Input();
  const catar::ImageComparison c = catar::CompareImages(a, b, options);
  if (!c.ok())
  {
    throw std::runtime_error("image comparison failed: " + c.error);
  }
  Accuracy acc;
  acc.iou = c.silhouetteIoU;
  acc.meanBoundary = c.meanBoundaryDistance;
  acc.maxBoundary = c.maxBoundaryDistance;
  acc.psnr = c.psnr;
  acc.edgeError = EdgeError(a, b);
  if (trianglesComparable && c.trianglesCompared)
  {
    acc.differingTriangles = static_cast<long long>(c.differentTrianglePixels);
  }
  int x0 = a.color.width, y0 = a.color.height, x1 = -1, y1 = -1;
  for (int y = 0; y < a.color.height; ++y)
  {
    for (int x = 0; x < a.color.width; ++x)
    {
      if (a.triangleIds.at(x, y) >= 0 || b.triangleIds.at(x, y) >= 0)
      {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
    }
  }
  if (x1 < 0)
  {
    acc.ssim = 1.0; // no object in either image
    return acc;
  }
  const int margin = 8;
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(a.color.width - 1, x1 + margin);
  y1 = std::min(a.color.height - 1, y1 + margin);
  auto crop = [&](const catar::ConstImageView& v) {
    return catar::ConstImageView{ v.pixel(x0, y0), x1 - x0 + 1, y1 - y0 + 1, v.rowStride };
  };
  acc.ssim = catar::ComputeSSIM(crop(a.color), crop(b.color));
  return acc;
}

struct Row
{
  std::string object, configuration;
  vtkIdType triangles = 0;
  std::string solver;
  double frameMs = 0;
  bool hasAccuracy = false;
  Accuracy accuracy;
  int series = 0; ///< chart: 0 quartic remesh rows, 1 iterative remesh rows, 2 variants,
                  ///< 3 adaptive tessellation, 4 anti-aliasing rows (8x8 reference), 5 the
                  ///< reference ray tracer; -1 none
};

std::vector<std::string> Fields(const Row& r)
{
  const Accuracy& a = r.accuracy;
  const bool acc = r.hasAccuracy;
  return { r.object, r.configuration, std::to_string(r.triangles), r.solver,
    Number(r.frameMs, "%.2f"), Number(r.frameMs > 0 ? 1e3 / r.frameMs : 0.0, "%.2f"),
    acc ? Number(a.iou, "%.4f") : "", acc ? Number(a.meanBoundary, "%.3f") : "",
    acc ? Number(a.maxBoundary, "%.2f") : "", acc ? Number(a.psnr, "%.2f") : "",
    acc ? Number(a.ssim, "%.4f") : "", acc ? Number(a.edgeError, "%.2f") : "",
    acc && a.differingTriangles >= 0 ? std::to_string(a.differingTriangles) : "" };
}

const char* const kColumns[] = { "object", "configuration", "triangles", "solver", "frame_ms",
  "fps", "iou", "mean_boundary_px", "max_boundary_px", "psnr_db", "ssim", "edge_error_levels",
  "differing_triangle_pixels" };

void PrintRow(const Row& r)
{
  std::printf("|");
  for (const std::string& f : Fields(r))
  {
    std::printf(" %s |", f.empty() ? "-" : f.c_str());
  }
  std::printf("\n");
  std::fflush(stdout);
}

void WriteCsv(const std::string& file, const std::vector<Row>& rows)
{
  std::vector<std::vector<std::string>> table;
  for (const Row& r : rows)
  {
    table.push_back(Fields(r));
  }
  WriteCsvTable(file, std::vector<std::string>(std::begin(kColumns), std::end(kColumns)), table);
}

// Two panels, fps on x: the mean boundary error (left) and 1 - SSIM (right), one point series
// for each solver over the remeshed meshes, one for the input-mesh variants.
void WriteChart(const std::string& file, const std::vector<Row>& rows, const std::string& object)
{
  vtkNew<vtkContextView> view;
  vtkRenderWindow* window = view->GetRenderWindow();
  if (std::strstr(window->GetClassName(), "XOpenGL") &&
    (!std::getenv("DISPLAY") || !*std::getenv("DISPLAY")))
  {
    throw std::runtime_error("--chart needs an X display for off-screen OpenGL: run under "
                             "xvfb-run -a (" +
      std::string(window->GetClassName()) + ")");
  }
  window->SetOffScreenRendering(1);
  window->SetSize(1000, 500);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartMatrix> matrix;
  view->GetScene()->AddItem(matrix);
  matrix->SetSize(vtkVector2i(2, 1));
  matrix->SetGutter(vtkVector2f(40.0f, 20.0f));

  constexpr int kSeries = 6;
  const char* const seriesNames[kSeries] = { "quartic solver (input + remeshed)",
    "iterative solver (input + remeshed)", "input: depth / flat / shadows variants",
    "adaptive tessellation per frame", "anti-aliasing off / 2x2 / 4x4 (8x8 reference)",
    "exact ray tracer, 1 ray/px (0 by definition; vs 8x8)" };
  const unsigned char seriesColors[kSeries][3] = { { 31, 119, 180 }, { 214, 39, 40 },
    { 90, 90, 90 }, { 44, 160, 44 }, { 148, 103, 189 }, { 255, 127, 14 } };
  const int markers[kSeries] = { vtkPlotPoints::CIRCLE, vtkPlotPoints::DIAMOND, vtkPlotPoints::PLUS,
    vtkPlotPoints::SQUARE, vtkPlotPoints::CROSS, vtkPlotPoints::SQUARE };
  for (int panel = 0; panel < 2; ++panel)
  {
    vtkChartXY* chart = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(panel, 0)));
    if (!chart)
    {
      throw std::runtime_error("chart: no vtkChartXY in the chart matrix");
    }
    chart->SetTitle(panel == 0 ? object + ": silhouette error against speed"
                               : object + ": colour error against speed");
    chart->GetTitleProperties()->SetFontSize(16);
    chart->GetTitleProperties()->SetBold(true);
    chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("frames per second");
    chart->GetAxis(vtkAxis::LEFT)
      ->SetTitle(panel == 0 ? "mean boundary distance (px)" : "1 - SSIM (object box)");
    for (int a : { vtkAxis::BOTTOM, vtkAxis::LEFT })
    {
      chart->GetAxis(a)->GetTitleProperties()->SetFontSize(14);
      chart->GetAxis(a)->GetLabelProperties()->SetFontSize(12);
    }
    chart->SetShowLegend(true);
    chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
    chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
    chart->GetLegend()->GetLabelProperties()->SetFontSize(12);
    double xMin = std::numeric_limits<double>::max(), xMax = 0.0, yMax = 0.0;
    for (int s = 0; s < kSeries; ++s)
    {
      vtkNew<vtkFloatArray> x, y;
      x->SetName("fps");
      y->SetName(panel == 0 ? "mean boundary px" : "1 - SSIM");
      for (const Row& r : rows)
      {
        if (r.series != s || !r.hasAccuracy || r.frameMs <= 0)
        {
          continue;
        }
        const double v = panel == 0 ? r.accuracy.meanBoundary : 1.0 - r.accuracy.ssim;
        if (std::isfinite(v))
        {
          const double fps = 1e3 / r.frameMs;
          x->InsertNextValue(static_cast<float>(fps));
          y->InsertNextValue(static_cast<float>(v));
          xMin = std::min(xMin, fps);
          xMax = std::max(xMax, fps);
          yMax = std::max(yMax, v);
        }
      }
      if (x->GetNumberOfTuples() == 0)
      {
        continue;
      }
      vtkNew<vtkTable> table;
      table->AddColumn(x);
      table->AddColumn(y);
      auto* plot = vtkPlotPoints::SafeDownCast(chart->AddPlot(vtkChart::POINTS));
      if (!plot)
      {
        throw std::runtime_error("chart: cannot add a point plot");
      }
      plot->SetInputData(table, 0, 1);
      plot->SetLabel(seriesNames[s]);
      plot->SetColor(seriesColors[s][0], seriesColors[s][1], seriesColors[s][2], 255);
      plot->SetMarkerStyle(markers[s]);
      plot->SetMarkerSize(s == 1 ? 7.0f : s == 5 ? 13.0f : 12.0f); // iterative inside quartic
    }
    // Fixed ranges: fps on a log scale (the rows span one to two decades), the error from just
    // below 0 (points at 0 stay visible) to well above the largest (room for the legend).
    if (xMax > 0.0)
    {
      vtkAxis* xAxis = chart->GetAxis(vtkAxis::BOTTOM);
      xAxis->SetLogScale(xMax > 4.0 * xMin);
      xAxis->SetBehavior(vtkAxis::FIXED);
      if (xAxis->GetLogScale())
      {
        xAxis->SetUnscaledRange(xMin / 1.25, xMax * 1.25);
      }
      else
      {
        xAxis->SetUnscaledRange(0.0, xMax * 1.1);
      }
      yMax = std::max(yMax, panel == 0 ? 0.01 : 1e-4);
      vtkAxis* yAxis = chart->GetAxis(vtkAxis::LEFT);
      yAxis->SetBehavior(vtkAxis::FIXED);
      yAxis->SetUnscaledRange(-0.03 * yMax, 1.45 * yMax);
    }
  }
  const int errors = Output->Errors;
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkNew<vtkPNGWriter> png;
  png->SetFileName(file.c_str());
  png->SetInputConnection(grab->GetOutputPort());
  png->Write();
  Check("chart " + file, errors, png->GetErrorCode() == 0);
  std::printf("wrote %s\n", file.c_str());
}

const char* SolverName(int solver)
{
  return solver == vtkCatadioptricProjection::QUARTIC ? "quartic" : "iterative";
}

std::string VariantLabel(const FrameOptions& o)
{
  std::string s = o.visibility == vtkCatadioptricCompositor::PAINTER ? "painter" : "depth buffer";
  s += o.shading == vtkCatadioptricLighting::FLAT ? ", flat" : ", gouraud";
  s += o.shadows ? ", shadows" : "";
  s += o.cullBackFaces ? ", back faces culled" : "";
  if (o.adaptive > 0)
  {
    s += ", adaptive " + Number(o.adaptive, "%g") + " px";
  }
  if (o.antialias > 1)
  {
    s += ", antialiased " + std::to_string(o.antialias) + "x" + std::to_string(o.antialias);
  }
  return s;
}

struct Run
{
  vtkCatadioptricCamera* camera;
  vtkImageData* frame;
  vtkPolyData* original;
  int frames;
  int samples;
  // References of kAccuracyFrame, by (shading, shadows, samples per pixel side).
  std::map<std::tuple<int, bool, int>, Rendering> references;

  // The reference image of kAccuracyFrame for these options: the ray tracer on the original mesh
  // with the lighting filter of `pipeline` (its lights already moved to kAccuracyFrame).
  const Rendering& Reference(const FrameOptions& o, FramePipeline& pipeline, int samples)
  {
    const auto key = std::make_tuple(o.shading, o.shadows, samples);
    auto it = this->references.find(key);
    if (it != this->references.end())
    {
      return it->second;
    }
    const int errors = Output->Errors;
    vtkSmartPointer<vtkCatadioptricRayTracer> tracer = this->Tracer(pipeline.GetLighting());
    tracer->SetSamples(samples);
    tracer->OutputVisibleTriangleOn();
    tracer->Update();
    Check("reference ray tracer", errors, tracer->GetNumberOfHits() > 0);
    return this->references.emplace(key, Keep(tracer->GetOutput(), "reference ray tracer"))
      .first->second;
  }

  // Times the fast path on `mesh`, then renders kAccuracyFrame with ids and compares it.
  Row Measure(const std::string& object, const std::string& label, vtkPolyData* mesh,
    const FrameOptions& o, bool trianglesComparable, int series, int referenceSamples = 0)
  {
    Row r;
    r.object = object;
    r.configuration = label;
    r.triangles = mesh->GetNumberOfPolys();
    r.solver = SolverName(o.solver);
    r.series = series;
    int errors = Output->Errors;
    FramePipeline pipeline(mesh, this->camera, this->frame, o);
    MedianFrame(pipeline, this->frames, &r.frameMs);
    Check("fast path (" + label + ")", errors);
    pipeline.GetCompositor()->OutputVisibleTriangleOn();
    pipeline.Frame(kAccuracyFrame);
    Check("fast path image (" + label + ")", errors);
    const Rendering fast = Keep(pipeline.GetOutput(), "compositor");
    const Rendering& exact =
      this->Reference(o, pipeline, referenceSamples > 0 ? referenceSamples : this->samples);
    if (fast.width != exact.width || fast.height != exact.height)
    {
      throw std::runtime_error("the fast path and the reference differ in size");
    }
    r.accuracy = Compare(fast, exact, trianglesComparable);
    r.hasAccuracy = true;
    return r;
  }

  // The reference renderer for the input mesh, lit as `lighting` lights it, at this study's
  // samples per pixel.
  vtkSmartPointer<vtkCatadioptricRayTracer> Tracer(vtkCatadioptricLighting* lighting) const
  {
    auto tracer = vtkSmartPointer<vtkCatadioptricRayTracer>::New();
    tracer->SetCamera(this->camera);
    tracer->SetFrameData(this->frame);
    tracer->AddMeshData(this->original);
    tracer->SetMeshLighting(0, lighting);
    tracer->SetSamples(this->samples);
    return tracer;
  }

  // The reference renderer's own frame time: median of `n` frames (lights moved, camera marked
  // modified: the tracer keeps its rays and ray scene while the camera's model and the mesh are
  // unchanged), Gouraud, no shadows, without ids. Error 0 by definition.
  Row ReferenceSpeed(const std::string& object, int n)
  {
    const int errors = Output->Errors;
    FramePipeline lights(this->original, this->camera, this->frame, FrameOptions());
    vtkSmartPointer<vtkCatadioptricRayTracer> tracer = this->Tracer(lights.GetLighting());
    tracer->Update(); // warm-up: rays back-projected
    std::vector<double> times;
    for (int f = 1; f <= n; ++f)
    {
      lights.MoveLights(f);
      this->camera->Modified();
      const auto t0 = Clock::now();
      tracer->Update();
      times.push_back(Ms(t0, Clock::now()));
    }
    Check("reference ray tracer timing", errors);
    Row r;
    r.object = object;
    r.configuration = "reference ray tracer (" + std::to_string(this->samples) + "x" +
      std::to_string(this->samples) + " samples), gouraud, scene kept; the reference itself";
    r.triangles = this->original->GetNumberOfPolys();
    r.solver = "exact";
    r.frameMs = Median(times);
    r.series = 5;
    r.hasAccuracy = true; // error 0 by definition
    r.accuracy.iou = 1.0;
    r.accuracy.psnr = std::numeric_limits<double>::infinity();
    r.accuracy.ssim = 1.0;
    r.accuracy.differingTriangles = 0;
    return r;
  }
};
} // namespace

int main(int argc, char* argv[])
{
  int frames = 100;
  int samples = 1;
  bool quick = false;
  std::string csv, chart;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--samples") && i + 1 < argc)
    {
      samples = std::min(8, std::max(1, std::atoi(argv[++i])));
    }
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--chart") && i + 1 < argc)
    {
      chart = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else
    {
      std::fprintf(stderr,
        "usage: BenchmarkTrade [--frames N] [--samples N] [--csv FILE] [--chart FILE.png] "
        "[--quick]\n");
      return 2;
    }
  }
  if (quick)
  {
    frames = 2;
  }
  vtkCatadioptricParallel::EnableThreads();
  vtkNew<CountingOutputWindow> output;
  Output = output;
  vtkOutputWindow::SetInstance(output);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // the window above prints instead

  try
  {
    vtkNew<vtkCatadioptricCamera> camera;
    DemoCamera(camera);
    int errors = Output->Errors;
    vtkSmartPointer<vtkImageData> frame = CameraFrame(camera);
    std::string object;
    vtkSmartPointer<vtkPolyData> mesh = BunnyOrSphere(object);
    Check("scene set-up", errors, mesh && mesh->GetNumberOfPolys() > 0);
    Run run{ camera, frame, mesh, frames, samples, {} };

    std::printf("Speed (median of %d frames, 1328x1048) and accuracy of frame %d against the "
                "ray-traced reference of the input mesh (%s):\n\n",
      frames, kAccuracyFrame, object.c_str());
    std::printf(
      "| object | configuration | triangles | solver | frame (ms) | fps | IoU | mean "
      "boundary (px) | max boundary (px) | PSNR (dB) | SSIM | edge error (levels) | "
      "differing-triangle pixels |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);
    std::vector<Row> rows;
    auto add = [&rows](const Row& r) {
      PrintRow(r);
      rows.push_back(r);
    };

    // 1. Remesh targets x solvers (painter, Gouraud, no shadows).
    struct Mesh
    {
      std::string label;
      vtkSmartPointer<vtkPolyData> mesh;
      bool input;
    };
    std::vector<Mesh> meshes{ { "input", mesh, true } };
    const std::vector<double> areas =
      quick ? std::vector<double>{ 1e-4 } : std::vector<double>{ 1e-4, 1e-5, 2e-6 };
    const std::vector<double> tolerances =
      quick ? std::vector<double>{} : std::vector<double>{ 2.0, 0.5 };
    for (int mode = 0; mode < 2; ++mode)
    {
      for (double p : mode == 0 ? areas : tolerances)
      {
        vtkNew<vtkCatadioptricRemesher> remesher;
        remesher->SetInputData(mesh);
        char label[64];
        if (mode == 0)
        {
          remesher->SetModeToTargetArea();
          remesher->SetTargetArea(p);
          std::snprintf(label, sizeof(label), "remesh area %g m^2", p);
        }
        else
        {
          remesher->SetModeToPixelTolerance();
          remesher->SetPixelTolerance(p);
          remesher->SetCamera(camera);
          std::snprintf(label, sizeof(label), "remesh %g px", p);
        }
        errors = Output->Errors;
        remesher->Update();
        Check(label, errors, remesher->GetOutput()->GetNumberOfPolys() > 0);
        vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
        out->ShallowCopy(remesher->GetOutput());
        meshes.push_back({ label, out, false });
      }
    }
    for (const Mesh& m : meshes)
    {
      for (int solver :
        { vtkCatadioptricProjection::QUARTIC, vtkCatadioptricProjection::ITERATIVE })
      {
        FrameOptions o;
        o.solver = solver;
        add(run.Measure(object, m.label + "; " + VariantLabel(o), m.mesh, o, m.input,
          solver == vtkCatadioptricProjection::QUARTIC ? 0 : 1));
      }
    }

    // Back-face culling on the input mesh (closed for the sphere, nearly so for the bunny).
    {
      FrameOptions o;
      o.solver = vtkCatadioptricProjection::ITERATIVE;
      o.cullBackFaces = true;
      add(run.Measure(object, "input; " + VariantLabel(o), mesh, o, true, 2));
    }

    // 2. Input mesh, quartic: painter / depth buffer x flat / Gouraud x shadows off / on (the
    // painter, Gouraud, no-shadow case is the first row above).
    for (bool shadows : { false, true })
    {
      for (int visibility :
        { vtkCatadioptricCompositor::PAINTER, vtkCatadioptricCompositor::DEPTH_BUFFER })
      {
        for (int shading : { vtkCatadioptricLighting::FLAT, vtkCatadioptricLighting::GOURAUD })
        {
          FrameOptions o;
          o.visibility = visibility;
          o.shading = shading;
          o.shadows = shadows;
          const bool baseline = visibility == vtkCatadioptricCompositor::PAINTER &&
            shading == vtkCatadioptricLighting::GOURAUD && !shadows;
          // --quick: only the depth buffer and shadows beside the baseline.
          const bool keep = !quick ||
            (shading == vtkCatadioptricLighting::GOURAUD &&
              (visibility == vtkCatadioptricCompositor::DEPTH_BUFFER) != shadows);
          if (!baseline && keep)
          {
            add(run.Measure(object, "input; " + VariantLabel(o), mesh, o, true, 2));
          }
        }
      }
    }

    // 3. Per-frame adaptive tessellation, on a coarse remesh and on the input (iterative).
    for (const Mesh& m : meshes)
    {
      if (!m.input && m.label != "remesh area 0.0001 m^2")
      {
        continue;
      }
      for (double p : quick ? std::vector<double>{ 1.0 } : std::vector<double>{ 1.0, 0.25 })
      {
        FrameOptions o;
        o.solver = vtkCatadioptricProjection::ITERATIVE;
        o.adaptive = p;
        add(run.Measure(object, m.label + "; " + VariantLabel(o), m.mesh, o, false, 3));
      }
    }

    // 4. Anti-aliasing, against a reference of 8 x 8 samples per pixel (the rows without it
    // again, for comparison).
    for (int aa : quick ? std::vector<int>{ 1, 4 } : std::vector<int>{ 1, 2, 4 })
    {
      FrameOptions o;
      o.solver = vtkCatadioptricProjection::ITERATIVE;
      o.antialias = aa;
      add(run.Measure(
        object, "input; " + VariantLabel(o) + "; reference 8x8 samples", mesh, o, false, 4, 8));
    }

    // 5. The reference renderer's own speed (error 0 by definition), and its image at this
    // study's samples against its own 8 x 8 (the anti-aliasing rows' reference).
    const Row reference = run.ReferenceSpeed(object, quick ? 2 : std::min(frames, 30));
    add(reference);
    {
      const auto exact =
        run.references.find(std::make_tuple(int(vtkCatadioptricLighting::GOURAUD), false, samples));
      const auto fine =
        run.references.find(std::make_tuple(int(vtkCatadioptricLighting::GOURAUD), false, 8));
      if (exact != run.references.end() && fine != run.references.end() && samples != 8)
      {
        Row r = reference;
        r.configuration = "reference ray tracer (" + std::to_string(samples) + "x" +
          std::to_string(samples) + " samples), gouraud, scene kept; reference 8x8 samples";
        r.accuracy = Compare(exact->second, fine->second, false);
        add(r);
      }
    }
    for (const auto& reference : run.references)
    {
      if (std::get<2>(reference.first) != samples)
      {
        continue;
      }
      const std::vector<catar::RasterId>& ids = reference.second.ids;
      std::printf("\nThe reference's silhouette covers %lld pixels.\n",
        static_cast<long long>(
          std::count_if(ids.begin(), ids.end(), [](catar::RasterId id) { return id >= 0; })));
      break; // the same in every reference
    }

    if (!csv.empty())
    {
      WriteCsv(csv, rows);
    }
    if (!chart.empty())
    {
      WriteChart(chart, rows, object);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "BenchmarkTrade: %s\n", e.what());
    vtkOutputWindow::SetInstance(nullptr);
    return 1;
  }
  vtkOutputWindow::SetInstance(nullptr);
  return 0;
}
