/**
 * @class   vtkCatadioptricPainterSort
 * @brief   orders polygons far to near for a non-central camera (the paper's Algorithm 1)
 *
 * The input is the output of vtkCatadioptricProjection. Its polygons are ordered by descending
 * CentroidDepth (the distance from each cell's centroid to the centroid's own reflection point on
 * the mirror), so that drawing them in order paints the nearest last. Ties keep the input order.
 * Cell data is reordered with the cells; points and point data are passed unchanged. Only
 * polygons are kept (vertices, lines and strips are dropped with a warning). With
 * DropInvisibleCells on, cells whose Visible flag is 0 are removed.
 *
 * The output gets the cell array OriginalCellId (vtkIdTypeArray): each cell's id in the input
 * (vertices and lines counted, as vtkPolyData numbers cells), so that results on the sorted mesh
 * (vtkCatadioptricCompositor's VisibleTriangle ids) refer to the unsorted one. An input that
 * already has an OriginalCellId array keeps its values, reordered with the cells.
 */
#ifndef vtkCatadioptricPainterSort_h
#define vtkCatadioptricPainterSort_h

#include "CatadioptricARFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // std::unique_ptr

namespace catar
{
class DepthOrder;
}

class CATADIOPTRICARFILTERS_EXPORT vtkCatadioptricPainterSort : public vtkPolyDataAlgorithm
{
public:
  static vtkCatadioptricPainterSort* New();
  vtkTypeMacro(vtkCatadioptricPainterSort, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Remove cells that cannot be drawn (cell array Visible == 0). Default off.
  vtkSetMacro(DropInvisibleCells, bool);
  vtkGetMacro(DropInvisibleCells, bool);
  vtkBooleanMacro(DropInvisibleCells, bool);
  ///@}

protected:
  vtkCatadioptricPainterSort();
  ~vtkCatadioptricPainterSort() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool DropInvisibleCells = false;
  // The order's buffers, kept between executions.
  std::unique_ptr<catar::DepthOrder> Order;

private:
  // RequestData's work (RequestData reports running out of memory).
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  vtkCatadioptricPainterSort(const vtkCatadioptricPainterSort&) = delete;
  void operator=(const vtkCatadioptricPainterSort&) = delete;
};

#endif
