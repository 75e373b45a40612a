/**
 * @class   vtkCatadioptricColorArray
 * @brief   reads RGBA colours from a point or cell colour array, or a solid colour
 *
 * Not a vtkObject (C++ only). Looks for the named array in the point data first, then in the
 * cell data. Unsigned char arrays are read as 0-255, other types as 0-1; 1 (grey), 2 (grey,
 * alpha), 3 (RGB) or 4 (RGBA) components. Without an array, Get() returns the solid colour.
 * Get() is thread-safe.
 */
#ifndef vtkCatadioptricColorArray_h
#define vtkCatadioptricColorArray_h

#include "CatadioptricARCommonModule.h" // for export macro
#include "vtkType.h"                    // for vtkIdType

class vtkDataArray;
class vtkPolyData;

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricColorArray
{
public:
  /// Finds `name` (may be null or empty: no array) in `mesh`; `solid` is RGBA in [0,1].
  vtkCatadioptricColorArray(vtkPolyData* mesh, const char* name, const float solid[4]);

  /// True when an array was found.
  bool HasArray() const { return this->Array != nullptr; }
  /// True when the array is point data (Gouraud), false for cell data (flat).
  bool IsPerPoint() const { return this->PerPoint; }
  /// Number of components of the array (0 without one).
  int GetNumberOfComponents() const { return this->Components; }
  /// The array found (null without one), for callers that read it with typed access.
  vtkDataArray* GetArray() const { return this->Array; }

  /// The colour of point `pointId` (point data) or cell `cellId` (cell data), RGBA in [0,1].
  void Get(vtkIdType pointId, vtkIdType cellId, float rgba[4]) const;

private:
  vtkDataArray* Array = nullptr;
  bool PerPoint = false;
  bool Bytes = false;
  int Components = 0;
  float Solid[4];
};

#endif
