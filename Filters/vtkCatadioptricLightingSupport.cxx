#include "vtkCatadioptricLightingSupport.h"

#include "RayScene.h"

#include "vtkCatadioptricMeshCheck.h"
#include "vtkCellArray.h"
#include "vtkIdList.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"

#include <Eigen/Geometry>

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
    if (!l->GetPositional())
    {
      s.kind = catar::LightSource::Kind::Directional;
    }
    else
    {
      s.kind =
        l->GetConeAngle() < 90.0 ? catar::LightSource::Kind::Spot : catar::LightSource::Kind::Point;
    }
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

std::vector<catar::Vec3> vtkCatadioptricLightingSupport::VertexNormals(vtkPolyData* mesh)
{
  std::vector<catar::Vec3> normals(mesh->GetNumberOfPoints(), catar::Vec3::Zero());
  vtkCellArray* polys = mesh->GetPolys();
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, ids);
    const vtkIdType n = ids->GetNumberOfIds();
    catar::Vec3 area = catar::Vec3::Zero();
    for (vtkIdType k = 0; k < n; ++k)
    {
      double a[3], b[3];
      mesh->GetPoint(ids->GetId(k), a);
      mesh->GetPoint(ids->GetId((k + 1) % n), b);
      area += V3(a).cross(V3(b));
    }
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
      for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
      {
        tris.push_back(offset + static_cast<std::uint32_t>(ids->GetId(0)));
        tris.push_back(offset + static_cast<std::uint32_t>(ids->GetId(k)));
        tris.push_back(offset + static_cast<std::uint32_t>(ids->GetId(k + 1)));
      }
    }
  }
  if (!scene.Build(xyz, tris))
  {
    error = scene.GetError();
    return false;
  }
  return true;
}
