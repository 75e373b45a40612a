// ParaView's GUI on its first day: the demo scene opened with the scene reader and applied as a
// user clicks Apply (ParaView's own properties panel and apply step, pqApplyBehavior), with the
// plugin loaded as the GUI loads it. Its frame must show in its own colours with no colour legend,
// and its objects in their scene colours (cell array Colors, Map Scalars off), not a colour a
// block. The apply step itself is ParaView's: without the plugin's GUI part the frame has an
// "RGBA Magnitude" legend and the objects block colours.
//   TestParaViewApply PLUGIN.so SCENE.yaml
#include "pqActiveObjects.h"
#include "pqApplyBehavior.h"
#include "pqDataRepresentation.h"
#include "pqInterfaceTracker.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPVApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqPluginManager.h"
#include "pqPropertiesPanel.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqServerResource.h"
#include "pqStandardPropertyWidgetInterface.h"
#include "vtkDataObject.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QApplication>
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QString>

#include <cstring>
#include <iostream>
#include <string>

namespace
{
int failures = 0;

void Check(bool holds, const std::string& what)
{
  std::cout << (holds ? "ok:   " : "FAIL: ") << what << "\n";
  failures += holds ? 0 : 1;
}

// The representation of one output port of the source in the view, or null.
pqDataRepresentation* Shown(pqPipelineSource* source, int port, pqView* view)
{
  pqOutputPort* output = source->getOutputPort(port);
  return output ? output->getRepresentation(view) : nullptr;
}

std::string ColourArray(vtkSMProxy* representation)
{
  const char* name =
    vtkSMPropertyHelper(representation, "ColorArrayName").GetInputArrayNameToProcess();
  return name ? name : "";
}
}

int main(int argc, char* argv[])
{
  if (argc != 3)
  {
    std::cerr << "usage: TestParaViewApply PLUGIN.so SCENE.yaml\n";
    return 2;
  }
  const QString plugin = QString::fromLocal8Bit(argv[1]);
  const QString scene = QString::fromLocal8Bit(argv[2]);

  // ParaView's options parse the command line: it gets the program's name alone.
  int coreArgc = 1;
  char* coreArgv[] = { argv[0], nullptr };
  QApplication application(coreArgc, coreArgv);
  pqPVApplicationCore core(coreArgc, coreArgv);
  // The GUI's standard panel widgets (decorators), as ParaView's main window registers them.
  core.interfaceTracker()->addInterface(
    new pqStandardPropertyWidgetInterface(core.interfaceTracker()));
  pqObjectBuilder* builder = core.getObjectBuilder();
  pqServer* server = builder->createServer(pqServerResource("builtin:"));
  pqActiveObjects::instance().setActiveServer(server);

  QString error;
  const bool loaded = core.getPluginManager()->loadExtension(server, plugin, &error, false) !=
    pqPluginManager::NOTLOADED;
  Check(loaded, "the plugin loads as the GUI loads it " + error.toStdString());
  if (!loaded)
  {
    return 1;
  }

  pqView* view = builder->createView(pqRenderView::renderViewType(), server);
  pqActiveObjects::instance().setActiveView(view);
  pqPropertiesPanel panel;
  pqApplyBehavior applyBehavior;
  applyBehavior.registerPanel(&panel);

  pqPipelineSource* reader =
    builder->createReader("sources", "CatadioptricSceneReader", QStringList(scene), server);
  Check(reader != nullptr, "the scene reader opens " + scene.toStdString());
  if (!reader)
  {
    return 1;
  }
  pqActiveObjects::instance().setActiveSource(reader);
  panel.apply();
  // The plugin's part runs once the apply step has returned to the event loop.
  QElapsedTimer waited;
  waited.start();
  while (waited.elapsed() < 500)
  {
    QCoreApplication::processEvents();
  }

  pqDataRepresentation* image = Shown(reader, 0, view);
  pqDataRepresentation* objects = Shown(reader, 1, view);
  Check(image && objects, "Apply shows both outputs (Image and Objects) in the render view");
  if (image)
  {
    vtkSMProxy* proxy = image->getProxy();
    Check(std::strcmp(proxy->GetXMLName(), "CatadioptricImageRepresentation") == 0,
      std::string("the frame shows with the plugin's image representation (") +
        proxy->GetXMLName() + ")");
    Check(vtkSMPropertyHelper(proxy, "MapScalars").GetAsInt() == 0,
      "the frame shows its own RGBA (Map Scalars off)");
    Check(!vtkSMPVRepresentationProxy::IsScalarBarVisible(proxy, view->getProxy()),
      "the frame has no colour legend (coloured by '" + ColourArray(proxy) + "')");
  }
  if (objects)
  {
    vtkSMProxy* proxy = objects->getProxy();
    Check(ColourArray(proxy) == "Colors" &&
        vtkSMPropertyHelper(proxy, "ColorArrayName").GetInputArrayAssociation() ==
          vtkDataObject::CELL,
      "the objects are coloured by their cell array Colors (coloured by '" + ColourArray(proxy) +
        "')");
    Check(vtkSMPropertyHelper(proxy, "MapScalars").GetAsInt() == 0,
      "the objects show their scene colours (Map Scalars off)");
    Check(!vtkSMPVRepresentationProxy::IsScalarBarVisible(proxy, view->getProxy()),
      "the objects have no colour legend");
  }
  applyBehavior.unregisterPanel(&panel);
  builder->destroySources(server);
  std::cout << (failures ? "FAILED" : "passed") << "\n";
  return failures ? 1 : 0;
}
