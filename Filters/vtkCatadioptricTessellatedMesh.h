/**
 * @class   vtkCatadioptricTessellatedMesh
 * @brief   a projected mesh with the triangles this frame's image needs split (private helper)
 *
 * vtkCatadioptricProjection's per-frame tessellation (Module/Projection/ImageTessellation.h):
 * triangles that cross the visibility boundary, and (adaptive) those whose edges bend more than a
 * tolerance, are replaced by their pieces; new points take point data interpolated from their input
 * triangle's vertices, pieces take their triangle's cell data. Not wrapped.
 */
#ifndef vtkCatadioptricTessellatedMesh_h
#define vtkCatadioptricTessellatedMesh_h

#include "CatadioptricARFiltersModule.h" // for export macro
#include "ImageTessellation.h"           // for catar::TessellationOptions
#include "vtkType.h"                     // for vtkIdType

#include <cstdint> // for std::int64_t
#include <vector>  // for std::vector

class vtkPolyData;

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricTessellatedMesh
{
public:
  /// Tessellates the triangles of `input` that need it this frame (polygons of more sides are
  /// left as they are), given the projections of its points (`status`, one ProjectionStatus per
  /// input point, `pixels`, two per point, and `mirrorPoints`, three per point, camera frame: where
  /// new points' reflections are searched from). When any is split, `output` becomes the refined
  /// mesh: the input points then the new ones (with point data interpolated from their
  /// triangle's vertices), cells in the input's order with each split triangle's pieces in its
  /// place (with its cell data); `added` holds the new points' projections. At most 2^22 pieces
  /// are made in all (each split triangle's share of that bounds its depth). Returns the number of
  /// triangles split; 0 leaves `output` and `added` as they are. `sources` (may be null) receives,
  /// when a triangle is split, each output cell's input cell, or -1 for a piece.
  static vtkIdType Refine(vtkPolyData* input, const catar::Projector& projector,
    const catar::TessellationOptions& options, const unsigned char* status, const double* pixels,
    const double* mirrorPoints, catar::Tessellation& added, vtkPolyData* output,
    std::vector<std::int64_t>* sources = nullptr);
};

#endif
