/**
 * @class   vtkCatadioptricLightingSupport
 * @brief   conversions shared by the lighting filter and the reference ray tracer
 *
 * Not a vtkObject (C++ only, not wrapped): vtkLights to Core light sources, a vtkProperty to a
 * Core material, and area-weighted vertex normals, so that the fast path and the exact reference
 * light a scene from the very same parameters; and the shadow rays' scene made from meshes (the
 * lighting filter's own, and vtkCatadioptricOccluders' shared one).
 */
#ifndef vtkCatadioptricLightingSupport_h
#define vtkCatadioptricLightingSupport_h

#include "CatadioptricARCommonModule.h" // for export macro
#include "Lighting.h"                   // for catar::LightSource, catar::Material
#include "ShadeBatch.h"                 // for catar::ShadingMaterial

#include <string> // for std::string
#include <vector> // for std::vector

namespace catar
{
class RayScene;
}
class vtkDataArray;
class vtkLight;
class vtkLightCollection;
class vtkPolyData;
class vtkProperty;

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricLightingSupport
{
public:
  /// The lights that are switched on: not positional = directional; positional with
  /// ConeAngle < 90 = spotlight; otherwise a point light. Colours times Intensity.
  static std::vector<catar::LightSource> ConvertLights(vtkLightCollection* lights);

  /// The kind of light a vtkLight is (as ConvertLights reads it): not positional = directional;
  /// positional with ConeAngle < 90 = spot; otherwise point.
  static catar::LightSource::Kind LightKind(vtkLight* light);

  /// Ka = Ambient * AmbientColor, Kd = Diffuse * DiffuseColor, Ks = Specular * SpecularColor,
  /// shininess = SpecularPower, and the given emission.
  static catar::Material ConvertProperty(vtkProperty* property, const double emission[3]);

  /// A material of a multi-material mesh (Core's ShadingMaterial).
  using MaterialEntry = catar::ShadingMaterial;

  /// The number of components of a material in the field-data array "Materials": ambient,
  /// diffuse, specular, specular power, ambient colour (3), diffuse colour (3), specular colour
  /// (3), opacity; as vtkProperty names them.
  static constexpr int MaterialComponents = 14;

  /// A mesh's materials: the field-data array "Materials" (MaterialComponents doubles a material)
  /// and the point-data array "MaterialIndex" (one integer a point, into Materials). Both absent:
  /// true, `materials` empty and `index` null. One without the other, an index out of range or a
  /// wrong size: false with a sentence in `error`.
  static bool ReadMaterials(vtkPolyData* mesh, const double emission[3],
    std::vector<MaterialEntry>& materials, vtkDataArray*& index, std::string& error);

  /// Writes `properties` as a mesh's "Materials" field data (see ReadMaterials).
  static void WriteMaterials(vtkPolyData* mesh, const std::vector<vtkProperty*>& properties);

  /// Area-weighted vertex normals (Newell normals of the polygons summed at their vertices),
  /// unit length; (0, 0, 1) where a point has no polygon.
  static std::vector<catar::Vec3> VertexNormals(vtkPolyData* mesh);

  /// Builds `scene` from the polygons of `meshes` (world coordinates, fan-triangulated), the
  /// meshes' points one after another in that order. Returns false and says why in `error` when
  /// a mesh's cells name points it does not have, or Embree cannot build it (NaN coordinates, ...).
  static bool BuildRayScene(
    const std::vector<vtkPolyData*>& meshes, catar::RayScene& scene, std::string& error);
};

#endif
