/**
 * @class   vtkCatadioptricMeshConversion
 * @brief   vtkPolyData <-> catar::mesh::TriangleMesh, for the mesh-preparation filters
 *
 * Static functions only; C++ only (not wrapped).
 */
#ifndef vtkCatadioptricMeshConversion_h
#define vtkCatadioptricMeshConversion_h

#include "CatadioptricARFiltersModule.h" // for export macro

#include <string> // for std::string
#include <vector> // for std::vector

class vtkPolyData;
namespace catar
{
namespace mesh
{
struct TriangleMesh;
}
}

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricMeshConversion
{
public:
  /// Triangles of `input` (polygons fan-triangulated, strips split; vertices and lines ignored,
  /// which adds a warning) with every numeric point-data array as a point attribute. Points are
  /// copied as they are (repairs are the mesh algorithms' job).
  static void ToTriangleMesh(
    vtkPolyData* input, catar::mesh::TriangleMesh& mesh, std::vector<std::string>& warnings);

  /// `output` made from `mesh`: points, triangles, and the point attributes as arrays of the type
  /// and name of `prototype`'s point arrays (same active scalars, normals, texture coordinates;
  /// active normals are renormalised). Attributes `prototype` lacks become double arrays.
  static void FromTriangleMesh(
    const catar::mesh::TriangleMesh& mesh, vtkPolyData* prototype, vtkPolyData* output);

  /// Copies to each cell of `output` the cell data of the `input` cell nearest to the cell's
  /// centroid (a vtkStaticCellLocator on input). Nothing happens when input has no cell data.
  static void TransferCellData(vtkPolyData* input, vtkPolyData* output);
};

#endif
