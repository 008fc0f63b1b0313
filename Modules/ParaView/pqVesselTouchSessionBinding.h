// Binds the panel to THE haptic session: the "VesselTouchHapticSession" proxy registered under
// the pipeline name "VesselTouchSession" (the one vesseltouch.logic() creates), so the panel and
// the Python console drive one object. Finds it through pqServerManagerModel, follows it being
// added/removed (also by a state file), creates it when asked, and reports any change of its
// properties (from Python, a loaded state, the properties panel) with propertiesModified().
// One session at a time: when another "VesselTouchSession" is registered (File > Load State or
// LoadState() while a session exists), the new one is adopted, the old one is stopped at once and
// deleted right after, as vesseltouch.logic() does in pvpython.
#ifndef pqVesselTouchSessionBinding_h
#define pqVesselTouchSessionBinding_h

#include "pqVesselTouchCenterlineDelivery.h"

#include <QObject>
#include <QPointer>

#include "vtkNew.h"

#include <functional>

class pqPipelineSource;
class pqRenderView;
class vtkEventQtSlotConnect;
class vtkObject;
class vtkSMProxy;

class pqVesselTouchSessionBinding : public QObject
{
  Q_OBJECT
public:
  /// The pipeline name of the shared session.
  static const char* registrationName();

  explicit pqVesselTouchSessionBinding(QObject* parent = nullptr);
  ~pqVesselTouchSessionBinding() override;

  /// The session proxy, or null when there is none.
  vtkSMProxy* proxy() const;
  pqPipelineSource* source() const;

  /// The session, created on the active server (registered as "VesselTouchSession") when there
  /// is none. Null when there is no server.
  vtkSMProxy* ensureSession();

  /// Sets the session's centerline input (a VesselCenterline, or port 1 of a VesselPhantom).
  /// Connected to a pvserver, the centerline is delivered to the client first, where the
  /// session lives (pqVesselTouchCenterlineDelivery); call it again after a new extraction.
  void setCenterline(vtkSMProxy* centerline, unsigned int port);
  /// Whether the session has a centerline (its Input, or the copy delivered from a pvserver).
  bool hasCenterline() const;
  /// Copies the camera and size of `view` into the session's camera properties.
  void copyCamera(pqRenderView* view);
  /// Start/Stop commands. start() returns whether the session runs afterwards.
  bool start();
  void stop();
  /// The pvserver was lost (issue 19, item 6): the session's connection-lost fault with
  /// `message` (zero force at once, the loop stopped, the skeleton held:
  /// vtkVesselTouchHapticSession::ReportConnectionLost). Only the client-side object is touched.
  void reportConnectionLost(const QString& message);
  /// Writes the skeleton the session holds (its input polydata, in this process) as VTK XML
  /// PolyData; false when there is none or the file cannot be written.
  bool saveSkeleton(const QString& fileName) const;
  /// Calls `write` on the session proxy (when there is one), then UpdateVTKObjects, without
  /// reporting these changes back as propertiesModified() and without lighting ParaView's Apply
  /// button: the running session feels them at its next tick.
  void writeProperties(const std::function<void(vtkSMProxy*)>& write);

Q_SIGNALS:
  /// The session proxy appeared, was replaced or went away (null).
  void sessionProxyChanged(vtkSMProxy* session);
  /// Properties of the session changed from elsewhere (coalesced, once per event loop turn).
  void propertiesModified();

private Q_SLOTS:
  void onSourceAdded(pqPipelineSource* source);
  void onSourceRemoved(pqPipelineSource* source);
  void onPropertyModified(vtkObject* caller, unsigned long event, void* clientData, void* callData);
  void emitPropertiesModified();

private:
  void adopt(pqPipelineSource* source);
  static bool isSession(pqPipelineSource* source);

  QPointer<pqPipelineSource> Source;
  pqVesselTouchCenterlineDelivery Delivery;
  vtkNew<vtkEventQtSlotConnect> Connector;
  bool Pushing = false;
  bool Pending = false;
  Q_DISABLE_COPY(pqVesselTouchSessionBinding)
};

#endif
