// The per-pixel path length (OutputPathLength, the CLI's --depth) against a closed form: a plane
// seen in the mirror, where the reflected ray of every pixel meets the plane at a distance given
// by the ray-plane intersection. The fast path interpolates the vertices' exact path lengths
// across each triangle; the reference ray tracer intersects the ray itself.
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkTypeInt64Array.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
// Square planes facing the mirror, centred on x = 0, z = 1.
struct Plane
{
  double y;    // where it stands
  double half; // half its side
};

// The demo camera (mirror centre at world (0, 0, 1), camera at (0, -0.14, 1) looking along +y)
// and square planes behind the camera, facing the mirror, n x n quads each.
std::string PlaneScene(const std::string& renderer, const std::string& visibility, int n,
  const std::vector<Plane>& planes)
{
  std::string text =
    "camera: { image_width: 664, image_height: 524,\n"
    "  camera_matrix: [500, 0, 331.5, 0, 500, 261.5, 0, 0, 1],\n"
    "  mirror: { center: [0, 0, 0.14], radius: 0.05 },\n"
    "  world_to_camera: [1, 0, 0, 0,  0, 0, -1, 1,  0, 1, 0, 0.14,  0, 0, 0, 1] }\n"
    "renderer: " +
    renderer + "\nvisibility: " + visibility + "\nbackground: { type: color }\nobjects:\n";
  for (const Plane& p : planes)
  {
    text += "  - { type: plane, size: [" + std::to_string(2 * p.half) + ", " +
      std::to_string(2 * p.half) + "], resolution: " + std::to_string(n) +
      ", rotate: [90, 0, 0], translate: [0, " + std::to_string(p.y) + ", 1.0] }\n";
  }
  return text;
}

struct Comparison
{
  long compared = 0;              // pixels well inside the plane's image
  long nanMismatch = 0;           // PathLength NaN exactly where no triangle is seen: mismatches
  double median = 0, largest = 0; // relative error against the closed form
  std::vector<long> perPlane;     // pixels compared where each plane is the nearest
};

// The closed form of every pixel: the nearest plane its reflected ray meets well inside (its edge
// pixels are partly what lies behind).
Comparison Compare(const std::string& renderer, const std::string& visibility, int n,
  const std::vector<Plane>& planes = { { -0.5, 0.4 } })
{
  Comparison c;
  vtkNew<vtkCatadioptricSceneRenderer> r;
  const std::string path = ::testing::TempDir() + "/catar_path_length.yaml";
  FILE* f = std::fopen(path.c_str(), "w");
  const std::string text = PlaneScene(renderer, visibility, n, planes);
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  r->SetSceneFileName(path.c_str());
  r->OutputPathLengthOn();
  r->OutputVisibleTriangleOn();
  EXPECT_TRUE(r->Render()) << r->GetLastError();
  vtkImageData* image = r->GetOutput();
  auto* depth = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("PathLength"));
  auto* ids = vtkTypeInt64Array::SafeDownCast(image->GetPointData()->GetArray("VisibleTriangle"));
  if (!depth || !ids)
  {
    ADD_FAILURE() << "no PathLength or VisibleTriangle array";
    return c;
  }
  int dims[3];
  image->GetDimensions(dims);
  vtkCatadioptricCamera* camera = r->GetCamera();
  std::vector<double> errors;
  c.perPlane.assign(planes.size(), 0);
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      const vtkIdType i = static_cast<vtkIdType>(dims[1] - 1 - y) * dims[0] + x; // VTK rows
      const float d = depth->GetValue(i);
      c.nanMismatch += std::isnan(d) != (ids->GetValue(i) < 0);
      const double pixel[2] = { double(x), double(y) };
      double o[3], v[3];
      if (camera->BackProjectPixel(pixel, o, v) != vtkCatadioptricCamera::VALID || v[1] >= 0)
      {
        continue;
      }
      double t = std::numeric_limits<double>::infinity();
      bool nearEdge = false;
      std::size_t nearest = 0;
      for (std::size_t k = 0; k < planes.size(); ++k)
      {
        const Plane& p = planes[k];
        const double tp = (p.y - o[1]) / v[1];
        const double hx = o[0] + tp * v[0], hz = o[2] + tp * v[2];
        const double inside = std::max(std::abs(hx), std::abs(hz - 1.0));
        if (tp < t && inside < p.half - 0.02)
        {
          t = tp;
          nearest = k;
        }
        nearEdge = nearEdge || std::abs(inside - p.half) <= 0.02;
      }
      if (std::isinf(t) || nearEdge || std::isnan(d))
      {
        continue;
      }
      errors.push_back(std::abs(d - t) / t);
      c.perPlane[nearest] += 1;
    }
  }
  c.compared = static_cast<long>(errors.size());
  if (!errors.empty())
  {
    std::sort(errors.begin(), errors.end());
    c.median = errors[errors.size() / 2];
    c.largest = errors.back();
  }
  std::printf("[ depth    ] %s/%s, %zu plane(s) of %d x %d quads: %ld pixels (%ld of the "
              "front plane), relative error median %.2e, largest %.2e, NaN where no triangle: "
              "%ld mismatches\n",
    renderer.c_str(), visibility.c_str(), planes.size(), n, n, c.compared, c.perPlane.back(),
    c.median, c.largest, c.nanMismatch);
  return c;
}
} // namespace

// Linear interpolation across each triangle: the error is the interpolation's, of second order
// in the triangles' size (half the size, a quarter of the error), and the same with the depth
// buffer as in painter order (one plane: nothing hides anything).
TEST(PathLength, FastPathAgainstTheClosedForm)
{
  const Comparison coarse = Compare("fast", "painter", 32);
  const Comparison fine = Compare("fast", "painter", 64);
  const Comparison depth = Compare("fast", "depth", 64);
  for (const Comparison& c : { coarse, fine, depth })
  {
    EXPECT_GT(c.compared, 15000);
    EXPECT_EQ(c.nanMismatch, 0);
  }
  EXPECT_LT(fine.median, 2e-4);
  EXPECT_LT(fine.largest, 4e-4);
  const double ratio = coarse.median / fine.median;
  EXPECT_GT(ratio, 3.0);
  EXPECT_LT(ratio, 5.5);
  EXPECT_EQ(depth.compared, fine.compared);
  EXPECT_DOUBLE_EQ(depth.median, fine.median);
  EXPECT_DOUBLE_EQ(depth.largest, fine.largest);
}

// A small plane in front of a large one: the path length is the front plane's where it is seen,
// in painter order as with the depth buffer.
TEST(PathLength, TheSurfaceSeen)
{
  const std::vector<Plane> planes = { { -0.5, 0.4 }, { -0.3, 0.12 } };
  for (const char* visibility : { "painter", "depth" })
  {
    const Comparison c = Compare("fast", visibility, 64, planes);
    EXPECT_GT(c.perPlane[0], 5000) << visibility;
    EXPECT_GT(c.perPlane[1], 5000) << visibility; // the front plane
    EXPECT_EQ(c.nanMismatch, 0) << visibility;
    EXPECT_LT(c.median, 2e-4) << visibility;
    EXPECT_LT(c.largest, 1e-3) << visibility;
  }
  const Comparison c = Compare("reference", "painter", 64, planes);
  EXPECT_GT(c.perPlane[1], 5000);
  EXPECT_LT(c.largest, 1e-5);
}

TEST(PathLength, ReferenceAgainstTheClosedForm)
{
  const Comparison c = Compare("reference", "painter", 64);
  EXPECT_GT(c.compared, 15000);
  EXPECT_EQ(c.nanMismatch, 0);
  // Single-precision rays (Embree): a few parts in 10^8.
  EXPECT_LT(c.median, 1e-6);
  EXPECT_LT(c.largest, 1e-5);
}
