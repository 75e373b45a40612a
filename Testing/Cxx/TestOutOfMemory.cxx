// Running out of memory: every stage that allocates in proportion to its input says which stage,
// how much it asked for and how much was left, and fails cleanly (Module/Base/Memory.h,
// vtkCatadioptricAllocation). The limits are real: the address-space limit (setrlimit, as
// `ulimit -v`) lowered for the call and put back. Not under AddressSanitizer, whose shadow memory
// takes terabytes of address space.
#include "Memory.h"
#include "TestUtilities.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

#if defined(__SANITIZE_ADDRESS__)
#define CATAR_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CATAR_ADDRESS_SANITIZER 1
#endif
#endif

namespace
{
bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

#if defined(__linux__) && !defined(CATAR_ADDRESS_SANITIZER)
// The address-space limit lowered to the process's present size plus `headroom` bytes for the
// object's lifetime (the soft limit only: it is raised back at the end).
class AddressSpaceLimit
{
public:
  explicit AddressSpaceLimit(double headroom)
  {
    getrlimit(RLIMIT_AS, &this->Saved);
    std::ifstream statm("/proc/self/statm");
    double pages = 0.0;
    statm >> pages;
    rlimit lowered = this->Saved;
    lowered.rlim_cur = static_cast<rlim_t>(pages * sysconf(_SC_PAGESIZE) + headroom);
    setrlimit(RLIMIT_AS, &lowered);
  }
  ~AddressSpaceLimit() { setrlimit(RLIMIT_AS, &this->Saved); }
  AddressSpaceLimit(const AddressSpaceLimit&) = delete;
  AddressSpaceLimit& operator=(const AddressSpaceLimit&) = delete;

private:
  rlimit Saved{};
};
#define CATAR_HAS_LIMIT 1
#endif
} // namespace

// The sizes are written as people read them.
TEST(OutOfMemory, SizesAreReadable)
{
  EXPECT_EQ(catar::FormatBytes(512), "512 bytes");
  EXPECT_EQ(catar::FormatBytes(8.0e6), "8.0 MB");
  EXPECT_EQ(catar::FormatBytes(839e6), "839 MB");
  EXPECT_EQ(catar::FormatBytes(5.1e9), "5.1 GB");
}

// An array larger than any machine's memory: refused before VTK sees it (the Debian build of VTK
// aborts when its own allocation fails), with the array's name and size; the array is as it was.
TEST(OutOfMemory, AnArrayTooLargeIsRefusedWithItsSize)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName("MirrorPoint");
  a->SetNumberOfComponents(3);
  vtkCatadioptricAllocation::Tuples(a, 4);
  a->SetValue(0, 7.0);
  try
  {
    vtkCatadioptricAllocation::Tuples(a, vtkIdType(1) << 50);
    FAIL() << "2^50 points were allocated";
  }
  catch (const catar::OutOfMemory& e)
  {
    const std::string m = e.what();
    EXPECT_TRUE(Contains(m, "MirrorPoint: 3377699720527872 values of 8 bytes (27 PB)")) << m;
    EXPECT_TRUE(Contains(m, " left under ")) << m;
  }
  EXPECT_EQ(a->GetNumberOfTuples(), 4);
  EXPECT_EQ(a->GetValue(0), 7.0);
  // Growing keeps the values; room already there is reused.
  vtkCatadioptricAllocation::Grow(a, 1000);
  EXPECT_EQ(a->GetNumberOfTuples(), 1000);
  EXPECT_EQ(a->GetValue(0), 7.0);
  double* values = a->GetPointer(0);
  vtkCatadioptricAllocation::Tuples(a, 10);
  vtkCatadioptricAllocation::Tuples(a, 1000);
  EXPECT_EQ(a->GetPointer(0), values);
  // Image scalars: of the type asked for, reused while no one else holds them.
  vtkNew<vtkImageData> image;
  image->SetDimensions(64, 32, 1);
  vtkCatadioptricAllocation::Scalars(image, VTK_UNSIGNED_CHAR, 4);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  ASSERT_TRUE(vtkUnsignedCharArray::SafeDownCast(scalars));
  EXPECT_EQ(scalars->GetNumberOfTuples(), 64 * 32);
  EXPECT_EQ(scalars->GetNumberOfComponents(), 4);
  vtkCatadioptricAllocation::Scalars(image, VTK_UNSIGNED_CHAR, 4);
  EXPECT_EQ(image->GetPointData()->GetScalars(), scalars);
  EXPECT_THROW(catar::RequireMemory(1e30, "a test"), catar::OutOfMemory);
  EXPECT_NO_THROW(catar::RequireMemory(1e3, "a test"));
}

#if defined(CATAR_HAS_LIMIT)
// What is left is measured under the address-space limit, and the limit is named.
TEST(OutOfMemory, TheAddressSpaceLimitIsMeasured)
{
  const AddressSpaceLimit limit(64e6);
  const catar::MemoryHeadroom left = catar::AvailableMemory();
  EXPECT_GT(left.bytes, 40e6);
  EXPECT_LT(left.bytes, 70e6);
  EXPECT_TRUE(Contains(left.bound, "the address-space limit (ulimit -v ")) << left.bound;
  try
  {
    catar::RequireMemory(200e6, "a mesh of 1000000 triangles");
    FAIL() << "200 MB fitted in 64 MB";
  }
  catch (const catar::OutOfMemory& e)
  {
    EXPECT_TRUE(Contains(e.what(), "a mesh of 1000000 triangles needs about 200 MB; ")) << e.what();
  }
}

// A projection whose arrays do not fit: the filter fails with an error naming the stage, the
// mesh's size, the array and what was left; the same filter works again once memory is there.
// (It aborted in VTK's allocation.)
TEST(OutOfMemory, AFilterThatRunsOutSaysWhereAndHowMuch)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.06, -0.32, 0.92);
  sphere->SetRadius(0.03);
  sphere->SetThetaResolution(400);
  sphere->SetPhiResolution(400);
  sphere->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(sphere->GetOutput());
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputData(mesh);
  projection->SetCamera(catar_test::DemoCamera());
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(projection->GetOutputPort());
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(projection);
  errors->Watch(sort);
  {
    const AddressSpaceLimit limit(1e6);
    EXPECT_EQ(projection->GetExecutive()->Update(), 0);
  }
  ASSERT_EQ(errors->Count, 1);
  const std::string m = errors->Last;
  EXPECT_TRUE(Contains(m, "out of memory while projecting 159202 points and 318400 cells")) << m;
  EXPECT_TRUE(Contains(m, " left under the address-space limit (ulimit -v ")) << m;
  // The sort, after the projection: its own stage named.
  projection->Modified();
  projection->Update();
  EXPECT_EQ(errors->Count, 1) << errors->Last;
  {
    const AddressSpaceLimit limit(1e6);
    EXPECT_EQ(sort->GetExecutive()->Update(), 0);
  }
  ASSERT_EQ(errors->Count, 2);
  EXPECT_TRUE(
    Contains(errors->Last, "out of memory while sorting 318400 triangles (159202 points)"))
    << errors->Last;
  sort->Modified();
  sort->Update();
  EXPECT_EQ(errors->Count, 2) << errors->Last;
  EXPECT_EQ(sort->GetOutput()->GetNumberOfCells() > 0, true);
}
#endif
