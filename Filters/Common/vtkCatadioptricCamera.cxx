#include "vtkCatadioptricCamera.h"

#include "CalibrationIO.h"
#include "CameraModel.h"
#include "Memory.h"
#include "Mirror.h"
#include "Projector.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricParallel.h"
#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerVectorKey.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricCamera);

// The status codes of the wrapped class are Core's, value for value.
static_assert(vtkCatadioptricCamera::VALID == static_cast<int>(catar::ProjectionStatus::Valid) &&
    vtkCatadioptricCamera::OUTSIDE_IMAGE ==
      static_cast<int>(catar::ProjectionStatus::OutsideImage) &&
    vtkCatadioptricCamera::INSIDE_MIRROR ==
      static_cast<int>(catar::ProjectionStatus::InsideMirror) &&
    vtkCatadioptricCamera::HIDDEN_BY_MIRROR ==
      static_cast<int>(catar::ProjectionStatus::HiddenByMirror) &&
    vtkCatadioptricCamera::NO_REFLECTION ==
      static_cast<int>(catar::ProjectionStatus::NoReflection) &&
    vtkCatadioptricCamera::INVALID_INPUT == static_cast<int>(catar::ProjectionStatus::InvalidInput),
  "vtkCatadioptricCamera::StatusCodes must match catar::ProjectionStatus");

namespace
{
// The `solver` number of ProjectWorldPoint(s): 0 quartic, 1 iterative, anything else automatic.
catar::SolverType SolverFromNumber(int solver)
{
  return solver == 0 ? catar::SolverType::Quartic
    : solver == 1    ? catar::SolverType::Iterative
                     : catar::SolverType::Automatic;
}

// An integer-vector key that the executives copy from a filter's first input to its outputs
// during REQUEST_INFORMATION (plain keys stay where they were set).
class ImageSizeKey : public vtkInformationIntegerVectorKey
{
public:
  ImageSizeKey()
    : vtkInformationIntegerVectorKey("IMAGE_SIZE", "vtkCatadioptricCamera", 2)
  {
  }
  void CopyDefaultInformation(
    vtkInformation* request, vtkInformation* fromInfo, vtkInformation* toInfo) override
  {
    if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()) && fromInfo->Has(this))
    {
      this->ShallowCopy(fromInfo, toInfo);
    }
  }
};
// Deleted with the other keys by vtkInformationKeyLookup at exit, as vtkInformationKeyMacro's.
vtkInformationIntegerVectorKey* const theImageSizeKey = new ImageSizeKey;
} // namespace

void vtkCatadioptricCamera::SetDistortion(double k1, double k2, double p1, double p2, double k3)
{
  const double d[5] = { k1, k2, p1, p2, k3 };
  if (!std::equal(d, d + 5, this->Distortion))
  {
    std::copy(d, d + 5, this->Distortion);
    this->Modified();
  }
}

bool vtkCatadioptricCamera::SetLens(const char* lens, const std::vector<double>& coefficients)
{
  catar::LensType type = catar::LensType::Pinhole;
  catar::Distortion d;
  if (!lens || !catar::LensFromName(lens, type))
  {
    this->LastError =
      std::string("unknown lens model '") + (lens ? lens : "(null)") + "' (pinhole or fisheye)";
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  if (!d.SetCoefficients(type, coefficients))
  {
    this->LastError = type == catar::LensType::Fisheye
      ? "a fisheye lens takes 4 coefficients (k1 k2 k3 k4)"
      : "a pinhole lens takes 4, 5, 8, 12 or 14 coefficients (OpenCV's order)";
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  if (static_cast<int>(type) != this->Lens ||
    !std::equal(d.Data(), d.Data() + d.kCount, this->Distortion))
  {
    this->Lens = static_cast<int>(type);
    std::copy(d.Data(), d.Data() + d.kCount, this->Distortion);
    this->Modified();
  }
  return true;
}

const char* vtkCatadioptricCamera::GetLens()
{
  return catar::LensName(static_cast<catar::LensType>(this->Lens));
}

std::vector<double> vtkCatadioptricCamera::GetDistortionCoefficients()
{
  catar::Distortion d;
  std::copy(this->Distortion, this->Distortion + d.kCount, d.Data());
  return d.Coefficients(static_cast<catar::LensType>(this->Lens));
}

vtkInformationIntegerVectorKey* vtkCatadioptricCamera::IMAGE_SIZE()
{
  return theImageSizeKey;
}

namespace
{
const char* const kIntrinsicsName = "CameraIntrinsics";
const char* const kDistortionName = "CameraDistortion";
const char* const kLensName = "CameraLens";
const char* const kMirrorTypeName = "MirrorType";
const char* const kMirrorParametersName = "MirrorParameters";
const char* const kPoseName = "WorldToCamera";

void AddArray(vtkFieldData* fd, const char* name, const double* values, int n)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(1);
  vtkCatadioptricAllocation::Tuples(a, n);
  std::copy(values, values + n, a->GetPointer(0));
  fd->RemoveArray(name);
  fd->AddArray(a);
}

bool GetArray(vtkFieldData* fd, const char* name, double* values, int n)
{
  vtkDataArray* a = fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  if (!a || a->GetNumberOfValues() != n)
  {
    return false;
  }
  for (int i = 0; i < n; ++i)
  {
    values[i] = a->GetVariantValue(i).ToDouble();
  }
  return true;
}
} // namespace

vtkCatadioptricCamera::vtkCatadioptricCamera()
  : WorldToCamera(vtkSmartPointer<vtkMatrix4x4>::New())
{
  // The mirror of the demo rig (Data/scenes/demo.yaml), whose lens the defaults above are.
  static const catar::MirrorDescription demoMirror = catar::DemoCamera().mirror;
  this->MirrorType = demoMirror.type;
  this->MirrorParameters = demoMirror.parameters;
}

bool vtkCatadioptricCamera::SetMirrorType(const char* type)
{
  const catar::MirrorType* t = type ? catar::FindMirrorType(type) : nullptr;
  if (!t)
  {
    this->LastError = std::string("unknown mirror type '") + (type ? type : "(null)") +
      "' (known: " + catar::MirrorTypeNames() + ")";
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  if (this->MirrorType != t->name)
  {
    this->MirrorType = t->name;
    this->MirrorParameters = t->defaults;
    this->Modified();
  }
  return true;
}

std::vector<std::string> vtkCatadioptricCamera::GetMirrorTypes()
{
  std::vector<std::string> names;
  for (const catar::MirrorType& t : catar::MirrorTypes())
  {
    if (catar::FindMirrorType(t.name) == &t) // a name with variants once
    {
      names.push_back(t.name);
    }
  }
  return names;
}

std::vector<std::string> vtkCatadioptricCamera::GetMirrorParameterKeys(const char* type)
{
  std::vector<std::string> keys;
  if (const catar::MirrorType* t = type ? catar::FindMirrorType(type) : nullptr)
  {
    for (const catar::MirrorParameter& p : t->parameters)
    {
      keys.push_back(p.key);
    }
  }
  return keys;
}

namespace
{
// The variant of a type the numbers are for (the first when their count fits none).
const catar::MirrorType* Variant(const std::string& type, std::size_t count)
{
  const catar::MirrorType* t = catar::FindMirrorType(type, count);
  return t ? t : catar::FindMirrorType(type);
}
} // namespace

bool vtkCatadioptricCamera::SetMirrorParameter(const char* key, const std::vector<double>& values)
{
  const catar::MirrorType* t = Variant(this->MirrorType, this->MirrorParameters.size());
  const catar::MirrorParameter* p = t && key ? t->FindParameter(key) : nullptr;
  if (!p || static_cast<int>(values.size()) != p->count)
  {
    this->LastError = !p
      ? "a " + this->MirrorType + " mirror has no parameter '" + (key ? key : "(null)") + "'"
      : "mirror parameter '" + p->key + "' takes " + std::to_string(p->count) + " numbers, not " +
        std::to_string(values.size());
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  if (static_cast<int>(this->MirrorParameters.size()) != t->ParameterCount())
  {
    this->MirrorParameters = t->defaults; // a malformed model given through SetModel
  }
  const auto offset = static_cast<std::size_t>(t->ParameterOffset(p->key));
  if (!std::equal(values.begin(), values.end(), this->MirrorParameters.begin() + offset))
  {
    std::copy(values.begin(), values.end(), this->MirrorParameters.begin() + offset);
    this->Modified();
  }
  return true;
}

bool vtkCatadioptricCamera::SetMirrorParameter(const char* key, double value)
{
  return this->SetMirrorParameter(key, std::vector<double>{ value });
}

bool vtkCatadioptricCamera::SetMirrorParameter(const char* key, const double matrix[4][4])
{
  return this->SetMirrorParameter(key, std::vector<double>(&matrix[0][0], &matrix[0][0] + 16));
}

std::vector<double> vtkCatadioptricCamera::GetMirrorParameter(const char* key)
{
  const catar::MirrorType* t = Variant(this->MirrorType, this->MirrorParameters.size());
  const catar::MirrorParameter* p = t && key ? t->FindParameter(key) : nullptr;
  if (!p || static_cast<int>(this->MirrorParameters.size()) != t->ParameterCount())
  {
    return {};
  }
  const auto first = this->MirrorParameters.begin() + t->ParameterOffset(p->key);
  return std::vector<double>(first, first + p->count);
}

bool vtkCatadioptricCamera::SetMirrorParameters(const std::vector<double>& values)
{
  // Any variant of the type whose count the numbers have (see catar::FindMirrorType).
  const catar::MirrorType* t = catar::FindMirrorType(this->MirrorType, values.size());
  if (!t)
  {
    t = catar::FindMirrorType(this->MirrorType);
    this->LastError = "a " + this->MirrorType + " mirror takes " +
      std::to_string(t ? t->ParameterCount() : 0) + " numbers, not " +
      std::to_string(values.size());
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  if (values != this->MirrorParameters)
  {
    this->MirrorParameters = values;
    this->Modified();
  }
  return true;
}

vtkCatadioptricCamera::~vtkCatadioptricCamera() = default;

const char* vtkCatadioptricCamera::GetStatusName(int status)
{
  if (status < 0 || status > INVALID_INPUT)
  {
    return "unknown";
  }
  return catar::ToString(static_cast<catar::ProjectionStatus>(status));
}

void vtkCatadioptricCamera::SetWorldToCamera(vtkMatrix4x4* matrix)
{
  if (!matrix)
  {
    vtkErrorMacro("SetWorldToCamera: null matrix");
    return;
  }
  this->WorldToCamera->DeepCopy(matrix);
  this->Modified();
}

vtkMatrix4x4* vtkCatadioptricCamera::GetWorldToCamera()
{
  return this->WorldToCamera;
}

void vtkCatadioptricCamera::SetWorldToCameraElements(const double elements[16])
{
  this->WorldToCamera->DeepCopy(elements);
  this->Modified();
}

void vtkCatadioptricCamera::SetWorldToCamera(const double matrix[4][4])
{
  this->SetWorldToCameraElements(&matrix[0][0]);
}

void vtkCatadioptricCamera::GetWorldToCameraElements(double elements[16])
{
  vtkMatrix4x4::DeepCopy(elements, this->WorldToCamera);
}

void vtkCatadioptricCamera::GetCameraPosition(double position[3])
{
  const catar::Vec3 p = this->GetModel().CameraToWorld(catar::Vec3::Zero());
  std::copy(p.data(), p.data() + 3, position);
}

vtkMTimeType vtkCatadioptricCamera::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->WorldToCamera->GetMTime());
}

catar::CameraModel vtkCatadioptricCamera::GetModel()
{
  catar::CameraModel m;
  m.intrinsics.fx = this->FocalLength[0];
  m.intrinsics.fy = this->FocalLength[1];
  m.intrinsics.cx = this->PrincipalPoint[0];
  m.intrinsics.cy = this->PrincipalPoint[1];
  m.intrinsics.skew = this->Skew;
  m.intrinsics.width = this->ImageWidth;
  m.intrinsics.height = this->ImageHeight;
  m.lens = static_cast<catar::LensType>(this->Lens);
  std::copy(this->Distortion, this->Distortion + m.distortion.kCount, m.distortion.Data());
  m.mirror = catar::MirrorDescription(this->MirrorType, this->MirrorParameters);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m.worldToCamera(r, c) = this->WorldToCamera->GetElement(r, c);
    }
  }
  return m;
}

void vtkCatadioptricCamera::SetModel(const catar::CameraModel& m)
{
  this->FocalLength[0] = m.intrinsics.fx;
  this->FocalLength[1] = m.intrinsics.fy;
  this->PrincipalPoint[0] = m.intrinsics.cx;
  this->PrincipalPoint[1] = m.intrinsics.cy;
  this->Skew = m.intrinsics.skew;
  this->ImageWidth = m.intrinsics.width;
  this->ImageHeight = m.intrinsics.height;
  this->Lens = static_cast<int>(m.lens);
  std::copy(m.distortion.Data(), m.distortion.Data() + m.distortion.kCount, this->Distortion);
  this->MirrorType = m.mirror.type;
  this->MirrorParameters = m.mirror.parameters;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      this->WorldToCamera->SetElement(r, c, m.worldToCamera(r, c));
    }
  }
  this->Modified();
}

bool vtkCatadioptricCamera::IsValid()
{
  this->LastError = this->GetModel().Validate();
  return this->LastError.empty();
}

bool vtkCatadioptricCamera::Load(const char* fileName)
{
  if (!fileName || !*fileName)
  {
    this->LastError = "no calibration file name given";
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  catar::CameraModel m;
  std::string error;
  if (!catar::LoadCalibration(fileName, m, error))
  {
    this->LastError = error;
    vtkErrorMacro(<< error);
    return false;
  }
  this->LastError.clear();
  this->SetModel(m);
  return true;
}

bool vtkCatadioptricCamera::Save(const char* fileName)
{
  if (!fileName || !*fileName)
  {
    this->LastError = "no calibration file name given";
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  std::string error;
  if (!catar::SaveCalibration(fileName, this->GetModel(), error))
  {
    this->LastError = error;
    vtkErrorMacro(<< error);
    return false;
  }
  this->LastError.clear();
  return true;
}

int vtkCatadioptricCamera::ProjectWorldPoint(
  const double point[3], double pixel[2], double mirrorPoint[3])
{
  return this->ProjectWorldPoint(point, pixel, mirrorPoint, 2);
}

int vtkCatadioptricCamera::ProjectWorldPoint(
  const double point[3], double pixel[2], double mirrorPoint[3], int solver)
{
  const catar::Projector proj(this->GetModel());
  const catar::ProjectedPoint q =
    proj.ProjectWorld(catar::Vec3(point[0], point[1], point[2]), SolverFromNumber(solver));
  pixel[0] = q.pixel.x();
  pixel[1] = q.pixel.y();
  std::copy(q.mirrorPoint.data(), q.mirrorPoint.data() + 3, mirrorPoint);
  return static_cast<int>(q.status);
}

int vtkCatadioptricCamera::BackProjectPixel(
  const double pixel[2], double origin[3], double direction[3])
{
  const catar::Projector proj(this->GetModel());
  const catar::BackProjectedRay r = proj.BackProjectWorld(catar::Vec2(pixel[0], pixel[1]));
  std::copy(r.mirrorPoint.data(), r.mirrorPoint.data() + 3, origin);
  std::copy(r.direction.data(), r.direction.data() + 3, direction);
  return static_cast<int>(r.status);
}

namespace
{
// The checks both batch calls share: the input's components, the outputs there, a valid camera.
bool CheckBatch(vtkDataArray* in, int components, std::initializer_list<vtkDataArray*> outs,
  const std::string& what, std::string& error)
{
  if (!in || in->GetNumberOfComponents() != components)
  {
    error = what + ": the input array must have " + std::to_string(components) + " components";
    return false;
  }
  for (vtkDataArray* out : outs)
  {
    if (!out)
    {
      error = what + ": every output array must be given";
      return false;
    }
  }
  return true;
}

// Gives each output array of a batch n tuples of its components; false with the sizes in
// `error` when the memory left does not hold them.
bool AllocateBatch(std::initializer_list<std::pair<vtkDataArray*, int>> outputs, vtkIdType n,
  const std::string& what, std::string& error)
{
  try
  {
    for (const auto& output : outputs)
    {
      output.first->SetNumberOfComponents(output.second);
      vtkCatadioptricAllocation::Tuples(output.first, n);
    }
    return true;
  }
  catch (const catar::OutOfMemory& e)
  {
    error =
      what + ": out of memory for the results of " + std::to_string(n) + " points: " + e.what();
  }
  return false;
}
} // namespace

bool vtkCatadioptricCamera::ProjectWorldPoints(vtkDataArray* points, vtkDoubleArray* pixels,
  vtkIntArray* statuses, vtkDoubleArray* mirrorPoints, int solver)
{
  const catar::Projector proj(this->GetModel());
  std::string error;
  if (CheckBatch(points, 3, { pixels, statuses, mirrorPoints }, "ProjectWorldPoints", error) &&
    !proj.IsValid())
  {
    error = "ProjectWorldPoints: " + proj.GetError();
  }
  if (!error.empty())
  {
    this->LastError = error;
    vtkErrorMacro(<< error);
    return false;
  }
  const vtkIdType n = points->GetNumberOfTuples();
  if (!AllocateBatch(
        { { pixels, 2 }, { statuses, 1 }, { mirrorPoints, 3 } }, n, "ProjectWorldPoints", error))
  {
    this->LastError = error;
    vtkErrorMacro(<< error);
    return false;
  }
  const catar::SolverType type = SolverFromNumber(solver);
  double* pixel = pixels->GetPointer(0);
  int* status = statuses->GetPointer(0);
  double* mirror = mirrorPoints->GetPointer(0);
  vtkCatadioptricParallel::For(0, n, 256, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      double p[3];
      points->GetTuple(i, p);
      const catar::ProjectedPoint q = proj.ProjectWorld(catar::Vec3(p[0], p[1], p[2]), type);
      pixel[2 * i] = q.pixel.x();
      pixel[2 * i + 1] = q.pixel.y();
      std::copy(q.mirrorPoint.data(), q.mirrorPoint.data() + 3, mirror + 3 * i);
      status[i] = static_cast<int>(q.status);
    }
  });
  return true;
}

bool vtkCatadioptricCamera::BackProjectPixels(
  vtkDataArray* pixels, vtkDoubleArray* origins, vtkDoubleArray* directions, vtkIntArray* statuses)
{
  const catar::Projector proj(this->GetModel());
  std::string error;
  if (CheckBatch(pixels, 2, { origins, directions, statuses }, "BackProjectPixels", error) &&
    !proj.IsValid())
  {
    error = "BackProjectPixels: " + proj.GetError();
  }
  if (!error.empty())
  {
    this->LastError = error;
    vtkErrorMacro(<< error);
    return false;
  }
  const vtkIdType n = pixels->GetNumberOfTuples();
  if (!AllocateBatch(
        { { origins, 3 }, { directions, 3 }, { statuses, 1 } }, n, "BackProjectPixels", error))
  {
    this->LastError = error;
    vtkErrorMacro(<< error);
    return false;
  }
  double* origin = origins->GetPointer(0);
  double* direction = directions->GetPointer(0);
  int* status = statuses->GetPointer(0);
  vtkCatadioptricParallel::For(0, n, 256, [&](vtkIdType b, vtkIdType e) {
    std::vector<catar::Vec2> in(static_cast<std::size_t>(e - b));
    for (vtkIdType i = b; i < e; ++i)
    {
      double p[2];
      pixels->GetTuple(i, p);
      in[static_cast<std::size_t>(i - b)] = catar::Vec2(p[0], p[1]);
    }
    std::vector<catar::BackProjectedRay> out(in.size());
    proj.BackProjectWorld(in.size(), in.data(), out.data());
    for (vtkIdType i = b; i < e; ++i)
    {
      const catar::BackProjectedRay& r = out[static_cast<std::size_t>(i - b)];
      std::copy(r.mirrorPoint.data(), r.mirrorPoint.data() + 3, origin + 3 * i);
      std::copy(r.direction.data(), r.direction.data() + 3, direction + 3 * i);
      status[i] = static_cast<int>(r.status);
    }
  });
  return true;
}

void vtkCatadioptricCamera::WriteToFieldData(vtkFieldData* fd)
{
  if (!fd)
  {
    return;
  }
  const double intr[7] = { this->FocalLength[0], this->FocalLength[1], this->PrincipalPoint[0],
    this->PrincipalPoint[1], this->Skew, static_cast<double>(this->ImageWidth),
    static_cast<double>(this->ImageHeight) };
  AddArray(fd, kIntrinsicsName, intr, 7);
  AddArray(fd, kDistortionName, this->Distortion, catar::Distortion::kCount);
  vtkNew<vtkStringArray> lens;
  lens->SetName(kLensName);
  lens->InsertNextValue(catar::LensName(static_cast<catar::LensType>(this->Lens)));
  fd->RemoveArray(kLensName);
  fd->AddArray(lens);
  vtkNew<vtkStringArray> type;
  type->SetName(kMirrorTypeName);
  type->InsertNextValue(this->MirrorType);
  fd->RemoveArray(kMirrorTypeName);
  fd->AddArray(type);
  AddArray(fd, kMirrorParametersName, this->MirrorParameters.data(),
    static_cast<int>(this->MirrorParameters.size()));
  double pose[16];
  this->GetWorldToCameraElements(pose);
  AddArray(fd, kPoseName, pose, 16);
}

bool vtkCatadioptricCamera::ReadFromFieldData(vtkFieldData* fd)
{
  double intr[7], pose[16];
  double dist[catar::Distortion::kCount] = {};
  vtkDataArray* distArray =
    fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(kDistortionName)) : nullptr;
  const int distCount =
    distArray && distArray->GetNumberOfValues() == 5 ? 5 : catar::Distortion::kCount;
  vtkStringArray* lensArray =
    fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(kLensName)) : nullptr;
  catar::LensType lens = catar::LensType::Pinhole;
  if (lensArray &&
    (lensArray->GetNumberOfValues() != 1 || !catar::LensFromName(lensArray->GetValue(0), lens)))
  {
    this->LastError = "field data holds an unknown lens model";
    return false;
  }
  vtkStringArray* typeArray =
    fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(kMirrorTypeName)) : nullptr;
  vtkDataArray* parameterArray =
    fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(kMirrorParametersName)) : nullptr;
  const catar::MirrorType* type = typeArray && typeArray->GetNumberOfValues() == 1 && parameterArray
    ? catar::FindMirrorType(
        typeArray->GetValue(0), static_cast<std::size_t>(parameterArray->GetNumberOfValues()))
    : nullptr;
  std::vector<double> mirror(type ? static_cast<std::size_t>(type->ParameterCount()) : 0);
  if (!GetArray(fd, kIntrinsicsName, intr, 7) || !GetArray(fd, kDistortionName, dist, distCount) ||
    !type || !GetArray(fd, kMirrorParametersName, mirror.data(), static_cast<int>(mirror.size())) ||
    !GetArray(fd, kPoseName, pose, 16))
  {
    this->LastError = "field data holds no camera (run vtkCatadioptricProjection first)";
    return false;
  }
  if (!(intr[5] >= 1 && intr[6] >= 1 && intr[5] <= catar::kMaxImageSide &&
        intr[6] <= catar::kMaxImageSide))
  {
    this->LastError = "field data camera has an invalid image size";
    return false;
  }
  this->FocalLength[0] = intr[0];
  this->FocalLength[1] = intr[1];
  this->PrincipalPoint[0] = intr[2];
  this->PrincipalPoint[1] = intr[3];
  this->Skew = intr[4];
  this->ImageWidth = static_cast<int>(intr[5]);
  this->ImageHeight = static_cast<int>(intr[6]);
  this->Lens = static_cast<int>(lens);
  std::copy(dist, dist + catar::Distortion::kCount, this->Distortion);
  this->MirrorType = type->name;
  this->MirrorParameters = mirror;
  this->WorldToCamera->DeepCopy(pose);
  this->Modified();
  return this->IsValid();
}

void vtkCatadioptricCamera::DeepCopy(vtkCatadioptricCamera* other)
{
  if (other && other != this)
  {
    this->SetModel(other->GetModel());
  }
}

void vtkCatadioptricCamera::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ImageSize: " << this->ImageWidth << " x " << this->ImageHeight << "\n";
  os << indent << "FocalLength: " << this->FocalLength[0] << ", " << this->FocalLength[1] << "\n";
  os << indent << "PrincipalPoint: " << this->PrincipalPoint[0] << ", " << this->PrincipalPoint[1]
     << "\n";
  os << indent << "Skew: " << this->Skew << "\n";
  os << indent << "Lens: " << catar::LensName(static_cast<catar::LensType>(this->Lens)) << "\n";
  os << indent << "Distortion:";
  for (double d : this->Distortion)
  {
    os << " " << d;
  }
  os << "\n";
  os << indent << "MirrorType: " << this->MirrorType << "\n";
  os << indent << "MirrorParameters:";
  for (double v : this->MirrorParameters)
  {
    os << " " << v;
  }
  os << "\n";
  os << indent << "WorldToCamera:\n";
  this->WorldToCamera->PrintSelf(os, indent.GetNextIndent());
}
