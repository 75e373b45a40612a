// vtkCatadioptricCompositor: pixel placement and row order, painter order, merging of meshes,
// colour arrays, frames, and errors. Meshes are built by hand with ImageCoordinates, so the
// expected pixels follow from the documented rules, not from the projection.
// Visibility (painter vs depth buffer) and the VisibleTriangle ids run the real projection and
// check pixels against exact back projection through the mirror and exact ray-plane hits.
#include "Projector.h"
#include "Rasterizer.h"
#include "SceneDescription.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricColorArray.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkCatadioptricTriangleBins.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include "TestUtilities.h"

#include <Eigen/Geometry> // cross products
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <vector>

namespace
{
constexpr int W = 40;
constexpr int H = 30;

// A mesh of triangles given directly in pixels (x right, y down), as if projected.
vtkSmartPointer<vtkPolyData> PixelMesh(
  const std::vector<std::array<double, 6>>& tris, const std::vector<double>& depths)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  vtkNew<vtkDoubleArray> px;
  px->SetName("ImageCoordinates");
  px->SetNumberOfComponents(2);
  vtkNew<vtkCellArray> cells;
  for (const auto& t : tris)
  {
    vtkIdType ids[3];
    for (int k = 0; k < 3; ++k)
    {
      ids[k] = pts->InsertNextPoint(t[2 * k], t[2 * k + 1], 0.0);
      px->InsertNextTuple2(t[2 * k], t[2 * k + 1]);
    }
    cells->InsertNextCell(3, ids);
  }
  mesh->SetPoints(pts);
  mesh->SetPolys(cells);
  mesh->GetPointData()->AddArray(px);
  vtkNew<vtkDoubleArray> depth;
  depth->SetName("CentroidDepth");
  vtkNew<vtkUnsignedCharArray> vis;
  vis->SetName("Visible");
  for (double d : depths)
  {
    depth->InsertNextValue(d);
    vis->InsertNextValue(1);
  }
  mesh->GetCellData()->AddArray(depth);
  mesh->GetCellData()->AddArray(vis);
  vtkNew<vtkCatadioptricCamera> cam;
  cam->SetImageWidth(W);
  cam->SetImageHeight(H);
  cam->SetFocalLength(30, 30);
  cam->SetPrincipalPoint(19.5, 14.5);
  cam->WriteToFieldData(mesh->GetFieldData());
  return mesh;
}

void CellColors(vtkPolyData* mesh, const std::vector<std::array<unsigned char, 4>>& colors)
{
  vtkNew<vtkUnsignedCharArray> c;
  c->SetName("Colors");
  c->SetNumberOfComponents(4);
  for (const auto& rgba : colors)
  {
    c->InsertNextTypedTuple(rgba.data());
  }
  mesh->GetCellData()->AddArray(c);
}

// RGBA of the pixel (x, y) in the OpenCV convention (y down) of a VTK image (row 0 at bottom).
std::array<int, 4> At(vtkImageData* img, int x, int y)
{
  const unsigned char* p =
    static_cast<unsigned char*>(img->GetScalarPointer(x, img->GetDimensions()[1] - 1 - y, 0));
  return { p[0], p[1], p[2], p[3] };
}
} // namespace

TEST(vtkCatadioptricCompositor, PixelCentresAndRowOrder)
{
  // Triangle covering the top-left region: pixels whose centres are inside.
  auto mesh = PixelMesh({ { -0.5, -0.5, 10.5, -0.5, -0.5, 6.5 } }, { 1.0 });
  vtkNew<vtkCatadioptricCompositor> comp;
  comp->AddMeshData(mesh);
  comp->SetColor(1, 0, 0);
  comp->SetColorArrayName(nullptr);
  comp->SetBackgroundColor(0, 0, 1, 1);
  comp->Update();
  vtkImageData* img = comp->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  ASSERT_EQ(dims[0], W);
  ASSERT_EQ(dims[1], H);
  ASSERT_EQ(img->GetNumberOfScalarComponents(), 4);
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      // Inside test for the centre (x, y): x/11 + y/7 < 1 in the shifted frame (strictly, the
      // hypotenuse is neither top nor left, so centres exactly on it are not drawn).
      const double u = (x + 0.5) / 11.0 + (y + 0.5) / 7.0;
      const bool inside = u < 1.0;
      const auto c = At(img, x, y);
      if (inside)
      {
        EXPECT_EQ(c, (std::array<int, 4>{ 255, 0, 0, 255 })) << x << "," << y;
      }
      else
      {
        EXPECT_EQ(c, (std::array<int, 4>{ 0, 0, 255, 255 })) << x << "," << y;
      }
    }
  }
}

TEST(vtkCatadioptricCompositor, PainterOrderAndMergingByDepth)
{
  // Two overlapping squares (two triangles each); within one mesh the later cell wins.
  auto square = [](double x0, double y0, double x1, double y1) {
    return std::vector<std::array<double, 6>>{ { x0, y0, x1, y0, x1, y1 },
      { x0, y0, x1, y1, x0, y1 } };
  };
  std::vector<std::array<double, 6>> tris = square(2, 2, 20, 20);
  const auto second = square(10, 10, 30, 25);
  tris.insert(tris.end(), second.begin(), second.end());
  auto mesh = PixelMesh(tris, { 2.0, 2.0, 1.0, 1.0 });
  CellColors(
    mesh, { { 255, 0, 0, 255 }, { 255, 0, 0, 255 }, { 0, 255, 0, 255 }, { 0, 255, 0, 255 } });
  vtkNew<vtkCatadioptricCompositor> comp;
  comp->AddMeshData(mesh);
  comp->Update();
  EXPECT_EQ(At(comp->GetOutput(), 15, 15), (std::array<int, 4>{ 0, 255, 0, 255 }));
  EXPECT_EQ(At(comp->GetOutput(), 5, 5), (std::array<int, 4>{ 255, 0, 0, 255 }));
  EXPECT_EQ(At(comp->GetOutput(), 25, 22), (std::array<int, 4>{ 0, 255, 0, 255 }));

  // Split into two meshes given in the "wrong" order: depth decides (nearer = smaller depth).
  auto far = PixelMesh(square(2, 2, 20, 20), { 2.0, 2.0 });
  CellColors(far, { { 255, 0, 0, 255 }, { 255, 0, 0, 255 } });
  auto near = PixelMesh(square(10, 10, 30, 25), { 1.0, 1.0 });
  CellColors(near, { { 0, 255, 0, 255 }, { 0, 255, 0, 255 } });
  vtkNew<vtkCatadioptricCompositor> merged;
  merged->AddMeshData(near);
  merged->AddMeshData(far);
  merged->Update();
  EXPECT_EQ(At(merged->GetOutput(), 15, 15), (std::array<int, 4>{ 0, 255, 0, 255 }));
  EXPECT_EQ(merged->GetNumberOfDrawnTriangles(), 4);
}

TEST(vtkCatadioptricCompositor, GouraudAlphaAndInvisibleCells)
{
  auto mesh = PixelMesh({ { 0, 0, 30, 0, 0, 20 }, { 35, 25, 39, 25, 39, 29 } }, { 1.0, 1.0 });
  // Point colours: red, green, blue at the three corners of the first triangle.
  vtkNew<vtkFloatArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  const float rgb[6][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 1 }, { 1, 1, 1 },
    { 1, 1, 1 } };
  for (const auto& c : rgb)
  {
    colors->InsertNextTuple3(c[0], c[1], c[2]);
  }
  mesh->GetPointData()->AddArray(colors);
  // Hide the second triangle.
  vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetArray("Visible"))->SetValue(1, 0);
  vtkNew<vtkCatadioptricCompositor> comp;
  comp->AddMeshData(mesh);
  comp->SetOpacity(0.5);
  comp->SetBackgroundColor(0, 0, 0, 1);
  comp->Update();
  // Pixel (6, 4): barycentric weights (1 - 6/30 - 4/20, 6/30, 4/20) = (0.6, 0.2, 0.2).
  const auto c = At(comp->GetOutput(), 6, 4);
  EXPECT_NEAR(c[0], 0.5 * 0.6 * 255, 1.0);
  EXPECT_NEAR(c[1], 0.5 * 0.2 * 255, 1.0);
  EXPECT_NEAR(c[2], 0.5 * 0.2 * 255, 1.0);
  EXPECT_EQ(c[3], 255);
  EXPECT_EQ(At(comp->GetOutput(), 38, 27), (std::array<int, 4>{ 0, 0, 0, 255 }));
  EXPECT_EQ(comp->GetNumberOfSkippedTriangles(), 1);
}

TEST(vtkCatadioptricCompositor, FrameIsTheBackground)
{
  vtkNew<vtkImageData> frame;
  frame->SetDimensions(W, H, 1);
  frame->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  unsigned char* p = static_cast<unsigned char*>(frame->GetScalarPointer());
  for (int i = 0; i < W * H; ++i)
  {
    p[3 * i] = static_cast<unsigned char>(i % 251);
    p[3 * i + 1] = 7;
    p[3 * i + 2] = 9;
  }
  auto mesh = PixelMesh({ { 0, 0, 5, 0, 0, 5 } }, { 1.0 });
  vtkNew<vtkCatadioptricCompositor> comp;
  comp->SetFrameData(frame);
  comp->AddMeshData(mesh);
  comp->SetColorArrayName("");
  comp->SetColor(1, 1, 1);
  comp->Update();
  vtkImageData* out = comp->GetOutput();
  // A pixel away from the triangle keeps the frame's value (same VTK index).
  const unsigned char* o = static_cast<unsigned char*>(out->GetScalarPointer(20, 3, 0));
  const unsigned char* f = static_cast<unsigned char*>(frame->GetScalarPointer(20, 3, 0));
  EXPECT_EQ(o[0], f[0]);
  EXPECT_EQ(o[1], 7);
  EXPECT_EQ(o[2], 9);
  EXPECT_EQ(o[3], 255);
  EXPECT_EQ(At(out, 1, 1), (std::array<int, 4>{ 255, 255, 255, 255 }));
}

TEST(vtkCatadioptricCompositor, ErrorsAreClear)
{
  vtkNew<catar_test::ErrorCounter> errors;
  // Frame size differs from the camera image.
  vtkNew<vtkImageData> frame;
  frame->SetDimensions(W + 1, H, 1);
  frame->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  vtkNew<vtkCatadioptricCompositor> comp;
  errors->Watch(comp);
  comp->SetFrameData(frame);
  comp->AddMeshData(PixelMesh({ { 0, 0, 5, 0, 0, 5 } }, { 1.0 }));
  comp->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("41x30"), std::string::npos) << errors->Last;
  // A mesh that was not projected.
  vtkNew<vtkCatadioptricCompositor> comp2;
  errors->Watch(comp2);
  auto raw = PixelMesh({ { 0, 0, 5, 0, 0, 5 } }, { 1.0 });
  raw->GetPointData()->RemoveArray("ImageCoordinates");
  comp2->AddMeshData(raw);
  comp2->Update();
  EXPECT_EQ(errors->Count, 2);
  EXPECT_NE(errors->Last.find("ImageCoordinates"), std::string::npos) << errors->Last;
  // Nothing connected and no size.
  vtkNew<vtkCatadioptricCompositor> comp3;
  errors->Watch(comp3);
  comp3->Update();
  EXPECT_EQ(errors->Count, 3);
  // Nothing connected but a size: a background image.
  comp3->SetImageSize(8, 6);
  comp3->SetBackgroundColor(1, 0, 0, 1);
  comp3->Update();
  EXPECT_EQ(errors->Count, 3);
  EXPECT_EQ(At(comp3->GetOutput(), 7, 5), (std::array<int, 4>{ 255, 0, 0, 255 }));
}

namespace
{
// Two triangles covering the whole image, with texture coordinates that put the centre of
// texel (i, j) on the centre of pixel (i, H - 1 - j): texture row 0 is the image's bottom row.
vtkSmartPointer<vtkPolyData> TexturedQuad()
{
  auto mesh = PixelMesh({ { -0.5, -0.5, W - 0.5, -0.5, -0.5, H - 0.5 },
                          { W - 0.5, -0.5, W - 0.5, H - 0.5, -0.5, H - 0.5 } },
    { 1.0, 1.0 });
  vtkDataArray* px = mesh->GetPointData()->GetArray("ImageCoordinates");
  vtkNew<vtkFloatArray> tc;
  tc->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    tc->InsertNextTuple2(
      (px->GetComponent(i, 0) + 0.5) / W, 1.0 - (px->GetComponent(i, 1) + 0.5) / H);
  }
  mesh->GetPointData()->SetTCoords(tc);
  return mesh;
}

// A W x H RGB texture whose texel (i, j) is (6 i, 8 j, 100).
vtkSmartPointer<vtkImageData> GradientTexture(int components = 3)
{
  auto tex = vtkSmartPointer<vtkImageData>::New();
  tex->SetDimensions(W, H, 1);
  tex->AllocateScalars(VTK_UNSIGNED_CHAR, components);
  for (int j = 0; j < H; ++j)
  {
    for (int i = 0; i < W; ++i)
    {
      unsigned char* p = static_cast<unsigned char*>(tex->GetScalarPointer(i, j, 0));
      const unsigned char rgb[3] = { static_cast<unsigned char>(6 * i),
        static_cast<unsigned char>(8 * j), 100 };
      std::copy(rgb, rgb + components, p);
    }
  }
  return tex;
}
} // namespace

TEST(vtkCatadioptricCompositor, TextureModulatesTheColour)
{
  auto mesh = TexturedQuad();
  CellColors(mesh, { { 128, 255, 64, 255 }, { 128, 255, 64, 255 } });
  vtkNew<vtkCatadioptricCompositor> comp;
  comp->AddMeshData(mesh);
  comp->AddTextureData(GradientTexture());
  comp->Update();
  vtkImageData* img = comp->GetOutput();
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      // At texel centres bilinear sampling returns the texel; the colour multiplies it.
      const int j = H - 1 - y;
      const double expected[3] = { 6.0 * x * 128 / 255, 8.0 * j, 100.0 * 64 / 255 };
      const auto c = At(img, x, y);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_NEAR(c[k], expected[k], 1.0) << x << "," << y << " channel " << k;
      }
      EXPECT_EQ(c[3], 255);
    }
  }
}

TEST(vtkCatadioptricCompositor, TextureIndexChoosesAndNegativeDisables)
{
  vtkNew<catar_test::ErrorCounter> errors;
  auto mesh = TexturedQuad();
  CellColors(mesh, { { 255, 255, 255, 255 }, { 255, 255, 255, 255 } });
  vtkNew<vtkIntArray> index;
  index->SetName("TextureIndex");
  index->InsertNextValue(1);
  mesh->GetFieldData()->AddArray(index);
  vtkNew<vtkCatadioptricCompositor> comp;
  errors->Watch(comp);
  comp->AddMeshData(mesh);
  auto grey = GradientTexture(1); // texel (i, j) = 6 i, grey
  comp->AddTextureData(GradientTexture());
  comp->AddTextureData(grey);
  comp->Update();
  EXPECT_EQ(errors->Count, 0);
  EXPECT_EQ(At(comp->GetOutput(), 10, 3), (std::array<int, 4>{ 60, 60, 60, 255 }));
  // A negative index: the mesh is not textured although it has texture coordinates.
  index->SetValue(0, -1);
  mesh->Modified();
  comp->Update();
  EXPECT_EQ(At(comp->GetOutput(), 10, 3), (std::array<int, 4>{ 255, 255, 255, 255 }));
  // An index beyond the connected textures is an error naming both numbers.
  index->SetValue(0, 2);
  mesh->Modified();
  comp->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("texture 2 but 2 are connected"), std::string::npos) << errors->Last;
  // A texture that is not unsigned char is refused.
  vtkNew<vtkImageData> floats;
  floats->SetDimensions(4, 4, 1);
  floats->AllocateScalars(VTK_FLOAT, 3);
  comp->RemoveAllTextureConnections();
  comp->AddTextureData(floats);
  comp->Update();
  EXPECT_EQ(errors->Count, 2);
  EXPECT_NE(errors->Last.find("unsigned char"), std::string::npos) << errors->Last;
}

// ---------------------------------------------------------------------------------------------
// Visibility: painter order vs depth buffer, and per-pixel visible-triangle ids.

namespace
{
using catar::Vec3;

// A planar convex polygon in world coordinates (corners in order) with a solid colour.
struct Facet
{
  std::vector<Vec3> corners;
  std::array<unsigned char, 3> color;
};

// Camera of the visibility tests: the world frame is the camera frame (x right, y down, z
// forward); a 5 cm mirror 14 cm ahead; objects behind the camera (z < 0) are seen in the mirror
// near the image centre.
vtkSmartPointer<vtkCatadioptricCamera> VisibilityCamera()
{
  auto cam = vtkSmartPointer<vtkCatadioptricCamera>::New();
  cam->SetImageWidth(240);
  cam->SetImageHeight(240);
  cam->SetFocalLength(600, 600);
  cam->SetPrincipalPoint(119.5, 119.5);
  cam->SetMirrorParameter("center", { 0, 0, 0.14 });
  cam->SetMirrorParameter("radius", 0.05);
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  cam->SetWorldToCameraElements(identity);
  return cam;
}

// The facets as a mesh of polygon cells, each facet cut into n x n pieces (a quad, which must be
// a parallelogram, into n x n quads that the compositor splits into fans; a triangle into n^2
// triangles) so that straight projected edges and screen-space PathLength interpolation stay
// close to the exact curved image; colours as uchar cell data "Colors".
vtkSmartPointer<vtkPolyData> FacetMesh(const std::vector<Facet>& facets, int n = 1)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  for (const Facet& f : facets)
  {
    const Vec3& o = f.corners[0];
    const Vec3 u = f.corners[1] - o;
    const Vec3 v = f.corners.back() - o; // quad: corner 3; triangle: corner 2
    const bool quad = f.corners.size() == 4;
    // Grid points o + (i u + j v) / n; a triangle keeps i + j <= n.
    std::vector<vtkIdType> id((n + 1) * (n + 1), -1);
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= n; ++i)
      {
        if (quad || i + j <= n)
        {
          const Vec3 p = o + (static_cast<double>(i) * u + static_cast<double>(j) * v) / n;
          id[j * (n + 1) + i] = pts->InsertNextPoint(p.x(), p.y(), p.z());
        }
      }
    }
    auto at = [&](int i, int j) { return id[j * (n + 1) + i]; };
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        if (quad)
        {
          const vtkIdType q[4] = { at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1) };
          cells->InsertNextCell(4, q);
          colors->InsertNextTypedTuple(f.color.data());
        }
        else if (i + j < n)
        {
          const vtkIdType t[3] = { at(i, j), at(i + 1, j), at(i, j + 1) };
          cells->InsertNextCell(3, t);
          colors->InsertNextTypedTuple(f.color.data());
          if (i + j + 1 < n)
          {
            const vtkIdType t2[3] = { at(i + 1, j), at(i + 1, j + 1), at(i, j + 1) };
            cells->InsertNextCell(3, t2);
            colors->InsertNextTypedTuple(f.color.data());
          }
        }
      }
    }
  }
  mesh->SetPoints(pts);
  mesh->SetPolys(cells);
  mesh->GetCellData()->AddArray(colors);
  return mesh;
}

// Where the reflected ray (origin o, unit direction d) meets the facet's plane: distance t along
// the ray, and whether the hit lies inside the polygon by at least `margin` (metres) from every
// edge (inside), or outside by at least `margin` from some edge line (outside); neither when it
// is close to the boundary.
struct Hit
{
  double t = 0;
  bool inside = false;
  bool outside = true;
};

Hit Intersect(const Facet& f, const Vec3& o, const Vec3& d, double margin)
{
  Hit h;
  const Vec3 n = (f.corners[1] - f.corners[0]).cross(f.corners[2] - f.corners[0]).normalized();
  const double dn = d.dot(n);
  if (std::fabs(dn) < 1e-12)
  {
    return h;
  }
  h.t = (f.corners[0] - o).dot(n) / dn;
  if (h.t <= 0)
  {
    return h;
  }
  const Vec3 p = o + h.t * d;
  double minDistance = 1e300;
  const size_t k = f.corners.size();
  for (size_t i = 0; i < k; ++i)
  {
    const Vec3& a = f.corners[i];
    const Vec3& b = f.corners[(i + 1) % k];
    // In-plane inward normal of edge a->b (corners counter-clockwise about n).
    const Vec3 inward = n.cross(b - a).normalized();
    minDistance = std::min(minDistance, (p - a).dot(inward));
  }
  h.inside = minDistance >= margin;
  h.outside = minDistance <= -margin;
  return h;
}

// The facet a pixel must show: the one hit first along the pixel's reflected ray (exact back
// projection through the mirror, exact ray-plane intersections). -1 for none (background), -2
// when the pixel is too close to call (near a facet boundary, where the rasterised straight edges
// differ from the true curved ones, or where the two nearest hits are closer than `tie` metres,
// within the error of interpolating PathLength linearly in screen space).
int ExpectedFacet(const catar::Projector& projector, const std::vector<Facet>& facets, int x, int y,
  double margin, double tie)
{
  const catar::BackProjectedRay ray = projector.BackProjectWorld(catar::Vec2(x, y));
  if (!catar::HasProjection(ray.status))
  {
    return -1;
  }
  int best = -1;
  double bestT = 1e300, secondT = 1e300;
  for (size_t i = 0; i < facets.size(); ++i)
  {
    const Hit h = Intersect(facets[i], ray.mirrorPoint, ray.direction, margin);
    if (!h.inside && !h.outside)
    {
      return -2;
    }
    if (!h.inside)
    {
      continue;
    }
    if (h.t < bestT)
    {
      secondT = bestT;
      bestT = h.t;
      best = static_cast<int>(i);
    }
    else if (h.t < secondT)
    {
      secondT = h.t;
    }
  }
  if (secondT - bestT < tie)
  {
    return -2;
  }
  return best;
}

struct VisibilityScore
{
  int checked = 0;       // pixels with a clear expected facet, at least two facets behind it
  int wrong = 0;         // of those, pixels showing another colour
  int checkedSingle = 0; // pixels with exactly one facet (or background), as a sanity check
  int wrongSingle = 0;
};

// Compares every pixel of the compositor's output with the exact expectation.
VisibilityScore Score(vtkImageData* img, vtkCatadioptricCamera* cam,
  const std::vector<Facet>& facets, double margin, double tie)
{
  const catar::Projector projector(cam->GetModel());
  VisibilityScore s;
  const int w = img->GetDimensions()[0], h = img->GetDimensions()[1];
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const int e = ExpectedFacet(projector, facets, x, y, margin, tie);
      if (e == -2)
      {
        continue;
      }
      // Count the facets behind the ray's first hit, to tell overlaps from single coverage.
      const catar::BackProjectedRay ray = projector.BackProjectWorld(catar::Vec2(x, y));
      int hits = 0;
      for (const Facet& f : facets)
      {
        hits += catar::HasProjection(ray.status) &&
            Intersect(f, ray.mirrorPoint, ray.direction, margin).inside
          ? 1
          : 0;
      }
      const auto c = At(img, x, y);
      const std::array<int, 4> expected = e < 0
        ? std::array<int, 4>{ 0, 0, 255, 255 }
        : std::array<int, 4>{ facets[e].color[0], facets[e].color[1], facets[e].color[2], 255 };
      const bool ok = c == expected;
      if (hits >= 2)
      {
        ++s.checked;
        s.wrong += ok ? 0 : 1;
      }
      else
      {
        ++s.checkedSingle;
        s.wrongSingle += ok ? 0 : 1;
      }
    }
  }
  return s;
}

vtkSmartPointer<vtkImageData> Composite(vtkCatadioptricCamera* cam,
  const std::vector<vtkSmartPointer<vtkPolyData>>& meshes, int visibility, bool sort = true,
  bool ids = false)
{
  vtkNew<vtkCatadioptricCompositor> comp;
  comp->SetBackgroundColor(0, 0, 1, 1);
  comp->SetVisibility(visibility);
  comp->SetOutputVisibleTriangle(ids);
  std::vector<vtkSmartPointer<vtkAlgorithm>> keep;
  for (const auto& mesh : meshes)
  {
    auto proj = vtkSmartPointer<vtkCatadioptricProjection>::New();
    proj->SetCamera(cam);
    proj->SetInputData(mesh);
    keep.push_back(proj);
    if (sort)
    {
      auto painter = vtkSmartPointer<vtkCatadioptricPainterSort>::New();
      painter->SetInputConnection(proj->GetOutputPort());
      keep.push_back(painter);
      comp->AddMeshConnection(painter->GetOutputPort());
    }
    else
    {
      comp->AddMeshConnection(proj->GetOutputPort());
    }
  }
  comp->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(comp->GetOutput());
  return out;
}

// Two quads crossing like an X along a line through `centre` parallel to world x, tilted by
// +-angle from the plane facing the mirror (z = const): each one is nearer the mirror on one side
// of the crossing line and farther on the other, so no order of the two is right everywhere.
std::vector<Facet> CrossedQuads(const Vec3& centre, double halfX, double halfS, double angleDeg)
{
  const double a = angleDeg * 3.14159265358979323846 / 180.0;
  const Vec3 ex(1, 0, 0);
  const Vec3 sA(0, std::cos(a), std::sin(a));
  const Vec3 sB(0, std::cos(a), -std::sin(a));
  auto quad = [&](const Vec3& s, std::array<unsigned char, 3> color) {
    return Facet{ { centre - halfX * ex - halfS * s, centre + halfX * ex - halfS * s,
                    centre + halfX * ex + halfS * s, centre - halfX * ex + halfS * s },
      color };
  };
  return { quad(sA, { 255, 0, 0 }), quad(sB, { 0, 255, 0 }) };
}
} // namespace

TEST(vtkCatadioptricCompositor, DepthBufferResolvesInterpenetratingQuads)
{
  // Two 30 x 24 cm quads crossing like an X, +-35 degrees from facing the mirror, each cut into
  // 9 x 9 quads: the middle row of pieces straddles the crossing line, where a red and a green
  // piece have the same centroid, so any painter order is wrong on half of that band.
  auto cam = VisibilityCamera();
  const std::vector<Facet> facets = CrossedQuads(Vec3(0.02, 0.01, -0.2), 0.15, 0.12, 35.0);
  const int n = 9;
  const auto mesh = FacetMesh(facets, n);
  // Pixels closer than 4 mm (~1.5 px) to a quad's edge or with exact path lengths closer than
  // 1 mm (~0.2 px from the crossing line) are not judged.
  const double margin = 0.004, tie = 0.001;

  const auto depth = Composite(cam, { mesh }, vtkCatadioptricCompositor::DEPTH_BUFFER);
  const VisibilityScore d = Score(depth, cam, facets, margin, tie);
  EXPECT_GT(d.checked, 3000);
  EXPECT_EQ(d.wrong, 0) << "of " << d.checked << " pixels where the quads overlap";
  EXPECT_GT(d.checkedSingle, 3000);
  EXPECT_EQ(d.wrongSingle, 0) << "of " << d.checkedSingle;

  // The painter's order is wrong in the straddling band (measured: ~450 pixels) and right
  // elsewhere.
  const auto painter = Composite(cam, { mesh }, vtkCatadioptricCompositor::PAINTER);
  const VisibilityScore p = Score(painter, cam, facets, margin, tie);
  EXPECT_EQ(p.checked, d.checked);
  EXPECT_GT(p.wrong, 100) << "of " << p.checked;
  EXPECT_EQ(p.wrongSingle, 0);
  std::printf("[ visibility ] interpenetrating quads, pixels wrong where they overlap: painter %d "
              "of %d, depth buffer %d of %d\n",
    p.wrong, p.checked, d.wrong, d.checked);

  // Two meshes, one quad each, given in either order: the same picture, right again.
  const auto a = FacetMesh({ facets[0] }, n);
  const auto b = FacetMesh({ facets[1] }, n);
  const auto ab = Composite(cam, { a, b }, vtkCatadioptricCompositor::DEPTH_BUFFER);
  const auto ba = Composite(cam, { b, a }, vtkCatadioptricCompositor::DEPTH_BUFFER);
  EXPECT_EQ(Score(ab, cam, facets, margin, tie).wrong, 0);
  const unsigned char* pab = static_cast<unsigned char*>(ab->GetScalarPointer());
  const unsigned char* pba = static_cast<unsigned char*>(ba->GetScalarPointer());
  EXPECT_TRUE(std::equal(pab, pab + 4 * ab->GetNumberOfPoints(), pba));
}

TEST(vtkCatadioptricCompositor, DepthBufferResolvesCyclicOverlap)
{
  // Three long triangles ("sticks") along the sides of a triangle P0 P1 P2 in a plane facing
  // the mirror; stick i runs from P_i (raised 4 cm towards the mirror) to P_{i+1} (lowered 4 cm),
  // so at P1 stick 1 is over stick 0, at P2 stick 2 over 1, at P0 stick 0 over 2: a cycle no
  // painter order can draw.
  auto cam = VisibilityCamera();
  const Vec3 c(0.0, 0.0, -0.2);
  const double r = 0.09, lift = 0.04, halfWidth = 0.05, overshoot = 0.04;
  Vec3 p[3];
  for (int i = 0; i < 3; ++i)
  {
    const double a = (90.0 + 120.0 * i) * 3.14159265358979323846 / 180.0;
    p[i] = c + Vec3(r * std::cos(a), r * std::sin(a), 0.0);
  }
  const std::array<unsigned char, 3> colors[3] = { { 255, 0, 0 }, { 0, 255, 0 }, { 255, 255, 0 } };
  std::vector<Facet> facets;
  for (int i = 0; i < 3; ++i)
  {
    // Along the stick: from P_i at +lift (nearer the mirror, larger z) to P_{i+1} at -lift.
    const Vec3 from = p[i] + Vec3(0, 0, lift);
    const Vec3 to = p[(i + 1) % 3] - Vec3(0, 0, lift);
    const Vec3 along = (to - from).normalized();
    const Vec3 across = Vec3(0, 0, 1).cross(along).normalized() * halfWidth;
    // Base before P_i, apex well beyond P_{i+1}: the stick is still wide at both crossings.
    const Vec3 base = from - overshoot * along;
    const Vec3 apex = to + 5.0 * overshoot * along;
    facets.push_back(Facet{ { base - across, apex, base + across }, colors[i] });
  }
  const double tie = 0.001;

  // The three triangles as they are. Their 40 cm edges project to chords up to ~1 cm (in the
  // triangle's plane) inside the true curved image, so pixels closer than 1 cm to an edge are
  // not judged.
  const auto three = FacetMesh(facets);
  ASSERT_EQ(three->GetNumberOfCells(), 3);
  const auto depth = Composite(cam, { three }, vtkCatadioptricCompositor::DEPTH_BUFFER);
  const VisibilityScore d = Score(depth, cam, facets, 0.01, tie);
  EXPECT_GT(d.checked, 500);
  EXPECT_EQ(d.wrong, 0) << "of " << d.checked << " pixels where the triangles overlap";
  EXPECT_GT(d.checkedSingle, 2000);
  EXPECT_EQ(d.wrongSingle, 0) << "of " << d.checkedSingle;
  const auto painter = Composite(cam, { three }, vtkCatadioptricCompositor::PAINTER);
  const VisibilityScore s = Score(painter, cam, facets, 0.01, tie);
  EXPECT_GT(s.wrong, 100) << "a painter order cannot draw a cycle";
  std::printf("[ visibility ] cyclic sticks, pixels wrong where they overlap: painter %d of %d, "
              "depth buffer %d of %d\n",
    s.wrong, s.checked, d.wrong, d.checked);

  // Finely meshed (64 triangles each) the edges follow the curves: judged up to 4 mm from them.
  const auto fine =
    Composite(cam, { FacetMesh(facets, 8) }, vtkCatadioptricCompositor::DEPTH_BUFFER);
  const VisibilityScore f = Score(fine, cam, facets, 0.004, tie);
  EXPECT_GT(f.checked, 1000);
  EXPECT_EQ(f.wrong, 0) << "of " << f.checked;
  EXPECT_EQ(f.wrongSingle, 0) << "of " << f.checkedSingle;
}

namespace
{
// The colour that encodes (mesh, original cell): unique per cell, never the blue background.
std::array<unsigned char, 3> IdColor(int mesh, vtkIdType cell)
{
  return { static_cast<unsigned char>(cell % 256), static_cast<unsigned char>(cell / 256),
    static_cast<unsigned char>(50 + 100 * mesh) };
}

void ColorCellsById(vtkPolyData* mesh, int index)
{
  vtkNew<vtkUnsignedCharArray> c;
  c->SetName("Colors");
  c->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i)
  {
    c->InsertNextTypedTuple(IdColor(index, i).data());
  }
  mesh->GetCellData()->AddArray(c);
}

// A sphere (triangles) in front of a plane of quads, both behind the camera.
std::vector<vtkSmartPointer<vtkPolyData>> SphereAndQuads()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.03, 0.0, -0.15);
  sphere->SetRadius(0.05);
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(10);
  sphere->Update();
  auto s = vtkSmartPointer<vtkPolyData>::New();
  s->DeepCopy(sphere->GetOutput());
  ColorCellsById(s, 0);

  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.12, -0.1, -0.26);
  plane->SetPoint1(0.16, -0.1, -0.26);
  plane->SetPoint2(-0.12, 0.1, -0.22);
  plane->SetResolution(7, 5);
  plane->Update();
  auto q = vtkSmartPointer<vtkPolyData>::New();
  q->DeepCopy(plane->GetOutput());
  ColorCellsById(q, 1);
  return { s, q };
}

// Checks the ids against the colours: -1 on the background, else the pixel shows the colour of
// cell (id & 0xFFFFFFFF) - cellOffset[mesh] of mesh (id >> 32). Returns the pixels per mesh.
std::array<int, 2> CheckIds(vtkImageData* img, const std::array<vtkIdType, 2>& cells,
  const std::array<vtkIdType, 2>& cellOffset)
{
  std::array<int, 2> perMesh = { 0, 0 };
  auto* ids = vtkTypeInt64Array::SafeDownCast(img->GetPointData()->GetArray("VisibleTriangle"));
  EXPECT_NE(ids, nullptr);
  if (!ids)
  {
    return perMesh;
  }
  const vtkIdType n = img->GetNumberOfPoints();
  EXPECT_EQ(ids->GetNumberOfTuples(), n);
  EXPECT_EQ(ids->GetNumberOfComponents(), 1);
  const unsigned char* rgba = static_cast<unsigned char*>(img->GetScalarPointer());
  int bad = 0;
  for (vtkIdType i = 0; i < n && bad < 5; ++i)
  {
    const vtkTypeInt64 id = ids->GetValue(i);
    const unsigned char* p = rgba + 4 * i;
    if (id == -1)
    {
      if (!(p[0] == 0 && p[1] == 0 && p[2] == 255))
      {
        ADD_FAILURE() << "pixel " << i << " is drawn but has id -1";
        ++bad;
      }
      continue;
    }
    const int mesh = static_cast<int>(id >> 32);
    if (mesh < 0 || mesh > 1)
    {
      ADD_FAILURE() << "pixel " << i << ": id " << id << " names no mesh";
      ++bad;
      continue;
    }
    const vtkIdType cell = static_cast<vtkIdType>(id & 0xFFFFFFFF) - cellOffset[mesh];
    if (cell < 0 || cell >= cells[mesh])
    {
      ADD_FAILURE() << "pixel " << i << ": id " << id << " names no cell";
      ++bad;
      continue;
    }
    const auto c = IdColor(mesh, cell);
    if (!(p[0] == c[0] && p[1] == c[1] && p[2] == c[2]))
    {
      ADD_FAILURE() << "pixel " << i << ": id names mesh " << mesh << " cell " << cell
                    << " but the pixel shows another cell's colour";
      ++bad;
    }
    ++perMesh[mesh];
  }
  return perMesh;
}
} // namespace

TEST(vtkCatadioptricCompositor, VisibleTriangleIdsNameTheDrawnCell)
{
  auto cam = VisibilityCamera();
  const auto meshes = SphereAndQuads();
  const std::array<vtkIdType, 2> cells = { meshes[0]->GetNumberOfCells(),
    meshes[1]->GetNumberOfCells() };

  // Default: no id array, and the picture is the same as with the ids.
  const auto plain = Composite(cam, meshes, vtkCatadioptricCompositor::PAINTER);
  EXPECT_EQ(plain->GetPointData()->GetArray("VisibleTriangle"), nullptr);
  EXPECT_EQ(plain->GetPointData()->GetNumberOfArrays(), 1);

  for (int visibility :
    { vtkCatadioptricCompositor::PAINTER, vtkCatadioptricCompositor::DEPTH_BUFFER })
  {
    SCOPED_TRACE(visibility == vtkCatadioptricCompositor::PAINTER ? "painter" : "depth buffer");
    // Painter-sorted meshes: the ids come from OriginalCellId, i.e. the unsorted cells.
    const auto sorted = Composite(cam, meshes, visibility, true, true);
    const auto perMesh = CheckIds(sorted, cells, { 0, 0 });
    EXPECT_GT(perMesh[0], 500);
    EXPECT_GT(perMesh[1], 500);
    if (visibility == vtkCatadioptricCompositor::PAINTER)
    {
      const unsigned char* a = static_cast<unsigned char*>(plain->GetScalarPointer());
      const unsigned char* b = static_cast<unsigned char*>(sorted->GetScalarPointer());
      EXPECT_TRUE(std::equal(a, a + 4 * plain->GetNumberOfPoints(), b));
    }
    // Unsorted meshes (no OriginalCellId): the index in the mesh.
    const auto unsorted = Composite(cam, meshes, visibility, false, true);
    const auto perMeshUnsorted = CheckIds(unsorted, cells, { 0, 0 });
    EXPECT_GT(perMeshUnsorted[0], 500);
  }

  // An OriginalCellId already on the input survives the sort (values kept, reordered).
  auto tagged = vtkSmartPointer<vtkPolyData>::New();
  tagged->DeepCopy(meshes[1]);
  vtkNew<vtkIdTypeArray> original;
  original->SetName("OriginalCellId");
  for (vtkIdType c = 0; c < tagged->GetNumberOfCells(); ++c)
  {
    original->InsertNextValue(1000 + c);
  }
  tagged->GetCellData()->AddArray(original);
  const auto withTags =
    Composite(cam, { meshes[0], tagged }, vtkCatadioptricCompositor::DEPTH_BUFFER, true, true);
  const auto perMeshTagged = CheckIds(withTags, cells, { 0, 1000 });
  EXPECT_GT(perMeshTagged[1], 500);
}

TEST(vtkCatadioptricPainterSort, OriginalCellIdFollowsTheCells)
{
  auto cam = VisibilityCamera();
  const auto meshes = SphereAndQuads();
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputData(meshes[0]);
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(proj->GetOutputPort());
  sort->Update();
  vtkPolyData* out = sort->GetOutput();
  auto* ids = vtkIdTypeArray::SafeDownCast(out->GetCellData()->GetArray("OriginalCellId"));
  ASSERT_NE(ids, nullptr);
  ASSERT_EQ(ids->GetNumberOfTuples(), out->GetNumberOfCells());
  vtkDataArray* colors = out->GetCellData()->GetArray("Colors");
  int moved = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    const vtkIdType orig = ids->GetValue(c);
    moved += orig != c ? 1 : 0;
    const auto expected = IdColor(0, orig);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(colors->GetComponent(c, k), expected[k]) << "cell " << c;
    }
  }
  EXPECT_GT(moved, 10); // the sort did reorder
  // Sorting again keeps the first ids.
  vtkNew<vtkCatadioptricPainterSort> again;
  again->SetInputConnection(sort->GetOutputPort());
  again->Update();
  vtkDataArray* ids2 = again->GetOutput()->GetCellData()->GetArray("OriginalCellId");
  ASSERT_NE(ids2, nullptr);
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    EXPECT_EQ(ids2->GetComponent(c, 0), ids->GetValue(c));
  }
}

TEST(vtkCatadioptricCompositor, DepthBufferIgnoresDrawOrderAndDrawsTranslucentLast)
{
  // The squares of PainterOrderAndMergingByDepth with PathLength per point, but the far red one
  // listed last (painter order wrong): the depth buffer still shows the near green one on top.
  auto square = [](double x0, double y0, double x1, double y1) {
    return std::vector<std::array<double, 6>>{ { x0, y0, x1, y0, x1, y1 },
      { x0, y0, x1, y1, x0, y1 } };
  };
  std::vector<std::array<double, 6>> tris = square(10, 10, 30, 25);
  const auto red = square(2, 2, 20, 20);
  tris.insert(tris.end(), red.begin(), red.end());
  auto mesh = PixelMesh(tris, { 1.0, 1.0, 1.0, 1.0 });
  vtkNew<vtkDoubleArray> path;
  path->SetName("PathLength");
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    path->InsertNextValue(i < 6 ? 1.0 : 2.0);
  }
  mesh->GetPointData()->AddArray(path);
  CellColors(
    mesh, { { 0, 255, 0, 255 }, { 0, 255, 0, 255 }, { 255, 0, 0, 255 }, { 255, 0, 0, 255 } });
  vtkNew<vtkCatadioptricCompositor> comp;
  comp->AddMeshData(mesh);
  comp->Update();
  EXPECT_EQ(At(comp->GetOutput(), 15, 15), (std::array<int, 4>{ 255, 0, 0, 255 })); // painter
  comp->SetVisibilityToDepthBuffer();
  EXPECT_STREQ(comp->GetVisibilityAsString(), "DepthBuffer");
  comp->Update();
  EXPECT_EQ(At(comp->GetOutput(), 15, 15), (std::array<int, 4>{ 0, 255, 0, 255 }));
  EXPECT_EQ(At(comp->GetOutput(), 5, 5), (std::array<int, 4>{ 255, 0, 0, 255 }));
  EXPECT_EQ(At(comp->GetOutput(), 25, 22), (std::array<int, 4>{ 0, 255, 0, 255 }));

  // The near green square half transparent and listed first: it is drawn after the opaque red
  // one and blends over it (painter order would let red cover it).
  vtkUnsignedCharArray* colors =
    vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetArray("Colors"));
  colors->SetComponent(0, 3, 128);
  colors->SetComponent(1, 3, 128);
  mesh->Modified();
  comp->Update();
  const auto blended = At(comp->GetOutput(), 15, 15);
  EXPECT_NEAR(blended[0], 127, 1);
  EXPECT_NEAR(blended[1], 128, 1);
  EXPECT_EQ(blended[2], 0);
  comp->SetVisibilityToPainter();
  comp->Update();
  EXPECT_EQ(At(comp->GetOutput(), 15, 15), (std::array<int, 4>{ 255, 0, 0, 255 }));
}

TEST(vtkCatadioptricCompositor, DepthBufferNeedsPathLength)
{
  vtkNew<catar_test::ErrorCounter> errors;
  vtkNew<vtkCatadioptricCompositor> comp;
  errors->Watch(comp);
  comp->AddMeshData(PixelMesh({ { 0, 0, 5, 0, 0, 5 } }, { 1.0 }));
  comp->SetVisibility(vtkCatadioptricCompositor::DEPTH_BUFFER);
  comp->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("PathLength"), std::string::npos) << errors->Last;
  EXPECT_NE(errors->Last.find("DEPTH_BUFFER"), std::string::npos) << errors->Last;
  // The painter needs no PathLength.
  comp->SetVisibility(vtkCatadioptricCompositor::PAINTER);
  comp->Update();
  EXPECT_EQ(errors->Count, 1);
}

TEST(vtkCatadioptricSceneRenderer, VisibilityKeyChoosesTheCompositorMode)
{
  const std::string head = R"(%YAML:1.0
---
camera:
  image_width: 240
  image_height: 240
  camera_matrix: [ 600.0, 0.0, 119.5, 0.0, 600.0, 119.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
  world_to_camera: [ 1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1 ]
background: { type: color, color: [ 0, 0, 1 ] }
objects:
  - { type: plane, size: [ 0.3, 0.24 ], resolution: 9, rotate: [ 35, 0, 0 ],
      translate: [ 0.02, 0.01, -0.2 ], color: [ 1, 0, 0 ] }
  - { type: plane, size: [ 0.3, 0.24 ], resolution: 9, rotate: [ -35, 0, 0 ],
      translate: [ 0.02, 0.01, -0.2 ], color: [ 0, 1, 0 ] }
)";
  // The key: default painter, depth, and an error that names it.
  catar::SceneDescription scene;
  std::string error;
  ASSERT_TRUE(catar::ParseScene(head, "", scene, error)) << error;
  EXPECT_EQ(scene.visibility, "painter");
  ASSERT_TRUE(catar::ParseScene(head + "visibility: depth\n", "", scene, error)) << error;
  EXPECT_EQ(scene.visibility, "depth");
  EXPECT_FALSE(catar::ParseScene(head + "visibility: zbuffer\n", "", scene, error));
  EXPECT_NE(error.find("'visibility'"), std::string::npos) << error;
  EXPECT_NE(error.find("zbuffer"), std::string::npos) << error;

  // The renderer's compositor follows it: the crossed planes of
  // DepthBufferResolvesInterpenetratingQuads, right with `depth`, wrong in places with `painter`.
  auto cam = VisibilityCamera();
  const std::vector<Facet> facets = CrossedQuads(Vec3(0.02, 0.01, -0.2), 0.15, 0.12, 35.0);
  VisibilityScore score[2];
  const char* modes[2] = { "painter", "depth" };
  for (int k = 0; k < 2; ++k)
  {
    const std::string path =
      ::testing::TempDir() + "/catar_visibility_" + std::string(modes[k]) + ".yaml";
    {
      std::ofstream file(path);
      file << head << "visibility: " << modes[k] << "\n";
    }
    vtkNew<vtkCatadioptricSceneRenderer> renderer;
    renderer->SetSceneFileName(path.c_str());
    ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
    score[k] = Score(renderer->GetOutput(), cam, facets, 0.004, 0.001);
    std::remove(path.c_str());
  }
  EXPECT_GT(score[1].checked, 3000);
  EXPECT_EQ(score[1].wrong, 0) << "of " << score[1].checked;
  EXPECT_EQ(score[1].wrongSingle, 0) << "of " << score[1].checkedSingle;
  EXPECT_GT(score[0].wrong, 100) << "of " << score[0].checked;
}

namespace
{
// A random "projected" mesh for the reference comparison: triangles and quads of assorted sizes
// (most about a pixel, as a detailed mesh seen in the mirror, some large) in a w x h image, with
// the arrays the projection writes, some invisible cells and some points out of reach (NaN,
// beyond the guard band).
vtkSmartPointer<vtkPolyData> RandomPixelMesh(unsigned seed, int w, int h, int cells)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-3, w + 3), uy(-3, h + 3), big(-25, 25), small(-1, 1);
  std::uniform_real_distribution<double> ud(0.5, 2.0);
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  vtkNew<vtkDoubleArray> px;
  px->SetName("ImageCoordinates");
  px->SetNumberOfComponents(2);
  vtkNew<vtkDoubleArray> path;
  path->SetName("PathLength");
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkDoubleArray> depth;
  depth->SetName("CentroidDepth");
  vtkNew<vtkUnsignedCharArray> vis;
  vis->SetName("Visible");
  for (int c = 0; c < cells; ++c)
  {
    const double cx = ux(rng), cy = uy(rng);
    const bool large = rng() % 20 == 0;
    const int n = rng() % 6 == 0 ? 4 : 3;
    std::vector<vtkIdType> ids;
    for (int k = 0; k < n; ++k)
    {
      double x = cx + (large ? big(rng) : small(rng));
      double y = cy + (large ? big(rng) : small(rng));
      if (rng() % 400 == 0)
      {
        x = rng() % 2 ? std::numeric_limits<double>::quiet_NaN() : 3e6;
      }
      ids.push_back(pts->InsertNextPoint(x, y, 0.0));
      px->InsertNextTuple2(x, y);
      path->InsertNextValue(ud(rng));
    }
    polys->InsertNextCell(n, ids.data());
    depth->InsertNextValue(ud(rng));
    vis->InsertNextValue(rng() % 10 == 0 ? 0 : 1);
  }
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  mesh->GetPointData()->AddArray(px);
  mesh->GetPointData()->AddArray(path);
  mesh->GetCellData()->AddArray(depth);
  mesh->GetCellData()->AddArray(vis);
  vtkNew<vtkCatadioptricCamera> cam;
  cam->SetImageWidth(w);
  cam->SetImageHeight(h);
  cam->SetFocalLength(30, 30);
  cam->SetPrincipalPoint(0.5 * (w - 1), 0.5 * (h - 1));
  cam->WriteToFieldData(mesh->GetFieldData());
  return mesh;
}

// A colour array for mesh: 0 unsigned char RGBA per point, 1 float RGB per point (values outside
// [0, 1] too), 2 unsigned char RGBA per cell, 3 none (the solid colour).
void RandomColours(vtkPolyData* mesh, int kind, unsigned seed)
{
  std::mt19937 rng(seed);
  if (kind == 3)
  {
    return;
  }
  vtkSmartPointer<vtkDataArray> colours;
  const vtkIdType n = kind == 2 ? mesh->GetNumberOfCells() : mesh->GetNumberOfPoints();
  if (kind == 1)
  {
    colours = vtkSmartPointer<vtkFloatArray>::New();
    colours->SetNumberOfComponents(3);
    colours->SetNumberOfTuples(n);
    std::uniform_real_distribution<double> u(-0.1, 1.1);
    for (vtkIdType i = 0; i < n; ++i)
    {
      colours->SetTuple3(i, u(rng), u(rng), u(rng));
    }
  }
  else
  {
    colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
    colours->SetNumberOfComponents(4);
    colours->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      colours->SetTuple4(i, rng() % 256, rng() % 256, rng() % 256, rng() % 3 ? 255 : rng() % 256);
    }
  }
  colours->SetName("Colors");
  (kind == 2 ? static_cast<vtkFieldData*>(mesh->GetCellData())
             : static_cast<vtkFieldData*>(mesh->GetPointData()))
    ->AddArray(colours);
}

// The compositor's documented drawing, done the plain way: every fan triangle of every visible
// polygon, its vertices read through vtkDataArray and vtkCatadioptricColorArray, in cell order,
// meshes merged by a stable sort on CentroidDepth, opaque ones first with a depth buffer, each
// drawn with catar::rasterizeTriangle band by band (the compositor's bands).
struct Reference
{
  std::vector<unsigned char> rgba; // VTK row order
  std::vector<catar::RasterId> ids;
};

Reference DrawReference(const std::vector<vtkPolyData*>& meshes, int w, int h, float opacity,
  bool depthBuffer, bool wantIds)
{
  struct Tri
  {
    catar::RasterVertex v[3];
    double depth;
    bool opaque;
    catar::RasterId id;
  };
  std::vector<Tri> tris;
  const float solid[4] = { 0.8f, 0.8f, 0.8f, 1.0f };
  for (size_t m = 0; m < meshes.size(); ++m)
  {
    vtkPolyData* mesh = meshes[m];
    vtkDataArray* pixels = mesh->GetPointData()->GetArray("ImageCoordinates");
    vtkDataArray* path = mesh->GetPointData()->GetArray("PathLength");
    vtkDataArray* visible = mesh->GetCellData()->GetArray("Visible");
    vtkDataArray* depth = mesh->GetCellData()->GetArray("CentroidDepth");
    const vtkCatadioptricColorArray colour(mesh, "Colors", solid);
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < mesh->GetPolys()->GetNumberOfCells(); ++c)
    {
      mesh->GetPolys()->GetCellAtId(c, ids);
      if (visible->GetComponent(c, 0) == 0)
      {
        continue;
      }
      auto vertex = [&](vtkIdType p) {
        catar::RasterVertex v;
        v.x = pixels->GetComponent(p, 0);
        v.y = pixels->GetComponent(p, 1);
        float rgba[4];
        colour.Get(p, c, rgba);
        v.r = rgba[0];
        v.g = rgba[1];
        v.b = rgba[2];
        v.a = rgba[3] * opacity;
        v.depth = depthBuffer ? static_cast<float>(path->GetComponent(p, 0)) : 0.0f;
        return v;
      };
      for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
      {
        Tri t{ { vertex(ids->GetId(0)), vertex(ids->GetId(k)), vertex(ids->GetId(k + 1)) },
          depth->GetComponent(c, 0), false, (static_cast<catar::RasterId>(m) << 32) + c };
        t.opaque = t.v[0].a >= 1 && t.v[1].a >= 1 && t.v[2].a >= 1;
        tris.push_back(t);
      }
    }
  }
  if (meshes.size() > 1)
  {
    std::stable_sort(
      tris.begin(), tris.end(), [](const Tri& a, const Tri& b) { return a.depth > b.depth; });
  }
  if (depthBuffer)
  {
    std::stable_partition(tris.begin(), tris.end(), [](const Tri& t) { return t.opaque; });
  }
  Reference ref;
  ref.rgba.assign(4 * static_cast<size_t>(w) * h, 0);
  for (size_t i = 3; i < ref.rgba.size(); i += 4)
  {
    ref.rgba[i] = 255; // BackgroundColor (0, 0, 0, 1)
  }
  ref.ids.assign(static_cast<size_t>(w) * h, -1);
  std::vector<float> zbuf(static_cast<size_t>(w) * h, std::numeric_limits<float>::infinity());
  catar::ImageView view{ ref.rgba.data() + 4 * static_cast<std::ptrdiff_t>(w) * (h - 1), w, h,
    -4 * static_cast<std::ptrdiff_t>(w) };
  catar::DepthView write{ zbuf.data(), w, h, w };
  catar::DepthView test = write;
  test.write = false;
  catar::IdView idView{ ref.ids.data() + static_cast<std::ptrdiff_t>(w) * (h - 1), w, h, -w };
  const int band = vtkCatadioptricTriangleBins::BandHeight;
  for (int y0 = 0; y0 < h; y0 += band)
  {
    const catar::PixelRect clip{ 0, y0, w, std::min(h, y0 + band) };
    for (const Tri& t : tris)
    {
      catar::rasterizeTriangle(view, t.v[0], t.v[1], t.v[2], clip,
        depthBuffer ? (t.opaque ? &write : &test) : nullptr, nullptr, wantIds ? &idView : nullptr,
        t.id);
    }
  }
  return ref;
}
} // namespace

TEST(vtkCatadioptricCompositor, MatchesTheRasteriserTriangleByTriangle)
{
  // The compositor gathers, snaps and bins its triangles in parallel before drawing the bands;
  // the picture (and the ids) must be bit for bit those of drawing each triangle with
  // catar::rasterizeTriangle, band after band, in the documented order. Colours of every kind
  // (unsigned char and float point colours, cell colours, the solid colour), translucency,
  // invisible cells, points out of reach, fans of quads, one and two meshes, painter order and
  // depth buffer, with and without ids; an image of several bands.
  const int w = 150, h = 140;
  for (int round = 0; round < 16; ++round)
  {
    SCOPED_TRACE("round " + std::to_string(round));
    const int nMeshes = round % 2 + 1;
    const bool depthBuffer = round % 4 >= 2;
    const bool wantIds = round % 3 == 0;
    const float opacity = round % 5 == 4 ? 0.6f : 1.0f;
    std::vector<vtkSmartPointer<vtkPolyData>> keep;
    std::vector<vtkPolyData*> meshes;
    vtkNew<vtkCatadioptricCompositor> comp;
    comp->SetBackgroundColor(0, 0, 0, 1);
    comp->SetOpacity(opacity);
    comp->SetVisibility(
      depthBuffer ? vtkCatadioptricCompositor::DEPTH_BUFFER : vtkCatadioptricCompositor::PAINTER);
    comp->SetOutputVisibleTriangle(wantIds);
    for (int m = 0; m < nMeshes; ++m)
    {
      auto mesh = RandomPixelMesh(round * 7 + m, w, h, 6000);
      RandomColours(mesh, (round / 2 + m) % 4, round * 11 + m);
      keep.push_back(mesh);
      meshes.push_back(mesh);
      comp->AddMeshData(mesh);
    }
    comp->Update();
    const Reference ref = DrawReference(meshes, w, h, opacity, depthBuffer, wantIds);
    vtkImageData* out = comp->GetOutput();
    const unsigned char* rgba = static_cast<unsigned char*>(out->GetScalarPointer());
    EXPECT_TRUE(std::equal(ref.rgba.begin(), ref.rgba.end(), rgba));
    auto* ids = vtkTypeInt64Array::SafeDownCast(out->GetPointData()->GetArray("VisibleTriangle"));
    ASSERT_EQ(ids != nullptr, wantIds);
    if (ids)
    {
      EXPECT_TRUE(std::equal(ref.ids.begin(), ref.ids.end(), ids->GetPointer(0)));
    }
    // The second execution reuses the buffers of the first: same result.
    comp->Modified();
    comp->Update();
    EXPECT_TRUE(std::equal(ref.rgba.begin(), ref.rgba.end(),
      static_cast<unsigned char*>(comp->GetOutput()->GetScalarPointer())));
  }
}

// Without a frame, the compositor's extent is known before any data: the projection announces
// its camera's image size (vtkCatadioptricCamera::IMAGE_SIZE) and the filters in between pass it
// on. ParaView's image views read the extent from this information; a wrong guess made them
// print "Incorrect dimensionality" for a compositor shown without a frame.
TEST(vtkCatadioptricCompositor, AnnouncesTheCameraImageSizeWithoutAFrame)
{
  auto camera = catar_test::DemoCamera();
  camera->SetImageWidth(332);
  camera->SetImageHeight(262);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.06, -0.32, 0.92);
  sphere->SetRadius(0.03);
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputConnection(sphere->GetOutputPort());
  projection->SetCamera(camera);
  vtkNew<vtkCatadioptricLighting> lighting;
  lighting->SetInputConnection(projection->GetOutputPort());
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(lighting->GetOutputPort());
  vtkNew<vtkCatadioptricCompositor> compositor;
  compositor->AddInputConnection(1, sort->GetOutputPort());
  compositor->UpdateInformation();
  int extent[6];
  compositor->GetOutputInformation(0)->Get(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  EXPECT_EQ(extent[1], 331);
  EXPECT_EQ(extent[3], 261);
  // The camera changes: the announced size follows.
  camera->SetImageWidth(166);
  camera->SetImageHeight(131);
  compositor->UpdateInformation();
  compositor->GetOutputInformation(0)->Get(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  EXPECT_EQ(extent[1], 165);
  EXPECT_EQ(extent[3], 130);
  // And the image made has that extent.
  compositor->Update();
  int dims[3];
  compositor->GetOutput()->GetDimensions(dims);
  EXPECT_EQ(dims[0], 166);
  EXPECT_EQ(dims[1], 131);
  // No camera object or file: the panel camera's size (the demo camera's, 1328 x 1048); a bad
  // panel camera announces no size (the projection reports it when it runs).
  vtkNew<vtkCatadioptricProjection> bare;
  bare->SetInputConnection(sphere->GetOutputPort());
  bare->UpdateInformation();
  ASSERT_TRUE(bare->GetOutputInformation(0)->Has(vtkCatadioptricCamera::IMAGE_SIZE()));
  EXPECT_EQ(bare->GetOutputInformation(0)->Get(vtkCatadioptricCamera::IMAGE_SIZE())[0], 1328);
  EXPECT_EQ(bare->GetOutputInformation(0)->Get(vtkCatadioptricCamera::IMAGE_SIZE())[1], 1048);
  bare->SetCameraImageSize(-1, 1048);
  bare->UpdateInformation();
  EXPECT_FALSE(bare->GetOutputInformation(0)->Has(vtkCatadioptricCamera::IMAGE_SIZE()));
}
