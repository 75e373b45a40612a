#include "vtkCatadioptricSceneRenderer.h"

#include "FileOutput.h"
#include "MarkerPoseTracker.h"
#include "Markers.h"
#include "Memory.h"
#include "MeshFileCheck.h"
#include "SceneDescription.h"
#include "SceneFrames.h"
#include "VideoIO.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricEnvironmentSource.h"
#include "vtkCatadioptricErrorText.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricLightingSupport.h"
#include "vtkCatadioptricOccluders.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricSceneObjects.h"
#include "vtkCellData.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTrivialProducer.h"
#include "vtkUnsignedCharArray.h"
#include "vtksys/SystemTools.hxx"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricSceneRenderer);

namespace
{
const char* const kStageNames[] = { "scene", "meshes", "background", "projection", "lighting",
  "sort", "composite" };
constexpr int kNumberOfStages = 7;
// The stages that run for every frame (background .. composite): a frame costs their sum.
constexpr int kFirstPerFrameStage = 2;

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

// What a mesh must share with the meshes it is drawn with in one pipeline: polygons only, the
// same type of points and the same point and cell arrays (name, type, components, attribute).
// "" for a mesh that is drawn alone.
std::string Layout(vtkPolyData* mesh)
{
  if (!mesh->GetPoints() || mesh->GetNumberOfPolys() == 0 ||
    mesh->GetNumberOfCells() != mesh->GetNumberOfPolys())
  {
    return "";
  }
  std::ostringstream s;
  s << mesh->GetPoints()->GetDataType();
  for (vtkDataSetAttributes* data : { static_cast<vtkDataSetAttributes*>(mesh->GetPointData()),
         static_cast<vtkDataSetAttributes*>(mesh->GetCellData()) })
  {
    s << "|";
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = data->GetAbstractArray(a);
      s << (array->GetName() ? array->GetName() : "") << ":" << array->GetDataType() << ":"
        << array->GetNumberOfComponents() << ":" << data->IsArrayAnAttribute(a) << ";";
    }
  }
  return s.str();
}

// Whether object b can be drawn in one pipeline with object a: neither is textured (a texture is
// named per mesh) nor moves, and both are tessellated alike. Materials may differ: they travel
// with the joined mesh.
bool Joinable(const catar::SceneObject& a, const catar::SceneObject& b)
{
  return a.texture.empty() && b.texture.empty() && a.keyframes.Empty() && b.keyframes.Empty() &&
    a.adaptiveTolerance == b.adaptiveTolerance;
}

// An object's placement: translation times rotation (its `rotate`, Rz Ry Rx, as BuildObject).
catar::Mat4 Placement(const catar::Vec3& position, const Eigen::Quaterniond& rotation)
{
  catar::Mat4 m = catar::Mat4::Identity();
  m.topLeftCorner<3, 3>() = rotation.toRotationMatrix();
  m.topRightCorner<3, 1>() = position;
  return m;
}

// Sets the camera's world-to-camera pose; a camera at that pose already is left untouched (not
// modified, so that its projections do not run again).
void SetPose(vtkCatadioptricCamera* camera, const catar::Mat4& pose)
{
  double current[16], rowMajor[16];
  camera->GetWorldToCameraElements(current);
  bool same = true;
  for (int i = 0; i < 16; ++i)
  {
    rowMajor[i] = pose(i / 4, i % 4);
    same = same && current[i] == rowMajor[i];
  }
  if (!same)
  {
    camera->SetWorldToCameraElements(rowMajor);
  }
}

catar::Mat4 Placement(const catar::SceneObject& o)
{
  return Placement(o.translate, catar::RotationFromDegrees(o.rotate));
}

bool SameMaterial(const catar::SceneObject& a, const catar::SceneObject& b)
{
  return a.ambient == b.ambient && a.diffuse == b.diffuse && a.specular == b.specular &&
    a.specularPower == b.specularPower && a.specularColor == b.specularColor;
}

// An object's material on top of the lighting filter's defaults.
void ApplyMaterial(const catar::SceneObject& o, vtkProperty* property)
{
  property->SetAmbient(o.ambient);
  property->SetDiffuse(o.diffuse);
  property->SetSpecular(o.specular);
  property->SetSpecularPower(o.specularPower);
  property->SetSpecularColor(o.specularColor.data());
}

// What rendering takes, for the memory checks made before the allocations (measured with
// `/usr/bin/time -f %M` on spheres of 0.26 and 1.04 million triangles, a 1 million triangle STL
// and a 4096 x 3232 image: about 270 bytes a triangle through preparation, projection, sort and
// drawing; 11 bytes a pixel, 27 with the triangle ids). The figures used are below those, so
// that only what cannot fit is refused; running out later is still reported by the stage.
constexpr double kBytesPerTriangle = 200.0;
constexpr double kBytesPerPixel = 8.0;
constexpr double kBytesPerPixelWithIds = 24.0;

// "objects[2] 'ball'", for messages.
std::string ObjectLabel(const catar::SceneObject& o, size_t i)
{
  return "objects[" + std::to_string(i) + "]" + (o.name.empty() ? "" : " '" + o.name + "'");
}

// About how many triangles an object has before remeshing (from its resolution, or its file).
double EstimatedTriangles(const catar::SceneObject& o)
{
  return o.type == "mesh" ? catar::EstimatedMeshTriangles(o.file)
                          : catar::ProceduralTriangles(o.type, o.resolution);
}

// Throws catar::OutOfMemory, naming the object, its size and the key that makes it smaller, when
// rendering it would need more memory than is left.
void RequireObjectMemory(const catar::SceneObject& o, size_t i)
{
  const double triangles = EstimatedTriangles(o);
  const std::string what = o.type == "mesh"
    ? "'" + o.file + "' (about " + std::to_string(static_cast<long long>(triangles)) + " triangles)"
    : "a " + o.type + " of resolution " + std::to_string(o.resolution) + " (about " +
      std::to_string(static_cast<long long>(triangles)) + " triangles)";
  try
  {
    catar::RequireMemory(triangles * kBytesPerTriangle, what);
  }
  catch (const catar::OutOfMemory& e)
  {
    throw catar::OutOfMemory(ObjectLabel(o, i) + ": " + e.what() +
      (o.type == "mesh" ? "; simplify the mesh" : "; lower its 'resolution'"));
  }
}

// False with the sizes in `error` when a width x height frame (and its triangle ids) needs more
// memory than is left.
bool RequireImageMemory(int width, int height, bool ids, std::string& error)
{
  const double pixels = static_cast<double>(width) * height;
  try
  {
    catar::RequireMemory(pixels * (ids ? kBytesPerPixelWithIds : kBytesPerPixel),
      "a " + std::to_string(width) + " x " + std::to_string(height) + " image" +
        (ids ? " with its triangle ids" : ""));
    return true;
  }
  catch (const catar::OutOfMemory& e)
  {
    error = std::string("output: ") + e.what() + "; ask for a smaller 'output' size";
    return false;
  }
}
} // namespace

struct vtkCatadioptricSceneRenderer::Internals
{
  catar::SceneDescription Scene;
  bool Loaded = false;
  std::string LoadedName;
  std::string Error;
  std::string MeshReports;
  // Every file the loaded scene reads (SceneDescription::InputFiles()).
  std::vector<std::string> InputFiles;
  double Times[kNumberOfStages] = { 0, 0, 0, 0, 0, 0, 0 };
  vtkIdType Triangles = 0;
  vtkNew<vtkCatadioptricCamera> Camera;
  vtkSmartPointer<vtkAlgorithm> Background; // environment source or the image read; may be null
  vtkNew<vtkLightCollection> Lights;
  std::vector<vtkSmartPointer<vtkCatadioptricProjection>> Projections;
  std::vector<vtkSmartPointer<vtkCatadioptricLighting>> Lightings;
  std::vector<vtkSmartPointer<vtkCatadioptricPainterSort>> Sorts;
  vtkNew<vtkCatadioptricCompositor> Compositor;
  // The exact reference renderer, used instead of the fast path (projection, lighting, sort,
  // compositor) when UseReference.
  vtkNew<vtkCatadioptricRayTracer> Tracer;
  bool UseReference = false;
  // The last error of a stage's filter, kept and passed on to the output window as VTK would
  // (an error that does not fail the stage is still seen): a failed stage's error is the
  // renderer's, in the stage's own words (the programs print the two identical lines once).
  std::string StageError;
  vtkNew<vtkCallbackCommand> StageErrors;
  void Observe(vtkObject* stage)
  {
    if (!stage->HasObserver(vtkCommand::ErrorEvent, this->StageErrors))
    {
      stage->AddObserver(vtkCommand::ErrorEvent, this->StageErrors);
    }
  }
  static void OnStageError(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    if (callData)
    {
      static_cast<Internals*>(clientData)->StageError =
        vtkCatadioptricErrorText::Short(static_cast<const char*>(callData));
      vtkOutputWindowDisplayErrorText(static_cast<const char*>(callData));
    }
  }
  // Progress of long work, passed on as the renderer's ProgressEvent.
  std::string ProgressText;
  vtkNew<vtkCallbackCommand> Progress;
  // Every object's mesh, for the shadows: one ray-query structure shared by the lighting filters.
  vtkNew<vtkCatadioptricOccluders> Occluders;

  // The sequence: its plan, the frame set up last, the background video and its current frame,
  // the keyframed objects (their transform from the built mesh, placed at the object's own
  // translate and rotate, to the frame's placement).
  catar::SceneFrames Frames;
  int CurrentFrame = -1;
  catar::FrameReader Video;
  vtkNew<vtkImageData> VideoImage;
  struct Moving
  {
    std::size_t object;
    vtkSmartPointer<vtkTransform> transform;
    catar::Mat4 baseInverse;
    catar::Mat4 current;
    vtkSmartPointer<vtkTransformPolyDataFilter> mover; // the object's mesh, moved
  };
  std::vector<Moving> MovingObjects;
  // Every object's mesh as built (world coordinates, at its own placement) and its name.
  std::vector<vtkSmartPointer<vtkPolyData>> ObjectMeshes;
  std::vector<std::string> ObjectNames;
  // Pose from markers: the board, the still background's pixels (top row first) for an image
  // background, and the last estimation.
  bool UseMarkers = false;
  catar::MarkerPoseTracker Tracker;
  catar::Frame StillFrame;
  std::string PoseReport; // GetPoseReport()'s text
  // Work of ApplyFrame that belongs to the next Render()'s frame: decoding the background's
  // frame (counted in the background stage) and estimating the pose from markers; and the pose
  // time of the last Render() (0 when it estimated none).
  double PendingDecodeTime = 0.0;
  double PendingPoseTime = 0.0;
  double FramePoseTime = 0.0;

  bool ApplyFrame(int k);
  void EstimatePose(const catar::Frame& frame, double time);
};

void vtkCatadioptricSceneRenderer::Internals::EstimatePose(const catar::Frame& frame, double time)
{
  // Only a reliable pose moves the camera; another keeps the previous frame's (the tracker's
  // report says which).
  const catar::FramePose& pose = this->Tracker.Track(
    this->Camera->GetModel(), frame.width, frame.height, frame.rgba.data(), time);
  if (pose.verdict == catar::PoseVerdict::Reliable)
  {
    SetPose(this->Camera, pose.result.worldToCamera);
  }
  this->PendingPoseTime += pose.seconds;
}

bool vtkCatadioptricSceneRenderer::Internals::ApplyFrame(int k)
{
  const double time = this->Frames.Time(k);
  // The camera (with markers, below, from the frame).
  if (!this->UseMarkers)
  {
    SetPose(this->Camera, this->Frames.Pose(k));
  }
  for (Moving& m : this->MovingObjects)
  {
    catar::Vec3 position;
    Eigen::Quaterniond rotation;
    this->Scene.objects[m.object].keyframes.At(time, position, rotation);
    const catar::Mat4 motion = Placement(position, rotation) * m.baseInverse;
    if (motion != m.current)
    {
      double rowMajor[16];
      for (int i = 0; i < 16; ++i)
      {
        rowMajor[i] = motion(i / 4, i % 4);
      }
      m.transform->SetMatrix(rowMajor);
      m.current = motion;
    }
  }
  // Lights (vtkLight's setters mark it modified only when the value changes).
  vtkCollectionSimpleIterator it;
  this->Lights->InitTraversal(it);
  for (const catar::SceneLight& l : this->Scene.lighting.lights)
  {
    vtkLight* light = this->Lights->GetNextLight(it);
    if (light && !l.keyframes.empty())
    {
      catar::Vec3 position, focal;
      l.At(time, position, focal);
      light->SetPosition(position.data());
      light->SetFocalPoint(focal.data());
    }
  }
  // The background's frame, in VTK's row order.
  const long long videoFrame = this->Frames.VideoFrame(k);
  if (videoFrame >= 0)
  {
    const auto start = Clock::now();
    catar::Frame frame;
    if (!this->Video.Read(videoFrame, frame, this->Error))
    {
      this->Error = "background: " + this->Error;
      return false;
    }
    vtkCatadioptricImageSupport::FromFrame(frame, this->VideoImage);
    this->PendingDecodeTime += Seconds(start, Clock::now());
    if (this->UseMarkers)
    {
      this->EstimatePose(frame, time);
    }
  }
  else if (this->UseMarkers && this->CurrentFrame < 0)
  {
    this->EstimatePose(this->StillFrame, time); // an image background: once
  }
  this->CurrentFrame = k;
  return true;
}

vtkCatadioptricSceneRenderer::vtkCatadioptricSceneRenderer()
  : Internal(new Internals)
{
  this->Internal->StageErrors->SetClientData(this->Internal.get());
  this->Internal->StageErrors->SetCallback(&Internals::OnStageError);
  // The remeshers' and the reference renderer's progress, passed on as the renderer's.
  this->Internal->Progress->SetClientData(this);
  this->Internal->Progress->SetCallback(
    [](vtkObject* caller, unsigned long, void* clientData, void*) {
      auto* self = static_cast<vtkCatadioptricSceneRenderer*>(clientData);
      auto* algorithm = vtkAlgorithm::SafeDownCast(caller);
      double fraction = algorithm ? algorithm->GetProgress() : 0.0;
      self->InvokeEvent(vtkCommand::ProgressEvent, &fraction);
      // A stop asked for (by an observer of the event just sent) reaches the running algorithm,
      // which honours its AbortExecute at its next step.
      if (self->GetAbortExecute() && algorithm)
      {
        algorithm->SetAbortExecute(1);
      }
    });
  this->Internal->Tracer->AddObserver(vtkCommand::ProgressEvent, this->Internal->Progress);
}

int vtkCatadioptricSceneRenderer::GetNumberOfInputFiles()
{
  return this->Internal->Loaded ? static_cast<int>(this->Internal->InputFiles.size()) : 0;
}

const char* vtkCatadioptricSceneRenderer::GetInputFile(int i)
{
  return i >= 0 && i < this->GetNumberOfInputFiles()
    ? this->Internal->InputFiles[static_cast<std::size_t>(i)].c_str()
    : nullptr;
}

const char* vtkCatadioptricSceneRenderer::GetProgressText()
{
  return this->Internal->ProgressText.c_str();
}

vtkCatadioptricSceneRenderer::~vtkCatadioptricSceneRenderer()
{
  this->SetSceneFileName(nullptr);
  this->SetMarkerBoardFileName(nullptr);
}

const char* vtkCatadioptricSceneRenderer::GetDemoSceneText()
{
  return catar::DemoSceneText();
}

bool vtkCatadioptricSceneRenderer::LoadScene()
{
  Internals& in = *this->Internal;
  in.Loaded = false;
  in.Error.clear();
  this->AbortExecute = false; // not SetAbortExecute: that marks the renderer modified
  in.ObjectMeshes.clear();
  in.ObjectNames.clear();
  std::fill(in.Times, in.Times + kNumberOfStages, 0.0);
  const std::string name = this->SceneFileName ? this->SceneFileName : "";
  auto t0 = Clock::now();
  catar::SceneDescription scene;
  if (name.empty())
  {
    scene = catar::DemoScene();
  }
  else
  {
    // A name not found as given is looked for on the data search path (CATAR_DATA_PATH, then the
    // installed data), as every front end does; not found, the error names where it looked.
    const std::string found = catar::FindDataFile("", name, &in.Error);
    if (!in.Error.empty() || !catar::LoadScene(found, scene, in.Error))
    {
      vtkErrorMacro(<< in.Error);
      return false;
    }
  }
  catar::CameraModel model = scene.camera;
  if (scene.width > 0 && scene.height > 0 &&
    (scene.width != model.intrinsics.width || scene.height != model.intrinsics.height))
  {
    model = model.Resized(scene.width, scene.height);
  }
  in.Camera->SetModel(model);
  // The sequence's frames; the camera at frame 0's pose before the meshes are prepared (the
  // pixel-tolerance remeshing looks through it).
  in.Scene = scene;
  in.CurrentFrame = -1;
  in.PendingDecodeTime = in.PendingPoseTime = in.FramePoseTime = 0.0;
  in.MovingObjects.clear();
  long long videoFrames = 0;
  double videoFps = 0.0;
  if (scene.background.type == "video")
  {
    if (!in.Video.Open(scene.background.video, in.Error))
    {
      in.Error = "background: " + in.Error;
      vtkErrorMacro(<< in.Error);
      return false;
    }
    videoFrames = in.Video.GetNumberOfFrames();
    videoFps = in.Video.GetFrameRate();
  }
  if (!in.Frames.Plan(in.Scene, videoFrames, videoFps, in.Error))
  {
    vtkErrorMacro(<< in.Error);
    return false;
  }
  if (videoFrames > 0 && !in.Video.GetNote().empty())
  {
    in.Frames.note += (in.Frames.note.empty() ? "" : "; ") + in.Video.GetNote();
  }
  // Pose from markers: the renderer's board file, else the scene's.
  const std::string boardFile = this->MarkerBoardFileName && *this->MarkerBoardFileName
    ? std::string(this->MarkerBoardFileName)
    : scene.markerBoardFile;
  in.UseMarkers = !boardFile.empty();
  in.Tracker = catar::MarkerPoseTracker();
  if (in.UseMarkers)
  {
    if (scene.background.type != "video" && scene.background.type != "image")
    {
      in.Error = "markers: the pose from markers needs a background of type video or image";
      vtkErrorMacro(<< in.Error);
      return false;
    }
    catar::MarkerBoard board;
    if (!catar::LoadMarkerBoard(boardFile, board, in.Error))
    {
      in.Error = "markers: " + in.Error;
      vtkErrorMacro(<< in.Error);
      return false;
    }
    in.Tracker = catar::MarkerPoseTracker(board);
    if (scene.background.type == "image")
    {
      catar::FrameReader still;
      if (!still.Open(scene.background.image, in.Error) || !still.Read(0, in.StillFrame, in.Error))
      {
        in.Error = "background: " + in.Error;
        vtkErrorMacro(<< in.Error);
        return false;
      }
    }
  }
  SetPose(in.Camera, in.Frames.Pose(0));
  auto t1 = Clock::now();
  in.Times[0] = Seconds(t0, t1);

  // Lights, shared by every object.
  in.Lights->RemoveAllItems();
  for (const catar::SceneLight& l : scene.lighting.lights)
  {
    vtkNew<vtkLight> light;
    light->SetPositional(l.type != "directional");
    light->SetPosition(l.position.data());
    light->SetFocalPoint(l.focalPoint.data());
    light->SetConeAngle(l.type == "spot" ? l.coneAngle : 90.0);
    light->SetExponent(l.exponent);
    light->SetIntensity(l.intensity);
    light->SetAmbientColor(l.ambient.data());
    light->SetDiffuseColor(l.color.data());
    light->SetSpecularColor(l.color.data());
    light->SetAttenuationValues(l.attenuation.data());
    in.Lights->AddItem(light);
  }
  const bool lit = scene.lighting.shading != "none";

  // Meshes: prepared once.
  in.Projections.clear();
  in.Lightings.clear();
  in.Sorts.clear();
  in.Compositor->RemoveAllInputConnections(1);
  in.Triangles = 0;
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  try
  {
    in.MeshReports.clear();
    for (size_t i = 0; i < scene.objects.size(); ++i)
    {
      catar::SceneObject o = scene.objects[i];
      RequireObjectMemory(o, i);
      // The renderer's remesh settings override the scene's.
      if (this->RemeshTargetArea > 0.0)
      {
        o.remesh.mode = "area";
        o.remesh.targetArea = this->RemeshTargetArea;
      }
      else if (this->RemeshPixelTolerance > 0.0)
      {
        o.remesh.mode = "pixels";
        o.remesh.pixelTolerance = this->RemeshPixelTolerance;
      }
      std::string report;
      in.ProgressText = "remeshing " + (o.name.empty() ? o.type : o.name);
      try
      {
        meshes.push_back(vtkCatadioptricSceneObjects::Remesh(
          vtkCatadioptricSceneObjects::BuildObject(o), o.remesh, in.Camera, report, in.Progress));
      }
      catch (const std::bad_alloc&)
      {
        throw catar::OutOfMemory(ObjectLabel(o, i) + ": " +
          catar::OutOfMemoryWhile("preparing its mesh of about " +
            std::to_string(static_cast<long long>(EstimatedTriangles(o))) + " triangles"));
      }
      if (!report.empty())
      {
        in.MeshReports += (o.name.empty() ? o.type : o.name) + ": " + report + "\n";
      }
      in.Triangles += meshes.back()->GetNumberOfPolys();
    }
  }
  catch (const std::exception& e)
  {
    in.Error = (name.empty() ? std::string("demo scene") : name) + ": " + e.what();
    vtkErrorMacro(<< in.Error);
    return false;
  }
  in.Compositor->RemoveAllTextureConnections();
  in.Tracer->RemoveAllTextureConnections();
  in.Tracer->RemoveAllInputConnections(1);
  // Scene key `renderer` (fast or reference), or the renderer's ReferenceSamples.
  in.UseReference = this->ReferenceSamples > 0 || scene.renderer == "reference";
  in.Tracer->SetSamples(
    this->ReferenceSamples > 0 ? this->ReferenceSamples : scene.referenceSamples);
  in.Tracer->SetCamera(in.Camera);
  // Scene key `visibility`: painter order (default) or a depth buffer on the path length.
  in.Compositor->SetVisibility(scene.visibility == "depth" ? vtkCatadioptricCompositor::DEPTH_BUFFER
                                                           : vtkCatadioptricCompositor::PAINTER);
  // Scene key `antialias`, or the renderer's Antialias.
  const int samples = this->Antialias > 0 ? this->Antialias : scene.antialiasSamples;
  in.Compositor->SetAntialias(samples > 1);
  in.Compositor->SetAntialiasSamples(std::max(2, samples));
  int textures = 0;
  for (size_t i = 0; i < meshes.size(); ++i)
  {
    const catar::SceneObject& o = scene.objects[i];
    vtkNew<vtkIntArray> index;
    index->SetName(vtkCatadioptricArrayNames::TextureIndex);
    meshes[i]->GetFieldData()->AddArray(index);
    if (o.texture.empty())
    {
      index->InsertNextValue(-1); // untextured, even when the mesh has texture coordinates
      continue;
    }
    try
    {
      vtkSmartPointer<vtkImageData> texture = vtkCatadioptricSceneObjects::Texture(o);
      in.Compositor->AddTextureData(texture);
      in.Tracer->AddTextureData(texture);
    }
    catch (const std::exception& e)
    {
      in.Error = (name.empty() ? std::string("demo scene") : name) + ": " + e.what();
      vtkErrorMacro(<< in.Error);
      return false;
    }
    index->InsertNextValue(textures++);
  }
  // Consecutive objects that look alike (untextured, the same material when lit, meshes of the
  // same layout) go down one pipeline as one mesh, their points and polygons one after another:
  // per-object filters cost more than a small object's triangles. The image is the same: every
  // stage works point by point and cell by cell, and the painter sort of the joined mesh keeps
  // equal depths in object order, as the compositor's merge of separate meshes does. Not with
  // the iterative solver: it starts each point's Newton at a neighbour's reflection point, so the
  // first points of a joined object would be the same only to rounding.
  const bool join = this->JoinObjects && scene.solver != catar::SolverType::Iterative;
  std::vector<vtkSmartPointer<vtkPolyData>> groups;
  std::vector<size_t> groupFirst; // the first object of each group (its material)
  for (size_t i = 0; i < meshes.size();)
  {
    const std::string layout = join ? Layout(meshes[i]) : std::string();
    size_t end = i + 1;
    bool oneMaterial = true;
    while (!layout.empty() && end < meshes.size() &&
      Joinable(scene.objects[i], scene.objects[end]) && Layout(meshes[end]) == layout)
    {
      oneMaterial = oneMaterial && SameMaterial(scene.objects[i], scene.objects[end]);
      ++end;
    }
    if (end == i + 1)
    {
      groups.push_back(meshes[i]);
    }
    else
    {
      std::vector<vtkPolyData*> parts;
      for (size_t j = i; j < end; ++j)
      {
        parts.push_back(meshes[j]);
      }
      vtkNew<vtkAppendPolyData> append;
      auto joined = vtkSmartPointer<vtkPolyData>::New();
      append->ExecuteAppend(joined, parts.data(), static_cast<int>(parts.size()));
      vtkNew<vtkIntArray> index;
      index->SetName(vtkCatadioptricArrayNames::TextureIndex);
      index->InsertNextValue(-1);
      joined->GetFieldData()->AddArray(index);
      if (lit && !oneMaterial)
      {
        // Each object's material, and each point's object.
        std::vector<vtkSmartPointer<vtkProperty>> properties;
        std::vector<vtkProperty*> table;
        vtkNew<vtkIntArray> materialIndex;
        materialIndex->SetName(vtkCatadioptricArrayNames::MaterialIndex);
        vtkCatadioptricAllocation::Tuples(materialIndex, joined->GetNumberOfPoints());
        vtkIdType point = 0;
        vtkNew<vtkCatadioptricLighting> defaults;
        for (size_t j = i; j < end; ++j)
        {
          properties.push_back(vtkSmartPointer<vtkProperty>::New());
          properties.back()->DeepCopy(defaults->GetProperty());
          ApplyMaterial(scene.objects[j], properties.back());
          table.push_back(properties.back());
          for (vtkIdType k = 0; k < meshes[j]->GetNumberOfPoints(); ++k)
          {
            materialIndex->SetValue(point++, static_cast<int>(j - i));
          }
        }
        vtkCatadioptricLightingSupport::WriteMaterials(joined, table);
        joined->GetPointData()->AddArray(materialIndex);
      }
      groups.push_back(joined);
    }
    groupFirst.push_back(i);
    i = end;
  }
  // Keyframed objects (each its own group): moved by a transform in front of the projection.
  std::vector<vtkSmartPointer<vtkTransformPolyDataFilter>> movers(groups.size());
  for (size_t g = 0; g < groups.size(); ++g)
  {
    const catar::SceneObject& o = scene.objects[groupFirst[g]];
    if (o.keyframes.Empty())
    {
      continue;
    }
    Internals::Moving m;
    m.object = groupFirst[g];
    m.transform = vtkSmartPointer<vtkTransform>::New();
    m.baseInverse = Placement(o).inverse();
    m.current = catar::Mat4::Identity();
    movers[g] = vtkSmartPointer<vtkTransformPolyDataFilter>::New();
    movers[g]->SetTransform(m.transform);
    movers[g]->SetInputData(groups[g]);
    m.mover = movers[g];
    in.MovingObjects.push_back(m);
  }
  const bool shadows = lit && scene.lighting.shadows;
  in.Occluders->RemoveAllMeshes();
  for (size_t g = 0; g < groups.size() && shadows; ++g)
  {
    if (movers[g])
    {
      movers[g]->Update(); // its output is the mesh that casts the shadows, moved every frame
      in.Occluders->AddMesh(movers[g]->GetOutput());
    }
    else
    {
      in.Occluders->AddMesh(groups[g]);
    }
  }
  for (size_t g = 0; g < groups.size(); ++g)
  {
    const catar::SceneObject& o = scene.objects[groupFirst[g]];
    auto proj = vtkSmartPointer<vtkCatadioptricProjection>::New();
    if (movers[g])
    {
      proj->SetInputConnection(movers[g]->GetOutputPort());
    }
    else
    {
      proj->SetInputData(groups[g]);
    }
    proj->SetCamera(in.Camera);
    proj->SetBackFaceCulling(scene.cullBackFaces);
    proj->SetBoundaryTolerance(scene.boundaryTolerance);
    // The renderer's AdaptiveTolerance, else the group's objects' own, else the scene's.
    const double own = scene.objects[groupFirst[g]].adaptiveTolerance;
    proj->SetAdaptiveTolerance(this->AdaptiveTolerance > 0.0 ? this->AdaptiveTolerance
        : own >= 0.0                                         ? own
                                                             : scene.adaptiveTolerance);
    proj->SetSolver(static_cast<int>(scene.solver)); // the same numbers (vtkCatadioptricProjection)
    vtkAlgorithmOutput* last = proj->GetOutputPort();
    if (lit)
    {
      auto lighting = vtkSmartPointer<vtkCatadioptricLighting>::New();
      lighting->SetInputConnection(last);
      lighting->SetLights(in.Lights);
      lighting->SetShadingMode(scene.lighting.shading == "flat" ? vtkCatadioptricLighting::FLAT
                                                                : vtkCatadioptricLighting::GOURAUD);
      lighting->SetShadows(shadows);
      lighting->SetGlobalAmbient(scene.lighting.globalAmbient.data());
      ApplyMaterial(o, lighting->GetProperty());
      // Every object casts shadows, on itself and on the others: one structure for all.
      if (shadows)
      {
        lighting->SetOccluders(in.Occluders);
      }
      in.Lightings.push_back(lighting);
      in.Observe(lighting);
      last = lighting->GetOutputPort();
    }
    auto sort = vtkSmartPointer<vtkCatadioptricPainterSort>::New();
    sort->SetInputConnection(last);
    sort->DropInvisibleCellsOn();
    in.Compositor->AddMeshConnection(sort->GetOutputPort());
    in.Projections.push_back(proj);
    in.Sorts.push_back(sort);
    in.Observe(proj);
    in.Observe(sort);
    // The reference renderer: the same meshes in world coordinates, lit as the fast path.
    if (movers[g])
    {
      in.Tracer->AddMeshConnection(movers[g]->GetOutputPort());
    }
    else
    {
      in.Tracer->AddMeshData(groups[g]);
    }
    if (lit)
    {
      in.Tracer->SetMeshLighting(static_cast<int>(g), in.Lightings.back());
    }
  }
  in.ObjectMeshes = meshes;
  for (const catar::SceneObject& o : scene.objects)
  {
    in.ObjectNames.push_back(!o.name.empty() ? o.name
        : !o.file.empty()                    ? vtksys::SystemTools::GetFilenameName(o.file)
                                             : o.type);
  }
  auto t2 = Clock::now();
  in.Times[1] = Seconds(t1, t2);

  // Background.
  in.Background = nullptr;
  in.Compositor->SetFrameConnection(nullptr);
  in.Compositor->SetImageSize(0, 0);
  const catar::SceneBackground& bg = scene.background;
  if (bg.type == "environment" || bg.type == "panorama")
  {
    auto env = vtkSmartPointer<vtkCatadioptricEnvironmentSource>::New();
    env->SetCamera(in.Camera);
    env->SetSamples(bg.samples);
    if (bg.type == "panorama")
    {
      if (!bg.panorama.empty() && !vtksys::SystemTools::FileExists(bg.panorama, true))
      {
        in.Error = "background: 'file' cannot be read: " + bg.panorama;
        vtkErrorMacro(<< in.Error);
        return false;
      }
      env->SetModeToPanorama();
      env->SetPanoramaFileName(bg.panorama.empty() ? nullptr : bg.panorama.c_str());
      env->SetPanoramaRotation(bg.rotation);
      env->SetBackdropColor(bg.backdrop.x(), bg.backdrop.y(), bg.backdrop.z());
    }
    // A synthesised background that a transparent output throws away is not made at all (it was
    // most of the frame's time).
    in.Background = this->TransparentBackground ? nullptr : env;
  }
  else if (bg.type == "image")
  {
    std::string readError;
    vtkSmartPointer<vtkImageData> image =
      vtkCatadioptricImageSupport::ReadImageFile(bg.image, readError);
    if (!image)
    {
      in.Error = "background: 'image': " + readError;
      vtkErrorMacro(<< in.Error);
      return false;
    }
    auto producer = vtkSmartPointer<vtkTrivialProducer>::New();
    producer->SetOutput(image);
    in.Background = producer;
  }
  else if (bg.type == "video")
  {
    auto producer = vtkSmartPointer<vtkTrivialProducer>::New();
    producer->SetOutput(in.VideoImage);
    in.Background = producer;
  }
  else
  {
    in.Compositor->SetBackgroundColor(bg.color.x(), bg.color.y(), bg.color.z(), 1.0);
    in.Compositor->SetImageSize(model.intrinsics.width, model.intrinsics.height);
  }
  in.Tracer->SetFrameConnection(nullptr);
  in.Tracer->SetImageSize(model.intrinsics.width, model.intrinsics.height);
  in.Tracer->SetBackgroundColor(in.Compositor->GetBackgroundColor());
  if (in.Background && !this->TransparentBackground)
  {
    in.Compositor->SetFrameConnection(in.Background->GetOutputPort());
    in.Tracer->SetFrameConnection(in.Background->GetOutputPort());
  }
  if (this->TransparentBackground)
  {
    // The objects alone, over alpha 0 (a video or image background is still read: it sets the
    // sequence and the poses from markers).
    in.Compositor->SetBackgroundColor(0.0, 0.0, 0.0, 0.0);
    in.Compositor->SetImageSize(model.intrinsics.width, model.intrinsics.height);
    in.Tracer->SetBackgroundColor(0.0, 0.0, 0.0, 0.0);
  }
  if (!RequireImageMemory(
        model.intrinsics.width, model.intrinsics.height, this->OutputVisibleTriangle, in.Error))
  {
    vtkErrorMacro(<< in.Error);
    return false;
  }
  in.Compositor->SetOutputVisibleTriangle(this->OutputVisibleTriangle);
  in.Tracer->SetOutputVisibleTriangle(this->OutputVisibleTriangle);
  in.Compositor->SetOutputPathLength(this->OutputPathLength);
  in.Tracer->SetOutputPathLength(this->OutputPathLength);
  if (!in.ApplyFrame(0))
  {
    vtkErrorMacro(<< in.Error);
    return false;
  }
  in.LoadedName = name;
  in.InputFiles = scene.InputFiles();
  in.Loaded = true;
  return true;
}

vtkCatadioptricProjection* vtkCatadioptricSceneRenderer::GetProjection(int pipeline)
{
  const auto& p = this->Internal->Projections;
  return pipeline >= 0 && pipeline < static_cast<int>(p.size()) ? p[pipeline].Get() : nullptr;
}

vtkCatadioptricCompositor* vtkCatadioptricSceneRenderer::GetCompositor()
{
  return this->Internal->Compositor;
}

vtkCatadioptricLighting* vtkCatadioptricSceneRenderer::GetLighting(int pipeline)
{
  const auto& l = this->Internal->Lightings;
  return pipeline >= 0 && pipeline < static_cast<int>(l.size()) ? l[pipeline].Get() : nullptr;
}

double vtkCatadioptricSceneRenderer::GetPoseTime()
{
  return this->Internal->Tracker.Last().seconds;
}

const char* vtkCatadioptricSceneRenderer::GetPoseReport()
{
  Internals& in = *this->Internal;
  in.PoseReport = in.UseMarkers && in.Tracker.Frames() > 0 ? in.Tracker.Report() : std::string();
  return in.PoseReport.c_str();
}

int vtkCatadioptricSceneRenderer::GetNumberOfPoseFailures()
{
  return this->Internal->Tracker.Failures();
}

bool vtkCatadioptricSceneRenderer::GetUsesMarkers()
{
  return this->Internal->Loaded && this->Internal->UseMarkers;
}

bool vtkCatadioptricSceneRenderer::GetFramePoseFound()
{
  return this->Internal->UseMarkers &&
    this->Internal->Tracker.Last().verdict == catar::PoseVerdict::Reliable &&
    this->Internal->Tracker.Frames() > 0;
}

bool vtkCatadioptricSceneRenderer::GetAnyPoseFound()
{
  return this->Internal->UseMarkers && this->Internal->Tracker.AnyReliable();
}

const char* vtkCatadioptricSceneRenderer::GetFramePoseVerdict()
{
  const Internals& in = *this->Internal;
  return in.UseMarkers && in.Tracker.Frames() > 0
    ? catar::PoseVerdictName(in.Tracker.Last().verdict)
    : "";
}

const char* vtkCatadioptricSceneRenderer::GetFramePoseNote()
{
  return this->Internal->Tracker.Last().note.c_str();
}

double vtkCatadioptricSceneRenderer::GetFramePosePositionSigma()
{
  const catar::PoseResult& r = this->Internal->Tracker.Last().result;
  return r.ok ? r.uncertainty.positionSigma : std::numeric_limits<double>::quiet_NaN();
}

double vtkCatadioptricSceneRenderer::GetFramePoseAngleSigma()
{
  const catar::PoseResult& r = this->Internal->Tracker.Last().result;
  return r.ok ? r.uncertainty.angleSigmaDegrees : std::numeric_limits<double>::quiet_NaN();
}

int vtkCatadioptricSceneRenderer::GetFramePoseMarkers()
{
  return this->Internal->Tracker.Last().markersFound;
}

int vtkCatadioptricSceneRenderer::GetFramePoseInliers()
{
  return this->Internal->Tracker.Last().result.inlierCount;
}

int vtkCatadioptricSceneRenderer::GetFramePoseCorners()
{
  return static_cast<int>(this->Internal->Tracker.Last().result.inliers.size());
}

double vtkCatadioptricSceneRenderer::GetFramePoseRMS()
{
  const catar::PoseResult& r = this->Internal->Tracker.Last().result;
  return r.ok ? r.rmsPixels : std::numeric_limits<double>::quiet_NaN();
}

const catar::FramePose& vtkCatadioptricSceneRenderer::GetFramePose()
{
  return this->Internal->Tracker.Last();
}

bool vtkCatadioptricSceneRenderer::GetFramePoseEstimate(double worldToCamera[16])
{
  const catar::PoseResult& r = this->Internal->Tracker.Last().result;
  if (!this->Internal->UseMarkers || !r.ok)
  {
    return false;
  }
  for (int i = 0; i < 16; ++i)
  {
    worldToCamera[i] = r.worldToCamera(i / 4, i % 4);
  }
  return true;
}

int vtkCatadioptricSceneRenderer::GetNumberOfFrames()
{
  return this->Internal->Loaded ? static_cast<int>(this->Internal->Frames.count) : 0;
}

double vtkCatadioptricSceneRenderer::GetFrameTime(int frame)
{
  return this->Internal->Loaded ? this->Internal->Frames.Time(frame) : 0.0;
}

double vtkCatadioptricSceneRenderer::GetFrameRate()
{
  return this->Internal->Frames.fps;
}

const char* vtkCatadioptricSceneRenderer::GetSequenceNote()
{
  return this->Internal->Frames.note.c_str();
}

bool vtkCatadioptricSceneRenderer::RenderFrame(int frame)
{
  Internals& in = *this->Internal;
  const std::string name = this->SceneFileName ? this->SceneFileName : "";
  if ((!in.Loaded || in.LoadedName != name) && !this->LoadScene())
  {
    return false;
  }
  if (frame < 0 || frame >= in.Frames.count)
  {
    in.Error = "frame " + std::to_string(frame) + " is not in the sequence (it has " +
      std::to_string(in.Frames.count) + " frames, 0 to " + std::to_string(in.Frames.count - 1) +
      ")";
    vtkErrorMacro(<< in.Error);
    return false;
  }
  if (frame != in.CurrentFrame && !in.ApplyFrame(frame))
  {
    vtkErrorMacro(<< in.Error);
    return false;
  }
  return this->Render();
}

int vtkCatadioptricSceneRenderer::GetNumberOfPipelines()
{
  return static_cast<int>(this->Internal->Projections.size());
}

bool vtkCatadioptricSceneRenderer::Render()
{
  Internals& in = *this->Internal;
  const std::string name = this->SceneFileName ? this->SceneFileName : "";
  if (!in.Loaded || in.LoadedName != name)
  {
    if (!this->LoadScene())
    {
      return false;
    }
  }
  in.StageError.clear();
  in.Observe(in.Compositor);
  in.Observe(in.Tracer);
  auto fail = [&](const char* stage) {
    in.Error = in.StageError.empty() ? std::string(stage) + " failed" : in.StageError;
    vtkErrorMacro(<< in.Error);
    return false;
  };
  // What ApplyFrame did for this frame: the background's decoding and the pose estimation.
  const double decode = in.PendingDecodeTime;
  in.FramePoseTime = in.PendingPoseTime;
  in.PendingDecodeTime = in.PendingPoseTime = 0.0;
  auto t0 = Clock::now();
  if (in.Background)
  {
    in.Observe(in.Background);
    // The executive's answer: a source whose RequestData failed (an unreadable panorama) stops
    // here, not at the size check below.
    if (!in.Background->GetExecutive()->Update() || in.Background->GetErrorCode() != 0)
    {
      return fail("background");
    }
    vtkImageData* frame = vtkImageData::SafeDownCast(in.Background->GetOutputDataObject(0));
    int dims[3] = { 0, 0, 0 };
    if (frame)
    {
      frame->GetDimensions(dims);
    }
    if (dims[0] != in.Camera->GetImageWidth() || dims[1] != in.Camera->GetImageHeight())
    {
      in.Error = "the background image is " + std::to_string(dims[0]) + "x" +
        std::to_string(dims[1]) + " but the camera image is " +
        std::to_string(in.Camera->GetImageWidth()) + "x" +
        std::to_string(in.Camera->GetImageHeight());
      vtkErrorMacro(<< in.Error);
      return false;
    }
  }
  auto t1 = Clock::now();
  if (in.UseReference)
  {
    // Every frame anew (lights and objects may move without touching the tracer).
    in.Tracer->Modified();
    in.ProgressText = "reference render";
    if (!in.Tracer->GetExecutive()->Update())
    {
      return fail("reference renderer");
    }
    auto tr = Clock::now();
    in.Times[2] = decode + Seconds(t0, t1);
    in.Times[3] = in.Times[4] = in.Times[5] = 0.0;
    in.Times[6] = Seconds(t1, tr); // reported as the composite stage
    in.Error.clear();
    return true;
  }
  for (auto& p : in.Projections)
  {
    if (!p->GetExecutive()->Update())
    {
      return fail("projection");
    }
  }
  auto t2 = Clock::now();
  for (auto& l : in.Lightings)
  {
    if (!l->GetExecutive()->Update())
    {
      return fail("lighting");
    }
  }
  auto t3 = Clock::now();
  for (auto& s : in.Sorts)
  {
    if (!s->GetExecutive()->Update())
    {
      return fail("sort");
    }
  }
  auto t4 = Clock::now();
  if (!in.Compositor->GetExecutive()->Update())
  {
    return fail("composite");
  }
  auto t5 = Clock::now();
  in.Times[2] = decode + Seconds(t0, t1);
  in.Times[3] = Seconds(t1, t2);
  in.Times[4] = Seconds(t2, t3);
  in.Times[5] = Seconds(t3, t4);
  in.Times[6] = Seconds(t4, t5);
  in.Error.clear();
  return true;
}

vtkImageData* vtkCatadioptricSceneRenderer::GetOutput()
{
  return this->Internal->UseReference ? this->Internal->Tracer->GetOutput()
                                      : this->Internal->Compositor->GetOutput();
}

bool vtkCatadioptricSceneRenderer::WriteImage(const char* fileName)
{
  vtkImageData* image = this->GetOutput();
  if (!image || image->GetNumberOfPoints() == 0)
  {
    this->Internal->Error = "nothing rendered yet";
    vtkErrorMacro(<< this->Internal->Error);
    return false;
  }
  std::string error;
  if (!catar::WriteImageFile(
        fileName ? fileName : "", vtkCatadioptricImageSupport::ToFrame(image), error))
  {
    this->Internal->Error = error;
    vtkErrorMacro(<< error);
    return false;
  }
  this->Internal->Error.clear();
  return true;
}

bool vtkCatadioptricSceneRenderer::WritePNG(const char* fileName)
{
  vtkImageData* image = this->GetOutput();
  if (!image || image->GetNumberOfPoints() == 0)
  {
    this->Internal->Error = "nothing rendered yet";
    vtkErrorMacro(<< this->Internal->Error);
    return false;
  }
  if (!fileName || !*fileName)
  {
    this->Internal->Error = "no output file name given";
    vtkErrorMacro(<< this->Internal->Error);
    return false;
  }
  // Encoded in memory, then written with every error checked (vtkPNGWriter reports no full
  // disk).
  vtkNew<vtkPNGWriter> writer;
  writer->WriteToMemoryOn();
  writer->SetInputData(image);
  writer->Write();
  vtkUnsignedCharArray* png = writer->GetResult();
  std::string error;
  if (writer->GetErrorCode() != 0 || !png || png->GetNumberOfValues() == 0)
  {
    error = std::string(fileName) + ": the image could not be encoded as PNG";
  }
  else if (catar::WriteWholeFile(fileName,
             std::string(reinterpret_cast<const char*>(png->GetPointer(0)),
               static_cast<size_t>(png->GetNumberOfValues())),
             error))
  {
    return true;
  }
  this->Internal->Error = error;
  vtkErrorMacro(<< this->Internal->Error);
  return false;
}

vtkCatadioptricCamera* vtkCatadioptricSceneRenderer::GetCamera()
{
  return this->Internal->Camera;
}

int vtkCatadioptricSceneRenderer::GetNumberOfStages()
{
  return kNumberOfStages;
}

int vtkCatadioptricSceneRenderer::GetFirstPerFrameStage()
{
  return kFirstPerFrameStage;
}

double vtkCatadioptricSceneRenderer::GetFrameTime()
{
  double t = this->Internal->FramePoseTime;
  for (int s = kFirstPerFrameStage; s < kNumberOfStages; ++s)
  {
    t += this->Internal->Times[s];
  }
  return t;
}

double vtkCatadioptricSceneRenderer::GetFramePoseTime()
{
  return this->Internal->FramePoseTime;
}

vtkLightCollection* vtkCatadioptricSceneRenderer::GetLights()
{
  return this->Internal->Lights;
}

const char* vtkCatadioptricSceneRenderer::GetStageName(int stage)
{
  return (stage >= 0 && stage < kNumberOfStages) ? kStageNames[stage] : "";
}

double vtkCatadioptricSceneRenderer::GetStageTime(int stage)
{
  return (stage >= 0 && stage < kNumberOfStages) ? this->Internal->Times[stage] : 0.0;
}

vtkIdType vtkCatadioptricSceneRenderer::GetNumberOfTriangles()
{
  return this->Internal->Triangles;
}

int vtkCatadioptricSceneRenderer::GetNumberOfObjects()
{
  return static_cast<int>(this->Internal->ObjectMeshes.size());
}

const char* vtkCatadioptricSceneRenderer::GetObjectName(int object)
{
  const auto& names = this->Internal->ObjectNames;
  return object >= 0 && object < static_cast<int>(names.size()) ? names[object].c_str() : "";
}

vtkPolyData* vtkCatadioptricSceneRenderer::GetObjectMesh(int object)
{
  Internals& in = *this->Internal;
  if (object < 0 || object >= static_cast<int>(in.ObjectMeshes.size()))
  {
    return nullptr;
  }
  for (Internals::Moving& m : in.MovingObjects)
  {
    if (m.object == static_cast<std::size_t>(object))
    {
      m.mover->Update(); // placed for the current frame (ApplyFrame set its transform)
      return m.mover->GetOutput();
    }
  }
  return in.ObjectMeshes[object];
}

const char* vtkCatadioptricSceneRenderer::GetMeshReport()
{
  return this->Internal->MeshReports.c_str();
}

const char* vtkCatadioptricSceneRenderer::GetLastError()
{
  return this->Internal->Error.c_str();
}

void vtkCatadioptricSceneRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SceneFileName: " << (this->SceneFileName ? this->SceneFileName : "(demo)")
     << "\n";
  os << indent << "Triangles: " << this->Internal->Triangles << "\n";
  os << indent << "RemeshTargetArea: " << this->RemeshTargetArea << "\n";
  os << indent << "RemeshPixelTolerance: " << this->RemeshPixelTolerance << "\n";
  os << indent << "JoinObjects: " << (this->JoinObjects ? "On" : "Off") << "\n";
}
