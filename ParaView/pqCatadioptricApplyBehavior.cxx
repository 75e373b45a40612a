#include "pqCatadioptricApplyBehavior.h"

#include "pqApplicationCore.h"
#include "pqDataRepresentation.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"
#include "pqView.h"
#include "vtkDataObject.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QTimer>

#include <cstring>
#include <string>

namespace
{
// The representation of the plugin's images (Representations.xml); its Map Scalars is off.
constexpr const char* ImageRepresentation = "CatadioptricImageRepresentation";

bool IsPluginSource(pqPipelineSource* source)
{
  const char* name = source && source->getProxy() ? source->getProxy()->GetXMLName() : nullptr;
  return name && std::strncmp(name, "Catadioptric", std::strlen("Catadioptric")) == 0;
}

// Where a mesh of the plugin has its own colours: the scene reader's objects as a cell array
// "Colors", the lighting's output as a point array, both RGB(A) bytes. -1 when it has none.
int ObjectColoursAssociation(pqOutputPort* port)
{
  vtkPVDataInformation* information = port ? port->getDataInformation() : nullptr;
  for (int association : { vtkDataObject::CELL, vtkDataObject::POINT })
  {
    vtkPVArrayInformation* colours =
      information ? information->GetArrayInformation("Colors", association) : nullptr;
    if (colours && colours->GetDataType() == VTK_UNSIGNED_CHAR &&
      colours->GetNumberOfComponents() >= 3)
    {
      return association;
    }
  }
  return -1;
}
}

pqCatadioptricApplyBehavior::pqCatadioptricApplyBehavior(QObject* parent)
  : QObject(parent)
{
}

pqCatadioptricApplyBehavior::~pqCatadioptricApplyBehavior() = default;

void pqCatadioptricApplyBehavior::onStartup()
{
  pqApplicationCore* core = pqApplicationCore::instance();
  if (core && core->getServerManagerModel())
  {
    QObject::connect(core->getServerManagerModel(), &pqServerManagerModel::representationAdded,
      this, &pqCatadioptricApplyBehavior::representationAdded);
  }
}

void pqCatadioptricApplyBehavior::onShutdown()
{
  pqApplicationCore* core = pqApplicationCore::instance();
  if (core && core->getServerManagerModel())
  {
    QObject::disconnect(core->getServerManagerModel(), nullptr, this, nullptr);
  }
  this->Pending.clear();
}

void pqCatadioptricApplyBehavior::representationAdded(pqRepresentation* added)
{
  auto* representation = qobject_cast<pqDataRepresentation*>(added);
  if (!representation)
  {
    return;
  }
  if (this->Pending.isEmpty())
  {
    // After the apply step that added it has returned to the event loop (its input is set after
    // the representation is registered).
    QTimer::singleShot(0, this, &pqCatadioptricApplyBehavior::showPendingInOwnColours);
  }
  this->Pending.append(representation);
}

void pqCatadioptricApplyBehavior::showPendingInOwnColours()
{
  const QList<QPointer<pqDataRepresentation>> pending = this->Pending;
  this->Pending.clear();
  for (const QPointer<pqDataRepresentation>& representation : pending)
  {
    if (representation && pqCatadioptricApplyBehavior::ShowInOwnColours(representation))
    {
      representation->renderViewEventually();
    }
  }
}

bool pqCatadioptricApplyBehavior::ShowInOwnColours(pqDataRepresentation* representation)
{
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  pqView* view = representation ? representation->getView() : nullptr;
  if (!proxy || !view || !IsPluginSource(representation->getInput()) ||
    !proxy->GetProperty("MapScalars") || !proxy->GetProperty("ColorArrayName"))
  {
    return false;
  }
  const char* colouredBy =
    vtkSMPropertyHelper(proxy, "ColorArrayName").GetInputArrayNameToProcess();
  const std::string colourArray = colouredBy ? colouredBy : "";
  if (std::strcmp(proxy->GetXMLName(), ImageRepresentation) == 0)
  {
    // The image's RGBA shows as it is (Map Scalars off, the plugin's setting): a legend of its
    // magnitude says nothing. A colouring the user chose (a state file) keeps its legend.
    if (colourArray.empty() || vtkSMPropertyHelper(proxy, "MapScalars").GetAsInt() != 0)
    {
      return false;
    }
    vtkSMPVRepresentationProxy::SetScalarBarVisibility(proxy, view->getProxy(), false);
    return true;
  }
  // ParaView's default for a composite output (block colours) or none; a colouring the user
  // chose is kept.
  const int association = ObjectColoursAssociation(representation->getOutputPortFromInput());
  if (association < 0 || !(colourArray.empty() || colourArray == "vtkBlockColors"))
  {
    return false;
  }
  vtkSMPVRepresentationProxy::SetScalarColoring(proxy, "Colors", association);
  vtkSMPropertyHelper(proxy, "MapScalars").Set(0);
  proxy->UpdateVTKObjects();
  vtkSMPVRepresentationProxy::SetScalarBarVisibility(proxy, view->getProxy(), false);
  return true;
}
