#include "vtkCatadioptricAllocation.h"

#include "Memory.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <sstream>
#include <string>

namespace
{
// "NAME: N values of B bytes (X MB)".
std::string Describe(vtkAbstractArray* a, double values)
{
  std::ostringstream s;
  const char* name = a->GetName();
  s << (name && *name ? name : a->GetClassName()) << ": " << static_cast<long long>(values)
    << " values of " << a->GetDataTypeSize() << " bytes ("
    << catar::FormatBytes(values * a->GetDataTypeSize()) << ")";
  return s.str();
}

// Arrays from this size on are compared with the memory left before they are allocated: where
// the system overcommits, their allocation would succeed and the process be killed later. Reading
// what is left costs tens of microseconds (three small files), too much for every array of every
// frame; a smaller allocation that fails shows as malloc's null.
constexpr double kCheckedBytes = 16.0 * 1024.0 * 1024.0;

// Gives `a` room for n tuples, its first values kept when `keep` (as Resize). VTK's own
// allocation is not used for arrays of its standard layout: the Debian build aborts the program
// when one fails (it is built without NDEBUG). Their values are allocated here and handed to the
// array, which frees them; a failure throws catar::OutOfMemory.
void Allocate(vtkAbstractArray* a, vtkIdType n, bool keep)
{
  const double values = static_cast<double>(n) * a->GetNumberOfComponents();
  if (values > 0 && values <= static_cast<double>(a->GetSize()))
  {
    a->SetNumberOfTuples(n); // the room is there: VTK allocates nothing
    return;
  }
  const double bytes = values * a->GetDataTypeSize();
  if (bytes >= kCheckedBytes)
  {
    const catar::MemoryHeadroom headroom = catar::AvailableMemory();
    if (bytes > headroom.bytes)
    {
      throw catar::OutOfMemory(Describe(a, values) + " do not fit in the " +
        catar::FormatBytes(headroom.bytes) + " left under " + headroom.bound);
    }
  }
  if (a->GetArrayType() != vtkAbstractArray::AoSDataArrayTemplate)
  {
    if (keep)
    {
      a->Resize(n);
    }
    a->SetNumberOfTuples(n);
    return;
  }
  const std::size_t size = static_cast<std::size_t>(values) * a->GetDataTypeSize();
  void* memory = std::malloc(std::max<std::size_t>(size, 1));
  if (!memory)
  {
    throw catar::OutOfMemory(
      Describe(a, values) + " could not be allocated" + catar::MemoryLeftText());
  }
  if (keep && a->GetNumberOfValues() > 0)
  {
    const std::size_t old = static_cast<std::size_t>(a->GetNumberOfValues()) * a->GetDataTypeSize();
    std::memcpy(memory, a->GetVoidPointer(0), std::min(old, size));
  }
  // save = 0: the array owns the values and frees them with free().
  a->SetVoidArray(memory, static_cast<vtkIdType>(values), 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
}
} // namespace

void vtkCatadioptricAllocation::Tuples(vtkAbstractArray* a, vtkIdType n)
{
  Allocate(a, n, false);
}

void vtkCatadioptricAllocation::Grow(vtkAbstractArray* a, vtkIdType n)
{
  Allocate(a, n, true);
}

void vtkCatadioptricAllocation::Points(vtkPoints* p, vtkIdType n)
{
  Allocate(p->GetData(), n, false);
  p->Modified();
}

void vtkCatadioptricAllocation::Scalars(vtkImageData* image, int type, int components)
{
  // As vtkImageData::AllocateScalars: the image's scalars are reused when of the type and held
  // by no one else (a pipeline's image is not allocated again every frame).
  vtkSmartPointer<vtkDataArray> scalars = image->GetPointData()->GetScalars();
  if (!scalars || scalars->GetDataType() != type || scalars->GetReferenceCount() > 2)
  {
    scalars.TakeReference(vtkDataArray::CreateDataArray(type));
    scalars->SetName("ImageScalars");
    image->GetPointData()->SetScalars(scalars);
  }
  scalars->SetNumberOfComponents(components);
  Allocate(scalars, image->GetNumberOfPoints(), false);
  scalars->Modified();
}

std::string vtkCatadioptricAllocation::DescribeInput(vtkInformationVector* port)
{
  vtkIdType points = 0;
  vtkIdType cells = 0;
  const int meshes = port ? port->GetNumberOfInformationObjects() : 0;
  for (int i = 0; i < meshes; ++i)
  {
    if (vtkPolyData* mesh = vtkPolyData::GetData(port, i))
    {
      points += mesh->GetNumberOfPoints();
      cells += mesh->GetNumberOfCells();
    }
  }
  std::ostringstream s;
  s << cells << " triangles (" << points << " points)";
  if (meshes > 1)
  {
    s << " in " << meshes << " meshes";
  }
  return s.str();
}

std::string vtkCatadioptricAllocation::DescribeOutputImage(vtkInformationVector* outputs)
{
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  vtkInformation* info = outputs ? outputs->GetInformationObject(0) : nullptr;
  if (info && info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  }
  std::ostringstream s;
  s << "a " << extent[1] - extent[0] + 1 << " x " << extent[3] - extent[2] + 1 << " image";
  return s.str();
}

int vtkCatadioptricAllocation::Guard(
  vtkAlgorithm* self, const std::function<int()>& body, const std::function<std::string()>& what)
{
  std::string message;
  try
  {
    return body();
  }
  catch (const catar::OutOfMemory& e)
  {
    message = "out of memory while " + what() + ": " + e.what();
  }
  catch (const std::bad_alloc&)
  {
    message = catar::OutOfMemoryWhile(what());
  }
  vtkErrorWithObjectMacro(self, << message);
  return 0;
}
