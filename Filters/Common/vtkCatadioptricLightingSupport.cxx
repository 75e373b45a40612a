#include "vtkCatadioptricLightingSupport.h"

#include "Polygons.h"

#include "RayScene.h"

#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>

namespace
{
catar::Vec3 V3(const double v[3])
{
  return catar::Vec3(v[0], v[1], v[2]);
}
} // namespace

std::vector<catar::LightSource> vtkCatadioptricLightingSupport::ConvertLights(
  vtkLightCollection* lights)
{
  std::vector<catar::LightSource> out;
  if (!lights)
  {
    return out;
  }
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* l = lights->GetNextLight(it))
  {
    if (!l->GetSwitch())
    {
      continue;
    }
    catar::LightSource s;
    s.kind = LightKind(l);
    s.position = V3(l->GetPosition());
    s.focalPoint = V3(l->GetFocalPoint());
    const double i = l->GetIntensity();
    s.ambient = i * V3(l->GetAmbientColor());
    s.diffuse = i * V3(l->GetDiffuseColor());
    s.specular = i * V3(l->GetSpecularColor());
    s.coneAngle = l->GetConeAngle();
    s.exponent = l->GetExponent();
    s.attenuation = V3(l->GetAttenuationValues());
    out.push_back(s);
  }
  return out;
}

catar::LightSource::Kind vtkCatadioptricLightingSupport::LightKind(vtkLight* light)
{
  if (!light->GetPositional())
  {
    return catar::LightSource::Kind::Directional;
  }
  return light->GetConeAngle() < 90.0 ? catar::LightSource::Kind::Spot
                                      : catar::LightSource::Kind::Point;
}

catar::Material vtkCatadioptricLightingSupport::ConvertProperty(
  vtkProperty* prop, const double emission[3])
{
  catar::Material material;
  material.ambient = prop->GetAmbient() * V3(prop->GetAmbientColor());
  material.diffuse = prop->GetDiffuse() * V3(prop->GetDiffuseColor());
  material.specular = prop->GetSpecular() * V3(prop->GetSpecularColor());
  material.emission = V3(emission);
  material.shininess = prop->GetSpecularPower();
  return material;
}

bool vtkCatadioptricLightingSupport::ReadMaterials(vtkPolyData* mesh, const double emission[3],
  std::vector<MaterialEntry>& materials, vtkDataArray*& index, std::string& error)
{
  materials.clear();
  index = mesh->GetPointData()->GetArray(vtkCatadioptricArrayNames::MaterialIndex);
  vtkDataArray* table = mesh->GetFieldData()->GetArray(vtkCatadioptricArrayNames::Materials);
  if (!index && !table)
  {
    return true;
  }
  if (!index || !table)
  {
    error = std::string("A mesh with ") +
      (index ? "a point array 'MaterialIndex' needs the field array 'Materials'"
             : "a field array 'Materials' needs the point array 'MaterialIndex'") +
      " too.";
    return false;
  }
  if (table->GetNumberOfComponents() != MaterialComponents || index->GetNumberOfComponents() != 1 ||
    index->GetNumberOfTuples() != mesh->GetNumberOfPoints())
  {
    error = "'Materials' must have " + std::to_string(MaterialComponents) +
      " components and 'MaterialIndex' one value a point.";
    return false;
  }
  const vtkIdType count = table->GetNumberOfTuples();
  for (vtkIdType m = 0; m < count; ++m)
  {
    double v[MaterialComponents];
    table->GetTuple(m, v);
    MaterialEntry e;
    e.ambientK = v[0];
    e.diffuseK = v[1];
    e.material.ambient = v[0] * catar::Vec3(v[4], v[5], v[6]);
    e.material.diffuse = v[1] * catar::Vec3(v[7], v[8], v[9]);
    e.material.specular = v[2] * catar::Vec3(v[10], v[11], v[12]);
    e.material.shininess = v[3];
    e.material.emission = catar::Vec3(emission[0], emission[1], emission[2]);
    e.opacity = v[13];
    materials.push_back(e);
  }
  double range[2];
  index->GetRange(range, 0);
  if (mesh->GetNumberOfPoints() > 0 &&
    !(range[0] >= 0 && range[1] < static_cast<double>(count) && range[0] == std::floor(range[0])))
  {
    error = "'MaterialIndex' names material " +
      std::to_string(static_cast<long long>(range[0] < 0 ? range[0] : range[1])) +
      ", but 'Materials' has " + std::to_string(count) + ".";
    return false;
  }
  // Only a floating-point index can hold a fraction (the check runs every frame).
  const int type = index->GetDataType();
  const bool floating = type == VTK_FLOAT || type == VTK_DOUBLE;
  for (vtkIdType i = 0; floating && i < index->GetNumberOfTuples(); ++i)
  {
    const double m = index->GetComponent(i, 0);
    if (m != std::floor(m))
    {
      error = "'MaterialIndex' must hold whole numbers.";
      return false;
    }
  }
  return true;
}

void vtkCatadioptricLightingSupport::WriteMaterials(
  vtkPolyData* mesh, const std::vector<vtkProperty*>& properties)
{
  vtkNew<vtkDoubleArray> table;
  table->SetName(vtkCatadioptricArrayNames::Materials);
  table->SetNumberOfComponents(MaterialComponents);
  for (vtkProperty* p : properties)
  {
    double v[MaterialComponents] = { p->GetAmbient(), p->GetDiffuse(), p->GetSpecular(),
      p->GetSpecularPower() };
    p->GetAmbientColor(v + 4);
    p->GetDiffuseColor(v + 7);
    p->GetSpecularColor(v + 10);
    v[13] = p->GetOpacity();
    table->InsertNextTuple(v);
  }
  mesh->GetFieldData()->AddArray(table);
}

std::vector<catar::Vec3> vtkCatadioptricLightingSupport::VertexNormals(vtkPolyData* mesh)
{
  std::vector<catar::Vec3> normals(mesh->GetNumberOfPoints(), catar::Vec3::Zero());
  vtkCellArray* polys = mesh->GetPolys();
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, ids);
    const vtkIdType n = ids->GetNumberOfIds();
    const catar::Vec3 area =
      catar::PolygonNormal(ids->GetPointer(0), static_cast<std::size_t>(n), [&](vtkIdType id) {
        double a[3];
        mesh->GetPoint(id, a);
        return V3(a);
      });
    for (vtkIdType k = 0; k < n; ++k)
    {
      normals[ids->GetId(k)] += area;
    }
  }
  for (catar::Vec3& v : normals)
  {
    const double len = v.norm();
    v = len > 0 ? catar::Vec3(v / len) : catar::Vec3(0, 0, 1);
  }
  return normals;
}

bool vtkCatadioptricLightingSupport::BuildRayScene(
  const std::vector<vtkPolyData*>& meshes, catar::RayScene& scene, std::string& error)
{
  std::vector<float> xyz;
  std::vector<std::uint32_t> tris;
  vtkNew<vtkIdList> ids;
  for (vtkPolyData* mesh : meshes)
  {
    // An occluder's ids are read here, not by a filter's input check: a negative one would wrap
    // to another mesh's point.
    if (!vtkCatadioptricMeshCheck::CheckPointIds(mesh, error))
    {
      error = "an occluder mesh: " + error;
      return false;
    }
    const std::uint32_t offset = static_cast<std::uint32_t>(xyz.size() / 3);
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      xyz.insert(xyz.end(),
        { static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]) });
    }
    vtkCellArray* polys = mesh->GetPolys();
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    {
      polys->GetCellAtId(c, ids);
      catar::PolygonTriangles(ids->GetPointer(0), static_cast<std::size_t>(ids->GetNumberOfIds()),
        [&](vtkIdType a, vtkIdType b, vtkIdType d) {
          tris.push_back(offset + static_cast<std::uint32_t>(a));
          tris.push_back(offset + static_cast<std::uint32_t>(b));
          tris.push_back(offset + static_cast<std::uint32_t>(d));
        });
    }
  }
  if (!scene.Build(xyz, tris))
  {
    error = scene.GetError();
    return false;
  }
  return true;
}
