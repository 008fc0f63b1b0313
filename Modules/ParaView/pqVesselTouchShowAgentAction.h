// The toolbar's "Agent" toggle: draws the haptic session's agent in the active render view
// (pqVesselTouchAgentDisplay), bound to the session proxy registered as "VesselTouchSession"
// (vesseltouch.logic()) or else the first VesselTouchHapticSession, following the active view and
// the sessions as they come and go.
#ifndef pqVesselTouchShowAgentAction_h
#define pqVesselTouchShowAgentAction_h

#include <QAction>

class pqPipelineSource;
class pqVesselTouchAgentDisplay;
class vtkSMProxy;

class pqVesselTouchShowAgentAction : public QAction
{
  Q_OBJECT
public:
  explicit pqVesselTouchShowAgentAction(QObject* parent = nullptr);
  ~pqVesselTouchShowAgentAction() override;

  pqVesselTouchAgentDisplay* display() const { return this->Display; }

  /// The session proxy the GUI uses: "VesselTouchSession" (vesseltouch.logic()), else the first
  /// VesselTouchHapticSession source; null when there is none.
  static vtkSMProxy* findSession();

private Q_SLOTS:
  void rebind();
  void onSourceRemoved(pqPipelineSource* source);

private:
  pqVesselTouchAgentDisplay* Display = nullptr;
  Q_DISABLE_COPY(pqVesselTouchShowAgentAction)
};

#endif
