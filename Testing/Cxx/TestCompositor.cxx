// vtkCatadioptricCompositor: pixel placement and row order, painter order, merging of meshes,
// colour arrays, frames, and errors. Meshes are built by hand with ImageCoordinates, so the
// expected pixels follow from the documented rules, not from the projection.
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <array>
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
  EXPECT_NE(errors->Last.find("texture 2 but 2 are connected"), std::string::npos)
    << errors->Last;
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
