// The VesselTouch toolbar: one-click actions bound to the active render view: "MIP", "Agent"
// (draw the haptic session's agent over the MIP) and "Trace with mouse" (the mouse as the
// session's pointer device).
#ifndef pqVesselTouchToolBar_h
#define pqVesselTouchToolBar_h

#include <QToolBar>

class pqVesselTouchShowAgentAction;
class pqVesselTouchTraceWithMouseAction;

class pqVesselTouchToolBar : public QToolBar
{
  Q_OBJECT
public:
  explicit pqVesselTouchToolBar(QWidget* parent = nullptr);

  pqVesselTouchShowAgentAction* showAgentAction() const { return this->ShowAgent; }
  pqVesselTouchTraceWithMouseAction* traceWithMouseAction() const { return this->TraceWithMouse; }

private:
  pqVesselTouchShowAgentAction* ShowAgent = nullptr;
  pqVesselTouchTraceWithMouseAction* TraceWithMouse = nullptr;
  Q_DISABLE_COPY(pqVesselTouchToolBar)
};

#endif
