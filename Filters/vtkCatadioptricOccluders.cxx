#include "vtkCatadioptricOccluders.h"

#include "RayScene.h"

#include "vtkCallbackCommand.h"
#include "vtkCatadioptricLightingSupport.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

vtkStandardNewMacro(vtkCatadioptricOccluders);

struct vtkCatadioptricOccluders::Internals
{
  using Source = std::tuple<vtkPoints*, vtkMTimeType, vtkMTimeType>;

  std::vector<vtkSmartPointer<vtkPolyData>> Meshes;
  catar::RayScene Scene;
  // What the scene was built from: per mesh its points object, their MTime and the polygons'.
  std::vector<Source> Sources;
  std::vector<Source> Current; // scratch: the same, now
  bool Built = false;
  int Builds = 0;
  std::mutex Mutex; // one Update() at a time

  // The objects whose MTimes make up the meshes' geometry (each mesh, its points and their data
  // array, its polygons and their offsets and connectivity arrays) are watched: a modification
  // of any marks the structure stale and modifies the occluders object. GetMTime() and an
  // Update() that finds it not stale then cost no pass over the meshes, so that N lighting
  // filters sharing N meshes do not cost N x N checks a frame.
  vtkCatadioptricOccluders* Self = nullptr;
  vtkNew<vtkCallbackCommand> Callback;
  std::vector<vtkWeakPointer<vtkObject>> Watched; // six per mesh (null where none)
  std::vector<unsigned long> Tags;
  std::atomic<bool> Stale{ true };

  static void OnModified(vtkObject*, unsigned long, void* clientData, void*)
  {
    auto* in = static_cast<Internals*>(clientData);
    in->Stale = true;
    in->Self->Modified();
  }

  // What mesh is made of now, appended to parts.
  static void PartsOf(vtkPolyData* mesh, std::vector<vtkObject*>& parts)
  {
    vtkPoints* pts = mesh->GetPoints();
    vtkCellArray* polys = mesh->GetPolys();
    parts.insert(parts.end(),
      { mesh, pts, pts ? pts->GetData() : nullptr, polys, polys->GetOffsetsArray(),
        polys->GetConnectivityArray() });
  }

  void Watch(vtkObject* object)
  {
    this->Watched.emplace_back(object);
    this->Tags.push_back(
      object ? object->AddObserver(vtkCommand::ModifiedEvent, this->Callback) : 0);
  }

  void Unwatch()
  {
    for (size_t i = 0; i < this->Watched.size(); ++i)
    {
      if (vtkObject* object = this->Watched[i])
      {
        object->RemoveObserver(this->Tags[i]);
      }
    }
    this->Watched.clear();
    this->Tags.clear();
  }

  void WatchMesh(vtkPolyData* mesh)
  {
    std::vector<vtkObject*> parts;
    PartsOf(mesh, parts);
    for (vtkObject* part : parts)
    {
      this->Watch(part);
    }
  }

  // Watches what the meshes are made of now, when that is not what is watched.
  void Rewatch()
  {
    std::vector<vtkObject*> parts;
    for (vtkPolyData* mesh : this->Meshes)
    {
      PartsOf(mesh, parts);
    }
    bool same = parts.size() == this->Watched.size();
    for (size_t i = 0; i < parts.size() && same; ++i)
    {
      same = this->Watched[i].Get() == parts[i];
    }
    if (!same)
    {
      this->Unwatch();
      for (vtkObject* part : parts)
      {
        this->Watch(part);
      }
    }
  }
};

vtkCatadioptricOccluders::vtkCatadioptricOccluders()
  : Internal(new Internals)
{
  this->Internal->Self = this;
  this->Internal->Callback->SetCallback(Internals::OnModified);
  this->Internal->Callback->SetClientData(this->Internal.get());
}

vtkCatadioptricOccluders::~vtkCatadioptricOccluders()
{
  this->Internal->Unwatch();
}

void vtkCatadioptricOccluders::AddMesh(vtkPolyData* mesh)
{
  if (mesh)
  {
    this->Internal->Meshes.emplace_back(mesh);
    this->Internal->WatchMesh(mesh);
    this->Internal->Stale = true;
    this->Modified();
  }
}

void vtkCatadioptricOccluders::RemoveAllMeshes()
{
  if (!this->Internal->Meshes.empty())
  {
    this->Internal->Meshes.clear();
    this->Internal->Unwatch();
    this->Internal->Stale = true;
    this->Modified();
  }
}

int vtkCatadioptricOccluders::GetNumberOfMeshes()
{
  return static_cast<int>(this->Internal->Meshes.size());
}

vtkPolyData* vtkCatadioptricOccluders::GetMesh(int index)
{
  return index >= 0 && index < this->GetNumberOfMeshes() ? this->Internal->Meshes[index].Get()
                                                         : nullptr;
}

bool vtkCatadioptricOccluders::Update()
{
  Internals& in = *this->Internal;
  std::lock_guard<std::mutex> lock(in.Mutex);
  if (in.Built && !in.Stale)
  {
    return true;
  }
  // Cleared before looking: a modification from now on marks it again.
  in.Stale = false;
  in.Current.clear();
  for (vtkPolyData* mesh : in.Meshes)
  {
    vtkPoints* pts = mesh->GetPoints();
    in.Current.emplace_back(pts, pts ? pts->GetMTime() : 0, mesh->GetPolys()->GetMTime());
  }
  // The points or polygons of a mesh may be other objects now: watch those.
  in.Rewatch();
  if (in.Built && in.Current == in.Sources)
  {
    return true;
  }
  const std::vector<vtkPolyData*> meshes(in.Meshes.begin(), in.Meshes.end());
  std::string error;
  in.Built = vtkCatadioptricLightingSupport::BuildRayScene(meshes, in.Scene, error);
  if (!in.Built)
  {
    in.Sources.clear();
    vtkErrorMacro("Cannot build the occluders' ray scene: " << error);
    return false;
  }
  in.Sources.swap(in.Current);
  ++in.Builds;
  return true;
}

vtkIdType vtkCatadioptricOccluders::GetNumberOfTriangles()
{
  return static_cast<vtkIdType>(this->Internal->Scene.GetNumberOfTriangles());
}

int vtkCatadioptricOccluders::GetNumberOfBuilds()
{
  return this->Internal->Builds;
}

const catar::RayScene& vtkCatadioptricOccluders::GetRayScene()
{
  return this->Internal->Scene;
}

void vtkCatadioptricOccluders::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Meshes: " << this->Internal->Meshes.size() << "\n";
  os << indent << "Triangles: " << this->Internal->Scene.GetNumberOfTriangles() << "\n";
  os << indent << "Builds: " << this->Internal->Builds << "\n";
}
