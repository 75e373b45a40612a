#include "vtkCatadioptricRayTracer.h"

#include "Polygons.h"
#include "Projector.h"
#include "RayTracer.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricColorArray.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricLightingSupport.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricRayTracer);

// The camera slot by hand (not vtkCatadioptricCameraSlotMacro): GetMTime also includes the
// lighting filters'.
void vtkCatadioptricRayTracer::SetCamera(vtkCatadioptricCamera* camera)
{
  if (this->CameraSlot.SetCamera(camera))
  {
    this->Modified();
  }
}

vtkCatadioptricCamera* vtkCatadioptricRayTracer::GetCamera()
{
  return this->CameraSlot.GetCamera();
}

void vtkCatadioptricRayTracer::SetCalibrationFileName(const char* fileName)
{
  if (this->CameraSlot.SetCalibrationFileName(fileName))
  {
    this->Modified();
  }
}

vtkCatadioptricCameraSlotMirrorMacro(vtkCatadioptricRayTracer);
vtkCatadioptricCameraSlotPanelMacro(vtkCatadioptricRayTracer);
vtkCatadioptricCameraSlotTrajectoryMacro(vtkCatadioptricRayTracer);

const char* vtkCatadioptricRayTracer::GetCalibrationFileName()
{
  return this->CameraSlot.GetCalibrationFileName();
}

vtkCatadioptricCamera* vtkCatadioptricRayTracer::ResolveCamera(vtkInformation* outInfo)
{
  std::string error;
  vtkCatadioptricCamera* camera = this->CameraSlot.Resolve(error, outInfo);
  if (!camera)
  {
    vtkErrorMacro(<< error);
  }
  return camera;
}

namespace
{
// A mesh of port 1 as the tracer has it, and what it was made from. The geometry (points,
// triangles, their cell ids) is kept while the mesh is the same object and neither it, its
// points, its cells nor its OriginalCellId were modified; the arrays read for shading (colours,
// normals, texture coordinates) while, in addition, its point and cell data and the settings that
// choose them are the same. The tracer keeps the acceleration structure of a mesh given again as
// the same TraceMesh object.
struct MeshEntry
{
  // Geometry.
  vtkWeakPointer<vtkPolyData> Mesh;
  bool HasMesh = false;
  vtkMTimeType MeshTime = 0; // the mesh object's own (SetPoints, SetPolys, Modified)
  vtkPoints* Points = nullptr;
  vtkMTimeType PointsTime = 0;
  vtkCellArray* Cells[3] = { nullptr, nullptr, nullptr }; // verts, lines, polys
  vtkMTimeType CellsTime[3] = { 0, 0, 0 };
  vtkDataArray* Original = nullptr;
  vtkMTimeType OriginalTime = 0;
  std::vector<vtkIdType> TriangleCells; // per triangle, its cell
  // Shading arrays.
  bool HasArrays = false;
  vtkMTimeType PointDataTime = 0;
  vtkMTimeType CellDataTime = 0;
  std::string ColorName;
  float Solid[4] = { 0, 0, 0, 0 };
  bool Smooth = false;
  bool Textured = false;

  std::shared_ptr<catar::TraceMesh> Trace;
};
} // namespace

struct vtkCatadioptricRayTracer::Internals
{
  catar::RayTracer Tracer;
  std::vector<vtkSmartPointer<vtkCatadioptricLighting>> Lightings;
  std::vector<MeshEntry> Meshes; // per connection of port 1, from the last update
};

namespace
{
catar::Vec3 V3(const double v[3])
{
  return catar::Vec3(v[0], v[1], v[2]);
}

} // namespace

vtkCatadioptricRayTracer::vtkCatadioptricRayTracer()
  : Internal(new Internals)
{
}

vtkCatadioptricRayTracer::~vtkCatadioptricRayTracer() = default;

void vtkCatadioptricRayTracer::SetMeshLighting(int index, vtkCatadioptricLighting* lighting)
{
  if (index < 0)
  {
    vtkErrorMacro("Negative mesh index " << index << ".");
    return;
  }
  auto& l = this->Internal->Lightings;
  if (static_cast<std::size_t>(index) >= l.size())
  {
    l.resize(index + 1);
  }
  if (l[index] != lighting)
  {
    l[index] = lighting;
    this->Modified();
  }
}

vtkCatadioptricLighting* vtkCatadioptricRayTracer::GetMeshLighting(int index)
{
  const auto& l = this->Internal->Lightings;
  return index >= 0 && static_cast<std::size_t>(index) < l.size() ? l[index].Get() : nullptr;
}

void vtkCatadioptricRayTracer::RemoveAllMeshLightings()
{
  if (!this->Internal->Lightings.empty())
  {
    this->Internal->Lightings.clear();
    this->Modified();
  }
}

vtkIdType vtkCatadioptricRayTracer::GetNumberOfSceneBuilds()
{
  return static_cast<vtkIdType>(this->Internal->Tracer.GetNumberOfBuilds());
}

vtkIdType vtkCatadioptricRayTracer::GetNumberOfSceneRefits()
{
  return static_cast<vtkIdType>(this->Internal->Tracer.GetNumberOfRefits());
}

vtkIdType vtkCatadioptricRayTracer::GetNumberOfRayBackProjections()
{
  return static_cast<vtkIdType>(this->Internal->Tracer.GetNumberOfRayPreparations());
}

vtkMTimeType vtkCatadioptricRayTracer::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  t = std::max(t, this->CameraSlot.GetCameraMTime());
  for (const auto& l : this->Internal->Lightings)
  {
    if (l)
    {
      t = std::max(t, l->GetMTime());
    }
  }
  return t;
}

void vtkCatadioptricRayTracer::ImageSizeWithoutFrame(vtkInformationVector**, int size[2])
{
  size[0] = size[1] = 0;
  if (this->ImageSize[0] > 0 && this->ImageSize[1] > 0)
  {
    size[0] = this->ImageSize[0];
    size[1] = this->ImageSize[1];
  }
  else if (std::string ignored; vtkCatadioptricCamera* camera = this->CameraSlot.Resolve(ignored))
  {
    // RequestData reports a missing camera.
    size[0] = camera->GetImageWidth();
    size[1] = camera->GetImageHeight();
  }
}

namespace
{
// What the tracer needs of a mesh besides the mesh and its lighting filter.
struct MeshSettings
{
  const double* color;        // the sink's Color, for meshes without colours and lighting
  double opacity;             // the sink's Opacity
  const char* colorArrayName; // the sink's ColorArrayName, for meshes without lighting
  bool visibleTriangleIds;    // OutputVisibleTriangle
  std::size_t textureCount;   // textures connected
};

// The lights of the scene: the first lit mesh's lighting filter's; shadows when any asks.
struct SceneLighting
{
  std::vector<catar::LightSource> lights;
  catar::Vec3 globalAmbient = catar::Vec3::Zero();
  bool haveLights = false;
  bool shadows = false;
};

// The tracer's mesh of a VTK mesh in `entry`: triangles (polygons as fans), colours, normals,
// texture coordinates (each made again only when what it is made from changed), lighting.
// Returns "" or what is wrong, to follow "Mesh <index>".
std::string UpdateTraceMesh(vtkPolyData* mesh, vtkCatadioptricLighting* lighting,
  const MeshSettings& in, MeshEntry& entry, SceneLighting& scene)
{
  std::string meshError;
  if (!vtkCatadioptricMeshCheck::Check(mesh, meshError))
  {
    return ": " + meshError;
  }
  if (in.visibleTriangleIds && mesh->GetNumberOfCells() >= (vtkIdType(1) << 32))
  {
    return " has " + std::to_string(mesh->GetNumberOfCells()) +
      " cells: VisibleTriangle ids hold cell ids below 2^32.";
  }
  const vtkIdType nPts = mesh->GetNumberOfPoints();

  // Geometry: the same object, unmodified, with the same points, cells and original ids.
  vtkPoints* points = mesh->GetPoints();
  vtkCellArray* cells[3] = { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys() };
  vtkDataArray* original = mesh->GetCellData()->GetArray(vtkCatadioptricArrayNames::OriginalCellId);
  // The cells (and the ids they report) alone the same: the triangles are kept.
  bool sameCells = entry.Trace && entry.HasMesh && entry.Mesh == mesh &&
    entry.Original == original && entry.OriginalTime == (original ? original->GetMTime() : 0);
  for (int k = 0; k < 3; ++k)
  {
    sameCells = sameCells && entry.Cells[k] == cells[k] &&
      entry.CellsTime[k] == (cells[k] ? cells[k]->GetMTime() : 0);
  }
  const bool sameGeometry = sameCells && entry.MeshTime == mesh->vtkObject::GetMTime() &&
    entry.Points == points && entry.PointsTime == (points ? points->GetMTime() : 0);
  if (!sameGeometry)
  {
    // A new TraceMesh: the tracer refits or builds the scene again for it.
    MeshEntry previous = std::move(entry);
    entry = MeshEntry();
    entry.Trace = std::make_shared<catar::TraceMesh>();
    catar::TraceMesh& tm = *entry.Trace;
    tm.points.resize(nPts);
    vtkCatadioptricParallel::For(0, nPts, 4096, [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType i = b; i < e; ++i)
      {
        double p[3];
        points->GetPoint(i, p);
        tm.points[i] = V3(p);
      }
    });
    if (sameCells)
    {
      tm.triangles = previous.Trace->triangles;
      tm.triangleIds = previous.Trace->triangleIds;
      entry.TriangleCells = std::move(previous.TriangleCells);
    }
    else
    {
      const vtkIdType firstCell = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
      vtkCellArray* polys = mesh->GetPolys();
      const vtkIdType nPolys = polys->GetNumberOfCells();
      tm.triangles.reserve(static_cast<std::size_t>(nPolys));
      entry.TriangleCells.reserve(static_cast<std::size_t>(nPolys));
      tm.triangleIds.reserve(static_cast<std::size_t>(nPolys));
      vtkNew<vtkIdList> ids;
      for (vtkIdType c = 0; c < nPolys; ++c)
      {
        vtkIdType size;
        const vtkIdType* pts;
        polys->GetCellAtId(c, size, pts, ids);
        catar::PolygonTriangles(
          pts, static_cast<std::size_t>(size), [&](vtkIdType a, vtkIdType b, vtkIdType d) {
            tm.triangles.push_back({ static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
              static_cast<std::uint32_t>(d) });
            entry.TriangleCells.push_back(firstCell + c);
            tm.triangleIds.push_back(original
                ? static_cast<catar::RasterId>(original->GetComponent(firstCell + c, 0))
                : static_cast<catar::RasterId>(firstCell + c));
          });
      }
    }
    entry.Mesh = mesh;
    entry.HasMesh = true;
    entry.MeshTime = mesh->vtkObject::GetMTime();
    entry.Points = points;
    entry.PointsTime = points ? points->GetMTime() : 0;
    for (int k = 0; k < 3; ++k)
    {
      entry.Cells[k] = cells[k];
      entry.CellsTime[k] = cells[k] ? cells[k]->GetMTime() : 0;
    }
    entry.Original = original;
    entry.OriginalTime = original ? original->GetMTime() : 0;
  }
  catar::TraceMesh& tm = *entry.Trace;

  // What chooses the shading arrays.
  const char* colorName = lighting ? lighting->GetInputColorArrayName() : in.colorArrayName;
  float solid[4] = { static_cast<float>(in.color[0]), static_cast<float>(in.color[1]),
    static_cast<float>(in.color[2]), 1.0f };
  if (lighting)
  {
    const double* d = lighting->GetProperty()->GetDiffuseColor();
    for (int k = 0; k < 3; ++k)
    {
      solid[k] = static_cast<float>(d[k]);
    }
  }
  const bool shaded = lighting && lighting->GetShadingMode() != vtkCatadioptricLighting::NONE;
  const bool smooth = shaded && lighting->GetShadingMode() != vtkCatadioptricLighting::FLAT;
  int texture = -1;
  vtkDataArray* tcoords =
    in.textureCount > 0 ? vtkCatadioptricImageSupport::TextureCoordinates(mesh) : nullptr;
  if (tcoords)
  {
    std::string textureError;
    if (!vtkCatadioptricImageSupport::TextureIndex(mesh, texture, textureError))
    {
      return ": " + textureError;
    }
    if (texture >= static_cast<int>(in.textureCount))
    {
      return " asks for texture " + std::to_string(texture) + " but " +
        std::to_string(in.textureCount) + " are connected.";
    }
  }
  const bool textured = tcoords && texture >= 0;
  const bool sameArrays = entry.HasArrays &&
    entry.PointDataTime == mesh->GetPointData()->GetMTime() &&
    entry.CellDataTime == mesh->GetCellData()->GetMTime() &&
    entry.ColorName == (colorName ? colorName : "") && std::equal(solid, solid + 4, entry.Solid) &&
    entry.Smooth == smooth && entry.Textured == textured;
  if (!sameArrays)
  {
    const vtkCatadioptricColorArray colors(mesh, colorName, solid);
    tm.colorSource = catar::TraceMesh::ColorSource::Solid;
    tm.colors.clear();
    if (colors.HasArray())
    {
      tm.colorSource = colors.IsPerPoint() ? catar::TraceMesh::ColorSource::Point
                                           : catar::TraceMesh::ColorSource::Cell;
      const std::size_t n = colors.IsPerPoint() ? tm.points.size() : tm.triangles.size();
      tm.colors.resize(4 * n);
      vtkCatadioptricParallel::For(
        0, static_cast<vtkIdType>(n), 4096, [&](vtkIdType b, vtkIdType e) {
          for (vtkIdType i = b; i < e; ++i)
          {
            if (colors.IsPerPoint())
            {
              colors.Get(i, 0, &tm.colors[4 * i]);
            }
            else
            {
              colors.Get(0, entry.TriangleCells[i], &tm.colors[4 * i]);
            }
          }
        });
    }
    tm.normals.clear();
    if (smooth)
    {
      vtkDataArray* normals = mesh->GetPointData()->GetNormals();
      if (normals && normals->GetNumberOfComponents() == 3)
      {
        tm.normals.resize(nPts);
        std::vector<catar::Vec3> geometric; // for normals of zero length, NaN or Inf
        for (vtkIdType i = 0; i < nPts; ++i)
        {
          tm.normals[i] = V3(normals->GetTuple3(i)).normalized();
          if (!(tm.normals[i].squaredNorm() > 0.0))
          {
            if (geometric.empty())
            {
              geometric = vtkCatadioptricLightingSupport::VertexNormals(mesh);
            }
            tm.normals[i] = geometric[i];
          }
        }
      }
      else
      {
        tm.normals = vtkCatadioptricLightingSupport::VertexNormals(mesh);
      }
    }
    tm.tcoords.clear();
    if (textured)
    {
      tm.tcoords.resize(2 * static_cast<std::size_t>(nPts));
      for (vtkIdType i = 0; i < nPts; ++i)
      {
        tm.tcoords[2 * i] = static_cast<float>(tcoords->GetComponent(i, 0));
        tm.tcoords[2 * i + 1] = static_cast<float>(tcoords->GetComponent(i, 1));
      }
    }
    entry.HasArrays = true;
    entry.PointDataTime = mesh->GetPointData()->GetMTime();
    entry.CellDataTime = mesh->GetCellData()->GetMTime();
    entry.ColorName = colorName ? colorName : "";
    std::copy(solid, solid + 4, entry.Solid);
    entry.Smooth = smooth;
    entry.Textured = textured;
  }
  tm.texture = textured ? texture : -1;

  // Material and lights: read at every update (a few numbers).
  tm.color = catar::Vec3(solid[0], solid[1], solid[2]);
  tm.opacity = in.opacity;
  if (shaded)
  {
    vtkProperty* prop = lighting->GetProperty();
    tm.shading = smooth ? catar::TraceMesh::Shading::Smooth : catar::TraceMesh::Shading::Flat;
    tm.material = vtkCatadioptricLightingSupport::ConvertProperty(prop, lighting->GetEmission());
    tm.ambientFactor = prop->GetAmbient();
    tm.diffuseFactor = prop->GetDiffuse();
    tm.opacity *= prop->GetOpacity();
    tm.twoSided = lighting->GetTwoSidedLighting();
    if (!scene.haveLights)
    {
      scene.lights = vtkCatadioptricLightingSupport::ConvertLights(lighting->GetLights());
      scene.globalAmbient = V3(lighting->GetGlobalAmbient());
      scene.haveLights = true;
    }
    scene.shadows = scene.shadows || lighting->GetShadows();
    const std::string lightingError = catar::ValidateLighting(scene.lights, tm.material,
      scene.globalAmbient, tm.ambientFactor, tm.diffuseFactor, tm.opacity);
    if (!lightingError.empty())
    {
      return ": cannot shade: " + lightingError + ".";
    }
  }
  else
  {
    tm.shading = catar::TraceMesh::Shading::None;
    tm.material = catar::Material();
    tm.ambientFactor = tm.diffuseFactor = 1.0;
    tm.twoSided = true;
    if (lighting)
    {
      tm.opacity *= lighting->GetProperty()->GetOpacity();
    }
  }
  return std::string();
}

// The meshes to trace, one a port-1 input (an empty one for a missing input), each made again
// only where it changed (entries keep them between executions), lit with the tracer's
// SetMeshLighting or the lighting recorded in the mesh; the scene's lights gathered in
// sceneLighting. False, with an error, when a mesh cannot be used.
bool UpdateMeshes(vtkCatadioptricRayTracer* self, vtkInformationVector* meshInputs,
  const MeshSettings& settings, std::vector<MeshEntry>& entries,
  std::vector<std::shared_ptr<const catar::TraceMesh>>& meshes, SceneLighting& sceneLighting)
{
  const int nMeshes = meshInputs->GetNumberOfInformationObjects();
  entries.resize(static_cast<std::size_t>(nMeshes));
  meshes.assign(static_cast<std::size_t>(nMeshes), nullptr);
  for (int m = 0; m < nMeshes; ++m)
  {
    MeshEntry& entry = entries[static_cast<std::size_t>(m)];
    vtkPolyData* mesh = vtkPolyData::GetData(meshInputs, m);
    if (!mesh)
    {
      if (!entry.Trace || entry.HasMesh)
      {
        entry = MeshEntry();
        entry.Trace = std::make_shared<catar::TraceMesh>();
      }
      meshes[static_cast<std::size_t>(m)] = entry.Trace;
      continue;
    }
    // SetMeshLighting's, else the lighting recorded by the lighting filter that made the mesh.
    vtkCatadioptricLighting* lighting = self->GetMeshLighting(m);
    vtkSmartPointer<vtkCatadioptricLighting> recorded;
    if (!lighting && self->GetUseInputLighting() &&
      vtkCatadioptricLighting::HasLightingRecord(mesh->GetFieldData()))
    {
      recorded = vtkSmartPointer<vtkCatadioptricLighting>::New();
      if (!recorded->ReadFromFieldData(mesh->GetFieldData()))
      {
        vtkErrorWithObjectMacro(self,
          "Mesh " << m
                  << " has a malformed lighting record (field data LightingSettings, "
                     "LightingLights, LightingColorArray): turn UseInputLighting off "
                     "or light it again with vtkCatadioptricLighting.");
        return false;
      }
      lighting = recorded;
    }
    const std::string error = UpdateTraceMesh(mesh, lighting, settings, entry, sceneLighting);
    if (!error.empty())
    {
      entry = MeshEntry();
      vtkErrorWithObjectMacro(self, "Mesh " << m << error);
      return false;
    }
    meshes[static_cast<std::size_t>(m)] = entry.Trace;
  }
  return true;
}
} // namespace

int vtkCatadioptricRayTracer::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  // The trajectory's times (the meshes are still: the camera moves).
  std::string error;
  if (this->CameraSlot.GetTrajectoryFileName() &&
    !this->CameraSlot.AnnounceTimeSteps(outputVector->GetInformationObject(0), error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  return 1;
}

int vtkCatadioptricRayTracer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Out of memory (a mesh or an image too large for the memory left): the filter's error.
  return vtkCatadioptricAllocation::Guard(
    this, [&] { return this->Execute(inputVector, outputVector); },
    [&] {
      return "tracing " + vtkCatadioptricAllocation::DescribeInput(inputVector[1]) + " into " +
        vtkCatadioptricAllocation::DescribeOutputImage(outputVector);
    });
}

int vtkCatadioptricRayTracer::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->NumberOfMirrorRays = this->NumberOfTracedRays = 0;
  this->NumberOfHits = this->NumberOfShadowRays = 0;
  vtkCatadioptricCamera* camera = this->ResolveCamera(outputVector->GetInformationObject(0));
  if (!camera)
  {
    return 0;
  }
  const catar::CameraModel model = camera->GetModel();
  const catar::Projector projector(model);
  if (!projector.IsValid())
  {
    vtkErrorMacro("Invalid camera: " << projector.GetError());
    return 0;
  }
  const int width = model.intrinsics.width;
  const int height = model.intrinsics.height;

  // Frame or background, as the compositor.
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkImageData* frame = vtkImageData::GetData(inputVector[0]);
  const int frameComponents = this->CheckFrame(frame, width, height);
  int size[2] = { width, height }; // the camera's: ImageSize may only agree with it
  if (frameComponents < 0 || !this->ResolveImageSize(frame != nullptr, size[0], size[1]))
  {
    return 0;
  }
  unsigned char* out = vtkCatadioptricImageSupport::AllocateRGBA(output, width, height);
  const vtkIdType nPixels = static_cast<vtkIdType>(width) * height;
  if (frame)
  {
    vtkCatadioptricImageSupport::CopyFrame(
      static_cast<const unsigned char*>(frame->GetPointData()->GetScalars()->GetVoidPointer(0)),
      frameComponents, nPixels, out);
  }
  else
  {
    vtkCatadioptricImageSupport::FillColor(this->BackgroundColor, nPixels, out);
  }

  // Textures.
  std::vector<catar::TextureView> textures;
  std::string textureError;
  if (!vtkCatadioptricImageSupport::ReadTextures(
        inputVector[2], this->RepeatTextures, textures, textureError))
  {
    vtkErrorMacro(<< textureError);
    return 0;
  }

  // Meshes: made again only where they changed.
  Internals& in = *this->Internal;
  SceneLighting sceneLighting;
  const MeshSettings settings{ this->Color, this->Opacity, this->ColorArrayName,
    this->OutputVisibleTriangle, textures.size() };
  std::vector<std::shared_ptr<const catar::TraceMesh>> meshes;
  if (!UpdateMeshes(this, inputVector[1], settings, in.Meshes, meshes, sceneLighting))
  {
    return 0;
  }
  this->UpdateProgress(0.1);

  if (!in.Tracer.SetScene(meshes, textures, sceneLighting.lights, sceneLighting.globalAmbient,
        sceneLighting.shadows, vtkCatadioptricParallel::GetNumberOfThreads()))
  {
    in.Meshes.clear();
    vtkErrorMacro("Cannot build the scene: " << in.Tracer.GetError());
    return 0;
  }
  // The rays, back-projected again only for another lens, mirror, image size or sample count.
  if (!in.Tracer.PrepareRays(projector, this->Samples,
        [](std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
          vtkCatadioptricParallel::For(
            0, static_cast<vtkIdType>(n), 1, [&](vtkIdType b, vtkIdType e) {
              body(static_cast<std::size_t>(b), static_cast<std::size_t>(e));
            });
        }))
  {
    vtkErrorMacro(<< in.Tracer.GetError());
    return 0;
  }
  this->UpdateProgress(0.3);

  // VTK rows go bottom-up: address the image from its last row with a negative stride.
  catar::ImageView view;
  view.width = width;
  view.height = height;
  view.rowStride = -4 * static_cast<std::ptrdiff_t>(width);
  view.data = out + 4 * static_cast<std::ptrdiff_t>(width) * (height - 1);
  catar::RasterId* idData = nullptr;
  if (this->OutputVisibleTriangle)
  {
    vtkNew<vtkTypeInt64Array> visible;
    visible->SetName(vtkCatadioptricArrayNames::VisibleTriangle);
    vtkCatadioptricAllocation::Tuples(visible, nPixels);
    output->GetPointData()->AddArray(visible);
    idData = visible->GetPointer(0) + static_cast<std::ptrdiff_t>(width) * (height - 1);
  }
  float* pathData = nullptr;
  if (this->OutputPathLength)
  {
    vtkNew<vtkFloatArray> pathLength;
    pathLength->SetName(vtkCatadioptricArrayNames::PathLength);
    vtkCatadioptricAllocation::Tuples(pathLength, nPixels);
    output->GetPointData()->AddArray(pathLength);
    pathData = pathLength->GetPointer(0) + static_cast<std::ptrdiff_t>(width) * (height - 1);
  }
  const catar::RayTracer& tracer = in.Tracer;
  constexpr int kBand = 2 * catar::RayTracer::kTile;
  const int bands = (height + kBand - 1) / kBand;
  // Statistics per band, summed after the loop (no thread-local storage: the pool's threads are
  // not VTK's).
  std::vector<catar::RayTraceStatistics> statistics(static_cast<size_t>(bands));
  // In tenths, with the progress reported between them (from this thread: VTK's events are not
  // for the loop's threads).
  constexpr int kParts = 10;
  for (int part = 0; part < kParts; ++part)
  {
    const int b0 = bands * part / kParts, b1 = bands * (part + 1) / kParts;
    // A band at a time to whichever thread is free: the object fills a few bands only.
    vtkCatadioptricParallel::ForEachIndex(b0, b1, [&](vtkIdType band) {
      tracer.RenderRows(view, idData, -static_cast<std::ptrdiff_t>(width),
        static_cast<int>(band * kBand), static_cast<int>((band + 1) * kBand),
        &statistics[static_cast<size_t>(band)], pathData);
    });
    this->UpdateProgress(0.3 + 0.7 * (part + 1) / kParts);
  }
  for (const catar::RayTraceStatistics& s : statistics)
  {
    this->NumberOfMirrorRays += static_cast<vtkIdType>(s.mirrorRays);
    this->NumberOfTracedRays += static_cast<vtkIdType>(s.tracedRays);
    this->NumberOfHits += static_cast<vtkIdType>(s.hits);
    this->NumberOfShadowRays += static_cast<vtkIdType>(s.shadowRays);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricRayTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "UseInputLighting: " << (this->UseInputLighting ? "On" : "Off") << "\n";
  os << indent << "NumberOfMirrorRays: " << this->NumberOfMirrorRays << "\n";
  os << indent << "NumberOfTracedRays: " << this->NumberOfTracedRays << "\n";
  os << indent << "NumberOfHits: " << this->NumberOfHits << "\n";
  os << indent << "NumberOfShadowRays: " << this->NumberOfShadowRays << "\n";
}
