#include "vtkCatadioptricSceneObjects.h"

#include "Markers.h"

#include "MeshFileCheck.h"
#include "SafeCast.h"
#include "SceneDescription.h"

#include <Eigen/Geometry>

#include "vtkCallbackCommand.h"
#include "vtkCatadioptricAllocation.h"
#include "vtkCatadioptricArrayNames.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricErrorText.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkCylinderSource.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkPolyDataNormals.h"
#include "vtkPolyDataReader.h"
#include "vtkSTLReader.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTextureMapToSphere.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
// Collects the error messages an algorithm reports, without VTK's decoration, "; " between.
struct ErrorCollector
{
  std::string Messages;
  static void Callback(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    auto* self = static_cast<ErrorCollector*>(clientData);
    if (callData)
    {
      self->Messages += (self->Messages.empty() ? "" : "; ") +
        vtkCatadioptricErrorText::Short(static_cast<const char*>(callData));
    }
  }
};

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& file)
{
  if (!vtksys::SystemTools::FileExists(file, true))
  {
    throw std::runtime_error("mesh file not found: " + file);
  }
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(file));
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".stl")
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == ".vtk")
  {
    auto r = vtkSmartPointer<vtkPolyDataReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else
  {
    throw std::runtime_error(
      "unsupported mesh format '" + ext + "' (ply, obj, stl, vtp, vtk): " + file);
  }
  // Counts the header announces are checked against the file first (some readers trust them),
  // the reader's errors are collected, and the mesh it made is checked before any filter reads
  // it through its point ids.
  std::string error;
  if (!catar::CheckMeshFile(file, error))
  {
    throw std::runtime_error(error);
  }
  ErrorCollector errors;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(&ErrorCollector::Callback);
  callback->SetClientData(&errors);
  reader->AddObserver(vtkCommand::ErrorEvent, callback);
  reader->Update();
  vtkSmartPointer<vtkPolyData> out = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (reader->GetErrorCode() != 0 || !errors.Messages.empty())
  {
    throw std::runtime_error("cannot read " + file + ": " +
      (errors.Messages.empty() ? std::string("reader error") : errors.Messages));
  }
  if (!out || out->GetNumberOfPolys() + out->GetNumberOfStrips() == 0)
  {
    throw std::runtime_error("no surface read from " + file);
  }
  if (!vtkCatadioptricMeshCheck::CheckPointIds(out, error))
  {
    throw std::runtime_error(file + ": " + error);
  }
  // Arrays a reader made shorter than the points or cells (an OBJ file's normals that its faces
  // do not index) describe nothing usable: dropped, as if absent.
  for (vtkDataSetAttributes* data : { static_cast<vtkDataSetAttributes*>(out->GetPointData()),
         static_cast<vtkDataSetAttributes*>(out->GetCellData()) })
  {
    const vtkIdType n =
      data == out->GetPointData() ? out->GetNumberOfPoints() : out->GetNumberOfCells();
    for (int a = data->GetNumberOfArrays() - 1; a >= 0; --a)
    {
      if (data->GetAbstractArray(a)->GetNumberOfTuples() < n)
      {
        data->RemoveArray(a);
      }
    }
  }
  return out;
}

vtkSmartPointer<vtkPolyData> Procedural(const catar::SceneObject& o)
{
  vtkSmartPointer<vtkPolyDataAlgorithm> source;
  const int res = o.resolution;
  if (o.type == "box")
  {
    auto s = vtkSmartPointer<vtkTessellatedBoxSource>::New();
    s->SetBounds(-0.5 * o.size.x(), 0.5 * o.size.x(), -0.5 * o.size.y(), 0.5 * o.size.y(),
      -0.5 * o.size.z(), 0.5 * o.size.z());
    s->SetLevel(std::max(0, res - 1));
    s->QuadsOff();
    s->DuplicateSharedPointsOn();
    source = s;
  }
  else if (o.type == "sphere")
  {
    auto s = vtkSmartPointer<vtkSphereSource>::New();
    s->SetRadius(o.radius);
    s->SetThetaResolution(std::max(3, 2 * res));
    s->SetPhiResolution(std::max(3, res));
    source = s;
  }
  else if (o.type == "torus")
  {
    vtkNew<vtkParametricTorus> torus;
    torus->SetRingRadius(o.radius);
    torus->SetCrossSectionRadius(o.tubeRadius);
    auto s = vtkSmartPointer<vtkParametricFunctionSource>::New();
    s->SetParametricFunction(torus);
    s->SetUResolution(std::max(3, res));
    s->SetVResolution(std::max(3, res / 2));
    s->SetGenerateTextureCoordinates(!o.texture.empty());
    source = s;
  }
  else if (o.type == "cylinder")
  {
    auto s = vtkSmartPointer<vtkCylinderSource>::New();
    s->SetRadius(o.radius);
    s->SetHeight(o.height);
    s->SetResolution(std::max(3, res));
    s->CappingOn();
    source = s;
  }
  else if (o.type == "marker")
  {
    // The black square of side size and a white margin of one cell: (cells + 2) / cells wider.
    const int cells = catar::MarkerCells(o.markerDictionary);
    const double h = 0.5 * o.size.x() * (cells + 2) / std::max(1, cells);
    auto s = vtkSmartPointer<vtkPlaneSource>::New();
    s->SetOrigin(-h, -h, 0);
    s->SetPoint1(h, -h, 0);
    s->SetPoint2(-h, h, 0);
    s->SetResolution(res, res);
    source = s;
  }
  else // plane
  {
    auto s = vtkSmartPointer<vtkPlaneSource>::New();
    s->SetOrigin(-0.5 * o.size.x(), -0.5 * o.size.y(), 0);
    s->SetPoint1(0.5 * o.size.x(), -0.5 * o.size.y(), 0);
    s->SetPoint2(-0.5 * o.size.x(), 0.5 * o.size.y(), 0);
    s->SetResolution(res, res);
    source = s;
  }
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(source->GetOutputPort());
  tri->PassVertsOff();
  tri->PassLinesOff();
  tri->Update();
  return tri->GetOutput();
}

// Colours as a cell array "Colors" (RGBA, uchar): solid, per box face, or a checker.
void Colorize(vtkPolyData* mesh, const catar::SceneObject& o)
{
  static const double palette[6][3] = { { 0.85, 0.15, 0.15 }, { 0.15, 0.7, 0.2 },
    { 0.15, 0.35, 0.9 }, { 0.95, 0.85, 0.1 }, { 0.1, 0.8, 0.85 }, { 0.8, 0.2, 0.8 } };
  const vtkIdType n = mesh->GetNumberOfCells();
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName(vtkCatadioptricArrayNames::Colors);
  colors->SetNumberOfComponents(4);
  vtkCatadioptricAllocation::Tuples(colors, n);
  vtkNew<vtkIdList> ids;
  const unsigned char alpha = static_cast<unsigned char>(std::lround(255.0 * o.opacity));
  for (vtkIdType c = 0; c < n; ++c)
  {
    double rgb[3] = { o.color.x(), o.color.y(), o.color.z() };
    mesh->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() >= 3 && (o.faceColors || o.pattern == "checker"))
    {
      double p[3][3];
      for (int k = 0; k < 3; ++k)
      {
        mesh->GetPoint(ids->GetId(k), p[k]);
      }
      if (o.faceColors)
      {
        // The face of an axis-aligned box (object coordinates): the dominant normal axis.
        double e1[3], e2[3], nrm[3];
        for (int k = 0; k < 3; ++k)
        {
          e1[k] = p[1][k] - p[0][k];
          e2[k] = p[2][k] - p[0][k];
        }
        nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
        int axis = 0;
        for (int k = 1; k < 3; ++k)
        {
          if (std::abs(nrm[k]) > std::abs(nrm[axis]))
          {
            axis = k;
          }
        }
        const double centre = (p[0][axis] + p[1][axis] + p[2][axis]) / 3.0;
        const int face = 2 * axis + (centre > 0 ? 0 : 1);
        std::copy(palette[face], palette[face] + 3, rgb);
      }
      if (o.pattern == "checker")
      {
        long long parity = 0;
        for (int k = 0; k < 3; ++k)
        {
          // Parity only: cells of NaN or huge coordinates get a defined value.
          parity += catar::FloorToInteger((p[0][k] + p[1][k] + p[2][k]) / 3.0 / o.patternSize) & 1;
        }
        if (parity & 1)
        {
          for (double& v : rgb)
          {
            v *= 0.55;
          }
        }
      }
    }
    const unsigned char rgba[4] = { static_cast<unsigned char>(std::lround(255.0 * rgb[0])),
      static_cast<unsigned char>(std::lround(255.0 * rgb[1])),
      static_cast<unsigned char>(std::lround(255.0 * rgb[2])), alpha };
    colors->SetTypedTuple(c, rgba);
  }
  mesh->GetCellData()->AddArray(colors);
}

// Texture coordinates per face of an axis-aligned box centred at the origin (the paper's section
// 3.3): each face maps its two in-plane coordinates to [0, 1]. The box's points are duplicated
// per face, so every point belongs to one face.
void BoxTextureCoordinates(vtkPolyData* box, const catar::Vec3& size)
{
  vtkNew<vtkFloatArray> tc;
  tc->SetName("TCoords");
  tc->SetNumberOfComponents(2);
  vtkCatadioptricAllocation::Tuples(tc, box->GetNumberOfPoints());
  tc->FillValue(0.0f);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < box->GetNumberOfCells(); ++c)
  {
    box->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() < 3)
    {
      continue;
    }
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      box->GetPoint(ids->GetId(k), p[k]);
    }
    catar::Vec3 n =
      (catar::Vec3(p[1][0], p[1][1], p[1][2]) - catar::Vec3(p[0][0], p[0][1], p[0][2]))
        .cross(catar::Vec3(p[2][0], p[2][1], p[2][2]) - catar::Vec3(p[0][0], p[0][1], p[0][2]));
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double q[3];
      box->GetPoint(ids->GetId(k), q);
      tc->SetTuple2(ids->GetId(k), q[a] / size[a] + 0.5, q[b] / size[b] + 0.5);
    }
  }
  box->GetPointData()->SetTCoords(tc);
}

// A 256 x 256 RGB checkerboard of 8 x 8 squares, white and light grey, with thin dark lines.
vtkSmartPointer<vtkImageData> CheckerTexture()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(256, 256, 1);
  vtkCatadioptricAllocation::Scalars(image, VTK_UNSIGNED_CHAR, 3);
  unsigned char* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int j = 0; j < 256; ++j)
  {
    for (int i = 0; i < 256; ++i)
    {
      const bool line = (i % 32) < 2 || (j % 32) < 2;
      const bool odd = ((i / 32) + (j / 32)) & 1;
      const unsigned char v = line ? 60 : (odd ? 170 : 255);
      std::fill(p, p + 3, v);
      p += 3;
    }
  }
  return image;
}

// An ArUco marker with a white margin of one cell, 32 texels a cell (Markers.h), grey as RGB;
// VTK's rows (bottom first), so that texture coordinate v = 1 is the marker's top.
vtkSmartPointer<vtkImageData> MarkerTexture(const catar::SceneObject& o)
{
  const int side = 32 * (catar::MarkerCells(o.markerDictionary) + 2);
  std::vector<std::uint8_t> grey;
  std::string error;
  if (!catar::MarkerImage(o.markerDictionary, o.markerId, side, 1, grey, error))
  {
    throw std::runtime_error("marker: " + error);
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(side, side, 1);
  vtkCatadioptricAllocation::Scalars(image, VTK_UNSIGNED_CHAR, 3);
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int j = 0; j < side; ++j)
  {
    const std::uint8_t* row = grey.data() + static_cast<std::size_t>(side - 1 - j) * side;
    for (int i = 0; i < side; ++i, p += 3)
    {
      std::fill(p, p + 3, row[i]);
    }
  }
  return image;
}

vtkSmartPointer<vtkImageData> ReadTexture(const std::string& file)
{
  if (file == "checker")
  {
    return CheckerTexture();
  }
  std::string error;
  vtkSmartPointer<vtkImageData> image = vtkCatadioptricImageSupport::ReadImageFile(file, error);
  if (!image)
  {
    throw std::runtime_error("texture: " + error);
  }
  vtkDataArray* s = image->GetPointData()->GetScalars();
  if (!s || s->GetDataType() != VTK_UNSIGNED_CHAR)
  {
    throw std::runtime_error("texture must be an 8-bit image: " + file);
  }
  return image;
}

vtkSmartPointer<vtkPolyData> BuildObject(const catar::SceneObject& o)
{
  vtkSmartPointer<vtkPolyData> local;
  if (o.type == "mesh")
  {
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputData(ReadMesh(o.file));
    tri->PassVertsOff();
    tri->PassLinesOff();
    tri->Update();
    local = tri->GetOutput();
  }
  else
  {
    local = Procedural(o);
  }
  Colorize(local, o);
  if (!o.texture.empty())
  {
    if (o.type == "box")
    {
      BoxTextureCoordinates(local, o.size);
    }
    else if (!local->GetPointData()->GetTCoords())
    {
      vtkNew<vtkTextureMapToSphere> map;
      map->SetInputData(local);
      map->PreventSeamOn();
      map->Update();
      local = vtkPolyData::SafeDownCast(map->GetOutput());
    }
  }
  vtkNew<vtkTransform> t;
  t->PostMultiply();
  t->Scale(o.scale.x(), o.scale.y(), o.scale.z());
  t->RotateX(o.rotate.x());
  t->RotateY(o.rotate.y());
  t->RotateZ(o.rotate.z());
  t->Translate(o.translate.x(), o.translate.y(), o.translate.z());
  vtkNew<vtkTransformPolyDataFilter> xf;
  xf->SetTransform(t);
  xf->SetInputData(local);
  xf->Update();
  vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(xf->GetOutput());
  return out;
}
/// Collects warnings (repairs made) as short lines, without VTK's prefix, instead of printing
/// them: the scene's remeshing report lists them.
struct WarningCollector
{
  std::vector<std::string> Lines;
  static void Callback(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    if (!callData)
    {
      return;
    }
    static_cast<WarningCollector*>(clientData)
      ->Lines.push_back(vtkCatadioptricErrorText::Short(static_cast<const char*>(callData)));
  }
};

double FieldValue(vtkPolyData* mesh, const char* name)
{
  vtkDataArray* a = mesh->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() > 0 ? a->GetComponent(0, 0) : -1.0;
}
} // namespace

vtkSmartPointer<vtkPolyData> vtkCatadioptricSceneObjects::BuildObject(
  const catar::SceneObject& object)
{
  return ::BuildObject(object);
}

vtkSmartPointer<vtkImageData> vtkCatadioptricSceneObjects::Texture(const catar::SceneObject& o)
{
  return o.type == "marker" ? MarkerTexture(o) : ::ReadTexture(o.texture);
}

vtkSmartPointer<vtkImageData> vtkCatadioptricSceneObjects::ReadTexture(const std::string& file)
{
  return ::ReadTexture(file);
}

vtkSmartPointer<vtkPolyData> vtkCatadioptricSceneObjects::Remesh(vtkPolyData* mesh,
  const catar::SceneRemesh& remesh, vtkCatadioptricCamera* camera, std::string& report,
  vtkCommand* progress)
{
  report.clear();
  if (remesh.mode == "none")
  {
    return mesh;
  }
  vtkNew<vtkCatadioptricRemesher> remesher;
  remesher->SetInputData(mesh);
  remesher->SetIterations(remesh.iterations);
  remesher->SetMaximumTriangles(static_cast<vtkIdType>(remesh.maxTriangles));
  remesher->SetFeatureAngle(remesh.featureAngle);
  if (remesh.mode == "area")
  {
    remesher->SetModeToTargetArea();
    remesher->SetTargetArea(remesh.targetArea);
  }
  else
  {
    remesher->SetModeToPixelTolerance();
    remesher->SetPixelTolerance(remesh.pixelTolerance);
    remesher->SetCamera(camera);
  }
  ErrorCollector errors;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(&ErrorCollector::Callback);
  callback->SetClientData(&errors);
  remesher->AddObserver(vtkCommand::ErrorEvent, callback);
  WarningCollector warnings;
  vtkNew<vtkCallbackCommand> warningCallback;
  warningCallback->SetCallback(&WarningCollector::Callback);
  warningCallback->SetClientData(&warnings);
  remesher->AddObserver(vtkCommand::WarningEvent, warningCallback);
  if (progress)
  {
    remesher->AddObserver(vtkCommand::ProgressEvent, progress);
  }
  remesher->Update();
  if (remesher->GetAbortExecute())
  {
    throw std::runtime_error("stopped while remeshing");
  }
  if (remesher->GetErrorCode() != 0 || !errors.Messages.empty())
  {
    const std::string said = "Remeshing failed: ";
    throw std::runtime_error("remeshing failed: " +
      (errors.Messages.rfind(said, 0) == 0 ? errors.Messages.substr(said.size())
                                           : errors.Messages));
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(remesher->GetOutput());
  std::ostringstream line;
  line << mesh->GetNumberOfPolys() << " -> " << out->GetNumberOfPolys() << " triangles";
  if (auto* steps =
        vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("RemeshSteps")))
  {
    line << " (" << steps->GetValue(0) << ")";
  }
  line << ", mean area " << FieldValue(out, "MeanTriangleArea") << " m^2";
  if (remesh.mode == "pixels")
  {
    line << ", largest edge bend " << FieldValue(out, "MaximumEdgeBend") << " px (tolerance "
         << remesh.pixelTolerance << ")";
  }
  for (std::size_t i = 0; i < warnings.Lines.size(); ++i)
  {
    line << (i == 0 ? "; repaired: " : ", ") << warnings.Lines[i];
  }
  report = line.str();
  return out;
}
