#include "vtkCatadioptricColorArray.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>

vtkCatadioptricColorArray::vtkCatadioptricColorArray(
  vtkPolyData* mesh, const char* name, const float solid[4])
{
  std::copy(solid, solid + 4, this->Solid);
  if (!mesh || !name || !*name)
  {
    return;
  }
  if ((this->Array = mesh->GetPointData()->GetArray(name)))
  {
    this->PerPoint = true;
  }
  else
  {
    this->Array = mesh->GetCellData()->GetArray(name);
  }
  if (this->Array)
  {
    this->Bytes = this->Array->GetDataType() == VTK_UNSIGNED_CHAR;
    this->Components = std::min(4, this->Array->GetNumberOfComponents());
  }
}

void vtkCatadioptricColorArray::Get(vtkIdType pointId, vtkIdType cellId, float rgba[4]) const
{
  if (!this->Array)
  {
    std::copy(this->Solid, this->Solid + 4, rgba);
    return;
  }
  const vtkIdType id = this->PerPoint ? pointId : cellId;
  const double scale = this->Bytes ? 1.0 / 255.0 : 1.0;
  float v[4] = { 0, 0, 0, 1 };
  for (int k = 0; k < this->Components; ++k)
  {
    v[k] = static_cast<float>(this->Array->GetComponent(id, k) * scale);
  }
  if (this->Components < 3) // grey (+ alpha)
  {
    v[3] = this->Components == 2 ? v[1] : 1.0f;
    v[1] = v[2] = v[0];
  }
  std::copy(v, v + 4, rgba);
}
