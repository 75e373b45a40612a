/**
 * @class   vtkCatadioptricRayTracer
 * @brief   exact reference rendering of a scene through the mirror, one ray per sample
 *
 * The ground truth the fast path (projection, lighting, painter sort, compositor) is measured
 * against, and a rendering mode for users who want accuracy over speed. For every pixel (with
 * Samples x Samples supersampling), the pixel is back-projected, reflected off the spherical
 * mirror, and the reflected ray is intersected with the meshes (Embree,
 * Module/Reference/RayTracer.h). The hit point is shaded with the same Core equation as
 * vtkCatadioptricLighting, but exactly: the viewer is the pixel's own mirror point, the normal is
 * the face normal (FLAT) or the vertex normals interpolated at the hit (GOURAUD: per-pixel, where
 * the fast path interpolates vertex colours), shadows are traced by shadow rays against every mesh,
 * base colours and texture coordinates are interpolated at the hit.
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
 * global ambient, emission and input colour array) without running it. A mesh that is the output
 * of a vtkCatadioptricLighting filter (or of a later stage of the fast path) carries that filter's
 * lighting in its field data (vtkCatadioptricLighting::WriteToFieldData): without SetMeshLighting,
 * and with UseInputLighting on (the default), the mesh is lit with it exactly as SetMeshLighting
 * with that filter would light it; this is how ParaView's pipeline lights the reference. The
 * lights and global ambient of the first lit mesh light the whole scene, and shadows are traced
 * when any lit mesh has Shadows on. A mesh without lighting is drawn unlit with the array
 * ColorArrayName (point or cell data) or Color, as the compositor draws it.
 *
 * The camera comes from SetCamera(), CalibrationFileName or else the panel camera (CameraImageSize,
 * FocalLength, ..., WorldToCamera: the demo camera by default).
 *
 * Kept between updates: the rays, back-projected in the camera frame, while the lens, the mirror,
 * the image size and Samples stay (a new pose moves them, at render time); the ray scene (Embree's
 * acceleration structure) and the meshes' triangles while every mesh is the same object with the
 * same points, cells and OriginalCellId, unmodified (a light, a pose or a material that changes
 * only re-traces); the colours, normals and texture coordinates read from a mesh while, in
 * addition, its point and cell data are unmodified. Meshes whose points changed but not their
 * triangles refit the scene (Embree's two-level scene: each mesh's structure refitted to its
 * points); other changes build it again, with Embree on the threads of vtkSMPTools' setting. Tiles
 * of 8 x 8 pixels whose rays cannot reach the meshes' bounding sphere are skipped whole, rays that
 * cannot reach their bounding box are not traced, the others are traced a tile at a time (Embree's
 * ray streams). Work is split into bands of rows with vtkSMPTools.
 */
#ifndef vtkCatadioptricRayTracer_h
#define vtkCatadioptricRayTracer_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "vtkCatadioptricCameraSlot.h"     // for member
#include "vtkCatadioptricImageSink.h"

#include <memory> // for std::unique_ptr

class vtkCatadioptricCamera;
class vtkCatadioptricLighting;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricRayTracer : public vtkCatadioptricImageSink
{
public:
  static vtkCatadioptricRayTracer* New();
  vtkTypeMacro(vtkCatadioptricRayTracer, vtkCatadioptricImageSink);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // Ports, Color, Opacity, ColorArrayName, BackgroundColor, ImageSize, RepeatTextures and
  // OutputVisibleTriangle: vtkCatadioptricImageSink.

  ///@{
  /// The camera (vtkCatadioptricCameraSlot.h): SetCamera (takes precedence), else
  /// SetCalibrationFileName (a YAML/JSON calibration file), else the panel camera
  /// (SetCameraImageSize, SetFocalLength, SetPrincipalPoint, SetDistortion, SetWorldToCamera: the
  /// built-in demo camera's values until changed); SetMirrorType and SetMirrorParameter put
  /// another mirror in the camera's place;
  /// SetTrajectoryFileName moves the camera over time. Each with its getter.
  vtkCatadioptricCameraSlotDeclareMacro();
  vtkCatadioptricCameraSlotDeclareTrajectoryMacro();
  ///@}

  ///@{
  /// Lighting of mesh `index` (its connection on port 1) from a vtkCatadioptricLighting filter's
  /// parameters; null: unlit. The filter is not run.
  void SetMeshLighting(int index, vtkCatadioptricLighting* lighting);
  vtkCatadioptricLighting* GetMeshLighting(int index);
  void RemoveAllMeshLightings();
  ///@}

  ///@{
  /// Light a mesh that has no SetMeshLighting with the lighting recorded in its field data by
  /// vtkCatadioptricLighting, when it has one. Default on; off: such meshes are drawn unlit with
  /// ColorArrayName (for example the lit Colors of the lighting filter) or Color.
  vtkSetMacro(UseInputLighting, bool);
  vtkGetMacro(UseInputLighting, bool);
  vtkBooleanMacro(UseInputLighting, bool);
  ///@}

  ///@{
  /// Supersampling: Samples x Samples rays per pixel (1 to 8). Default 1.
  vtkSetClampMacro(Samples, int, 1, 8);
  vtkGetMacro(Samples, int);
  ///@}

  ///@{
  /// Counts of the last render: rays that reflect off the mirror, rays traced into the scene's
  /// bounds, hits, and shadow rays.
  vtkGetMacro(NumberOfMirrorRays, vtkIdType);
  vtkGetMacro(NumberOfTracedRays, vtkIdType);
  vtkGetMacro(NumberOfHits, vtkIdType);
  vtkGetMacro(NumberOfShadowRays, vtkIdType);
  ///@}

  ///@{
  /// What this tracer has made since it was created: ray scenes (acceleration structures) built,
  /// ray scenes refitted to moved points, and times the rays were back-projected. A new pose or
  /// light adds to none; meshes whose points changed (same triangles) refit the scene; a mesh
  /// whose cells changed, or one added or removed, builds it again; another lens, mirror, image
  /// size or sample count back-projects the rays again.
  vtkIdType GetNumberOfSceneBuilds();
  vtkIdType GetNumberOfSceneRefits();
  vtkIdType GetNumberOfRayBackProjections();
  ///@}

  /// Includes the camera's and the lighting filters' modification times.
  vtkMTimeType GetMTime() override;

protected:
  vtkCatadioptricRayTracer();
  ~vtkCatadioptricRayTracer() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// ImageSize, else the camera's image size.
  void ImageSizeWithoutFrame(vtkInformationVector** inputVector, int size[2]) override;

  vtkCatadioptricCameraSlotMembersMacro();
  int Samples = 1;
  bool UseInputLighting = true;
  vtkIdType NumberOfMirrorRays = 0;
  vtkIdType NumberOfTracedRays = 0;
  vtkIdType NumberOfHits = 0;
  vtkIdType NumberOfShadowRays = 0;

private:
  // RequestData's work (RequestData reports running out of memory).
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  vtkCatadioptricRayTracer(const vtkCatadioptricRayTracer&) = delete;
  void operator=(const vtkCatadioptricRayTracer&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
