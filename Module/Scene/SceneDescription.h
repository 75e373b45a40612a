// CatadioptricAR Core: scene files (YAML or JSON, read with yaml-cpp; OpenCV FileStorage files
// too).
//
// A scene names the camera (a calibration file or an inline calibration map), the output size,
// the background, and the objects (a mesh file or a procedural object, a transform, a colour).
// The keys are documented in Documentation/file-formats.md; every error names the key at fault.
#ifndef catarSceneDescription_h
#define catarSceneDescription_h

#include "CameraModel.h"
#include "Trajectory.h"

#include <string>
#include <vector>

namespace catar
{
/// How an object's mesh is prepared before projection (vtkCatadioptricRemesher): kept as it is,
/// remeshed to a target triangle area, or to a pixel tolerance through the scene's camera.
struct SceneRemesh
{
  std::string mode = "none";   ///< "none", "area" or "pixels"
  double targetArea = 1.2e-5;  ///< m^2 (after the object's scale), mode "area"
  double pixelTolerance = 0.5; ///< largest edge bend in pixels, mode "pixels"
  int iterations = 3;
  double featureAngle = 60.0;    ///< degrees: sharper edges are kept
  double maxTriangles = 4000000; ///< mode "pixels": the triangle budget (key max_triangles)
};

/// The most triangles a procedural object may have (its `resolution` is checked against it
/// before anything is built): 2^24.
constexpr double kMaxObjectTriangles = 16777216.0;

/// About how many triangles a procedural object of this type and resolution has (0 for "mesh").
double ProceduralTriangles(const std::string& type, int resolution);

/// One object of a scene.
struct SceneObject
{
  std::string name;
  /// "mesh" (a file any VTK reader takes) or a procedural object: "box", "sphere", "torus",
  /// "cylinder", "plane", "marker" (an ArUco marker, Markers.h: keys `id`, `dictionary`, and
  /// `size` the side of its black square; a white margin of one cell around it).
  std::string type = "box";
  std::string file;                ///< mesh file, resolved against the scene file's folder
  Vec3 size = Vec3(0.1, 0.1, 0.1); ///< box edge lengths; plane uses x, y
  double radius = 0.05;            ///< sphere, cylinder, torus ring radius
  double tubeRadius = 0.02;        ///< torus tube radius
  double height = 0.1;             ///< cylinder height
  int resolution = 16;             ///< subdivisions per unit feature (edge, ring)
  Vec3 translate = Vec3::Zero();   ///< world position, metres
  Vec3 rotate = Vec3::Zero();      ///< degrees about world x, then y, then z
  Vec3 scale = Vec3::Ones();
  Vec3 color = Vec3(0.8, 0.8, 0.8); ///< RGB in [0,1]
  double opacity = 1.0;
  bool faceColors = false; ///< box: a colour per face (the paper's figure 5)
  /// "none" or "checker": a 3D checker of `patternSize` (object coordinates) that darkens every
  /// other cell, so that an unlit object shows its shape and the mirror's bending.
  std::string pattern = "none";
  double patternSize = 0.02;
  /// Texture: "" (none), "checker" (a generated checkerboard) or an image file (resolved against
  /// the scene file's folder). Boxes get texture coordinates per face (the paper's section 3.3);
  /// meshes use their own.
  std::string texture;
  int markerId = 0;                             ///< type "marker"
  std::string markerDictionary = "DICT_4X4_50"; ///< type "marker"
  // Material (used when the scene is lit): coefficients times the object's colour, and the
  // specular colour and power.
  double ambient = 0.2;
  double diffuse = 0.8;
  double specular = 0.3;
  double specularPower = 20.0;
  Vec3 specularColor = Vec3(1, 1, 1);
  /// Mesh preparation; the scene's `remesh` unless the object has its own.
  SceneRemesh remesh;
  /// Key `adaptive: { pixel_tolerance: P }` in the object: its own per-frame adaptive
  /// tessellation (vtkCatadioptricProjection's AdaptiveTolerance, pixels; 0 off); -1 (unset):
  /// the scene's.
  double adaptiveTolerance = -1.0;
  /// Key `keyframes`: the object's placement over time, a sequence of `{time, translate,
  /// rotate}` (a keyframe without translate or rotate keeps the object's own); positions are
  /// interpolated linearly, rotations by slerp, clamped before the first and after the last. The
  /// mesh is built (and remeshed) at the object's own translate and rotate, then moved.
  Keyframes keyframes;
};

/// A keyframe of a light: its position and focal point at a time (both interpolated linearly).
struct SceneLightKeyframe
{
  double time = 0.0;
  Vec3 position = Vec3::Zero();
  Vec3 focalPoint = Vec3::Zero();
};

/// A light of the scene (world coordinates; colours in [0,1], multiplied by intensity).
struct SceneLight
{
  std::string type = "spot"; ///< "spot", "point" or "directional"
  Vec3 position = Vec3(0, 0, 2);
  Vec3 focalPoint = Vec3(0, 0, 0); ///< spot axis / direction of a directional light
  double coneAngle = 30.0;         ///< spot cone half angle, degrees
  double exponent = 1.0;
  Vec3 color = Vec3(1, 1, 1); ///< diffuse and specular colour
  Vec3 ambient = Vec3(0, 0, 0);
  double intensity = 1.0;
  Vec3 attenuation = Vec3(1, 0, 0);
  /// Key `keyframes`: `{time, position, focal_point}` (a keyframe without one of them keeps the
  /// light's own), times strictly increasing; clamped before the first and after the last.
  std::vector<SceneLightKeyframe> keyframes;
  /// Position and focal point at time t.
  void At(double t, Vec3& position, Vec3& focal) const;
};

/// How objects are lit. Without a `lighting` section scenes are unlit (shading "none").
struct SceneLighting
{
  std::string shading = "none"; ///< "none", "flat" or "gouraud"
  bool shadows = true;
  Vec3 globalAmbient = Vec3(0.2, 0.2, 0.2);
  std::vector<SceneLight> lights;
};

/// Background of the output image.
struct SceneBackground
{
  /// "environment" (procedural room), "panorama" (an equirectangular panorama reflected by the
  /// mirror), "color", "image" or "video" (a video file or a numbered image sequence, key `file`:
  /// the camera's own frames, one per frame of the sequence)
  std::string type = "environment";
  Vec3 color = Vec3(0, 0, 0);
  std::string image; ///< image file for type "image"
  int samples = 2;   ///< supersampling of the environment/panorama (samples x samples per pixel)
  /// Type "panorama" (key `file`): an equirectangular image file resolved against the scene
  /// file's folder; "" = the procedural room rendered into a panorama from the mirror centre.
  std::string panorama;
  double rotation = 0.0;               ///< type "panorama": degrees about world +z
  Vec3 backdrop = Vec3(0.5, 0.5, 0.5); ///< type "panorama": colour around the mirror
  /// Type "video" (key `file`): a video file or a printf pattern (`frames/%05d.png`), resolved
  /// against the scene file's folder.
  std::string video;
  /// Type "video", key `match`: how frame k pairs with the camera's poses: "index" (pose k of
  /// the trajectory) or "time" (the pose at the frame's time, start_time + k / fps).
  std::string match = "index";
  double fps = 0.0;       ///< key `fps`: frames a second; 0 = the video's own
  double startTime = 0.0; ///< key `start_time`: the time of frame 0 (match "time"), seconds
};

/// Key `sequence` (for scenes without a trajectory or a video background): `frames` frames at
/// `fps` frames a second, frame k at time k / fps.
struct SceneSequence
{
  int frames = 1;
  double fps = 30.0;
  bool given = false; ///< the scene has a `sequence` key (else keyframes set the frames)
};

struct SceneDescription
{
  std::string fileName; ///< where it was read from ("" for built-in)
  CameraModel camera;
  std::string calibrationFile; ///< the calibration file `camera` names ("" when inline)
  int width = 0;               ///< output size; 0 = the calibration's
  int height = 0;
  SolverType solver = SolverType::Automatic; ///< the faster where exact (SolverType)
  /// Key `visibility`: "painter" (the paper's painter order, default) or "depth" (a per-pixel
  /// depth buffer on the path length): vtkCatadioptricCompositor's Visibility.
  std::string visibility = "painter";
  /// Key `cull_back_faces` (0 or 1, default 0): vtkCatadioptricProjection's BackFaceCulling for
  /// every object (only for closed, consistently oriented meshes).
  bool cullBackFaces = false;
  /// Key `edges: { boundary_tolerance: B, adaptive_tolerance: A }` (pixels; defaults 0.25 and 0):
  /// vtkCatadioptricProjection's BoundaryTolerance and AdaptiveTolerance for every object
  /// (Documentation/edges-and-rasterisation.md). Key `adaptive: { pixel_tolerance: A }` is the same
  /// as adaptive_tolerance; an object's own `adaptive` overrides it for that object.
  double boundaryTolerance = 0.25;
  double adaptiveTolerance = 0.0;
  /// Key `renderer`: "fast" (default: projection, lighting, sort, compositing) or "reference"
  /// (the exact ray tracer); key `reference_samples` (1 to 8, default 1): its samples per pixel
  /// side.
  std::string renderer = "fast";
  int referenceSamples = 1;
  /// Key `antialias`: true (4 x 4 samples), false (default), or `{ samples: S }` (S = 2, 3 or 4
  /// per pixel side): vtkCatadioptricCompositor's Antialias and AntialiasSamples. 0: off.
  int antialiasSamples = 0;
  SceneBackground background;
  SceneLighting lighting;
  SceneRemesh remesh; ///< default of every object
  std::vector<SceneObject> objects;
  /// Key `trajectory` (a file, resolved against the scene file's folder; Trajectory.h gives the
  /// formats): the camera's poses over time, replacing the calibration's world_to_camera. Frame
  /// k of the sequence is pose k (or, with a video background matched by time, the pose at the
  /// frame's time).
  std::string trajectoryFile;
  Trajectory trajectory;
  SceneSequence sequence;
  /// Key `markers` (a marker board file, Markers.h, resolved against the scene file's folder):
  /// the camera's pose of every frame is estimated from the board's markers seen in the
  /// background's frame (an `image` or `video` background), instead of the calibration's pose
  /// or a trajectory.
  std::string markerBoardFile;

  /// Every file the scene reads, as resolved: the scene file, the calibration, meshes, textures,
  /// the background's image, panorama or video (a frame pattern as it is), the trajectory and
  /// the marker board. An output must be none of them.
  std::vector<std::string> InputFiles() const;

  /// Whether anything moves or changes from frame to frame (a trajectory, keyframes, a video).
  bool IsSequence() const;
};

/// The folders a relative file name in a scene is looked for in, after the scene file's own
/// folder: each folder of the environment variable CATAR_DATA_PATH (separated by ':'), then the
/// installed data (<prefix>/share/catadioptricar: calibration/, scenes/, meshes/).
std::vector<std::string> DataSearchPath();
/// The installed data folder (where `cmake --install` puts Data/).
std::string InstalledDataDir();
/// Where a file named in a scene is: an absolute name as it is; a relative one in `baseDir`
/// (the scene's folder), else in the first folder of DataSearchPath() that has it. When none
/// has it, `baseDir`/`path`, and `error` (when given) says "'path' not found; looked in ..." with
/// every folder tried; a URL ("https://...") is not looked for, and `error` says so.
std::string FindDataFile(
  const std::string& baseDir, const std::string& path, std::string* error = nullptr);
/// Whether `name` is a URL ("scheme://..."), which the project does not download.
bool IsUrl(const std::string& name);

/// Reads a scene file. Returns false and says why in `error` on failure.
bool LoadScene(const std::string& path, SceneDescription& scene, std::string& error);
/// Reads a scene from text; relative paths resolve against `baseDir`.
bool ParseScene(
  const std::string& text, const std::string& baseDir, SceneDescription& scene, std::string& error);

/// The built-in demo scene (the picture in README): the paper's parallelepiped and a torus, seen in
/// a spherical mirror hanging in a procedural room.
SceneDescription DemoScene();
/// The demo scene as YAML text (the same scene DemoScene() returns).
const char* DemoSceneText();
} // namespace catar

#endif
