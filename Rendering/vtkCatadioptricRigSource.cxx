#include "vtkCatadioptricRigSource.h"

#include "Projector.h"
#include "Rig.h"

#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricParallel.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCatadioptricRigSource);

namespace
{
// The rig's points (the camera centre, the frustum's far border, then the mirror, with the
// mirror's normals) and cells (the centre; the frustum's edges and border; the mirror's outlines
// when `outline`; the mirror's triangles) into `geometry`. Returns the number of the frustum's
// lines, the first lines.
vtkIdType RigToPolyData(const catar::RigGeometry& rig, bool outline, vtkPolyData* geometry)
{
  const vtkIdType borderStart = 1;
  const vtkIdType mirrorStart = borderStart + static_cast<vtkIdType>(rig.border.size());
  const vtkIdType pointCount = mirrorStart + static_cast<vtkIdType>(rig.mirrorPoints.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkCatadioptricAllocation::Points(points, pointCount);
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkCatadioptricAllocation::Tuples(normals, pointCount);
  normals->Fill(0.0);
  points->SetPoint(0, rig.centre.data());
  for (std::size_t k = 0; k < rig.border.size(); ++k)
  {
    points->SetPoint(borderStart + static_cast<vtkIdType>(k), rig.border[k].data());
  }
  for (std::size_t k = 0; k < rig.mirrorPoints.size(); ++k)
  {
    const vtkIdType id = mirrorStart + static_cast<vtkIdType>(k);
    points->SetPoint(id, rig.mirrorPoints[k].data());
    normals->SetTuple(id, rig.mirrorNormals[k].data());
  }

  // Cells, part by part (vertices, then lines, then triangles, as vtkPolyData orders them).
  vtkNew<vtkCellArray> verts;
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkCellArray> polys;
  const vtkIdType centre = 0;
  verts->InsertNextCell(1, &centre);
  vtkIdType lineCount = 0;
  for (int c = 0; c < 4; ++c)
  {
    if (rig.corners[c] >= 0)
    {
      const vtkIdType ends[2] = { centre, borderStart + rig.corners[c] };
      lines->InsertNextCell(2, ends);
      ++lineCount;
    }
  }
  if (rig.border.size() >= 2)
  {
    lines->InsertNextCell(static_cast<vtkIdType>(rig.border.size()) + 1);
    for (std::size_t k = 0; k <= rig.border.size(); ++k)
    {
      lines->InsertCellPoint(borderStart + static_cast<vtkIdType>(k % rig.border.size()));
    }
    ++lineCount;
  }
  const vtkIdType frustumLines = lineCount;
  if (outline)
  {
    for (const std::vector<int>& loop : rig.outlines)
    {
      lines->InsertNextCell(static_cast<vtkIdType>(loop.size()) + 1);
      for (std::size_t k = 0; k <= loop.size(); ++k)
      {
        lines->InsertCellPoint(mirrorStart + loop[k % loop.size()]);
      }
      ++lineCount;
    }
  }
  polys->AllocateEstimate(static_cast<vtkIdType>(rig.mirrorTriangles.size()), 3);
  for (const auto& t : rig.mirrorTriangles)
  {
    const vtkIdType ids[3] = { mirrorStart + t[0], mirrorStart + t[1], mirrorStart + t[2] };
    polys->InsertNextCell(3, ids);
  }

  geometry->SetPoints(points);
  geometry->SetVerts(verts);
  geometry->SetLines(lines);
  geometry->SetPolys(polys);
  geometry->GetPointData()->SetNormals(normals);
  return frustumLines;
}
} // namespace

vtkCatadioptricRigSource::vtkCatadioptricRigSource()
{
  this->SetNumberOfInputPorts(0);
}

vtkCatadioptricRigSource::~vtkCatadioptricRigSource() = default;

vtkCatadioptricCameraSlotMacro(vtkCatadioptricRigSource);
vtkCatadioptricCameraSlotValidMacro(vtkCatadioptricRigSource);
vtkCatadioptricCameraSlotTrajectoryMacro(vtkCatadioptricRigSource);

void vtkCatadioptricRigSource::SetFrustumLength(double length)
{
  if (!std::isfinite(length))
  {
    vtkErrorMacro("FrustumLength must be a finite number, not " << length << ".");
    return;
  }
  if (this->FrustumLength != length)
  {
    this->FrustumLength = length;
    this->Modified();
  }
}

int vtkCatadioptricRigSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  std::string error;
  if (!this->CameraSlot.AnnounceTimeSteps(outputVector->GetInformationObject(0), error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  return 1;
}

int vtkCatadioptricRigSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!output)
  {
    return 0;
  }
  vtkCatadioptricCamera* camera = this->ResolveValidCamera(outputVector->GetInformationObject(0));
  if (!camera)
  {
    return 0;
  }
  const catar::Projector projector(camera->GetModel());
  catar::RigOptions options;
  options.mirrorResolution = this->MirrorResolution;
  options.frustumLength = this->FrustumLength;
  options.borderSamples = this->BorderResolution;
  options.threads = vtkCatadioptricParallel::GetNumberOfThreads();
  catar::RigGeometry rig;
  std::string error;
  this->UpdateProgress(0.1);
  if (!catar::BuildRig(projector, options, rig, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->FrustumLengthUsed = rig.frustumLength;
  this->UpdateProgress(0.8);
  if (this->GetAbortExecute())
  {
    return 0;
  }

  // Points (the centre, the frustum's far border, the mirror) and cells, part by part.
  vtkNew<vtkPolyData> geometry;
  const vtkIdType frustumLines = RigToPolyData(rig, this->MirrorOutline != 0, geometry);
  vtkCellArray* polys = geometry->GetPolys();
  const vtkIdType lineCount = geometry->GetNumberOfLines();
  vtkNew<vtkIntArray> parts;
  parts->SetName(vtkCatadioptricArrayNames::RigPart);
  vtkCatadioptricAllocation::Tuples(parts, 1 + lineCount + polys->GetNumberOfCells());
  vtkIdType cell = 0;
  parts->SetValue(cell++, CAMERA_CENTRE);
  for (vtkIdType k = 0; k < lineCount; ++k)
  {
    parts->SetValue(cell++, k < frustumLines ? FRUSTUM : MIRROR_OUTLINE);
  }
  for (vtkIdType k = 0; k < polys->GetNumberOfCells(); ++k)
  {
    parts->SetValue(cell++, MIRROR);
  }

  output->ShallowCopy(geometry);
  output->GetCellData()->AddArray(parts);
  output->GetCellData()->SetActiveScalars(vtkCatadioptricArrayNames::RigPart);
  camera->WriteToFieldData(output->GetFieldData());
  this->UpdateProgress(1.0);
  return 1;
}

void vtkCatadioptricRigSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->CameraSlot.GetCamera() << "\n";
  const char* file = this->CameraSlot.GetCalibrationFileName();
  os << indent << "CalibrationFileName: " << (file ? file : "(none)") << "\n";
  const char* trajectory = this->CameraSlot.GetTrajectoryFileName();
  os << indent << "TrajectoryFileName: " << (trajectory ? trajectory : "(none)") << "\n";
  os << indent << "MirrorType: "
     << (*this->CameraSlot.GetMirrorType() ? this->CameraSlot.GetMirrorType() : "(the camera's)")
     << "\n";
  os << indent << "FrustumLength: " << this->FrustumLength
     << (this->FrustumLength > 0.0 ? "" : " (automatic)") << "\n";
  os << indent << "MirrorResolution: " << this->MirrorResolution << "\n";
  os << indent << "BorderResolution: " << this->BorderResolution << "\n";
  os << indent << "MirrorOutline: " << (this->MirrorOutline ? "on" : "off") << "\n";
  os << indent << "FrustumLengthUsed: " << this->FrustumLengthUsed << "\n";
}
