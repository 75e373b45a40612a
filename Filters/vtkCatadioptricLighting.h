/**
 * @class   vtkCatadioptricLighting
 * @brief   Phong lighting of a projected mesh, with the viewer at each point's reflection point
 *
 * The input is the output of vtkCatadioptricProjection (it needs MirrorPoint, and for flat
 * shading CentroidMirrorPoint, and the camera in field data). The output is the input plus a
 * colour array named "Colors" (RGBA, unsigned char) that vtkCatadioptricCompositor draws:
 *  - GOURAUD: point data, one colour per vertex, lit at the vertex with its normal and seen from
 *    the vertex's own reflection point (interpolated across each triangle by the compositor);
 *  - FLAT: cell data, one colour per cell, lit at the centroid with the face normal and seen from
 *    the centroid's own reflection point;
 *  - NONE: cell data, the unlit base colour (the paper's "blob").
 * The equation is in Module/Shading/Lighting.h (the paper's equation 12). Lights are vtkLights in
 * world coordinates: not positional = directional; positional with ConeAngle < 90 = spotlight (cone
 * half angle ConeAngle, Exponent, AttenuationValues); otherwise a point light. Colours are
 * multiplied by Intensity; lights switched off are ignored. The material is a vtkProperty:
 * Ka = Ambient * AmbientColor, Kd = Diffuse * DiffuseColor, Ks = Specular * SpecularColor,
 * shininess = SpecularPower, alpha = Opacity; Emission is set here.
 *
 * Several materials in one mesh: a field-data array "Materials" (14 doubles a material: Ambient,
 * Diffuse, Specular, SpecularPower, AmbientColor, DiffuseColor, SpecularColor, Opacity, as
 * vtkProperty names them) and a point-data array "MaterialIndex" (one integer a point) give each
 * point its own material in place of the property's (a cell takes its first point's); Emission
 * stays the filter's. vtkCatadioptricSceneRenderer draws objects of different materials as one
 * mesh this way.
 *
 * Base colours: when the input has an array named InputColorArrayName (point or cell data, RGB(A),
 * unsigned char 0-255 or floating 0-1), it replaces the material's ambient and diffuse colours per
 * point/cell (so a box with a colour per face is lit face by face).
 *
 * The output's field data records the lighting (WriteToFieldData: lights, material, shading mode,
 * shadows, two-sided lighting, global ambient, emission, base colour array), so that
 * vtkCatadioptricRayTracer lights the output alike without SetMeshLighting (ParaView's
 * pipeline). When the base colours are the input's "Colors", which the lit colours replace, they
 * are kept in the output as "BaseColors" (point or cell data, as they came) for the record to
 * name.
 *
 * Shadows: with Shadows on, a light contributes its diffuse and specular terms only where the
 * segment from the surface point to the light is free: Embree ray queries against the input's own
 * polygons and those of the meshes on input port 1 (optional, repeatable: the other objects of the
 * scene, in world coordinates). The acceleration structure is kept while no mesh changes. In a
 * scene of many objects, give every object's filter the same vtkCatadioptricOccluders instead
 * (SetOccluders): one structure of all the meshes, built once and shared, rather than one per
 * filter of every mesh.
 *
 * Points and cells that are not visible are left black. Work is split over the threads of
 * vtkCatadioptricParallel (as many as vtkSMPTools would use).
 */
#ifndef vtkCatadioptricLighting_h
#define vtkCatadioptricLighting_h

#include "CatadioptricARFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // for members

#include <memory> // for std::unique_ptr

class vtkCatadioptricOccluders;
class vtkFieldData;
class vtkLight;
class vtkLightCollection;
class vtkProperty;
namespace catar
{
class RayScene;
}

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricLighting : public vtkPolyDataAlgorithm
{
public:
  static vtkCatadioptricLighting* New();
  vtkTypeMacro(vtkCatadioptricLighting, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Other meshes that cast shadows (input port 1, world coordinates).
  void AddOccluderConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(1, output); }
  void AddOccluderData(vtkDataObject* mesh) { this->AddInputData(1, mesh); }
  void RemoveAllOccluderConnections() { this->RemoveAllInputConnections(1); }
  ///@}

  ///@{
  /// A shared shadow structure (default none). When set, shadows are traced against its meshes
  /// only, not against the input's own polygons: it should hold the input's mesh (before
  /// projection) and the other objects. Give the same object to the filters of every object of a
  /// scene. Occluders on input port 1 as well are an error.
  void SetOccluders(vtkCatadioptricOccluders* occluders);
  vtkCatadioptricOccluders* GetOccluders();
  ///@}

  ///@{
  /// The lights (world coordinates).
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  vtkLightCollection* GetLights();
  void SetLights(vtkLightCollection* lights);
  ///@}

  ///@{
  /// Convenience for scripts and ParaView, one light of each kind, all in world coordinates, the
  /// colour (r, g, b, 0 to 1) its diffuse and specular colour, no ambient:
  ///  - AddSpotLight: at `position` aimed at `focalPoint`, cone half angle in degrees (below 90),
  ///    exponent 1, no attenuation;
  ///  - AddPointLight: at `position`, shining every way, its light divided by
  ///    constant + linear d + quadratic d^2 at distance d (1 0 0: no fall-off; the three not
  ///    negative, not all 0);
  ///  - AddDirectionalLight: infinitely far in `direction` (from the scene towards the light, not
  ///    zero; any length), the same direction at every point, no attenuation.
  /// A bad value is an error and adds nothing.
  void AddSpotLight(double px, double py, double pz, double fx, double fy, double fz,
    double coneAngle, double r, double g, double b);
  void AddPointLight(double px, double py, double pz, double r, double g, double b, double constant,
    double linear, double quadratic);
  void AddDirectionalLight(double dx, double dy, double dz, double r, double g, double b);
  ///@}

  ///@{
  /// Remove the lights of one kind only (spot: positional with a cone angle below 90 degrees;
  /// point: positional with a cone of 90 degrees or more; directional: not positional), whether
  /// added with AddLight or the Add...Light shortcuts. ParaView's SpotLights, PointLights and
  /// DirectionalLights each clear their own kind with these before adding theirs.
  void RemoveAllSpotLights();
  void RemoveAllPointLights();
  void RemoveAllDirectionalLights();
  ///@}

  ///@{
  /// The lighting as field data: the record the filter leaves in its output's field data, so that
  /// vtkCatadioptricRayTracer, given that output as a mesh, lights it as this filter would
  /// (as if SetMeshLighting had been called with it). Three arrays: LightingSettings (23 doubles:
  /// shading mode, shadows, two-sided lighting, global ambient (3), emission (3), then the
  /// material as one row of "Materials": ambient, diffuse, specular, specular power, ambient
  /// colour (3), diffuse colour (3), specular colour (3), opacity), LightingLights (22 doubles a
  /// light that is switched on: positional, position (3), focal point (3), cone angle, exponent,
  /// attenuation (3), intensity, ambient, diffuse and specular colours (3 each)) and
  /// LightingColorArray (a string: the base colour array, "" for none).
  /// WriteToFieldData writes this filter's parameters with InputColorArrayName. ReadFromFieldData
  /// makes this filter's lights, material and settings those of a record: false, and the filter
  /// unchanged, when the field data holds no record or a malformed one. HasLightingRecord: whether
  /// any of the three arrays is there.
  void WriteToFieldData(vtkFieldData* fieldData);
  bool ReadFromFieldData(vtkFieldData* fieldData);
  static bool HasLightingRecord(vtkFieldData* fieldData);
  ///@}

  ///@{
  /// The material. A default vtkProperty (grey, no specular) is created.
  void SetProperty(vtkProperty* property);
  vtkProperty* GetProperty();
  ///@}

  ///@{
  /// Shortcuts to the material (the vtkProperty), for scripts and ParaView.
  void SetDiffuseColor(double r, double g, double b);
  void SetAmbient(double ambient);
  void SetDiffuse(double diffuse);
  void SetSpecular(double specular);
  void SetSpecularPower(double power);
  void SetOpacity(double opacity);
  ///@}

  /// Shading modes.
  enum ShadingModes
  {
    NONE = 0,   ///< unlit base colour per cell
    FLAT = 1,   ///< one lit colour per cell (centroid)
    GOURAUD = 2 ///< one lit colour per vertex, interpolated
  };
  ///@{
  /// Shading mode. Default GOURAUD.
  vtkSetClampMacro(ShadingMode, int, NONE, GOURAUD);
  vtkGetMacro(ShadingMode, int);
  void SetShadingModeToNone() { this->SetShadingMode(NONE); }
  void SetShadingModeToFlat() { this->SetShadingMode(FLAT); }
  void SetShadingModeToGouraud() { this->SetShadingMode(GOURAUD); }
  ///@}

  ///@{
  /// Shadows between the mesh's own triangles (the paper's illumination occlusion). Default on.
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  ///@}

  ///@{
  /// Light both sides of each surface (the normal is turned towards the viewer). Default on.
  vtkSetMacro(TwoSidedLighting, bool);
  vtkGetMacro(TwoSidedLighting, bool);
  vtkBooleanMacro(TwoSidedLighting, bool);
  ///@}

  ///@{
  /// Global ambient light (RGB). Default 0.2 0.2 0.2.
  vtkSetVector3Macro(GlobalAmbient, double);
  vtkGetVector3Macro(GlobalAmbient, double);
  ///@}

  ///@{
  /// Material emission (RGB). Default black.
  vtkSetVector3Macro(Emission, double);
  vtkGetVector3Macro(Emission, double);
  ///@}

  ///@{
  /// Name of the base colour array of the input. Default "Colors".
  vtkSetStringMacro(InputColorArrayName);
  vtkGetStringMacro(InputColorArrayName);
  ///@}

  /// The modification time includes the lights', the property's and, with shadows, the shared
  /// occluders'.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricLighting();
  ~vtkCatadioptricLighting() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkSmartPointer<vtkLightCollection> Lights;
  vtkSmartPointer<vtkProperty> Property;
  vtkSmartPointer<vtkCatadioptricOccluders> Occluders;
  int ShadingMode = GOURAUD;
  bool Shadows = true;
  bool TwoSidedLighting = true;
  double GlobalAmbient[3] = { 0.2, 0.2, 0.2 };
  double Emission[3] = { 0.0, 0.0, 0.0 };
  char* InputColorArrayName = nullptr;

private:
  // RequestData's work (RequestData reports running out of memory).
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  vtkCatadioptricLighting(const vtkCatadioptricLighting&) = delete;
  void operator=(const vtkCatadioptricLighting&) = delete;

  // Writes the record with `colorArrayName` as its base colour array.
  void WriteRecord(vtkFieldData* fieldData, const char* colorArrayName);
  // The output's record: the base colours the output still has (kept as BaseColors where the lit
  // Colors replace them) or none.
  void RecordLighting(vtkPolyData* input, vtkPolyData* output);

  struct Internals;
  std::unique_ptr<Internals> Internal;

  /// The scene that casts shadows: the shared occluders (SetOccluders), or the input's own
  /// triangles and those on port 1 (occluderInputs), built or refitted here. False, with an error,
  /// when both are given or the scene cannot be built.
  bool ShadowScene(
    vtkPolyData* input, vtkInformationVector* occluderInputs, const catar::RayScene*& shadowScene);
};

#endif
