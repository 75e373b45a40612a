#include "vtkCatadioptricSceneRenderer.h"

#include "SceneDescription.h"

#include <Eigen/Geometry>

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricEnvironmentSource.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCellData.h"
#include "vtkCylinderSource.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageReader2Factory.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkProperty.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkPolyDataNormals.h"
#include "vtkPolyDataReader.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTextureMapToSphere.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricSceneRenderer);

namespace
{
const char* const kStageNames[] = { "scene", "meshes", "background", "projection", "lighting",
  "sort", "composite" };
constexpr int kNumberOfStages = 7;
// The stages that run for every frame (projection .. composite).
constexpr int kFirstPerFrameStage = 3;

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& file)
{
  if (!vtksys::SystemTools::FileExists(file, true))
  {
    throw std::runtime_error("mesh file not found: " + file);
  }
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(file));
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".stl")
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".vtk")
  {
    auto r = vtkSmartPointer<vtkPolyDataReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else
  {
    throw std::runtime_error(
      "unsupported mesh format '" + ext + "' (ply, obj, stl, vtp, vtk): " + file);
  }
  reader->Update();
  vtkSmartPointer<vtkPolyData> out = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!out || out->GetNumberOfPolys() + out->GetNumberOfStrips() == 0)
  {
    throw std::runtime_error("no surface read from " + file);
  }
  return out;
}

vtkSmartPointer<vtkPolyData> Procedural(const catar::SceneObject& o)
{
  vtkSmartPointer<vtkPolyDataAlgorithm> source;
  const int res = o.resolution;
  if (o.type == "box")
  {
    auto s = vtkSmartPointer<vtkTessellatedBoxSource>::New();
    s->SetBounds(-0.5 * o.size.x(), 0.5 * o.size.x(), -0.5 * o.size.y(), 0.5 * o.size.y(),
      -0.5 * o.size.z(), 0.5 * o.size.z());
    s->SetLevel(std::max(0, res - 1));
    s->QuadsOff();
    s->DuplicateSharedPointsOn();
    source = s;
  }
  else if (o.type == "sphere")
  {
    auto s = vtkSmartPointer<vtkSphereSource>::New();
    s->SetRadius(o.radius);
    s->SetThetaResolution(std::max(3, 2 * res));
    s->SetPhiResolution(std::max(3, res));
    source = s;
  }
  else if (o.type == "torus")
  {
    vtkNew<vtkParametricTorus> torus;
    torus->SetRingRadius(o.radius);
    torus->SetCrossSectionRadius(o.tubeRadius);
    auto s = vtkSmartPointer<vtkParametricFunctionSource>::New();
    s->SetParametricFunction(torus);
    s->SetUResolution(std::max(3, res));
    s->SetVResolution(std::max(3, res / 2));
    s->SetGenerateTextureCoordinates(!o.texture.empty());
    source = s;
  }
  else if (o.type == "cylinder")
  {
    auto s = vtkSmartPointer<vtkCylinderSource>::New();
    s->SetRadius(o.radius);
    s->SetHeight(o.height);
    s->SetResolution(std::max(3, res));
    s->CappingOn();
    source = s;
  }
  else // plane
  {
    auto s = vtkSmartPointer<vtkPlaneSource>::New();
    s->SetOrigin(-0.5 * o.size.x(), -0.5 * o.size.y(), 0);
    s->SetPoint1(0.5 * o.size.x(), -0.5 * o.size.y(), 0);
    s->SetPoint2(-0.5 * o.size.x(), 0.5 * o.size.y(), 0);
    s->SetResolution(res, res);
    source = s;
  }
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(source->GetOutputPort());
  tri->PassVertsOff();
  tri->PassLinesOff();
  tri->Update();
  return tri->GetOutput();
}

// Colours as a cell array "Colors" (RGBA, uchar): solid, per box face, or a checker.
void Colorize(vtkPolyData* mesh, const catar::SceneObject& o)
{
  static const double palette[6][3] = { { 0.85, 0.15, 0.15 }, { 0.15, 0.7, 0.2 },
    { 0.15, 0.35, 0.9 }, { 0.95, 0.85, 0.1 }, { 0.1, 0.8, 0.85 }, { 0.8, 0.2, 0.8 } };
  const vtkIdType n = mesh->GetNumberOfCells();
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(n);
  vtkNew<vtkIdList> ids;
  const unsigned char alpha = static_cast<unsigned char>(std::lround(255.0 * o.opacity));
  for (vtkIdType c = 0; c < n; ++c)
  {
    double rgb[3] = { o.color.x(), o.color.y(), o.color.z() };
    mesh->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() >= 3 && (o.faceColors || o.pattern == "checker"))
    {
      double p[3][3];
      for (int k = 0; k < 3; ++k)
      {
        mesh->GetPoint(ids->GetId(k), p[k]);
      }
      if (o.faceColors)
      {
        // The face of an axis-aligned box (object coordinates): the dominant normal axis.
        double e1[3], e2[3], nrm[3];
        for (int k = 0; k < 3; ++k)
        {
          e1[k] = p[1][k] - p[0][k];
          e2[k] = p[2][k] - p[0][k];
        }
        nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
        int axis = 0;
        for (int k = 1; k < 3; ++k)
        {
          if (std::abs(nrm[k]) > std::abs(nrm[axis]))
          {
            axis = k;
          }
        }
        const double centre = (p[0][axis] + p[1][axis] + p[2][axis]) / 3.0;
        const int face = 2 * axis + (centre > 0 ? 0 : 1);
        std::copy(palette[face], palette[face] + 3, rgb);
      }
      if (o.pattern == "checker")
      {
        long parity = 0;
        for (int k = 0; k < 3; ++k)
        {
          parity +=
            static_cast<long>(std::floor((p[0][k] + p[1][k] + p[2][k]) / 3.0 / o.patternSize));
        }
        if (parity & 1)
        {
          for (double& v : rgb)
          {
            v *= 0.55;
          }
        }
      }
    }
    const unsigned char rgba[4] = { static_cast<unsigned char>(std::lround(255.0 * rgb[0])),
      static_cast<unsigned char>(std::lround(255.0 * rgb[1])),
      static_cast<unsigned char>(std::lround(255.0 * rgb[2])), alpha };
    colors->SetTypedTuple(c, rgba);
  }
  mesh->GetCellData()->AddArray(colors);
}

// Texture coordinates per face of an axis-aligned box centred at the origin (the paper's section
// 3.3): each face maps its two in-plane coordinates to [0, 1]. The box's points are duplicated
// per face, so every point belongs to one face.
void BoxTextureCoordinates(vtkPolyData* box, const catar::Vec3& size)
{
  vtkNew<vtkFloatArray> tc;
  tc->SetName("TCoords");
  tc->SetNumberOfComponents(2);
  tc->SetNumberOfTuples(box->GetNumberOfPoints());
  tc->FillValue(0.0f);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < box->GetNumberOfCells(); ++c)
  {
    box->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() < 3)
    {
      continue;
    }
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      box->GetPoint(ids->GetId(k), p[k]);
    }
    catar::Vec3 n = (catar::Vec3(p[1][0], p[1][1], p[1][2]) - catar::Vec3(p[0][0], p[0][1], p[0][2]))
                      .cross(catar::Vec3(p[2][0], p[2][1], p[2][2]) -
                        catar::Vec3(p[0][0], p[0][1], p[0][2]));
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double q[3];
      box->GetPoint(ids->GetId(k), q);
      tc->SetTuple2(ids->GetId(k), q[a] / size[a] + 0.5, q[b] / size[b] + 0.5);
    }
  }
  box->GetPointData()->SetTCoords(tc);
}

// A 256 x 256 RGB checkerboard of 8 x 8 squares, white and light grey, with thin dark lines.
vtkSmartPointer<vtkImageData> CheckerTexture()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(256, 256, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  unsigned char* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int j = 0; j < 256; ++j)
  {
    for (int i = 0; i < 256; ++i)
    {
      const bool line = (i % 32) < 2 || (j % 32) < 2;
      const bool odd = ((i / 32) + (j / 32)) & 1;
      const unsigned char v = line ? 60 : (odd ? 170 : 255);
      std::fill(p, p + 3, v);
      p += 3;
    }
  }
  return image;
}

vtkSmartPointer<vtkImageData> ReadTexture(const std::string& file)
{
  if (file == "checker")
  {
    return CheckerTexture();
  }
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(file.c_str()));
  if (!reader)
  {
    throw std::runtime_error("texture image cannot be read: " + file);
  }
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  vtkDataArray* s = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!s || s->GetDataType() != VTK_UNSIGNED_CHAR)
  {
    throw std::runtime_error("texture must be an 8-bit image: " + file);
  }
  return image;
}

vtkSmartPointer<vtkPolyData> BuildObject(const catar::SceneObject& o)
{
  vtkSmartPointer<vtkPolyData> local;
  if (o.type == "mesh")
  {
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputData(ReadMesh(o.file));
    tri->PassVertsOff();
    tri->PassLinesOff();
    tri->Update();
    local = tri->GetOutput();
  }
  else
  {
    local = Procedural(o);
  }
  Colorize(local, o);
  if (!o.texture.empty())
  {
    if (o.type == "box")
    {
      BoxTextureCoordinates(local, o.size);
    }
    else if (!local->GetPointData()->GetTCoords())
    {
      vtkNew<vtkTextureMapToSphere> map;
      map->SetInputData(local);
      map->PreventSeamOn();
      map->Update();
      local = vtkPolyData::SafeDownCast(map->GetOutput());
    }
  }
  vtkNew<vtkTransform> t;
  t->PostMultiply();
  t->Scale(o.scale.x(), o.scale.y(), o.scale.z());
  t->RotateX(o.rotate.x());
  t->RotateY(o.rotate.y());
  t->RotateZ(o.rotate.z());
  t->Translate(o.translate.x(), o.translate.y(), o.translate.z());
  vtkNew<vtkTransformPolyDataFilter> xf;
  xf->SetTransform(t);
  xf->SetInputData(local);
  xf->Update();
  vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(xf->GetOutput());
  return out;
}
} // namespace

struct vtkCatadioptricSceneRenderer::Internals
{
  catar::SceneDescription Scene;
  bool Loaded = false;
  std::string LoadedName;
  std::string Error;
  double Times[kNumberOfStages] = { 0, 0, 0, 0, 0, 0, 0 };
  vtkIdType Triangles = 0;
  vtkNew<vtkCatadioptricCamera> Camera;
  vtkSmartPointer<vtkAlgorithm> Background; // environment source or image reader; may be null
  vtkNew<vtkLightCollection> Lights;
  std::vector<vtkSmartPointer<vtkCatadioptricProjection>> Projections;
  std::vector<vtkSmartPointer<vtkCatadioptricLighting>> Lightings;
  std::vector<vtkSmartPointer<vtkCatadioptricPainterSort>> Sorts;
  vtkNew<vtkCatadioptricCompositor> Compositor;
};

vtkCatadioptricSceneRenderer::vtkCatadioptricSceneRenderer()
  : Internal(new Internals)
{
}

vtkCatadioptricSceneRenderer::~vtkCatadioptricSceneRenderer()
{
  this->SetSceneFileName(nullptr);
}

const char* vtkCatadioptricSceneRenderer::GetDemoSceneText()
{
  return catar::DemoSceneText();
}

bool vtkCatadioptricSceneRenderer::LoadScene()
{
  Internals& in = *this->Internal;
  in.Loaded = false;
  in.Error.clear();
  std::fill(in.Times, in.Times + kNumberOfStages, 0.0);
  const std::string name = this->SceneFileName ? this->SceneFileName : "";
  auto t0 = Clock::now();
  catar::SceneDescription scene;
  if (name.empty())
  {
    scene = catar::DemoScene();
  }
  else if (!catar::LoadScene(name, scene, in.Error))
  {
    vtkErrorMacro(<< in.Error);
    return false;
  }
  catar::CameraModel model = scene.camera;
  if (scene.width > 0 && scene.height > 0 &&
    (scene.width != model.intrinsics.width || scene.height != model.intrinsics.height))
  {
    model = model.Resized(scene.width, scene.height);
  }
  in.Camera->SetModel(model);
  auto t1 = Clock::now();
  in.Times[0] = Seconds(t0, t1);

  // Lights, shared by every object.
  in.Lights->RemoveAllItems();
  for (const catar::SceneLight& l : scene.lighting.lights)
  {
    vtkNew<vtkLight> light;
    light->SetPositional(l.type != "directional");
    light->SetPosition(l.position.data());
    light->SetFocalPoint(l.focalPoint.data());
    light->SetConeAngle(l.type == "spot" ? l.coneAngle : 90.0);
    light->SetExponent(l.exponent);
    light->SetIntensity(l.intensity);
    light->SetAmbientColor(l.ambient.data());
    light->SetDiffuseColor(l.color.data());
    light->SetSpecularColor(l.color.data());
    light->SetAttenuationValues(l.attenuation.data());
    in.Lights->AddItem(light);
  }
  const bool lit = scene.lighting.shading != "none";

  // Meshes: prepared once.
  in.Projections.clear();
  in.Lightings.clear();
  in.Sorts.clear();
  in.Compositor->RemoveAllInputConnections(1);
  in.Triangles = 0;
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  try
  {
    for (const catar::SceneObject& o : scene.objects)
    {
      meshes.push_back(BuildObject(o));
      in.Triangles += meshes.back()->GetNumberOfPolys();
    }
  }
  catch (const std::exception& e)
  {
    in.Error = (name.empty() ? std::string("demo scene") : name) + ": " + e.what();
    vtkErrorMacro(<< in.Error);
    return false;
  }
  in.Compositor->RemoveAllTextureConnections();
  int textures = 0;
  for (size_t i = 0; i < meshes.size(); ++i)
  {
    const catar::SceneObject& o = scene.objects[i];
    vtkNew<vtkIntArray> index;
    index->SetName("TextureIndex");
    meshes[i]->GetFieldData()->AddArray(index);
    if (o.texture.empty())
    {
      index->InsertNextValue(-1); // untextured, even when the mesh has texture coordinates
      continue;
    }
    try
    {
      in.Compositor->AddTextureData(ReadTexture(o.texture));
    }
    catch (const std::exception& e)
    {
      in.Error = (name.empty() ? std::string("demo scene") : name) + ": " + e.what();
      vtkErrorMacro(<< in.Error);
      return false;
    }
    index->InsertNextValue(textures++);
  }
  for (size_t i = 0; i < meshes.size(); ++i)
  {
    const catar::SceneObject& o = scene.objects[i];
    auto proj = vtkSmartPointer<vtkCatadioptricProjection>::New();
    proj->SetInputData(meshes[i]);
    proj->SetCamera(in.Camera);
    proj->SetSolver(scene.solver == catar::SolverType::Iterative
        ? vtkCatadioptricProjection::ITERATIVE
        : vtkCatadioptricProjection::QUARTIC);
    vtkAlgorithmOutput* last = proj->GetOutputPort();
    if (lit)
    {
      auto lighting = vtkSmartPointer<vtkCatadioptricLighting>::New();
      lighting->SetInputConnection(last);
      lighting->SetLights(in.Lights);
      lighting->SetShadingMode(scene.lighting.shading == "flat"
          ? vtkCatadioptricLighting::FLAT
          : vtkCatadioptricLighting::GOURAUD);
      lighting->SetShadows(scene.lighting.shadows);
      lighting->SetGlobalAmbient(scene.lighting.globalAmbient.data());
      lighting->SetAmbient(o.ambient);
      lighting->SetDiffuse(o.diffuse);
      lighting->SetSpecular(o.specular);
      lighting->SetSpecularPower(o.specularPower);
      lighting->GetProperty()->SetSpecularColor(o.specularColor.data());
      // The other objects cast shadows too.
      for (size_t j = 0; j < meshes.size(); ++j)
      {
        if (j != i)
        {
          lighting->AddOccluderData(meshes[j]);
        }
      }
      in.Lightings.push_back(lighting);
      last = lighting->GetOutputPort();
    }
    auto sort = vtkSmartPointer<vtkCatadioptricPainterSort>::New();
    sort->SetInputConnection(last);
    sort->DropInvisibleCellsOn();
    in.Compositor->AddMeshConnection(sort->GetOutputPort());
    in.Projections.push_back(proj);
    in.Sorts.push_back(sort);
  }
  auto t2 = Clock::now();
  in.Times[1] = Seconds(t1, t2);

  // Background.
  in.Background = nullptr;
  in.Compositor->SetFrameConnection(nullptr);
  in.Compositor->SetImageSize(0, 0);
  const catar::SceneBackground& bg = scene.background;
  if (bg.type == "environment")
  {
    auto env = vtkSmartPointer<vtkCatadioptricEnvironmentSource>::New();
    env->SetCamera(in.Camera);
    env->SetSamples(bg.samples);
    in.Background = env;
  }
  else if (bg.type == "image")
  {
    vtkSmartPointer<vtkImageReader2> reader;
    reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(bg.image.c_str()));
    if (!reader)
    {
      in.Error = "background image cannot be read: " + bg.image;
      vtkErrorMacro(<< in.Error);
      return false;
    }
    reader->SetFileName(bg.image.c_str());
    in.Background = reader;
  }
  else
  {
    in.Compositor->SetBackgroundColor(bg.color.x(), bg.color.y(), bg.color.z(), 1.0);
    in.Compositor->SetImageSize(model.intrinsics.width, model.intrinsics.height);
  }
  if (in.Background)
  {
    in.Compositor->SetFrameConnection(in.Background->GetOutputPort());
  }
  in.Scene = scene;
  in.LoadedName = name;
  in.Loaded = true;
  return true;
}

bool vtkCatadioptricSceneRenderer::Render()
{
  Internals& in = *this->Internal;
  const std::string name = this->SceneFileName ? this->SceneFileName : "";
  if (!in.Loaded || in.LoadedName != name)
  {
    if (!this->LoadScene())
    {
      return false;
    }
  }
  auto fail = [&](const char* stage) {
    in.Error = std::string(stage) + " failed (see the VTK error above)";
    vtkErrorMacro(<< in.Error);
    return false;
  };
  auto t0 = Clock::now();
  if (in.Background)
  {
    in.Background->Update();
    if (in.Background->GetErrorCode() != 0)
    {
      return fail("background");
    }
    vtkImageData* frame = vtkImageData::SafeDownCast(in.Background->GetOutputDataObject(0));
    int dims[3] = { 0, 0, 0 };
    if (frame)
    {
      frame->GetDimensions(dims);
    }
    if (dims[0] != in.Camera->GetImageWidth() || dims[1] != in.Camera->GetImageHeight())
    {
      in.Error = "the background image is " + std::to_string(dims[0]) + "x" +
        std::to_string(dims[1]) + " but the camera image is " +
        std::to_string(in.Camera->GetImageWidth()) + "x" +
        std::to_string(in.Camera->GetImageHeight());
      vtkErrorMacro(<< in.Error);
      return false;
    }
  }
  auto t1 = Clock::now();
  for (auto& p : in.Projections)
  {
    if (!p->GetExecutive()->Update())
    {
      return fail("projection");
    }
  }
  auto t2 = Clock::now();
  for (auto& l : in.Lightings)
  {
    if (!l->GetExecutive()->Update())
    {
      return fail("lighting");
    }
  }
  auto t3 = Clock::now();
  for (auto& s : in.Sorts)
  {
    if (!s->GetExecutive()->Update())
    {
      return fail("sort");
    }
  }
  auto t4 = Clock::now();
  if (!in.Compositor->GetExecutive()->Update())
  {
    return fail("composite");
  }
  auto t5 = Clock::now();
  in.Times[2] = Seconds(t0, t1);
  in.Times[3] = Seconds(t1, t2);
  in.Times[4] = Seconds(t2, t3);
  in.Times[5] = Seconds(t3, t4);
  in.Times[6] = Seconds(t4, t5);
  in.Error.clear();
  return true;
}

vtkImageData* vtkCatadioptricSceneRenderer::GetOutput()
{
  return this->Internal->Compositor->GetOutput();
}

bool vtkCatadioptricSceneRenderer::WritePNG(const char* fileName)
{
  vtkImageData* image = this->GetOutput();
  if (!image || image->GetNumberOfPoints() == 0)
  {
    this->Internal->Error = "nothing rendered yet";
    vtkErrorMacro(<< this->Internal->Error);
    return false;
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(fileName);
  writer->SetInputData(image);
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    this->Internal->Error = std::string("cannot write ") + fileName;
    vtkErrorMacro(<< this->Internal->Error);
    return false;
  }
  return true;
}

vtkCatadioptricCamera* vtkCatadioptricSceneRenderer::GetCamera()
{
  return this->Internal->Camera;
}

int vtkCatadioptricSceneRenderer::GetNumberOfStages()
{
  return kNumberOfStages;
}

int vtkCatadioptricSceneRenderer::GetFirstPerFrameStage()
{
  return kFirstPerFrameStage;
}

double vtkCatadioptricSceneRenderer::GetFrameTime()
{
  double t = 0.0;
  for (int s = kFirstPerFrameStage; s < kNumberOfStages; ++s)
  {
    t += this->Internal->Times[s];
  }
  return t;
}

vtkLightCollection* vtkCatadioptricSceneRenderer::GetLights()
{
  return this->Internal->Lights;
}

const char* vtkCatadioptricSceneRenderer::GetStageName(int stage)
{
  return (stage >= 0 && stage < kNumberOfStages) ? kStageNames[stage] : "";
}

double vtkCatadioptricSceneRenderer::GetStageTime(int stage)
{
  return (stage >= 0 && stage < kNumberOfStages) ? this->Internal->Times[stage] : 0.0;
}

vtkIdType vtkCatadioptricSceneRenderer::GetNumberOfTriangles()
{
  return this->Internal->Triangles;
}

const char* vtkCatadioptricSceneRenderer::GetLastError()
{
  return this->Internal->Error.c_str();
}

void vtkCatadioptricSceneRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SceneFileName: " << (this->SceneFileName ? this->SceneFileName : "(demo)")
     << "\n";
  os << indent << "Triangles: " << this->Internal->Triangles << "\n";
}
