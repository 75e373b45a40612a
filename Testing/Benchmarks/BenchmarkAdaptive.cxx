// Per-frame adaptive tessellation against pre-processing remeshing, along a path through the
// mirror's magnifying zones. Objects: the paper's raw 12-triangle box (30 x 12 x 9 cm, the demo's)
// and, when CATAR_SHARED_DATA names a folder holding stanford-bunny.obj, the raw Stanford bunny
// (69,451 triangles; skipped without it). Each object is moved (translated, never turned) through
// --placements places (default 8) from near the sphere's limb, where the mirror compresses the
// image radially, towards the region behind the camera, where it magnifies most, coming closer to
// the mirror on the way: its centre at world (d sin a, -d cos a, 0.9) m (the mirror's centre is
// (0, 0, 1), the camera at (0, -0.14, 1) looks along +y), d the horizontal distance from the
// mirror's centre going from 0.50 to 0.25 m (--distances), a the horizontal angle from the axis
// back past the camera going from 135 to 10 degrees (--angles; the limb reflects about 159). The
// path table gives, per place, the image's largest and smallest stretch at the object's centre
// (singular values of the pixel's derivative against the world point, px per mm) and their product,
// the object's size in the image (the reference's silhouette, pixels and box) and the largest edge
// bend of the raw mesh there.
//
// Configurations, each rendered at every place:
//  - "adaptive P": the raw mesh, vtkCatadioptricProjection::AdaptiveTolerance = P pixels
//    (P = off, 4, 1, 0.5, 0.25): the triangles whose edges bend more than P px in this frame's
//    image are split, every frame;
//  - "remesh P @first": the raw mesh remeshed ONCE by vtkCatadioptricRemesher in PIXEL_TOLERANCE
//    mode at P pixels for the FIRST place (as a user preparing the mesh for where it starts
//    would), then moved along the same path as it is (adaptive off).
// Every configuration keeps the default BoundaryTolerance (0.25 px), so "split" would count
// triangles cut at the visibility boundary too (none cross it on the default path).
//
// Per place and configuration: triangles drawn (the projection's output cells), input triangles
// the projection split, the projection's time and the frame time (projection + painter sort +
// compositing onto the 1328 x 1048 camera frame, unlit; median of --frames frames, default 30,
// fewer (at least 5) when a row has taken --max-seconds, default 1; the camera marked modified
// every frame so that projection and tessellation run again; --solver picks the projection's
// solver, default quartic, the filter's default), the largest edge bend of the drawn triangles
// (pixels, catar::EdgeBendPixels at the midpoint, as the tessellation and the remesher measure
// it), and the silhouette error against vtkCatadioptricRayTracer rendering the RAW mesh at the
// same place (one ray per pixel centre; catar::CompareImages on the visible-triangle ids: IoU,
// mean and max (Hausdorff) boundary distance in pixels; both images cropped to the union of the
// silhouettes grown by 8 px, which leaves these numbers unchanged), and the hole pixels: pixels
// the reference covers that the fast image leaves uncovered and enclosed (cracks between
// triangles, e.g. at the T-junctions a split triangle leaves beside an unsplit one).
// Printed: the path, a summary per object and configuration (mean and worst over the path), and
// per-place tables of triangles, frame time, edge bend and boundary errors; --rows prints every
// row, and --csv FILE writes them all.
//
//   CATAR_SHARED_DATA=../shared/data build/bin/BenchmarkAdaptive [--placements N] [--frames N]
//     [--max-seconds S] [--solver quartic|iterative] [--angles FROM TO] [--distances FROM TO]
//     [--object box|bunny] [--csv FILE] [--rows] [--path-only] [--quick]
//
// --path-only prints the path table and stops. --quick (CI smoke): 2 places, tolerance 1 px
// only, 2 frames. Speed is never asserted; a VTK error ends the program with status 1.
#include "BenchmarkErrors.h"
#include "BenchmarkScene.h"
#include "BenchmarkTable.h"
#include "FramePipeline.h" // Clock, Ms, Median, CameraFrame, CsvField

#include "EdgeBend.h"
#include "ImageMetrics.h"
#include "Projector.h"

#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkLogger.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>

namespace
{
using namespace catar_benchmark;

constexpr double kPi = 3.14159265358979323846;

vtkSmartPointer<vtkPolyData> Translated(vtkPolyData* mesh, const double d[3])
{
  vtkNew<vtkTransform> t;
  t->Translate(d);
  vtkNew<vtkTransformPolyDataFilter> xf;
  xf->SetTransform(t);
  xf->SetInputData(mesh);
  xf->Update();
  return xf->GetOutput();
}

// The objects centred at the origin (the box turned 30 degrees about z, as the demo has it).
vtkSmartPointer<vtkPolyData> Centred(vtkPolyData* placed)
{
  double b[6];
  placed->GetBounds(b);
  const double d[3] = { -0.5 * (b[0] + b[1]), -0.5 * (b[2] + b[3]), -0.5 * (b[4] + b[5]) };
  return Translated(placed, d);
}

/// One place on the path: the object's centre `distance` (horizontally) from the mirror's centre,
/// `angle` degrees (horizontally) from the axis that points from the mirror back past the camera
/// (0: straight behind the camera, where the mirror magnifies most; the limb reflects about 159
/// degrees), turned towards +x, 10 cm below the mirror's centre (so that the objects pass under
/// the camera).
struct Placement
{
  double angle = 0, distance = 0;
  double centre[3] = { 0, 0, 0 };
  double scaleMax = 0, scaleMin = 0; ///< ImageScales at the centre, pixels per mm
  long long pixels = 0;              ///< the reference's silhouette
  int boxW = 0, boxH = 0;            ///< its bounding box, pixels
  double rawBend = 0;                ///< the raw mesh's largest edge bend here, pixels
};

/// The image's scale at world point c, pixels per mm: the singular values of the 2x3 Jacobian of
/// the pixel against the world point (central differences, 0.1 mm), largest and smallest: how
/// much the mirror stretches the image there in its most and least magnified directions (the
/// least is the radial one, the one the limb compresses). -1 where c or a moved point is not seen.
void ImageScales(const catar::Projector& projector, const double c[3], double& big, double& small)
{
  big = small = -1.0;
  const double h = 1e-4;
  double j[2][3];
  for (int a = 0; a < 3; ++a)
  {
    catar::Vec3 p(c[0], c[1], c[2]), q(c[0], c[1], c[2]);
    p[a] += h;
    q[a] -= h;
    const catar::ProjectedPoint pp = projector.ProjectWorld(p), qq = projector.ProjectWorld(q);
    if (!catar::HasProjection(pp.status) || !catar::HasProjection(qq.status))
    {
      return;
    }
    for (int r = 0; r < 2; ++r)
    {
      j[r][a] = (pp.pixel[r] - qq.pixel[r]) / (2.0 * h) * 1e-3; // px per mm
    }
  }
  // Eigenvalues of J J^T (2x2, symmetric).
  double m[3] = { 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    m[0] += j[0][a] * j[0][a];
    m[1] += j[0][a] * j[1][a];
    m[2] += j[1][a] * j[1][a];
  }
  const double mean = 0.5 * (m[0] + m[2]);
  const double d = std::sqrt(0.25 * (m[0] - m[2]) * (m[0] - m[2]) + m[1] * m[1]);
  big = std::sqrt(mean + d);
  small = std::sqrt(std::max(0.0, mean - d));
}

std::vector<Placement> Path(int n, double angle0, double angle1, double distance0, double distance1,
  const catar::Projector& projector)
{
  std::vector<Placement> path(n);
  for (int k = 0; k < n; ++k)
  {
    const double s = n > 1 ? static_cast<double>(k) / (n - 1) : 0.0;
    Placement& p = path[k];
    p.angle = angle0 + s * (angle1 - angle0);
    p.distance = distance0 + s * (distance1 - distance0);
    const double a = p.angle * kPi / 180.0;
    // The mirror's centre is world (0, 0, 1); the camera looks along +y from (0, -0.14, 1).
    p.centre[0] = p.distance * std::sin(a);
    p.centre[1] = -p.distance * std::cos(a);
    p.centre[2] = 1.0 - 0.1;
    ImageScales(projector, p.centre, p.scaleMax, p.scaleMin);
  }
  return path;
}

/// Largest edge bend (pixels) over the edges of the mesh's visible polygons (cell data Visible
/// when the mesh has it), each edge of each polygon, on the threads.
double MaximumBend(vtkPolyData* mesh, const catar::Projector& projector)
{
  vtkCellArray* polys = mesh->GetPolys();
  const vtkIdType n = polys->GetNumberOfCells();
  auto* visible = vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetArray("Visible"));
  const vtkIdType firstPoly = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  vtkSMPThreadLocal<double> worst(0.0);
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    double& w = worst.Local();
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    for (vtkIdType c = begin; c < end; ++c)
    {
      if (visible && visible->GetValue(firstPoly + c) == 0)
      {
        continue;
      }
      it->GetCellAtId(c, npts, ids);
      for (vtkIdType k = 0; k < npts; ++k)
      {
        catar::Vec3 a, b;
        mesh->GetPoint(ids[k], a.data());
        mesh->GetPoint(ids[(k + 1) % npts], b.data());
        w = std::max(w, catar::EdgeBendPixels(projector, a, b));
      }
    }
  });
  double result = 0.0;
  for (double w : worst)
  {
    result = std::max(result, w);
  }
  return result;
}

/// A rendering's visible-triangle ids (-1: none), VTK row order.
struct Ids
{
  int width = 0, height = 0;
  std::vector<catar::RasterId> ids;
};

Ids Keep(vtkImageData* image, const std::string& what)
{
  int dims[3];
  image->GetDimensions(dims);
  auto* ids = vtkTypeInt64Array::SafeDownCast(image->GetPointData()->GetArray("VisibleTriangle"));
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1];
  if (dims[0] < 1 || dims[1] < 1 || !ids || ids->GetNumberOfTuples() != n)
  {
    throw std::runtime_error(what + ": no VisibleTriangle ids");
  }
  Ids r;
  r.width = dims[0];
  r.height = dims[1];
  r.ids.assign(ids->GetPointer(0), ids->GetPointer(0) + n);
  return r;
}

struct Accuracy
{
  double iou = 0, meanBoundary = 0, maxBoundary = 0;
  long long holes = 0; ///< reference pixels inside an enclosed hole of the fast image
};

// Silhouettes from the ids (id >= 0: the object), so the colours do not matter: CompareImages is
// given the same blank colour image for both. Both are cropped to the box of the union of the
// silhouettes grown by 8 px (clipped to the image): every pixel at the crop's edge is outside
// both silhouettes or on the image's edge, so the boundaries, IoU and distances are those of the
// whole images. Holes: the pixels the reference covers that the fast image leaves uncovered and
// enclosed (not 4-connected through uncovered pixels to the crop's edge): cracks between
// triangles, which the boundary distances count as far-off boundary pixels.
Accuracy Compare(const Ids& fast, const Ids& exact)
{
  if (fast.width != exact.width || fast.height != exact.height)
  {
    throw std::runtime_error("the fast path and the reference differ in size");
  }
  const int w = fast.width, h = fast.height;
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (fast.ids[i] >= 0 || exact.ids[i] >= 0)
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
    return Accuracy{ 1.0, 0.0, 0.0, 0 }; // neither shows the object
  }
  const int margin = 8;
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(w - 1, x1 + margin);
  y1 = std::min(h - 1, y1 + margin);
  const int cw = x1 - x0 + 1, ch = y1 - y0 + 1;
  std::vector<std::uint8_t> blank(static_cast<std::size_t>(4) * cw * ch, 0);
  auto input = [&](const Ids& r) {
    catar::ImageInput in;
    in.color = catar::ConstImageView{ blank.data(), cw, ch, static_cast<std::ptrdiff_t>(4) * cw };
    in.triangleIds = catar::TriangleIdView{ const_cast<catar::RasterId*>(
                                              r.ids.data() + static_cast<std::size_t>(y0) * w + x0),
      cw, ch, static_cast<std::ptrdiff_t>(w) };
    return in;
  };
  const catar::ImageComparison c = catar::CompareImages(input(fast), input(exact));
  if (!c.ok())
  {
    throw std::runtime_error("image comparison failed: " + c.error);
  }
  Accuracy acc{ c.silhouetteIoU, c.meanBoundaryDistance, c.maxBoundaryDistance, 0 };

  auto covered = [&](const Ids& r, int x, int y) {
    return r.ids[static_cast<std::size_t>(y0 + y) * w + x0 + x] >= 0;
  };
  std::vector<std::uint8_t> outside(static_cast<std::size_t>(cw) * ch, 0);
  std::vector<std::pair<int, int>> stack;
  auto reach = [&](int x, int y) {
    if (x >= 0 && y >= 0 && x < cw && y < ch && !outside[static_cast<std::size_t>(y) * cw + x] &&
      !covered(fast, x, y))
    {
      outside[static_cast<std::size_t>(y) * cw + x] = 1;
      stack.emplace_back(x, y);
    }
  };
  for (int x = 0; x < cw; ++x)
  {
    reach(x, 0);
    reach(x, ch - 1);
  }
  for (int y = 0; y < ch; ++y)
  {
    reach(0, y);
    reach(cw - 1, y);
  }
  while (!stack.empty())
  {
    const auto [x, y] = stack.back();
    stack.pop_back();
    reach(x - 1, y);
    reach(x + 1, y);
    reach(x, y - 1);
    reach(x, y + 1);
  }
  for (int y = 0; y < ch; ++y)
  {
    for (int x = 0; x < cw; ++x)
    {
      if (!outside[static_cast<std::size_t>(y) * cw + x] && !covered(fast, x, y) &&
        covered(exact, x, y))
      {
        ++acc.holes;
      }
    }
  }
  return acc;
}

/// Projection -> painter sort -> compositor onto the camera frame, unlit (solid colour): the
/// stages whose cost the tessellation changes.
class Pipeline
{
public:
  Pipeline(vtkCatadioptricCamera* camera, vtkImageData* frame, double adaptive, int solver)
    : Camera(camera)
  {
    this->Projection->SetCamera(camera);
    this->Projection->SetSolver(solver);
    this->Projection->SetAdaptiveTolerance(adaptive);
    this->Sort->SetInputConnection(this->Projection->GetOutputPort());
    this->Sort->DropInvisibleCellsOn();
    this->Compositor->SetFrameData(frame);
    this->Compositor->AddMeshConnection(this->Sort->GetOutputPort());
  }

  /// One frame, the camera marked modified first: {projection ms, projection + sort +
  /// compositing ms}.
  std::pair<double, double> Frame()
  {
    this->Camera->Modified();
    const auto t0 = Clock::now();
    this->Projection->Update();
    const auto t1 = Clock::now();
    this->Sort->Update();
    this->Compositor->Update();
    const auto t2 = Clock::now();
    return { Ms(t0, t1), Ms(t0, t2) };
  }

  vtkCatadioptricCamera* Camera;
  vtkNew<vtkCatadioptricProjection> Projection;
  vtkNew<vtkCatadioptricPainterSort> Sort;
  vtkNew<vtkCatadioptricCompositor> Compositor;
};

struct Row
{
  std::string object, configuration;
  int placement = 0;
  double angle = 0, distance = 0, scaleMax = 0, scaleMin = 0;
  vtkIdType inputTriangles = 0; ///< the mesh given to the projection
  vtkIdType triangles = 0;      ///< the projection's output cells
  vtkIdType split = 0;          ///< triangles the projection split
  vtkIdType rasterised = 0;     ///< triangles the compositor drew (visible ones)
  int frames = 0;               ///< frames timed
  double projectionMs = 0, frameMs = 0, bend = 0, prepMs = 0;
  Accuracy accuracy;
};

const char* const kColumns[] = { "object", "configuration", "placement", "angle_deg", "distance_m",
  "scale_max_px_per_mm", "scale_min_px_per_mm", "input_triangles", "triangles", "split_triangles",
  "rasterised_triangles", "projection_ms", "frame_ms", "max_bend_px", "iou", "mean_boundary_px",
  "max_boundary_px", "hole_px", "remesh_ms", "frames" };

std::vector<std::string> Fields(const Row& r)
{
  return { r.object, r.configuration, std::to_string(r.placement), Number(r.angle, "%.1f"),
    Number(r.distance, "%.3f"), Number(r.scaleMax, "%.3f"), Number(r.scaleMin, "%.3f"),
    std::to_string(r.inputTriangles), std::to_string(r.triangles), std::to_string(r.split),
    std::to_string(r.rasterised), Number(r.projectionMs, "%.3f"), Number(r.frameMs, "%.3f"),
    Number(r.bend, "%.3f"), Number(r.accuracy.iou, "%.4f"), Number(r.accuracy.meanBoundary, "%.3f"),
    Number(r.accuracy.maxBoundary, "%.2f"), std::to_string(r.accuracy.holes),
    r.prepMs > 0 ? Number(r.prepMs, "%.1f") : "", std::to_string(r.frames) };
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

struct Config
{
  std::string label;
  double adaptive = 0;                   ///< px, 0: off
  vtkSmartPointer<vtkPolyData> remeshed; ///< centred at the origin; null: the raw mesh
  double remeshMs = 0;
};

// Mean and largest of `f` over the rows.
template<typename F>
std::pair<double, double> MeanMax(const std::vector<const Row*>& rows, F f)
{
  double sum = 0, worst = -std::numeric_limits<double>::infinity();
  for (const Row* r : rows)
  {
    sum += f(*r);
    worst = std::max(worst, f(*r));
  }
  return { rows.empty() ? 0.0 : sum / rows.size(), worst };
}

void PrintSummary(const std::vector<Row>& rows, const std::vector<std::string>& order)
{
  std::printf("\nOver the path (mean / worst of the placements):\n\n"
              "| object | configuration | remesh (ms) | triangles | split | frame (ms) | max bend "
              "(px) | IoU | mean boundary (px) | max boundary (px) | hole pixels |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> objects;
  for (const Row& r : rows)
  {
    if (std::find(objects.begin(), objects.end(), r.object) == objects.end())
    {
      objects.push_back(r.object);
    }
  }
  for (const std::string& object : objects)
  {
    for (const std::string& config : order)
    {
      std::vector<const Row*> sel;
      for (const Row& r : rows)
      {
        if (r.object == object && r.configuration == config)
        {
          sel.push_back(&r);
        }
      }
      if (sel.empty())
      {
        continue;
      }
      const auto tri = MeanMax(sel, [](const Row& r) { return double(r.triangles); });
      const auto split = MeanMax(sel, [](const Row& r) { return double(r.split); });
      const auto frame = MeanMax(sel, [](const Row& r) { return r.frameMs; });
      const auto bend = MeanMax(sel, [](const Row& r) { return r.bend; });
      const auto iou = MeanMax(sel, [](const Row& r) { return -r.accuracy.iou; });
      const auto mean = MeanMax(sel, [](const Row& r) { return r.accuracy.meanBoundary; });
      const auto max = MeanMax(sel, [](const Row& r) { return r.accuracy.maxBoundary; });
      const auto holes = MeanMax(sel, [](const Row& r) { return double(r.accuracy.holes); });
      std::printf("| %s | %s | %s | %.0f / %.0f | %.0f / %.0f | %.2f / %.2f | %.3f / %.3f | "
                  "%.4f / %.4f | %s / %s | %s / %s | %.1f / %.0f |\n",
        object.c_str(), config.c_str(),
        sel.front()->prepMs > 0 ? Number(sel.front()->prepMs, "%.0f").c_str() : "-", tri.first,
        tri.second, split.first, split.second, frame.first, frame.second, bend.first, bend.second,
        -iou.first, -iou.second, Number(mean.first, "%.3f").c_str(),
        Number(mean.second, "%.3f").c_str(), Number(max.first, "%.2f").c_str(),
        Number(max.second, "%.2f").c_str(), holes.first, holes.second);
    }
  }
  std::fflush(stdout);
}

// One table per quantity: a row per configuration, a column per placement.
void PrintMatrix(const std::vector<Row>& rows, const std::string& object,
  const std::vector<std::string>& order, int placements, const char* title,
  std::string (*cell)(const Row&))
{
  std::printf("\n%s, %s:\n\n| configuration |", object.c_str(), title);
  for (int k = 0; k < placements; ++k)
  {
    std::printf(" %d |", k);
  }
  std::printf("\n|---|");
  for (int k = 0; k < placements; ++k)
  {
    std::printf("---|");
  }
  std::printf("\n");
  for (const std::string& config : order)
  {
    std::vector<const Row*> sel(placements, nullptr);
    bool any = false;
    for (const Row& r : rows)
    {
      if (r.object == object && r.configuration == config && r.placement < placements)
      {
        sel[r.placement] = &r;
        any = true;
      }
    }
    if (!any)
    {
      continue;
    }
    std::printf("| %s |", config.c_str());
    for (const Row* r : sel)
    {
      std::printf(" %s |", r ? cell(*r).c_str() : "-");
    }
    std::printf("\n");
  }
  std::fflush(stdout);
}

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
} // namespace

int main(int argc, char* argv[])
{
  int placements = 8;
  int frames = 30;
  double maxSeconds = 1.0;
  int solver = vtkCatadioptricProjection::QUARTIC;
  bool quick = false, printRows = false, pathOnly = false;
  double angles[2] = { 135.0, 10.0 };
  double distances[2] = { 0.50, 0.25 };
  std::string csv, only;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--placements") && i + 1 < argc)
    {
      placements = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--max-seconds") && i + 1 < argc)
    {
      maxSeconds = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--solver") && i + 1 < argc &&
      (!std::strcmp(argv[i + 1], "quartic") || !std::strcmp(argv[i + 1], "iterative")))
    {
      solver = !std::strcmp(argv[++i], "quartic") ? vtkCatadioptricProjection::QUARTIC
                                                  : vtkCatadioptricProjection::ITERATIVE;
    }
    else if (!std::strcmp(argv[i], "--angles") && i + 2 < argc)
    {
      angles[0] = std::atof(argv[++i]);
      angles[1] = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--distances") && i + 2 < argc)
    {
      distances[0] = std::atof(argv[++i]);
      distances[1] = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--object") && i + 1 < argc)
    {
      only = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--rows"))
    {
      printRows = true;
    }
    else if (!std::strcmp(argv[i], "--path-only"))
    {
      pathOnly = true;
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else
    {
      std::fprintf(stderr,
        "usage: BenchmarkAdaptive [--placements N] [--frames N] [--max-seconds S] "
        "[--solver quartic|iterative] [--angles FROM TO] "
        "[--distances FROM TO] [--object box|bunny] [--csv FILE] [--rows] [--path-only] "
        "[--quick]\n");
      return 2;
    }
  }
  if (quick)
  {
    placements = 2;
    frames = 2;
  }
  vtkCatadioptricParallel::EnableThreads();
  vtkNew<CountingOutputWindow> output;
  output->PrintWarnings = false; // the bunny's repairs, repeated for every remesh
  Output = output;
  vtkOutputWindow::SetInstance(output);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // the window above prints errors

  try
  {
    vtkNew<vtkCatadioptricCamera> camera;
    DemoCamera(camera);
    const catar::Projector projector(camera->GetModel());
    int errors = Output->Errors;
    vtkSmartPointer<vtkImageData> frame = CameraFrame(camera);
    Check("camera frame", errors);

    std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> objects;
    if (only.empty() || only == "box")
    {
      objects.emplace_back("box", Centred(PaperBox()));
    }
    if (only.empty() || only == "bunny")
    {
      if (vtkSmartPointer<vtkPolyData> bunny = SharedBunny())
      {
        objects.emplace_back("bunny", Centred(bunny));
      }
      else
      {
        std::printf("(no CATAR_SHARED_DATA/stanford-bunny.obj: the bunny is skipped)\n");
      }
    }
    Check("objects", errors);
    if (objects.empty())
    {
      throw std::runtime_error("no object: --object names box or bunny");
    }
    const std::vector<Placement> path0 =
      Path(placements, angles[0], angles[1], distances[0], distances[1], projector);
    const std::vector<double> tolerances =
      quick ? std::vector<double>{ 1.0 } : std::vector<double>{ 4.0, 1.0, 0.5, 0.25 };
    std::vector<std::string> order{ "adaptive off" };
    for (double p : tolerances)
    {
      order.push_back("adaptive " + Number(p, "%g") + " px");
    }
    for (double p : tolerances)
    {
      order.push_back("remesh " + Number(p, "%g") + " px @first");
    }

    std::printf("The path: the object's centre at (d sin a, -d cos a, 0.9) m, the mirror's centre "
                "at (0, 0, 1), the camera at (0, -0.14, 1) looking along +y: d the horizontal "
                "distance from the mirror's centre, a the horizontal angle from the axis back past "
                "the camera (0: behind the camera; the limb reflects about 159 deg). Scale: the "
                "image's largest and "
                "smallest stretch at the centre (singular values of the pixel's derivative against "
                "the point; the smallest is the radial one the limb compresses) and their product; "
                "size: the reference's silhouette; raw bend: the largest edge bend of "
                "the raw mesh there. Frame: projection + painter sort + compositing onto the "
                "1328x1048 camera frame, median of up to %d frames (%s solver).\n\n",
      frames, solver == vtkCatadioptricProjection::QUARTIC ? "quartic" : "iterative");
    std::printf("| object | placement | a (deg) | d (m) | centre (m) | scale max / min "
                "(px/mm) | area scale (px^2/mm^2) | silhouette (px) | box (px) | raw bend (px) |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);

    struct ObjectRun
    {
      std::string name;
      vtkSmartPointer<vtkPolyData> home;
      std::vector<Placement> path;
      std::vector<vtkSmartPointer<vtkPolyData>> placed;
      std::vector<Ids> references;
    };
    std::vector<ObjectRun> runs;
    vtkNew<vtkCatadioptricRayTracer> tracer;
    tracer->SetCamera(camera);
    tracer->SetFrameData(frame);
    tracer->OutputVisibleTriangleOn();
    for (const auto& object : objects)
    {
      ObjectRun run{ object.first, object.second, path0, {}, {} };
      for (int k = 0; k < placements; ++k)
      {
        Placement& p = run.path[k];
        run.placed.push_back(Translated(run.home, p.centre));
        errors = Output->Errors;
        tracer->RemoveAllMeshConnections();
        tracer->AddMeshData(run.placed.back());
        tracer->Update();
        Check("reference ray tracer", errors);
        run.references.push_back(Keep(tracer->GetOutput(), "reference ray tracer"));
        const Ids& ref = run.references.back();
        int x0 = ref.width, y0 = ref.height, x1 = -1, y1 = -1;
        for (int y = 0; y < ref.height; ++y)
        {
          for (int x = 0; x < ref.width; ++x)
          {
            if (ref.ids[static_cast<std::size_t>(y) * ref.width + x] >= 0)
            {
              ++p.pixels;
              x0 = std::min(x0, x);
              x1 = std::max(x1, x);
              y0 = std::min(y0, y);
              y1 = std::max(y1, y);
            }
          }
        }
        p.boxW = x1 >= 0 ? x1 - x0 + 1 : 0;
        p.boxH = x1 >= 0 ? y1 - y0 + 1 : 0;
        p.rawBend = MaximumBend(run.placed.back(), projector);
        std::printf("| %s | %d | %.1f | %.3f | (%.3f, %.3f, %.3f) | %.3f / %.3f | %.3f | %lld | "
                    "%dx%d | %.3f |\n",
          run.name.c_str(), k, p.angle, p.distance, p.centre[0], p.centre[1], p.centre[2],
          p.scaleMax, p.scaleMin, p.scaleMax * p.scaleMin, p.pixels, p.boxW, p.boxH, p.rawBend);
        std::fflush(stdout);
      }
      runs.push_back(std::move(run));
    }
    if (pathOnly)
    {
      vtkOutputWindow::SetInstance(nullptr);
      return 0;
    }

    std::vector<Row> rows;
    if (printRows)
    {
      std::printf("\n|");
      for (const char* c : kColumns)
      {
        std::printf(" %s |", c);
      }
      std::printf("\n|");
      for (std::size_t k = 0; k < std::size(kColumns); ++k)
      {
        std::printf("---|");
      }
      std::printf("\n");
    }
    for (ObjectRun& run : runs)
    {
      std::vector<Config> configs{ { "adaptive off", 0.0, nullptr, 0.0 } };
      for (double p : tolerances)
      {
        configs.push_back({ "adaptive " + Number(p, "%g") + " px", p, nullptr, 0.0 });
      }
      for (double p : tolerances)
      {
        vtkNew<vtkCatadioptricRemesher> remesher;
        remesher->SetInputData(run.placed[0]);
        remesher->SetModeToPixelTolerance();
        remesher->SetPixelTolerance(p);
        remesher->SetCamera(camera);
        errors = Output->Errors;
        const auto t0 = Clock::now();
        remesher->Update();
        const double ms = Ms(t0, Clock::now());
        Check("remesh " + run.name, errors, remesher->GetOutput()->GetNumberOfPolys() > 0);
        const double back[3] = { -run.path[0].centre[0], -run.path[0].centre[1],
          -run.path[0].centre[2] };
        configs.push_back({ "remesh " + Number(p, "%g") + " px @first", 0.0,
          Translated(remesher->GetOutput(), back), ms });
      }
      // Every configuration's pipeline at once: at each place their frames are interleaved in
      // blocks of kBlock, so that a change in the machine's speed (it is shared) touches them all
      // alike.
      constexpr int kBlock = 5;
      const std::size_t nc = configs.size();
      std::vector<std::unique_ptr<Pipeline>> pipelines;
      for (const Config& config : configs)
      {
        pipelines.push_back(std::make_unique<Pipeline>(camera, frame, config.adaptive, solver));
      }
      for (int k = 0; k < placements; ++k)
      {
        const Placement& p = run.path[k];
        std::vector<vtkSmartPointer<vtkPolyData>> meshes(nc);
        errors = Output->Errors;
        for (std::size_t c = 0; c < nc; ++c)
        {
          meshes[c] =
            configs[c].remeshed ? Translated(configs[c].remeshed, p.centre) : run.placed[k];
          pipelines[c]->Projection->SetInputData(meshes[c]);
          pipelines[c]->Frame(); // warm-up
        }
        Check(run.name + " at place " + std::to_string(k), errors);
        std::vector<std::vector<double>> projection(nc), total(nc);
        const auto start = Clock::now();
        for (int done = 0; done < frames;)
        {
          for (std::size_t c = 0; c < nc; ++c)
          {
            for (int b = 0; b < kBlock && done + b < frames; ++b)
            {
              const auto t = pipelines[c]->Frame();
              projection[c].push_back(t.first);
              total[c].push_back(t.second);
            }
          }
          done += kBlock;
          if (done >= 5 && Ms(start, Clock::now()) > 1e3 * maxSeconds * nc)
          {
            break;
          }
        }
        Check(run.name + " at place " + std::to_string(k), errors);
        for (std::size_t c = 0; c < nc; ++c)
        {
          const Config& config = configs[c];
          Pipeline& pipeline = *pipelines[c];
          Row r;
          r.object = run.name;
          r.configuration = config.label;
          r.placement = k;
          r.angle = p.angle;
          r.distance = p.distance;
          r.scaleMax = p.scaleMax;
          r.scaleMin = p.scaleMin;
          r.inputTriangles = meshes[c]->GetNumberOfPolys();
          r.triangles = pipeline.Projection->GetOutput()->GetNumberOfPolys();
          r.split = pipeline.Projection->GetNumberOfSplitTriangles();
          r.rasterised = pipeline.Compositor->GetNumberOfDrawnTriangles();
          r.frames = static_cast<int>(total[c].size());
          r.projectionMs = Median(projection[c]);
          r.frameMs = Median(total[c]);
          r.prepMs = config.remeshMs;
          r.bend = MaximumBend(pipeline.Projection->GetOutput(), projector);
          pipeline.Compositor->OutputVisibleTriangleOn();
          pipeline.Frame();
          Check(run.name + ", " + config.label + " (ids)", errors);
          r.accuracy =
            Compare(Keep(pipeline.Compositor->GetOutput(), "compositor"), run.references[k]);
          pipeline.Compositor->OutputVisibleTriangleOff();
          if (printRows)
          {
            PrintRow(r);
          }
          rows.push_back(r);
        }
      }
    }

    PrintSummary(rows, order);
    for (const ObjectRun& run : runs)
    {
      PrintMatrix(rows, run.name, order, placements, "triangles drawn per placement",
        [](const Row& r) { return std::to_string(r.triangles); });
      PrintMatrix(rows, run.name, order, placements, "frame (ms) per placement",
        [](const Row& r) { return Number(r.frameMs, "%.2f"); });
      PrintMatrix(rows, run.name, order, placements, "largest edge bend drawn (px) per placement",
        [](const Row& r) { return Number(r.bend, "%.2f"); });
      PrintMatrix(rows, run.name, order, placements, "mean boundary distance (px) per placement",
        [](const Row& r) { return Number(r.accuracy.meanBoundary, "%.3f"); });
      PrintMatrix(rows, run.name, order, placements, "max boundary distance (px) per placement",
        [](const Row& r) { return Number(r.accuracy.maxBoundary, "%.2f"); });
    }
    if (!csv.empty())
    {
      std::printf("\n");
      WriteCsv(csv, rows);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "BenchmarkAdaptive: %s\n", e.what());
    vtkOutputWindow::SetInstance(nullptr);
    return 1;
  }
  vtkOutputWindow::SetInstance(nullptr);
  return 0;
}
