// Ties the dock panel's session to the agent display and the mouse in the render view: while the
// panel's session runs, the toolbar's "Agent" toggle is switched on (the cone over the cached MIP,
// camera changes pushed to the session), and with the pointer device the "Trace with mouse"
// toggle too; when the session stops, "Trace with mouse" is switched off so the mouse gives the
// camera back. The toolbar actions keep the single instances of pqVesselTouchAgentDisplay and
// pqVesselTouchPointerInteraction, so the panel and the toolbar never draw or forward twice.
#ifndef pqVesselTouchViewBinding_h
#define pqVesselTouchViewBinding_h

#include <QObject>
#include <QPointer>

class pqVesselTouchDockPanel;
class vtkSMProxy;

class pqVesselTouchViewBinding : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchViewBinding(pqVesselTouchDockPanel* panel);
  ~pqVesselTouchViewBinding() override;

private Q_SLOTS:
  void setSession(vtkSMProxy* session);
  void setRunning(bool running);

private:
  /// The session's DeviceType is the pointer (mouse) device.
  bool sessionUsesPointer() const;

  vtkSMProxy* Session = nullptr;
  Q_DISABLE_COPY(pqVesselTouchViewBinding)
};

#endif
