// Helpers shared by the VTK tests.
#ifndef catarTestUtilities_h
#define catarTestUtilities_h

#include "TestCameras.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCommand.h"
#include "vtkObject.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <string>

namespace catar_test
{
/// Counts the error events of the objects it observes and keeps the last message.
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    ++this->Count;
    this->Last = callData ? static_cast<const char*>(callData) : "";
  }
  void Watch(vtkObject* object) { object->AddObserver(vtkCommand::ErrorEvent, this); }
  int Count = 0;
  std::string Last;
};

/// Counts the warning events of the objects it observes and keeps them all.
class WarningCounter : public vtkCommand
{
public:
  static WarningCounter* New() { return new WarningCounter; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    ++this->Count;
    this->All += callData ? static_cast<const char*>(callData) : "";
  }
  void Watch(vtkObject* object) { object->AddObserver(vtkCommand::WarningEvent, this); }
  int Count = 0;
  std::string All;
};
/// The demo camera (TestCameras.h: DemoCameraModel()): 1328 x 1048, a 5 cm mirror 14 cm ahead.
inline vtkSmartPointer<vtkCatadioptricCamera> DemoCamera()
{
  auto camera = vtkSmartPointer<vtkCatadioptricCamera>::New();
  camera->SetModel(DemoCameraModel());
  return camera;
}

/// Makes `camera` the demo rig with the smaller image (TestCameras.h: SmallDemoCameraModel()).
inline void SetSmallDemoCamera(vtkCatadioptricCamera* camera)
{
  camera->SetModel(SmallDemoCameraModel());
}

} // namespace catar_test

#endif
