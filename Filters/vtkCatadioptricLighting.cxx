#include "vtkCatadioptricLighting.h"

#include "Polygons.h"
#include "ShadeBatch.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricLightingSupport.h"

#include "CameraModel.h"
#include "Lighting.h"
#include "RayScene.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricColorArray.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricOccluders.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCatadioptricPointReader.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricLighting);

namespace
{
// Points (or cells) per parallel task: waking the pool's threads costs more than lighting a few
// hundred points; smaller meshes are lit inline.
constexpr vtkIdType kPointGrain = 512;
}

namespace
{
catar::Vec3 V3(const double* v)
{
  return catar::Vec3(v[0], v[1], v[2]);
}

// Whether one of n normals (read through the raw pointer of their type when given) has zero
// length or a NaN or infinite component.
bool HasDegenerateNormal(
  vtkDataArray* normals, const float* floats, const double* doubles, vtkIdType n)
{
  auto bad = [](double x, double y, double z) {
    const double q = x * x + y * y + z * z;
    return !(q > 0.0 && q < std::numeric_limits<double>::infinity());
  };
  for (vtkIdType i = 0; i < n; ++i)
  {
    double t[3];
    if (floats)
    {
      std::copy(floats + 3 * i, floats + 3 * i + 3, t);
    }
    else if (doubles)
    {
      std::copy(doubles + 3 * i, doubles + 3 * i + 3, t);
    }
    else
    {
      normals->GetTuple(i, t);
    }
    if (bad(t[0], t[1], t[2]))
    {
      return true;
    }
  }
  return false;
}

// The inputs of the per-point (Gouraud) shading: the projection's arrays, the normals (read
// through raw pointers where their type allows), base colours and materials.
struct PointInputs
{
  const vtkCatadioptricPointReader& points;
  vtkUnsignedCharArray* visibleBytes; // the projection's Visible as bytes, or null
  vtkDataArray* visible;
  const double* mirrorValues; // MirrorPoint as doubles, or null
  vtkDataArray* mirror;
  const std::vector<catar::Vec3>& normals;  // the given normals made unit, or the mesh's own
  const std::vector<catar::Vec3>* fallback; // for given normals of zero length, NaN or Inf
  const std::vector<float>& pointBase;      // cell colours averaged at points, or empty
  const vtkCatadioptricColorArray& base;
  vtkDataArray* materialIndex;
  const catar::PoseFrames& pose;
};

// RGBA of each of n points into out (4 bytes a point; invisible points 0): a batch per thread.
void ShadePoints(const PointInputs& in, vtkIdType nPts, const catar::ShadeBatch::Settings& shading,
  unsigned char* out)
{
  vtkCatadioptricParallel::For(0, nPts, kPointGrain, [&](vtkIdType b, vtkIdType e) {
    catar::ShadeBatch batch(shading);
    for (vtkIdType i = b; i < e; ++i)
    {
      unsigned char* o = out + 4 * i;
      if (in.visibleBytes ? in.visibleBytes->GetValue(i) == 0 : in.visible->GetComponent(i, 0) == 0)
      {
        std::fill(o, o + 4, 0);
        continue;
      }
      double mp[3];
      if (in.mirrorValues)
      {
        std::copy(in.mirrorValues + 3 * i, in.mirrorValues + 3 * i + 3, mp);
      }
      else
      {
        in.mirror->GetTuple(i, mp);
      }
      const catar::Vec3 p = in.points(i);
      catar::Vec3 n = in.normals[i];
      if (in.fallback && !(n.squaredNorm() > 0.0))
      {
        n = (*in.fallback)[i];
      }
      float rgba[4];
      if (in.pointBase.empty())
      {
        in.base.Get(i, 0, rgba);
      }
      else
      {
        std::copy(&in.pointBase[4 * i], &in.pointBase[4 * i] + 4, rgba);
      }
      // The viewer: the reflection point, camera to world.
      batch.Add(p, n, in.pose.ToWorld(V3(mp)), rgba, o,
        in.materialIndex ? static_cast<int>(in.materialIndex->GetComponent(i, 0)) : -1);
    }
  });
}

// The inputs of the per-cell shading (FLAT: shaded at the centroid; NONE: the base colour).
struct CellInputs
{
  const vtkCatadioptricPointReader& points;
  vtkCellArray* polys;
  vtkIdType first; // cell id of the first polygon
  vtkUnsignedCharArray* visibleBytes;
  vtkDataArray* visible;
  vtkDataArray* centroidMirror;
  const vtkCatadioptricColorArray& base;
  vtkDataArray* materialIndex;
  const std::vector<catar::ShadingMaterial>& materials;
  double opacity;
  bool flat;
  const catar::PoseFrames& pose;
};

// RGBA of each polygon into out, at its cell id (4 bytes a cell): a batch per thread.
void ShadeCells(
  const CellInputs& in, const catar::ShadeBatch::Settings& shading, unsigned char* out)
{
  vtkCatadioptricParallel::For(
    0, in.polys->GetNumberOfCells(), kPointGrain, [&](vtkIdType b, vtkIdType e) {
      catar::ShadeBatch batch(shading);
      vtkNew<vtkIdList> scratch;
      for (vtkIdType c = b; c < e; ++c)
      {
        const vtkIdType cellId = in.first + c;
        if (in.visibleBytes ? in.visibleBytes->GetValue(cellId) == 0
                            : in.visible->GetComponent(cellId, 0) == 0)
        {
          continue;
        }
        vtkIdType n = 0;
        const vtkIdType* pts = nullptr;
        in.polys->GetCellAtId(c, n, pts, scratch); // no copy when the ids are stored as vtkIdType
        catar::Vec3 centroid = catar::Vec3::Zero();
        catar::NewellNormal newell(in.points(pts[n - 1]));
        for (vtkIdType k = 0; k < n; ++k)
        {
          const catar::Vec3 a = in.points(pts[k]);
          centroid += a;
          newell.Add(a);
        }
        centroid /= static_cast<double>(n);
        const catar::Vec3& area = newell.Sum();
        // Base colour: a cell colour, or the mean of the point colours.
        float rgba[4] = { 0, 0, 0, 0 };
        for (vtkIdType k = 0; k < (in.base.IsPerPoint() ? n : 1); ++k)
        {
          float v[4];
          in.base.Get(pts[k], cellId, v);
          for (int j = 0; j < 4; ++j)
          {
            rgba[j] += v[j] / (in.base.IsPerPoint() ? n : 1);
          }
        }
        unsigned char* o = out + 4 * cellId;
        // A cell's material is its first point's.
        const int m =
          in.materialIndex ? static_cast<int>(in.materialIndex->GetComponent(pts[0], 0)) : -1;
        if (in.flat)
        {
          const double len = area.norm();
          const catar::Vec3 normal = len > 0 ? catar::Vec3(area / len) : catar::Vec3(0, 0, 1);
          double cm[3];
          in.centroidMirror->GetTuple(cellId, cm);
          batch.Add(centroid, normal, in.pose.ToWorld(V3(cm)), rgba, o, m);
        }
        else
        {
          o[0] = catar::ColourByte(rgba[0]);
          o[1] = catar::ColourByte(rgba[1]);
          o[2] = catar::ColourByte(rgba[2]);
          o[3] = catar::ColourByte((m < 0 ? in.opacity : in.materials[m].opacity) * rgba[3]);
        }
      }
    });
}

// The lit colours in place of any Colors array of the output's points and cells, in `to` (its
// point or its cell data).
void ReplaceColors(vtkPolyData* output, vtkDataArray* colors, vtkFieldData* to)
{
  output->GetPointData()->RemoveArray(vtkCatadioptricArrayNames::Colors);
  output->GetCellData()->RemoveArray(vtkCatadioptricArrayNames::Colors);
  to->AddArray(colors);
}
} // namespace

struct vtkCatadioptricLighting::Internals
{
  catar::RayScene Scene;
  // What the scene was built from: points object, its MTime and the polygons' MTime per mesh.
  std::vector<std::tuple<vtkPoints*, vtkMTimeType, vtkMTimeType>> Sources;
  bool Built = false;
  // Vertex normals of the input, and what they were computed from.
  std::vector<catar::Vec3> Normals;
  std::tuple<vtkPoints*, vtkMTimeType, vtkMTimeType> NormalsSource{ nullptr, 0, 0 };

  // Whether the input's normals have a degenerate one, and for which array and MTime: scanned
  // once, not every frame.
  std::tuple<vtkDataArray*, vtkMTimeType, bool> Degenerate{ nullptr, 0, false };

  bool HasDegenerate(vtkDataArray* normals, const float* floats, const double* doubles, vtkIdType n)
  {
    if (std::get<0>(this->Degenerate) != normals ||
      std::get<1>(this->Degenerate) != normals->GetMTime())
    {
      this->Degenerate = std::make_tuple(
        normals, normals->GetMTime(), HasDegenerateNormal(normals, floats, doubles, n));
    }
    return std::get<2>(this->Degenerate);
  }

  // The given normals made unit length, and for which array and MTime: once, not every frame.
  std::vector<catar::Vec3> UnitNormals;
  std::tuple<vtkDataArray*, vtkMTimeType, vtkIdType> UnitNormalsSource{ nullptr, 0, 0 };

  const std::vector<catar::Vec3>& GetUnitNormals(
    vtkDataArray* normals, const float* floats, const double* doubles, vtkIdType n)
  {
    const auto source = std::make_tuple(normals, normals->GetMTime(), n);
    if (source != this->UnitNormalsSource)
    {
      this->UnitNormals.resize(static_cast<std::size_t>(n));
      catar::Vec3* unit = this->UnitNormals.data();
      vtkCatadioptricParallel::For(0, n, kPointGrain, [&](vtkIdType b, vtkIdType e) {
        for (vtkIdType i = b; i < e; ++i)
        {
          if (floats)
          {
            unit[i] = catar::Vec3(floats[3 * i], floats[3 * i + 1], floats[3 * i + 2]).normalized();
          }
          else if (doubles)
          {
            unit[i] = V3(doubles + 3 * i).normalized();
          }
          else
          {
            double t[3];
            normals->GetTuple(i, t);
            unit[i] = V3(t).normalized();
          }
        }
      });
      this->UnitNormalsSource = source;
    }
    return this->UnitNormals;
  }

  // Cell base colours averaged at the points (Gouraud), and what they were averaged from: the
  // colour array and the polygons (held, so that the same pointer is the same object), their
  // MTimes, the point count and the first polygon's cell id. Averaged once, not every frame:
  // the projection passes the input's polygons and cell data on unchanged.
  std::vector<float> PointBase;
  vtkSmartPointer<vtkDataArray> PointBaseColors;
  vtkSmartPointer<vtkCellArray> PointBasePolys;
  std::tuple<vtkMTimeType, vtkMTimeType, vtkIdType, vtkIdType> PointBaseKey{ 0, 0, -1, -1 };

  const std::vector<float>& GetPointBase(vtkPolyData* mesh, const vtkCatadioptricColorArray& base)
  {
    vtkCellArray* polys = mesh->GetPolys();
    vtkDataArray* colors = base.GetArray();
    const vtkIdType nPts = mesh->GetNumberOfPoints();
    const vtkIdType first = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
    const auto key = std::make_tuple(colors->GetMTime(), polys->GetMTime(), nPts, first);
    if (colors == this->PointBaseColors && polys == this->PointBasePolys &&
      key == this->PointBaseKey)
    {
      return this->PointBase;
    }
    // catar::AverageAtPoints, its sums in the same order (cell by cell), so the same floats: the
    // cells' colours read on the threads, summed at their points in one pass over the raw
    // connectivity, and divided on the threads.
    const vtkIdType nPolys = polys->GetNumberOfCells();
    std::vector<float> cellColors(4 * static_cast<std::size_t>(nPolys));
    vtkCatadioptricParallel::For(0, nPolys, kPointGrain, [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType c = b; c < e; ++c)
      {
        base.Get(0, first + c, &cellColors[4 * static_cast<std::size_t>(c)]);
      }
    });
    std::vector<float>& sums = this->PointBase;
    sums.assign(4 * static_cast<std::size_t>(nPts), 0.0f);
    std::vector<int> count(static_cast<std::size_t>(nPts), 0);
    vtkNew<vtkIdList> scratch;
    for (vtkIdType c = 0; c < nPolys; ++c)
    {
      vtkIdType n = 0;
      const vtkIdType* pts = nullptr;
      polys->GetCellAtId(c, n, pts, scratch); // no copy when the ids are stored as vtkIdType
      const float* v = &cellColors[4 * static_cast<std::size_t>(c)];
      for (vtkIdType k = 0; k < n; ++k)
      {
        float* sum = &sums[4 * static_cast<std::size_t>(pts[k])];
        for (int j = 0; j < 4; ++j)
        {
          sum[j] += v[j];
        }
        ++count[static_cast<std::size_t>(pts[k])];
      }
    }
    vtkCatadioptricParallel::For(0, nPts, kPointGrain, [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType i = b; i < e; ++i)
      {
        for (int j = 0; j < 4; ++j)
        {
          sums[4 * static_cast<std::size_t>(i) + j] /= std::max(1, count[i]);
        }
      }
    });
    this->PointBaseColors = colors;
    this->PointBasePolys = polys;
    this->PointBaseKey = key;
    return this->PointBase;
  }

  const std::vector<catar::Vec3>& GetNormals(vtkPolyData* mesh)
  {
    vtkPoints* pts = mesh->GetPoints();
    const auto source = std::make_tuple(pts, pts->GetMTime(), mesh->GetPolys()->GetMTime());
    if (source != this->NormalsSource ||
      this->Normals.size() != static_cast<size_t>(mesh->GetNumberOfPoints()))
    {
      this->Normals = vtkCatadioptricLightingSupport::VertexNormals(mesh);
      this->NormalsSource = source;
    }
    return this->Normals;
  }

  // Builds (or keeps) the ray scene of the meshes' polygons (fan-triangulated).
  bool Update(const std::vector<vtkPolyData*>& meshes, std::string& error)
  {
    std::vector<std::tuple<vtkPoints*, vtkMTimeType, vtkMTimeType>> sources;
    for (vtkPolyData* mesh : meshes)
    {
      vtkPoints* pts = mesh->GetPoints();
      sources.emplace_back(pts, pts ? pts->GetMTime() : 0, mesh->GetPolys()->GetMTime());
    }
    if (this->Built && sources == this->Sources)
    {
      return true;
    }
    this->Built = vtkCatadioptricLightingSupport::BuildRayScene(meshes, this->Scene, error);
    if (!this->Built)
    {
      return false;
    }
    this->Sources = sources;
    return true;
  }
};

vtkCatadioptricLighting::vtkCatadioptricLighting()
  : Lights(vtkSmartPointer<vtkLightCollection>::New())
  , Property(vtkSmartPointer<vtkProperty>::New())
  , Internal(new Internals)
{
  this->SetNumberOfInputPorts(2);
  this->SetInputColorArrayName(vtkCatadioptricArrayNames::Colors);
  this->Property->SetSpecular(0.0);
}

int vtkCatadioptricLighting::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

vtkCatadioptricLighting::~vtkCatadioptricLighting()
{
  this->SetInputColorArrayName(nullptr);
}

void vtkCatadioptricLighting::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Lights->AddItem(light);
    this->Modified();
  }
}

void vtkCatadioptricLighting::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}

vtkLightCollection* vtkCatadioptricLighting::GetLights()
{
  return this->Lights;
}

void vtkCatadioptricLighting::SetLights(vtkLightCollection* lights)
{
  this->Lights = lights ? lights : vtkSmartPointer<vtkLightCollection>::New().GetPointer();
  this->Modified();
}

void vtkCatadioptricLighting::AddSpotLight(double px, double py, double pz, double fx, double fy,
  double fz, double coneAngle, double r, double g, double b)
{
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetPosition(px, py, pz);
  light->SetFocalPoint(fx, fy, fz);
  light->SetConeAngle(coneAngle);
  light->SetExponent(1.0);
  light->SetAmbientColor(0, 0, 0);
  light->SetDiffuseColor(r, g, b);
  light->SetSpecularColor(r, g, b);
  this->AddLight(light);
}

void vtkCatadioptricLighting::AddPointLight(double px, double py, double pz, double r, double g,
  double b, double constant, double linear, double quadratic)
{
  if (!(constant >= 0 && linear >= 0 && quadratic >= 0 && constant + linear + quadratic > 0))
  {
    vtkErrorMacro("A point light's attenuation (constant, linear, quadratic) must be three numbers "
                  "that are not negative and not all 0, not "
      << constant << ", " << linear << ", " << quadratic << ".");
    return;
  }
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetPosition(px, py, pz);
  light->SetConeAngle(180.0); // 90 or more: a point light
  light->SetAttenuationValues(constant, linear, quadratic);
  light->SetAmbientColor(0, 0, 0);
  light->SetDiffuseColor(r, g, b);
  light->SetSpecularColor(r, g, b);
  this->AddLight(light);
}

void vtkCatadioptricLighting::AddDirectionalLight(
  double dx, double dy, double dz, double r, double g, double b)
{
  const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(length > 0 && length < std::numeric_limits<double>::infinity()))
  {
    vtkErrorMacro("A directional light's direction (towards the light) must be finite and not "
                  "zero, not "
      << dx << ", " << dy << ", " << dz << ".");
    return;
  }
  // vtkLight's directional light shines from its position towards its focal point.
  vtkNew<vtkLight> light;
  light->SetPositional(false);
  light->SetPosition(dx, dy, dz);
  light->SetFocalPoint(0, 0, 0);
  light->SetAmbientColor(0, 0, 0);
  light->SetDiffuseColor(r, g, b);
  light->SetSpecularColor(r, g, b);
  this->AddLight(light);
}

namespace
{
// Removes the lights of one kind; true when it removed any.
bool RemoveLightsOfKind(vtkLightCollection* lights, catar::LightSource::Kind kind)
{
  std::vector<vtkLight*> doomed;
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* l = lights->GetNextLight(it))
  {
    if (vtkCatadioptricLightingSupport::LightKind(l) == kind)
    {
      doomed.push_back(l);
    }
  }
  for (vtkLight* l : doomed)
  {
    lights->RemoveItem(l);
  }
  return !doomed.empty();
}
} // namespace

void vtkCatadioptricLighting::RemoveAllSpotLights()
{
  if (RemoveLightsOfKind(this->Lights, catar::LightSource::Kind::Spot))
  {
    this->Modified();
  }
}

void vtkCatadioptricLighting::RemoveAllPointLights()
{
  if (RemoveLightsOfKind(this->Lights, catar::LightSource::Kind::Point))
  {
    this->Modified();
  }
}

void vtkCatadioptricLighting::RemoveAllDirectionalLights()
{
  if (RemoveLightsOfKind(this->Lights, catar::LightSource::Kind::Directional))
  {
    this->Modified();
  }
}

namespace
{
// The record's sizes (the header's WriteToFieldData says what they hold).
constexpr int kSettingsComponents = 23;
constexpr int kLightComponents = 22;
static_assert(kSettingsComponents == 9 + vtkCatadioptricLightingSupport::MaterialComponents,
  "the settings end with one material");
} // namespace

void vtkCatadioptricLighting::WriteToFieldData(vtkFieldData* fieldData)
{
  this->WriteRecord(fieldData, this->InputColorArrayName);
}

void vtkCatadioptricLighting::WriteRecord(vtkFieldData* fieldData, const char* colorArrayName)
{
  if (!fieldData)
  {
    return;
  }
  vtkProperty* p = this->Property;
  double s[kSettingsComponents] = { static_cast<double>(this->ShadingMode),
    this->Shadows ? 1.0 : 0.0, this->TwoSidedLighting ? 1.0 : 0.0, this->GlobalAmbient[0],
    this->GlobalAmbient[1], this->GlobalAmbient[2], this->Emission[0], this->Emission[1],
    this->Emission[2], p->GetAmbient(), p->GetDiffuse(), p->GetSpecular(), p->GetSpecularPower() };
  p->GetAmbientColor(s + 13);
  p->GetDiffuseColor(s + 16);
  p->GetSpecularColor(s + 19);
  s[22] = p->GetOpacity();
  vtkNew<vtkDoubleArray> settings;
  settings->SetName(vtkCatadioptricArrayNames::LightingSettings);
  settings->SetNumberOfComponents(kSettingsComponents);
  settings->InsertNextTuple(s);

  vtkNew<vtkDoubleArray> lights;
  lights->SetName(vtkCatadioptricArrayNames::LightingLights);
  lights->SetNumberOfComponents(kLightComponents);
  vtkCollectionSimpleIterator it;
  this->Lights->InitTraversal(it);
  while (vtkLight* l = this->Lights->GetNextLight(it))
  {
    if (!l->GetSwitch())
    {
      continue; // as ConvertLights: a light switched off lights nothing
    }
    double v[kLightComponents];
    v[0] = l->GetPositional() ? 1.0 : 0.0;
    l->GetPosition(v + 1);
    l->GetFocalPoint(v + 4);
    v[7] = l->GetConeAngle();
    v[8] = l->GetExponent();
    l->GetAttenuationValues(v + 9);
    v[12] = l->GetIntensity();
    l->GetAmbientColor(v + 13);
    l->GetDiffuseColor(v + 16);
    l->GetSpecularColor(v + 19);
    lights->InsertNextTuple(v);
  }

  vtkNew<vtkStringArray> colors;
  colors->SetName(vtkCatadioptricArrayNames::LightingColorArray);
  colors->InsertNextValue(colorArrayName ? colorArrayName : "");

  fieldData->AddArray(settings);
  fieldData->AddArray(lights);
  fieldData->AddArray(colors);
}

bool vtkCatadioptricLighting::HasLightingRecord(vtkFieldData* fieldData)
{
  return fieldData &&
    (fieldData->GetAbstractArray(vtkCatadioptricArrayNames::LightingSettings) ||
      fieldData->GetAbstractArray(vtkCatadioptricArrayNames::LightingLights) ||
      fieldData->GetAbstractArray(vtkCatadioptricArrayNames::LightingColorArray));
}

bool vtkCatadioptricLighting::ReadFromFieldData(vtkFieldData* fieldData)
{
  if (!fieldData)
  {
    return false;
  }
  vtkDataArray* settings = fieldData->GetArray(vtkCatadioptricArrayNames::LightingSettings);
  vtkDataArray* lights = fieldData->GetArray(vtkCatadioptricArrayNames::LightingLights);
  auto* colors = vtkStringArray::SafeDownCast(
    fieldData->GetAbstractArray(vtkCatadioptricArrayNames::LightingColorArray));
  if (!settings || !lights || !colors || settings->GetNumberOfComponents() != kSettingsComponents ||
    settings->GetNumberOfTuples() != 1 || lights->GetNumberOfComponents() != kLightComponents ||
    colors->GetNumberOfValues() != 1)
  {
    return false;
  }
  double s[kSettingsComponents];
  settings->GetTuple(0, s);
  if (!(s[0] == NONE || s[0] == FLAT || s[0] == GOURAUD))
  {
    return false;
  }
  vtkNew<vtkLightCollection> collection;
  for (vtkIdType i = 0; i < lights->GetNumberOfTuples(); ++i)
  {
    double v[kLightComponents];
    lights->GetTuple(i, v);
    vtkNew<vtkLight> l;
    l->SetPositional(v[0] != 0);
    l->SetPosition(v + 1);
    l->SetFocalPoint(v + 4);
    l->SetConeAngle(v[7]);
    l->SetExponent(v[8]);
    l->SetAttenuationValues(v + 9);
    l->SetIntensity(v[12]);
    l->SetAmbientColor(v + 13);
    l->SetDiffuseColor(v + 16);
    l->SetSpecularColor(v + 19);
    collection->AddItem(l);
  }
  vtkNew<vtkProperty> p;
  p->SetAmbient(s[9]);
  p->SetDiffuse(s[10]);
  p->SetSpecular(s[11]);
  p->SetSpecularPower(s[12]);
  p->SetAmbientColor(s + 13);
  p->SetDiffuseColor(s + 16);
  p->SetSpecularColor(s + 19);
  p->SetOpacity(s[22]);
  this->SetLights(collection);
  this->SetProperty(p);
  this->SetShadingMode(static_cast<int>(s[0]));
  this->SetShadows(s[1] != 0);
  this->SetTwoSidedLighting(s[2] != 0);
  this->SetGlobalAmbient(s + 3);
  this->SetEmission(s + 6);
  this->SetInputColorArrayName(colors->GetValue(0).c_str());
  return true;
}

void vtkCatadioptricLighting::RecordLighting(vtkPolyData* input, vtkPolyData* output)
{
  const float unused[4] = { 0, 0, 0, 1 };
  const vtkCatadioptricColorArray base(input, this->InputColorArrayName, unused);
  std::string name;
  if (base.HasArray() &&
    std::strcmp(this->InputColorArrayName, vtkCatadioptricArrayNames::Colors) != 0)
  {
    name = this->InputColorArrayName; // passed through as it is
  }
  else if (base.HasArray())
  {
    // The lit Colors replace the base colours: keep them (the same values, shared) as BaseColors.
    vtkSmartPointer<vtkDataArray> kept = vtk::TakeSmartPointer(base.GetArray()->NewInstance());
    kept->ShallowCopy(base.GetArray());
    kept->SetName(vtkCatadioptricArrayNames::BaseColors);
    output->GetPointData()->RemoveArray(vtkCatadioptricArrayNames::BaseColors);
    output->GetCellData()->RemoveArray(vtkCatadioptricArrayNames::BaseColors);
    if (base.IsPerPoint())
    {
      output->GetPointData()->AddArray(kept);
    }
    else
    {
      output->GetCellData()->AddArray(kept);
    }
    name = vtkCatadioptricArrayNames::BaseColors;
  }
  this->WriteRecord(output->GetFieldData(), name.c_str());
}

void vtkCatadioptricLighting::SetDiffuseColor(double r, double g, double b)
{
  this->Property->SetDiffuseColor(r, g, b);
}

void vtkCatadioptricLighting::SetAmbient(double ambient)
{
  this->Property->SetAmbient(ambient);
}

void vtkCatadioptricLighting::SetDiffuse(double diffuse)
{
  this->Property->SetDiffuse(diffuse);
}

void vtkCatadioptricLighting::SetSpecular(double specular)
{
  this->Property->SetSpecular(specular);
}

void vtkCatadioptricLighting::SetSpecularPower(double power)
{
  this->Property->SetSpecularPower(power);
}

void vtkCatadioptricLighting::SetOpacity(double opacity)
{
  this->Property->SetOpacity(opacity);
}

void vtkCatadioptricLighting::SetProperty(vtkProperty* property)
{
  this->Property = property ? property : vtkSmartPointer<vtkProperty>::New().GetPointer();
  this->Modified();
}

vtkProperty* vtkCatadioptricLighting::GetProperty()
{
  return this->Property;
}

void vtkCatadioptricLighting::SetOccluders(vtkCatadioptricOccluders* occluders)
{
  if (this->Occluders != occluders)
  {
    this->Occluders = occluders;
    this->Modified();
  }
}

vtkCatadioptricOccluders* vtkCatadioptricLighting::GetOccluders()
{
  return this->Occluders;
}

vtkMTimeType vtkCatadioptricLighting::GetMTime()
{
  vtkMTimeType t = std::max(this->Superclass::GetMTime(), this->Lights->GetMTime());
  t = std::max(t, this->Property->GetMTime());
  if (this->Occluders && this->Shadows)
  {
    t = std::max(t, this->Occluders->GetMTime());
  }
  vtkCollectionSimpleIterator it;
  this->Lights->InitTraversal(it);
  while (vtkLight* l = this->Lights->GetNextLight(it))
  {
    t = std::max(t, l->GetMTime());
  }
  return t;
}

bool vtkCatadioptricLighting::ShadowScene(
  vtkPolyData* input, vtkInformationVector* occluderInputs, const catar::RayScene*& shadowScene)
{
  if (this->Occluders)
  {
    if (occluderInputs->GetNumberOfInformationObjects() > 0)
    {
      vtkErrorMacro("Occluders on input port 1 and shared occluders (SetOccluders) were both "
                    "given: use one or the other.");
      return false;
    }
    if (!this->Occluders->Update())
    {
      vtkErrorMacro("Cannot build the shared occluders' ray scene.");
      return false;
    }
    shadowScene = &this->Occluders->GetRayScene();
  }
  else
  {
    std::vector<vtkPolyData*> meshes{ input };
    for (int i = 0; i < occluderInputs->GetNumberOfInformationObjects(); ++i)
    {
      if (vtkPolyData* occluder = vtkPolyData::GetData(occluderInputs, i))
      {
        meshes.push_back(occluder);
      }
    }
    std::string error;
    if (!this->Internal->Update(meshes, error))
    {
      vtkErrorMacro("Cannot build the shadow ray scene: " << error);
      return false;
    }
    shadowScene = &this->Internal->Scene;
  }
  return true;
}

int vtkCatadioptricLighting::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Out of memory (a mesh or an image too large for the memory left): the filter's error.
  return vtkCatadioptricAllocation::Guard(
    this, [&] { return this->Execute(inputVector, outputVector); },
    [&] { return "lighting " + vtkCatadioptricAllocation::DescribeInput(inputVector[0]); });
}

int vtkCatadioptricLighting::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = nullptr;
  vtkPolyData* output = nullptr;
  if (!vtkCatadioptricMeshCheck::InputAndOutput(this, inputVector, outputVector, input, output))
  {
    return 0;
  }
  std::string error;
  output->ShallowCopy(input);
  // The lighting recorded in the output, for the ray tracer to light the mesh alike.
  this->RecordLighting(input, output);
  const vtkIdType nPts = input->GetNumberOfPoints();
  if (nPts == 0)
  {
    return 1;
  }
  vtkNew<vtkCatadioptricCamera> camera;
  vtkDataArray* mirror = input->GetPointData()->GetArray(vtkCatadioptricArrayNames::MirrorPoint);
  vtkDataArray* pointVisible = input->GetPointData()->GetArray(vtkCatadioptricArrayNames::Visible);
  vtkDataArray* centroidMirror = input->GetCellData()->GetArray("CentroidMirrorPoint");
  vtkDataArray* cellVisible = input->GetCellData()->GetArray(vtkCatadioptricArrayNames::Visible);
  if (!camera->ReadFromFieldData(input->GetFieldData()) || !mirror || !pointVisible ||
    !cellVisible || (this->ShadingMode == FLAT && !centroidMirror))
  {
    vtkErrorMacro("The input was not projected: run vtkCatadioptricProjection before "
                  "vtkCatadioptricLighting.");
    return 0;
  }
  const catar::PoseFrames pose(camera->GetModel().worldToCamera);

  // Material and base colours; a material per point when the input carries a table of them.
  vtkProperty* prop = this->Property;
  const catar::Material material =
    vtkCatadioptricLightingSupport::ConvertProperty(prop, this->Emission);
  const double opacity = prop->GetOpacity();
  std::vector<catar::ShadingMaterial> materials;
  vtkDataArray* materialIndex = nullptr;
  if (!vtkCatadioptricLightingSupport::ReadMaterials(
        input, this->Emission, materials, materialIndex, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const float solid[4] = { static_cast<float>(prop->GetDiffuseColor()[0]),
    static_cast<float>(prop->GetDiffuseColor()[1]), static_cast<float>(prop->GetDiffuseColor()[2]),
    1.0f };
  const vtkCatadioptricColorArray base(input, this->InputColorArrayName, solid);
  const std::vector<catar::LightSource> lightList =
    vtkCatadioptricLightingSupport::ConvertLights(this->Lights);
  const catar::Vec3 globalAmbient = V3(this->GlobalAmbient);
  const int mode = this->ShadingMode;
  const catar::ShadingMaterial defaults{ material, prop->GetAmbient(), prop->GetDiffuse(),
    opacity };
  error = catar::ValidateShading(lightList, defaults, materials, globalAmbient);
  if (!error.empty())
  {
    vtkErrorMacro("Cannot shade: " << error << ".");
    return 0;
  }
  const catar::LightSet lights(lightList);

  // Shadows: the shared occluders, or the mesh's own triangles and those on port 1.
  const bool shadows = this->Shadows && mode != NONE && !lights.empty();
  const catar::RayScene* shadowScene = nullptr;
  if (shadows && !this->ShadowScene(input, inputVector[1], shadowScene))
  {
    return 0;
  }
  this->UpdateProgress(0.1);

  // The colour of point p with normal n seen from viewer (all world), base colour rgba: shaded
  // in batches (ShadeBatch), one per thread.
  catar::ShadeBatch::Settings shading;
  shading.lights = &lights;
  shading.defaults = defaults;
  shading.materials = &materials;
  shading.globalAmbient = globalAmbient;
  shading.baseColours = base.HasArray();
  shading.twoSided = this->TwoSidedLighting;
  shading.shadowScene = shadowScene;

  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName(vtkCatadioptricArrayNames::Colors);
  colors->SetNumberOfComponents(4);
  if (mode == GOURAUD)
  {
    vtkDataArray* inNormals = input->GetPointData()->GetNormals();
    const bool given = inNormals && inNormals->GetNumberOfComponents() == 3;
    // Cell base colours become point colours: the mean over the cells around each point, kept
    // while the colours and the polygons are unchanged.
    static const std::vector<float> noPointBase;
    const std::vector<float>& pointBase = base.HasArray() && !base.IsPerPoint()
      ? this->Internal->GetPointBase(input, base)
      : noPointBase;
    vtkCatadioptricAllocation::Tuples(colors, nPts);
    unsigned char* out = colors->GetPointer(0);
    // The projection's arrays (uint8 Visible, double MirrorPoint) are read directly.
    const vtkCatadioptricPointReader points(input->GetPoints());
    auto* visibleBytes = vtkUnsignedCharArray::SafeDownCast(pointVisible);
    auto* mirrorDoubles = vtkDoubleArray::SafeDownCast(mirror);
    // Double reflection points and float or double normals are read through raw pointers.
    const double* mirrorValues = (mirrorDoubles && mirror->GetNumberOfComponents() == 3)
      ? mirrorDoubles->GetPointer(0)
      : nullptr;
    auto* normalFloatArray = given ? vtkFloatArray::SafeDownCast(inNormals) : nullptr;
    auto* normalDoubleArray = given ? vtkDoubleArray::SafeDownCast(inNormals) : nullptr;
    const float* normalFloats = normalFloatArray ? normalFloatArray->GetPointer(0) : nullptr;
    const double* normalDoubles = normalDoubleArray ? normalDoubleArray->GetPointer(0) : nullptr;
    // Given normals made unit once (kept while the array is unchanged), else the mesh's own.
    const std::vector<catar::Vec3>& normals = given
      ? this->Internal->GetUnitNormals(inNormals, normalFloats, normalDoubles, nPts)
      : this->Internal->GetNormals(input);
    // Given normals of zero length or with NaN or Inf take the mesh's own vertex normal.
    const std::vector<catar::Vec3>* fallback =
      given && this->Internal->HasDegenerate(inNormals, normalFloats, normalDoubles, nPts)
      ? &this->Internal->GetNormals(input)
      : nullptr;
    const PointInputs pin{ points, visibleBytes, pointVisible, mirrorValues, mirror, normals,
      fallback, pointBase, base, materialIndex, pose };
    ShadePoints(pin, nPts, shading, out);
    ReplaceColors(output, colors, output->GetPointData());
  }
  else
  {
    const vtkIdType nCells = input->GetNumberOfCells();
    const vtkIdType first = input->GetNumberOfVerts() + input->GetNumberOfLines();
    vtkCatadioptricAllocation::Tuples(colors, nCells);
    colors->FillValue(0);
    unsigned char* out = colors->GetPointer(0);
    vtkCellArray* polys = input->GetPolys();
    const vtkCatadioptricPointReader points(input->GetPoints());
    auto* visibleBytes = vtkUnsignedCharArray::SafeDownCast(cellVisible);
    const CellInputs cin{ points, polys, first, visibleBytes, cellVisible, centroidMirror, base,
      materialIndex, materials, opacity, mode == FLAT, pose };
    ShadeCells(cin, shading, out);
    ReplaceColors(output, colors, output->GetCellData());
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricLighting::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* const modes[] = { "None", "Flat", "Gouraud" };
  os << indent << "ShadingMode: " << modes[this->ShadingMode] << "\n";
  os << indent << "Shadows: " << (this->Shadows ? "On" : "Off") << "\n";
  os << indent << "TwoSidedLighting: " << (this->TwoSidedLighting ? "On" : "Off") << "\n";
  os << indent << "GlobalAmbient: " << this->GlobalAmbient[0] << ", " << this->GlobalAmbient[1]
     << ", " << this->GlobalAmbient[2] << "\n";
  os << indent << "Emission: " << this->Emission[0] << ", " << this->Emission[1] << ", "
     << this->Emission[2] << "\n";
  os << indent << "InputColorArrayName: "
     << (this->InputColorArrayName ? this->InputColorArrayName : "(none)") << "\n";
  os << indent << "Lights: " << this->Lights->GetNumberOfItems() << "\n";
  os << indent << "Occluders: " << (this->Occluders ? "shared" : "(none)") << "\n";
}
