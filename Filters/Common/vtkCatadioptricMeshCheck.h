/**
 * @class   vtkCatadioptricMeshCheck
 * @brief   checks a mesh before a filter reads it through its point ids and arrays
 *
 * Every filter and sink that reads a mesh's cells through their point ids, or its point and cell
 * arrays through raw pointers, calls Check() first, where the data enters it: a cell naming a
 * point that does not exist (a negative id, or one past the points, as broken OBJ, PLY or legacy
 * VTK files and hand-made meshes give) or an array shorter than the points or cells it describes
 * is refused with a sentence, never read out of bounds.
 *
 * The point ids' range is computed in parallel, once per connectivity array: it is kept in the
 * array's vtkInformation and reused while the array's MTime is unchanged (downstream filters
 * share their input's cell arrays). Code that writes ids through raw pointers must call the
 * array's Modified(), as VTK requires for its own cached ranges.
 *
 * Static functions only; C++ only (not wrapped).
 */
#ifndef vtkCatadioptricMeshCheck_h
#define vtkCatadioptricMeshCheck_h

#include "CatadioptricARCommonModule.h" // for export macro
#include "vtkType.h"                    // for vtkIdType

#include <string> // for std::string

class vtkAlgorithm;
class vtkCellArray;
class vtkDataArray;
class vtkInformationVector;
class vtkPolyData;

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricMeshCheck
{
public:
  /// True when every cell of `mesh` (vertices, lines, polygons, strips) names points that exist
  /// (ids in [0, number of points)), every point-data array has at least one tuple per point and
  /// every cell-data array at least one per cell. Otherwise false, with a sentence naming the
  /// problem in `error` (e.g. "cell 12 names point 99, but the mesh has 8 points (ids 0 to 7)").
  static bool Check(vtkPolyData* mesh, std::string& error);

  /// A polydata filter's first step in RequestData: its input (port 0) and output, the input
  /// checked by Check(). False, with the error reported by `filter` ("Input and output must be
  /// vtkPolyData." or "Bad input mesh: ..."), when either is missing or the input fails.
  static bool InputAndOutput(vtkAlgorithm* filter, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector, vtkPolyData*& input, vtkPolyData*& output);

  /// The point ids' check alone.
  static bool CheckPointIds(vtkPolyData* mesh, std::string& error);

  /// The arrays' check alone.
  static bool CheckArraySizes(vtkPolyData* mesh, std::string& error);

  /// Smallest and largest id in `cells`' connectivity (an empty array gives 0, -1). Cached in the
  /// connectivity array's information while its MTime is unchanged.
  static void IdRange(vtkCellArray* cells, vtkIdType range[2]);
};

#endif
// VTK-HeaderTest-Exclude: vtkCatadioptricMeshCheck.h
