// The toolbar's "Trace with mouse" toggle: the mouse over the active render view becomes the
// haptic session's POINTER device (pqVesselTouchPointerInteraction). Checking it switches the
// session (pqVesselTouchShowAgentAction::findSession) to the pointer device and starts it;
// unchecking stops it. Ordinary camera interaction works whenever it is unchecked.
#ifndef pqVesselTouchTraceWithMouseAction_h
#define pqVesselTouchTraceWithMouseAction_h

#include <QAction>

class pqPipelineSource;
class pqVesselTouchPointerInteraction;

class pqVesselTouchTraceWithMouseAction : public QAction
{
  Q_OBJECT
public:
  explicit pqVesselTouchTraceWithMouseAction(QObject* parent = nullptr);
  ~pqVesselTouchTraceWithMouseAction() override;

  pqVesselTouchPointerInteraction* interaction() const { return this->Interaction; }

private Q_SLOTS:
  void rebind();
  void onSourceRemoved(pqPipelineSource* source);

private:
  pqVesselTouchPointerInteraction* Interaction = nullptr;
  Q_DISABLE_COPY(pqVesselTouchTraceWithMouseAction)
};

#endif
