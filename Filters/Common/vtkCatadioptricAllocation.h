/**
 * @class   vtkCatadioptricAllocation
 * @brief   allocations that say when they fail, and RequestData bodies that report running out
 *
 * When VTK cannot allocate an array's values it logs "Unable to allocate N elements" and leaves
 * the array empty; code that writes into it next crashes. These calls check the result and throw
 * catar::OutOfMemory (Module/Base/Memory.h) with the array's name and the size asked for. Guard
 * runs a filter's work and turns running out of memory (that exception, or std::bad_alloc) into
 * the filter's error naming the stage and its sizes, so that a program, the Python helpers and
 * ParaView report it instead of aborting. C++ only (not wrapped).
 */
#ifndef vtkCatadioptricAllocation_h
#define vtkCatadioptricAllocation_h

#include "CatadioptricARCommonModule.h" // export macro
#include "vtkType.h"

#include <functional>
#include <string>

class vtkAbstractArray;
class vtkAlgorithm;
class vtkImageData;
class vtkInformationVector;
class vtkPoints;

class CATADIOPTRICARCOMMON_EXPORT vtkCatadioptricAllocation
{
public:
  /// a->SetNumberOfTuples(n); throws catar::OutOfMemory ("ARRAY: N values of B bytes (X MB)
  /// could not be allocated") when VTK could not.
  static void Tuples(vtkAbstractArray* a, vtkIdType n);

  /// a->Resize(n) then a->SetNumberOfTuples(n) (the first values kept), checked as Tuples.
  static void Grow(vtkAbstractArray* a, vtkIdType n);

  /// p->SetNumberOfPoints(n), checked as Tuples.
  static void Points(vtkPoints* p, vtkIdType n);

  /// image->AllocateScalars(type, components) for its dimensions, checked as Tuples.
  static void Scalars(vtkImageData* image, int type, int components);

  /// The meshes on an input port, for Guard's `what`: "2093056 triangles (1046530 points)", or
  /// "3072 triangles (1536 points) in 2 meshes".
  static std::string DescribeInput(vtkInformationVector* port);

  /// The image an output port will hold (its whole extent), for Guard's `what`: "a 16384 x
  /// 12930 image".
  static std::string DescribeOutputImage(vtkInformationVector* outputs);

  /// Runs body() and returns its result; when it runs out of memory (catar::OutOfMemory, or
  /// std::bad_alloc, reported as catar::OutOfMemoryWhile(what())), reports it as `self`'s
  /// error and returns 0. `what` is asked only then: "projecting 1046530 points and 2093056
  /// triangles".
  static int Guard(
    vtkAlgorithm* self, const std::function<int()>& body, const std::function<std::string()>& what);
};

#endif
