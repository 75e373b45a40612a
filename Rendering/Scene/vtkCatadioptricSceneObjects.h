/**
 * @class   vtkCatadioptricSceneObjects
 * @brief   builds the objects of a scene description: meshes, colours, textures, remeshing
 *
 * Used by vtkCatadioptricSceneRenderer. Static functions only; they throw std::runtime_error
 * with a clear message on bad input (unreadable files, failed remeshing). C++ only (not wrapped).
 */
#ifndef vtkCatadioptricSceneObjects_h
#define vtkCatadioptricSceneObjects_h

#include "CatadioptricARSceneModule.h" // for export macro
#include "vtkSmartPointer.h"           // for return values

#include <string> // for std::string

class vtkCatadioptricCamera;
class vtkCommand;
class vtkImageData;
class vtkPolyData;
namespace catar
{
struct SceneObject;
struct SceneRemesh;
}

class CATADIOPTRICARSCENE_EXPORT vtkCatadioptricSceneObjects
{
public:
  /// The object's triangle mesh in world coordinates: read from its file (any of .ply .obj .stl
  /// .vtp .vtk) or made procedurally, coloured (colour, face colours, checker pattern), with
  /// texture coordinates when it is textured (per face for boxes, a spherical map for meshes
  /// without their own).
  static vtkSmartPointer<vtkPolyData> BuildObject(const catar::SceneObject& object);

  /// Prepares `mesh` as `remesh` says (vtkCatadioptricRemesher; `camera` for the pixel
  /// tolerance). Returns the mesh unchanged for mode "none". `report` receives one line on what
  /// was done (triangle counts, steps, and the achieved edge bend in pixel mode). `progress`, if
  /// given, observes the remesher's ProgressEvent.
  static vtkSmartPointer<vtkPolyData> Remesh(vtkPolyData* mesh, const catar::SceneRemesh& remesh,
    vtkCatadioptricCamera* camera, std::string& report, vtkCommand* progress = nullptr);

  /// A texture image: "checker" (a generated 256 x 256 RGB checkerboard) or an 8-bit image file.
  static vtkSmartPointer<vtkImageData> ReadTexture(const std::string& file);
  /// An object's texture: its marker pattern (type "marker") or ReadTexture(object.texture).
  static vtkSmartPointer<vtkImageData> Texture(const catar::SceneObject& object);
};

#endif
