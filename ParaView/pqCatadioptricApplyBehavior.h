// What the GUI's Apply does to the plugin's outputs, after ParaView's own apply step
// (pqApplyBehavior) has shown them: an image of the plugin (a compositor's, ray tracer's,
// environment's or the scene reader's frame) shows in its own colours without a colour legend,
// and a mesh with colours of its own (the scene reader's objects, cell array Colors; the
// lighting's output, point array Colors) shows in them, Map Scalars off, rather than in one colour
// a block. ParaView's apply step gives a legend to any scalar colouring and block colours to any
// composite output that is not scalar-coloured, and no server-manager setting changes either, so
// this is a GUI part (an auto-start of the plugin). Outputs shown from Python (paraview.simple)
// do not pass through it.
#ifndef pqCatadioptricApplyBehavior_h
#define pqCatadioptricApplyBehavior_h

#include <QList>
#include <QObject>
#include <QPointer>

class pqDataRepresentation;
class pqRepresentation;

class pqCatadioptricApplyBehavior : public QObject
{
  Q_OBJECT

public:
  explicit pqCatadioptricApplyBehavior(QObject* parent = nullptr);
  ~pqCatadioptricApplyBehavior() override;
  pqCatadioptricApplyBehavior(const pqCatadioptricApplyBehavior&) = delete;
  pqCatadioptricApplyBehavior& operator=(const pqCatadioptricApplyBehavior&) = delete;

  // The auto-start interface's calls (paraview_plugin_add_auto_start).
  void onStartup();
  void onShutdown();

  // Gives one representation of a plugin output its own colours and hides its legend; other
  // representations are left alone. True when it changed something. Public for the GUI test.
  static bool ShowInOwnColours(pqDataRepresentation* representation);

private Q_SLOTS:
  void representationAdded(pqRepresentation* representation);
  void showPendingInOwnColours();

private:
  // Representations added during an Apply, changed once the apply step is over (ParaView's
  // apply step sets the colouring and the legend after it has added them).
  QList<QPointer<pqDataRepresentation>> Pending;
};

#endif
