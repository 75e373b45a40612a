/**
 * @class   vtkCatadioptricRayTracer
 * @brief   exact reference rendering of a scene through the mirror, one ray per sample
 *
 * The ground truth the fast path (projection, lighting, painter sort, compositor) is measured
 * against, and a rendering mode for users who want accuracy over speed. For every pixel (with
 * Samples x Samples supersampling), the pixel is back-projected, reflected off the spherical
 * mirror, and the reflected ray is intersected with the meshes (Embree, Module/RayTracer.h). The
 * hit point is shaded with the same Core equation as vtkCatadioptricLighting, but exactly: the
 * viewer is the pixel's own mirror point, the normal is the face normal (FLAT) or the vertex
 * normals interpolated at the hit (GOURAUD: per-pixel, where the fast path interpolates vertex
 * colours), shadows are traced by shadow rays against every mesh, base colours and texture
 * coordinates are interpolated at the hit.
 *
 * Same inputs and output as vtkCatadioptricCompositor, so the two images compare pixel by pixel:
 * port 0 (optional) the camera frame; port 1 (repeatable) the meshes in world coordinates (the
 * raw meshes or the output of any stage of the fast path: only points, polygons, colours,
 * normals and texture coordinates are read); port 2 (optional, repeatable) textures, chosen per
 * mesh by its field data TextureIndex as in the compositor. Output: RGBA unsigned char image, VTK
 * row order, and with OutputVisibleTriangle the point data "VisibleTriangle" (int64 per pixel:
 * meshIndex * 2^32 + cell id of the triangle seen by the pixel's centre sample, -1 for none; the
 * cell id is the cell-data value OriginalCellId when the mesh has it, else the cell index).
 *
 * Lighting: SetMeshLighting(i, lighting) lights mesh i with the parameters of a
 * vtkCatadioptricLighting filter (its lights, property, shading mode, shadows, two-sided flag,
 * global ambient, emission and input colour array) without running it; the lights and global
 * ambient of the first such filter light the whole scene, and shadows are traced when any of
 * them has Shadows on. A mesh without lighting is drawn unlit with the array ColorArrayName
 * (point or cell data) or Color, as the compositor draws it.
 *
 * The camera comes from SetCamera() or CalibrationFileName. The rays are back-projected once per
 * camera and sample count and kept; rays whose reflection cannot reach the meshes' bounding box
 * are skipped. Work is split into bands of rows with vtkSMPTools.
 */
#ifndef vtkCatadioptricRayTracer_h
#define vtkCatadioptricRayTracer_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkCatadioptricCameraSlot.h"     // for member
#include "vtkImageAlgorithm.h"

#include <memory> // for std::unique_ptr

class vtkCatadioptricCamera;
class vtkCatadioptricLighting;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricRayTracer : public vtkImageAlgorithm
{
public:
  static vtkCatadioptricRayTracer* New();
  vtkTypeMacro(vtkCatadioptricRayTracer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The camera frame (port 0), the meshes (port 1, several) and textures (port 2, several).
  void SetFrameConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetFrameData(vtkDataObject* frame) { this->SetInputData(0, frame); }
  void AddMeshConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(1, output); }
  void AddMeshData(vtkDataObject* mesh) { this->AddInputData(1, mesh); }
  void RemoveAllMeshConnections() { this->RemoveAllInputConnections(1); }
  void AddTextureConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(2, output); }
  void AddTextureData(vtkDataObject* texture) { this->AddInputData(2, texture); }
  void RemoveAllTextureConnections() { this->RemoveAllInputConnections(2); }
  ///@}

  ///@{
  /// The camera; takes precedence over CalibrationFileName.
  void SetCamera(vtkCatadioptricCamera* camera);
  vtkCatadioptricCamera* GetCamera();
  void SetCalibrationFileName(const char* fileName);
  const char* GetCalibrationFileName();
  ///@}

  ///@{
  /// Lighting of mesh `index` (its connection on port 1) from a vtkCatadioptricLighting filter's
  /// parameters; null: unlit. The filter is not run.
  void SetMeshLighting(int index, vtkCatadioptricLighting* lighting);
  vtkCatadioptricLighting* GetMeshLighting(int index);
  void RemoveAllMeshLightings();
  ///@}

  ///@{
  /// Supersampling: Samples x Samples rays per pixel (1 to 8). Default 1.
  vtkSetClampMacro(Samples, int, 1, 8);
  vtkGetMacro(Samples, int);
  ///@}

  ///@{
  /// Unlit meshes: colour array name (default "Colors"), solid colour, and opacity of all meshes.
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  vtkSetVector3Macro(Color, double);
  vtkGetVector3Macro(Color, double);
  vtkSetClampMacro(Opacity, double, 0.0, 1.0);
  vtkGetMacro(Opacity, double);
  ///@}

  ///@{
  /// Without a frame: the background colour (RGBA) and image size (0: the camera's).
  vtkSetVector4Macro(BackgroundColor, double);
  vtkGetVector4Macro(BackgroundColor, double);
  vtkSetVector2Macro(ImageSize, int);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /// Texture coordinates outside [0,1] repeat (default) or clamp, as in the compositor.
  vtkSetMacro(RepeatTextures, bool);
  vtkGetMacro(RepeatTextures, bool);
  vtkBooleanMacro(RepeatTextures, bool);
  ///@}

  ///@{
  /// Add the "VisibleTriangle" point data to the output. Default off.
  vtkSetMacro(OutputVisibleTriangle, bool);
  vtkGetMacro(OutputVisibleTriangle, bool);
  vtkBooleanMacro(OutputVisibleTriangle, bool);
  ///@}

  ///@{
  /// Counts of the last render: rays that reflect off the mirror, rays traced into the scene's
  /// bounds, hits, and shadow rays.
  vtkGetMacro(NumberOfMirrorRays, vtkIdType);
  vtkGetMacro(NumberOfTracedRays, vtkIdType);
  vtkGetMacro(NumberOfHits, vtkIdType);
  vtkGetMacro(NumberOfShadowRays, vtkIdType);
  ///@}

  /// Includes the camera's and the lighting filters' modification times.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricRayTracer();
  ~vtkCatadioptricRayTracer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkCatadioptricCamera* ResolveCamera();

  vtkCatadioptricCameraSlot CameraSlot;
  int Samples = 1;
  char* ColorArrayName = nullptr;
  double Color[3] = { 1.0, 1.0, 1.0 };
  double Opacity = 1.0;
  double BackgroundColor[4] = { 0.0, 0.0, 0.0, 1.0 };
  int ImageSize[2] = { 0, 0 };
  bool RepeatTextures = true;
  bool OutputVisibleTriangle = false;
  vtkIdType NumberOfMirrorRays = 0;
  vtkIdType NumberOfTracedRays = 0;
  vtkIdType NumberOfHits = 0;
  vtkIdType NumberOfShadowRays = 0;

private:
  vtkCatadioptricRayTracer(const vtkCatadioptricRayTracer&) = delete;
  void operator=(const vtkCatadioptricRayTracer&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
