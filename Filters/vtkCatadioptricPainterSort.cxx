#include "vtkCatadioptricPainterSort.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <vector>

vtkStandardNewMacro(vtkCatadioptricPainterSort);

int vtkCatadioptricPainterSort::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkPolyData.");
    return 0;
  }
  const vtkIdType nCells = input->GetNumberOfCells();
  vtkDataArray* depthArray = input->GetCellData()->GetArray("CentroidDepth");
  if (nCells > 0 &&
    (!depthArray || depthArray->GetNumberOfComponents() != 1 ||
      depthArray->GetNumberOfTuples() != nCells))
  {
    vtkErrorMacro("The input has no CentroidDepth cell array: run vtkCatadioptricProjection "
                  "before vtkCatadioptricPainterSort.");
    return 0;
  }
  vtkUnsignedCharArray* visible =
    vtkUnsignedCharArray::SafeDownCast(input->GetCellData()->GetArray("Visible"));
  if (this->DropInvisibleCells && nCells > 0 && !visible)
  {
    vtkErrorMacro("DropInvisibleCells is on but the input has no uint8 Visible cell array.");
    return 0;
  }
  if (input->GetNumberOfVerts() + input->GetNumberOfLines() + input->GetNumberOfStrips() > 0)
  {
    vtkWarningMacro("Only polygons are sorted; vertices, lines and strips are dropped.");
  }

  const vtkIdType first = input->GetNumberOfVerts() + input->GetNumberOfLines();
  const vtkIdType nPolys = input->GetNumberOfPolys();
  std::vector<vtkIdType> order;
  order.reserve(nPolys);
  for (vtkIdType c = 0; c < nPolys; ++c)
  {
    if (!this->DropInvisibleCells || visible->GetValue(first + c))
    {
      order.push_back(c);
    }
  }
  std::vector<double> depth(nPolys);
  for (vtkIdType c = 0; c < nPolys; ++c)
  {
    depth[c] = depthArray->GetComponent(first + c, 0);
  }
  this->UpdateProgress(0.2);
  // Far to near; ties keep input order, so the result does not depend on the sort's stability.
  vtkSMPTools::Sort(order.begin(), order.end(), [&depth](vtkIdType a, vtkIdType b) {
    return depth[a] > depth[b] || (depth[a] == depth[b] && a < b);
  });
  this->UpdateProgress(0.6);

  // New polygon connectivity in the sorted order.
  vtkCellArray* inPolys = input->GetPolys();
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(order.size()), inPolys->GetNumberOfConnectivityIds());
  vtkNew<vtkIdList> ids;
  for (vtkIdType c : order)
  {
    inPolys->GetCellAtId(c, ids);
    polys->InsertNextCell(ids);
  }

  output->SetPoints(input->GetPoints());
  output->GetPointData()->PassData(input->GetPointData());
  output->GetFieldData()->PassData(input->GetFieldData());
  output->SetPolys(polys);

  // Cell data follows the cells.
  const vtkIdType nOut = static_cast<vtkIdType>(order.size());
  vtkNew<vtkIdList> sourceIds;
  vtkNew<vtkIdList> targetIds;
  sourceIds->SetNumberOfIds(nOut);
  targetIds->SetNumberOfIds(nOut);
  for (vtkIdType i = 0; i < nOut; ++i)
  {
    sourceIds->SetId(i, first + order[i]);
    targetIds->SetId(i, i);
  }
  vtkCellData* outCD = output->GetCellData();
  outCD->CopyAllocate(input->GetCellData(), nOut);
  outCD->CopyData(input->GetCellData(), sourceIds, targetIds);
  // OriginalCellId: each cell's index in the input, unless the input already carries the ids of
  // an earlier stage (then they were copied above, reordered with the cells).
  if (!input->GetCellData()->GetArray("OriginalCellId"))
  {
    vtkNew<vtkIdTypeArray> original;
    original->SetName("OriginalCellId");
    original->SetNumberOfTuples(nOut);
    for (vtkIdType i = 0; i < nOut; ++i)
    {
      original->SetValue(i, first + order[i]);
    }
    outCD->AddArray(original);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricPainterSort::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DropInvisibleCells: " << (this->DropInvisibleCells ? "On" : "Off") << "\n";
}
