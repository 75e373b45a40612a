// Objects joined into one pipeline draw the same image as one pipeline each: the scene renderer
// with JoinObjects on and off, on lit scenes whose objects have different materials (ambient,
// diffuse, specular, specular colour and power) and opacities, Gouraud and flat, with shadows.
// And the lighting filter's own checks of a mesh's "Materials" and "MaterialIndex".
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace
{
std::string Scene(const std::string& shading)
{
  std::ostringstream s;
  s << R"(camera:
  image_width: 664
  image_height: 524
  camera_matrix: [ 500.0, 0.0, 331.5, 0.0, 500.0, 261.5, 0.0, 0.0, 1.0 ]
  mirror: { type: sphere, center: [ 0.0, 0.0, 0.14 ], radius: 0.05 }
  world_to_camera: [ 1, 0, 0, 0,  0, 0, -1, 1.0,  0, 1, 0, 0.14,  0, 0, 0, 1 ]
background: { type: color, color: [ 0.1, 0.1, 0.1 ] }
lighting:
  shading: )"
    << shading << R"(
  shadows: true
  global_ambient: [ 0.3, 0.3, 0.3 ]
  lights:
    - { type: spot, position: [ 0.25, 0.05, 1.35 ], focal_point: [ 0.0, -0.22, 0.95 ],
        cone_angle: 45, exponent: 1, color: [ 1.0, 0.95, 0.85 ] }
    - { type: point, position: [ -0.3, -0.1, 1.2 ], color: [ 0.4, 0.4, 0.5 ] }
objects:
  - { type: box, size: [ 0.08, 0.06, 0.05 ], resolution: 4, translate: [ 0.14, -0.22, 0.9 ],
      rotate: [ 0, 0, 30 ], face_colors: true,
      material: { ambient: 0.3, diffuse: 0.8, specular: 0.2, specular_power: 20 } }
  - { type: sphere, radius: 0.04, resolution: 24, translate: [ 0.0, -0.25, 1.0 ],
      color: [ 0.9, 0.5, 0.1 ],
      material: { ambient: 0.1, diffuse: 0.6, specular: 0.9, specular_power: 60,
                  specular_color: [ 0.5, 0.8, 1.0 ] } }
  - { type: sphere, radius: 0.03, resolution: 24, translate: [ 0.1, -0.2, 1.08 ],
      color: [ 0.2, 0.8, 0.3 ],
      material: { ambient: 0.2, diffuse: 0.9, specular: 0.4, specular_power: 8,
                  specular_color: [ 1.0, 0.8, 0.5 ] } }
  - { type: sphere, radius: 0.02, resolution: 24, translate: [ 0.05, -0.2, 0.86 ],
      color: [ 0.8, 0.2, 0.3 ] }
  - { type: torus, radius: 0.05, tube_radius: 0.015, resolution: 32, opacity: 0.6,
      translate: [ -0.15, -0.22, 1.1 ], rotate: [ 70, 0, 20 ], color: [ 0.95, 0.55, 0.1 ],
      material: { ambient: 0.5, diffuse: 0.3, specular: 0.5, specular_power: 5 } }
  - { type: cylinder, radius: 0.02, height: 0.1, resolution: 24, translate: [ -0.1, -0.3, 0.9 ],
      color: [ 0.6, 0.6, 0.9 ] }
)";
  return s.str();
}

struct Frame
{
  std::string bytes;
  int pipelines = 0;
  long drawn = 0; // pixels that are not the background
};

Frame Render(const std::string& path, bool join)
{
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(path.c_str());
  renderer->SetJoinObjects(join);
  Frame f;
  if (!renderer->Render())
  {
    ADD_FAILURE() << renderer->GetLastError();
    return f;
  }
  f.pipelines = renderer->GetNumberOfPipelines();
  vtkUnsignedCharArray* rgba =
    vtkUnsignedCharArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetScalars());
  f.bytes.assign(reinterpret_cast<const char*>(rgba->GetPointer(0)),
    static_cast<size_t>(rgba->GetNumberOfValues()));
  for (vtkIdType i = 0; i < rgba->GetNumberOfTuples(); ++i)
  {
    f.drawn += rgba->GetValue(4 * i) != 26 || rgba->GetValue(4 * i + 2) != 26;
  }
  return f;
}
} // namespace

TEST(SceneJoining, JoinedObjectsDrawTheSameImage)
{
  for (const std::string shading : { "gouraud", "flat" })
  {
    const std::string path = ::testing::TempDir() + "/catar_joining_" + shading + ".yaml";
    std::ofstream(path) << Scene(shading);
    const Frame alone = Render(path, false);
    const Frame joined = Render(path, true);
    // One pipeline an object alone; joined, one a run of objects with the same arrays (the box
    // with a colour per face, the spheres of three materials, the torus and cylinder of two).
    EXPECT_EQ(alone.pipelines, 6) << shading;
    EXPECT_EQ(joined.pipelines, 3) << shading;
    EXPECT_GT(alone.drawn, 2000) << shading; // the objects are in the picture
    ASSERT_EQ(alone.bytes.size(), joined.bytes.size());
    EXPECT_TRUE(alone.bytes == joined.bytes) << shading << ": the images differ";
  }
}

TEST(SceneJoining, LightingRefusesBrokenMaterialTables)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.06, -0.32, 0.92);
  sphere->SetRadius(0.03);
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputConnection(sphere->GetOutputPort());
  projection->SetCamera(catar_test::DemoCamera());
  projection->Update();
  vtkNew<vtkLight> light;
  light->SetPosition(0.2, 0.0, 1.3);
  light->SetFocalPoint(0.06, -0.32, 0.92);
  vtkNew<vtkLightCollection> lights;
  lights->AddItem(light);
  const vtkIdType n = projection->GetOutput()->GetNumberOfPoints();
  struct Case
  {
    int materials;  // rows of "Materials" (-1: none)
    int components; // per row
    int index;      // the value of every MaterialIndex (-1: no array)
    const char* expected;
  };
  const Case cases[] = {
    { 2, 14, 0, nullptr },
    { -1, 14, 0, "needs the field array 'Materials'" },
    { 2, 14, -1, "needs the point array 'MaterialIndex'" },
    { 2, 14, 2, "names material 2, but 'Materials' has 2" },
    { 2, 13, 0, "14 components" },
  };
  for (const Case& c : cases)
  {
    vtkNew<vtkPolyData> mesh;
    mesh->ShallowCopy(projection->GetOutput());
    if (c.materials >= 0)
    {
      vtkNew<vtkDoubleArray> table;
      table->SetName("Materials");
      table->SetNumberOfComponents(c.components);
      table->SetNumberOfTuples(c.materials);
      table->Fill(0.5);
      mesh->GetFieldData()->AddArray(table);
    }
    if (c.index >= 0)
    {
      vtkNew<vtkIntArray> index;
      index->SetName("MaterialIndex");
      index->SetNumberOfTuples(n);
      index->Fill(c.index);
      mesh->GetPointData()->AddArray(index);
    }
    vtkNew<vtkCatadioptricLighting> lighting;
    lighting->SetInputData(mesh);
    lighting->SetLights(lights);
    vtkNew<catar_test::ErrorCounter> errors;
    errors->Watch(lighting);
    lighting->Update();
    if (c.expected)
    {
      EXPECT_NE(errors->Last.find(c.expected), std::string::npos)
        << "'" << errors->Last << "' lacks '" << c.expected << "'";
    }
    else
    {
      EXPECT_EQ(errors->Count, 0) << errors->Last;
      EXPECT_EQ(lighting->GetOutput()->GetPointData()->GetArray("Colors")->GetNumberOfTuples(), n);
    }
  }
}

// An object with its own `adaptive` gets a pipeline of its own and that tessellation; the others
// keep the scene's. And the scene's `antialias` reaches the compositor.
TEST(SceneJoining, ObjectsWithTheirOwnAdaptiveToleranceAreNotJoined)
{
  std::string text = Scene("gouraud");
  const std::string sphere = "  - { type: sphere, radius: 0.04, resolution: 24,";
  ASSERT_NE(text.find(sphere), std::string::npos);
  text.replace(text.find(sphere), sphere.size(),
    "  - { type: sphere, radius: 0.04, resolution: 3, adaptive: { pixel_tolerance: 0.01 },");
  text += "antialias: { samples: 3 }\n";
  const std::string path = ::testing::TempDir() + "/catar_joining_adaptive.yaml";
  std::ofstream(path) << text;
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(path.c_str());
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  // The box; the first sphere alone; the other two spheres; the torus and cylinder.
  ASSERT_EQ(renderer->GetNumberOfPipelines(), 4);
  for (int p = 0; p < 4; ++p)
  {
    vtkCatadioptricProjection* projection = renderer->GetProjection(p);
    EXPECT_EQ(projection->GetAdaptiveTolerance(), p == 1 ? 0.01 : 0.0) << p;
    if (p == 1)
    {
      EXPECT_GT(projection->GetNumberOfSplitTriangles(), 0);
    }
    else
    {
      EXPECT_EQ(projection->GetNumberOfSplitTriangles(), 0) << p;
    }
  }
  EXPECT_TRUE(renderer->GetCompositor()->GetAntialias());
  EXPECT_EQ(renderer->GetCompositor()->GetAntialiasSamples(), 3);
  EXPECT_GT(renderer->GetCompositor()->GetNumberOfEdgePixels(), 100);
}
