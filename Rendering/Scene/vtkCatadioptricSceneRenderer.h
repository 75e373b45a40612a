/**
 * @class   vtkCatadioptricSceneRenderer
 * @brief   renders a scene file (or the built-in demo) through the whole pipeline
 *
 * Reads a scene (YAML/JSON, see Documentation/file-formats.md), builds the objects (mesh files
 * through VTK's readers, or procedural boxes, spheres, tori, cylinders, planes), and runs, for
 * every frame, projection -> lighting (when the scene is lit; every object casts shadows on the
 * others)
 * -> painter sort -> compositing onto the background (a synthesised room, a colour, or an image
 * file). The scene key `visibility` sets the compositor's Visibility (painter order or a depth
 * buffer). Meshes are prepared once; Render() can be called again after the
 * camera pose changes, and then redoes only the per-frame stages, and of those only the work
 * whose inputs changed: the synthesised background is traced again only when the camera (or the
 * background's own settings) changed, not when only objects or lights moved or the camera was
 * merely marked modified; per-triangle colours are averaged at the vertices for Gouraud shading
 * once, not every frame.
 *
 * Consecutive objects that look alike (untextured, the same material when lit, meshes with the
 * same arrays) go through one pipeline as one mesh, so that a scene of many small objects does
 * not cost a pipeline per object; the image is the same. (Not with the iterative solver, whose
 * reflection points depend on their neighbours' in the last bits.) Shadows are traced against one
 * vtkCatadioptricOccluders of all the meshes, shared by the lighting filters and built once.
 *
 * The wall-clock time of each stage of the last Render() is kept (GetStageName / GetStageTime).
 */
#ifndef vtkCatadioptricSceneRenderer_h
#define vtkCatadioptricSceneRenderer_h

#include "CatadioptricARSceneModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr

namespace catar
{
struct FramePose;
}

class vtkCatadioptricCamera;
class vtkCatadioptricCompositor;
class vtkCatadioptricLighting;
class vtkCatadioptricProjection;
class vtkImageData;
class vtkLightCollection;
class vtkPolyData;

class CATADIOPTRICARSCENE_EXPORT vtkCatadioptricSceneRenderer : public vtkObject
{
public:
  static vtkCatadioptricSceneRenderer* New();
  vtkTypeMacro(vtkCatadioptricSceneRenderer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Scene file to read; when null or empty, the built-in demo scene is used. A name not found
  /// as given is looked for on the data search path (CATAR_DATA_PATH, then the installed data);
  /// found nowhere, LoadScene fails with an error that names every folder it looked in.
  vtkSetStringMacro(SceneFileName);
  vtkGetStringMacro(SceneFileName);
  ///@}

  ///@{
  /// Remeshing of every object, overriding the scene file's `remesh` settings: a target triangle
  /// area (m^2) or, when that is 0, a pixel tolerance (largest edge bend in pixels through the
  /// scene's camera). 0 (default) keeps the scene's settings. Applied at the next LoadScene().
  vtkSetClampMacro(RemeshTargetArea, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RemeshTargetArea, double);
  vtkSetClampMacro(RemeshPixelTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RemeshPixelTolerance, double);
  ///@}

  ///@{
  /// Adaptive tessellation of every object (vtkCatadioptricProjection's AdaptiveTolerance,
  /// pixels), overriding the scene's `edges`/`adaptive`; 0 (default) keeps the scene's. Applied
  /// at the next LoadScene().
  vtkSetClampMacro(AdaptiveTolerance, double, 0.0, 1e6);
  vtkGetMacro(AdaptiveTolerance, double);
  ///@}

  ///@{
  /// ReferenceSamples (default 0: the scene's key `renderer`): above 0, render with the exact
  /// reference ray tracer (vtkCatadioptricRayTracer) instead of the fast path, with this many
  /// samples per pixel side (1 to 8); its time is reported as the composite stage. Applied at
  /// the next LoadScene().
  vtkSetClampMacro(ReferenceSamples, int, 0, 8);
  vtkGetMacro(ReferenceSamples, int);
  ///@}

  ///@{
  /// TransparentBackground (default off): the objects alone over a transparent background
  /// (alpha 0), whatever the scene's background (a video or image background still sets the
  /// sequence and the poses from markers). Applied at the next LoadScene().
  vtkSetMacro(TransparentBackground, bool);
  vtkGetMacro(TransparentBackground, bool);
  vtkBooleanMacro(TransparentBackground, bool);
  ///@}

  ///@{
  /// OutputVisibleTriangle (default off): the output gets the compositor's VisibleTriangle array
  /// (per pixel, meshIndex * 2^32 + cell id of the triangle seen, -1 for none; see
  /// vtkCatadioptricCompositor). Applied at the next LoadScene().
  vtkSetMacro(OutputVisibleTriangle, bool);
  vtkGetMacro(OutputVisibleTriangle, bool);
  vtkBooleanMacro(OutputVisibleTriangle, bool);
  ///@}

  ///@{
  /// OutputPathLength (default off): the output gets the "PathLength" array (per pixel, float:
  /// the distance from the mirror to the surface seen, NaN for none; see
  /// vtkCatadioptricImageSink), from the fast path or the reference renderer. Applied at the
  /// next LoadScene().
  vtkSetMacro(OutputPathLength, bool);
  vtkGetMacro(OutputPathLength, bool);
  vtkBooleanMacro(OutputPathLength, bool);
  ///@}

  ///@{
  /// Anti-aliased edges (vtkCatadioptricCompositor's Antialias) with Antialias x Antialias
  /// samples per edge pixel (2 to 4), overriding the scene's `antialias`; 0 (default) keeps the
  /// scene's. Applied when the scene is next read.
  vtkSetClampMacro(Antialias, int, 0, 4);
  vtkGetMacro(Antialias, int);
  ///@}

  ///@{
  /// Draw consecutive objects that can share a pipeline as one mesh (default on): untextured
  /// objects with the same point and cell arrays, with the quartic solver; when lit, their
  /// materials travel with the mesh (vtkCatadioptricLighting's "Materials" and "MaterialIndex").
  /// The image is the same either way; joined, a scene of many small objects costs far less a
  /// frame. Applied at the next LoadScene().
  vtkSetMacro(JoinObjects, bool);
  vtkGetMacro(JoinObjects, bool);
  vtkBooleanMacro(JoinObjects, bool);
  ///@}

  /// The number of per-object pipelines (projection, lighting, sort) of the last LoadScene().
  int GetNumberOfPipelines();
  ///@{
  /// Pipeline i's projection and lighting filters (the lighting is null in an unlit scene; both
  /// null for i out of range): to inspect what a frame recomputed.
  vtkCatadioptricProjection* GetProjection(int pipeline);
  vtkCatadioptricLighting* GetLighting(int pipeline);
  ///@}
  /// The compositor that draws the frame (its statistics, e.g. GetNumberOfEdgePixels()).
  vtkCatadioptricCompositor* GetCompositor();

  /// One line per remeshed object of the last LoadScene(): triangle counts, steps, achieved edge
  /// bend ("" when nothing was remeshed).
  const char* GetMeshReport();

  /// Reads the scene and builds the pipeline (meshes are prepared here). Returns false on a bad
  /// scene (see GetLastError()). Render() calls it when needed.
  bool LoadScene();

  /// Renders a frame. Returns false on failure (see GetLastError()).
  bool Render();

  ///@{
  /// Sequences (Documentation/file-formats.md): a scene with a `trajectory`, a `video` background,
  /// keyframed objects or lights, or a `sequence` key has several frames; a still scene has one.
  /// LoadScene() plans them and sets up frame 0. RenderFrame(k) moves the camera, the objects
  /// and the lights to frame k, takes the background's frame k, and renders; only what moved is
  /// recomputed (a still camera keeps the projection of still objects; moving lights redo the
  /// lighting only). GetFrameRate() is the rate a video of the sequence plays at;
  /// GetSequenceNote() a sentence when video and trajectory differ in length ("" otherwise).
  int GetNumberOfFrames();
  /// Pose from markers (Documentation/markers.md): a marker board file whose markers, found in each
  /// background frame, give that frame's camera pose (overrides the scene's `markers`; "" keeps
  /// the scene's). Applied at the next LoadScene().
  vtkSetStringMacro(MarkerBoardFileName);
  vtkGetStringMacro(MarkerBoardFileName);
  /// With markers: the pose estimation of the last frame (seconds), a line on it (markers found,
  /// inliers, reprojection error and one sigma, or why it has no reliable pose), and the number
  /// of frames since LoadScene() without a reliable pose (they keep the previous frame's pose;
  /// frames before the first reliable pose keep the scene's camera pose).
  double GetPoseTime();
  const char* GetPoseReport();
  int GetNumberOfPoseFailures();
  /// Whether the loaded scene estimates its poses from markers, and whether the last rendered
  /// frame's pose was found reliable from that frame's own markers (false: it kept the previous
  /// one); whether any frame since LoadScene() had a reliable pose.
  bool GetUsesMarkers();
  bool GetFramePoseFound();
  bool GetAnyPoseFound();
  /// The last frame's pose estimation (Documentation/markers.md, "Guards"): its verdict
  /// ("reliable", "unreliable", "missing"; "" without markers), why it is not reliable (""
  /// when it is), its one-sigma uncertainty (camera centre in metres, rotation in degrees; NaN
  /// without a pose), the markers found, the corners that fit and those used, and the pose
  /// estimated even when it is not reliable (world to camera, 16 values row by row; false when
  /// there is none).
  const char* GetFramePoseVerdict();
  const char* GetFramePoseNote();
  double GetFramePosePositionSigma();
  double GetFramePoseAngleSigma();
  int GetFramePoseMarkers();
  int GetFramePoseInliers();
  int GetFramePoseCorners();
  double GetFramePoseRMS();
  bool GetFramePoseEstimate(double worldToCamera[16]);
#ifndef __VTK_WRAP__
  /// All of the above at once (C++ only): the tracker's record of the last frame.
  const catar::FramePose& GetFramePose();
#endif
  double GetFrameTime(int frame);
  double GetFrameRate();
  const char* GetSequenceNote();
  bool RenderFrame(int frame);
  ///@}

  /// The last rendered frame (RGBA, VTK row order), or nullptr.
  vtkImageData* GetOutput();

  /// Writes the last frame as PNG. Returns false on failure.
  bool WritePNG(const char* fileName);
  /// Writes the last frame in the format its extension names (.png, .jpg, .tif, .bmp, .webp,
  /// .exr where available; catar::WriteImageFile). Returns false on failure (GetLastError()).
  bool WriteImage(const char* fileName);

  /// Long work -- remeshing an object, a reference render -- invokes vtkCommand::ProgressEvent on
  /// the renderer with a `double*` fraction in [0, 1] as call data; GetProgressText() names the
  /// work ("remeshing bunny", "reference render").
  const char* GetProgressText();

  ///@{
  /// Every file the loaded scene reads, as resolved: the scene file (first: where it was found
  /// on the data search path; none for the built-in demo scene), the calibration, meshes,
  /// textures, the background's image, panorama or video (a frame pattern as it is), the
  /// trajectory and the marker board (catar::SceneDescription::InputFiles). None before a
  /// successful LoadScene. An output should be none of them.
  int GetNumberOfInputFiles();
  const char* GetInputFile(int i);
  ///@}

  ///@{
  /// Stops long work (remeshing in LoadScene, a reference render) at its next progress step, as
  /// vtkAlgorithm's AbortExecute does: set it from a ProgressEvent observer (or a signal
  /// handler). LoadScene then fails with an error that says so ("stopped while remeshing"), and
  /// clears it when it starts.
  vtkSetMacro(AbortExecute, bool);
  vtkGetMacro(AbortExecute, bool);
  vtkBooleanMacro(AbortExecute, bool);
  ///@}

  /// The scene's camera; change its pose and call Render() again for a new frame.
  vtkCatadioptricCamera* GetCamera();

  ///@{
  /// Timing of the last LoadScene()/Render(): stages "scene", "meshes", "background",
  /// "projection", "lighting", "sort", "composite"; seconds. The stages from
  /// GetFirstPerFrameStage() on ("background": decoding a video's frame and bringing the
  /// background up to date, then the fast path's stages) run for every frame; GetFrameTime() is
  /// everything the frame cost: their sum plus GetFramePoseTime(), the pose estimated from
  /// markers for this frame (0 when none was).
  int GetNumberOfStages();
  const char* GetStageName(int stage);
  double GetStageTime(int stage);
  int GetFirstPerFrameStage();
  double GetFrameTime();
  double GetFramePoseTime();
  ///@}

  /// The scene's lights (shared by every object); move them and call Render() again.
  vtkLightCollection* GetLights();

  /// Number of triangles in the scene's meshes.
  vtkIdType GetNumberOfTriangles();

  ///@{
  /// The scene's objects as the last LoadScene() built them, one per entry of its `objects`, in
  /// order: how many; a name (the object's `name`, else its mesh file's name, else its type); and
  /// its triangle mesh in world coordinates (remeshed as drawn, with the "Colors" cell array),
  /// placed for the frame set up last (a keyframed object moved there). "" and null for an object
  /// out of range. The meshes are the renderer's own: copy them before changing them.
  int GetNumberOfObjects();
  const char* GetObjectName(int object);
  vtkPolyData* GetObjectMesh(int object);
  ///@}

  /// The last error message ("" if none).
  const char* GetLastError();

  /// The built-in demo scene as YAML text.
  static const char* GetDemoSceneText();

protected:
  vtkCatadioptricSceneRenderer();
  ~vtkCatadioptricSceneRenderer() override;

  char* SceneFileName = nullptr;
  double RemeshTargetArea = 0.0;
  double RemeshPixelTolerance = 0.0;
  bool JoinObjects = true;
  double AdaptiveTolerance = 0.0;
  int Antialias = 0;
  bool AbortExecute = false;
  bool TransparentBackground = false;
  int ReferenceSamples = 0;
  bool OutputVisibleTriangle = false;
  bool OutputPathLength = false;
  char* MarkerBoardFileName = nullptr;

private:
  vtkCatadioptricSceneRenderer(const vtkCatadioptricSceneRenderer&) = delete;
  void operator=(const vtkCatadioptricSceneRenderer&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
