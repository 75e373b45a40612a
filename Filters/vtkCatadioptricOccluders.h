/**
 * @class   vtkCatadioptricOccluders
 * @brief   the meshes that cast shadows, in one ray-query structure shared by lighting filters
 *
 * Holds a set of meshes (vtkPolyData, world coordinates: their polygons, fan-triangulated) and one
 * Embree ray scene (catar::RayScene) built from all of them. Give the same object to the
 * vtkCatadioptricLighting of every object of a scene (vtkCatadioptricLighting::SetOccluders)
 * instead of connecting every other object to each filter's occluder port: N objects then build
 * one structure of N meshes, not N structures of N meshes each. It should hold every object,
 * the lit one included (an object shadows itself too).
 *
 * Update() builds the structure when it is out of date: when meshes were added or removed, or
 * when a mesh's points (the vtkPoints object, or its MTime) or polygons (MTime) changed since the
 * last build. The meshes, their points and polygons, and the arrays behind those are observed:
 * while none of them is modified, Update() returns at once, without a pass over the meshes (N
 * filters sharing N meshes cost N checks a frame, not N x N); after a modification it compares
 * the times and rebuilds only when the geometry changed. Add the meshes as they are before
 * projection (the projection's output shares their points and polygons, so that a moving camera
 * does not rebuild anything). Update() may be called from several threads: one builds, the
 * others wait and find it built; the structure is then queried concurrently (ray queries are
 * thread-safe). Meshes must not change while a filter is tracing rays.
 *
 * The modification time changes whenever a mesh, its points or polygons are modified, so that a
 * lighting filter given this object runs again when any occluder moves.
 */
#ifndef vtkCatadioptricOccluders_h
#define vtkCatadioptricOccluders_h

#include "CatadioptricARFiltersModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr

#ifndef __VTK_WRAP__
namespace catar
{
class RayScene;
}
#endif
class vtkPolyData;

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricOccluders : public vtkObject
{
public:
  static vtkCatadioptricOccluders* New();
  vtkTypeMacro(vtkCatadioptricOccluders, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The meshes that cast shadows (world coordinates). AddMesh ignores null; GetMesh returns null
  /// out of range.
  void AddMesh(vtkPolyData* mesh);
  void RemoveAllMeshes();
  int GetNumberOfMeshes();
  vtkPolyData* GetMesh(int index);
  ///@}

  /// Builds the ray-query structure when it is out of date (see above). Returns false, with a
  /// VTK error, when it cannot be built (e.g. coordinates that are NaN); the structure is then
  /// empty.
  bool Update();

  ///@{
  /// The structure of the last Update(): its triangles, and how many times it has been built
  /// (it is rebuilt only when a mesh changed).
  vtkIdType GetNumberOfTriangles();
  int GetNumberOfBuilds();
  ///@}

#ifndef __VTK_WRAP__
  /// The ray-query structure of the last Update() (C++ only): queries are thread-safe.
  const catar::RayScene& GetRayScene();
#endif

protected:
  vtkCatadioptricOccluders();
  ~vtkCatadioptricOccluders() override;

private:
  vtkCatadioptricOccluders(const vtkCatadioptricOccluders&) = delete;
  void operator=(const vtkCatadioptricOccluders&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
