/**
 * @class   vtkCatadioptricPointReader
 * @brief   reads a vtkPoints' coordinates without a virtual call per point (private)
 *
 * Float and double arrays of structures (what readers and sources make) are read through their
 * raw pointers; any other storage through vtkPoints::GetPoint. Header-only, not installed.
 */
#ifndef vtkCatadioptricPointReader_h
#define vtkCatadioptricPointReader_h

#include "CameraModel.h" // for catar::Vec3
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkPoints.h"

class vtkCatadioptricPointReader
{
public:
  explicit vtkCatadioptricPointReader(vtkPoints* points)
    : Points(points)
  {
    vtkDataArray* data = points->GetData();
    if (auto* d = vtkDoubleArray::SafeDownCast(data))
    {
      this->Doubles = d->GetPointer(0);
    }
    else if (auto* f = vtkFloatArray::SafeDownCast(data))
    {
      this->Floats = f->GetPointer(0);
    }
  }
  catar::Vec3 operator()(vtkIdType i) const
  {
    if (this->Doubles)
    {
      return catar::Vec3(this->Doubles[3 * i], this->Doubles[3 * i + 1], this->Doubles[3 * i + 2]);
    }
    if (this->Floats)
    {
      return catar::Vec3(this->Floats[3 * i], this->Floats[3 * i + 1], this->Floats[3 * i + 2]);
    }
    double p[3];
    this->Points->GetPoint(i, p);
    return catar::Vec3(p[0], p[1], p[2]);
  }

private:
  vtkPoints* Points;
  const double* Doubles = nullptr;
  const float* Floats = nullptr;
};

#endif
