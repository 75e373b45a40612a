/**
 * @class   vtkCatadioptricSceneReader
 * @brief   opens a scene file as what it describes: the rendered frame and the objects
 *
 * A source with no inputs for a scene file (YAML or JSON, Documentation/file-formats.md), drawn
 * by a vtkCatadioptricSceneRenderer. Two outputs:
 *
 * - port 0, the frame: an RGBA unsigned char image of the camera's size, the same pixels as
 *   vtkCatadioptricSceneRenderer (and the `catadioptric-render` program) give for the scene;
 * - port 1, the objects: a vtkMultiBlockDataSet with one vtkPolyData block per object of the
 *   scene, in its order, named after the object (its `name`, else its mesh file, else its type):
 *   the triangles drawn, in world coordinates, with the "Colors" cell array (RGBA), so that they
 *   can be shown in 3D beside the camera and mirror.
 *
 * A scene with a sequence (a trajectory, a video background, keyframes, or the `sequence` key)
 * announces its frames' times as time steps; a request for time t gives the last frame whose
 * time is not after t (the first frame before the first time), the camera, objects and lights
 * moved there. A still scene announces no time.
 *
 * The scene is read, and its meshes prepared, when the information is first asked for after
 * FileName or a property changes; a frame is drawn per request. A bad scene (unreadable, an
 * unknown key, a mesh that cannot be read) is an error with the scene parser's message, and the
 * outputs are empty. Long work (remeshing, the reference renderer) reports progress.
 */
#ifndef vtkCatadioptricSceneReader_h
#define vtkCatadioptricSceneReader_h

#include "CatadioptricARSceneModule.h" // for export macro
#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"           // for vtkNew member
#include "vtkCatadioptricSceneRenderer.h" // for vtkNew member
#include "vtkNew.h"                       // for vtkNew

#include <string> // for std::string

class vtkImageData;
class vtkMultiBlockDataSet;

class CATADIOPTRICARSCENE_EXPORT vtkCatadioptricSceneReader : public vtkAlgorithm
{
public:
  static vtkCatadioptricSceneReader* New();
  vtkTypeMacro(vtkCatadioptricSceneReader, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The scene file (YAML or JSON). A name not found as given is looked for on the data search
  /// path (CATAR_DATA_PATH, then the installed data), as `catadioptric-render` does.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// 1 when fileName looks like a scene file: YAML or JSON whose top level is a map with the key
  /// `camera` or `objects` (a calibration file has neither); 0 otherwise. A scene with a mistake
  /// in it is claimed, so that opening it says what the mistake is.
  int CanReadFile(const char* fileName);

  ///@{
  /// Remeshing of every object over the scene's `remesh` (as `catadioptric-render --target-area`
  /// and `--pixel-tolerance`): a target triangle area, or when that is 0 a pixel tolerance (the
  /// largest edge bend, pixels). 0 (default) keeps the scene's.
  vtkSetClampMacro(RemeshTargetArea, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RemeshTargetArea, double);
  vtkSetClampMacro(RemeshPixelTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RemeshPixelTolerance, double);
  ///@}

  ///@{
  /// ReferenceSamples: 0 (default) renders as the scene's key `renderer` says (fast or
  /// reference); 1 to 8 renders with the exact reference ray tracer, with this many rays per
  /// pixel side (as `catadioptric-render --reference --samples N`).
  vtkSetClampMacro(ReferenceSamples, int, 0, 8);
  vtkGetMacro(ReferenceSamples, int);
  ///@}

  ///@{
  /// TransparentBackground (default off): the objects alone over alpha 0 (as `--alpha`).
  vtkSetMacro(TransparentBackground, bool);
  vtkGetMacro(TransparentBackground, bool);
  vtkBooleanMacro(TransparentBackground, bool);
  ///@}

  /// The renderer that draws the frames (its stage times, its compositor). Its properties are set
  /// from the reader's at each reading of the scene.
  vtkCatadioptricSceneRenderer* GetRenderer();

  /// The frame of the sequence drawn by the last request (0 for a still scene).
  vtkGetMacro(CurrentFrame, int);

  ///@{
  /// The outputs: the frame (port 0) and the objects (port 1).
  vtkImageData* GetImageOutput();
  vtkMultiBlockDataSet* GetObjectsOutput();
  ///@}

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inInfo, vtkInformationVector* outInfo) override;

protected:
  vtkCatadioptricSceneReader();
  ~vtkCatadioptricSceneReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*);

  char* FileName = nullptr;
  double RemeshTargetArea = 0.0;
  double RemeshPixelTolerance = 0.0;
  int ReferenceSamples = 0;
  bool TransparentBackground = false;
  int CurrentFrame = 0;

private:
  vtkCatadioptricSceneReader(const vtkCatadioptricSceneReader&) = delete;
  void operator=(const vtkCatadioptricSceneReader&) = delete;

  /// Reads the scene when the reader changed since the last reading (a bad scene is reported
  /// then, once); false when the scene could not be read.
  bool Load();
  static void OnRendererEvent(vtkObject*, unsigned long, void*, void*);

  vtkNew<vtkCatadioptricSceneRenderer> Renderer;
  vtkNew<vtkCallbackCommand> Observer;
  vtkTimeStamp LoadTime;
  bool Loaded = false;
  std::string LoadError;
};

#endif
