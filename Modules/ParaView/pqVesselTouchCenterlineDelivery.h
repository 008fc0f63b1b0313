// The centerline delivered to the haptic session in the client (issue 19, item 1), the C++ twin of
// vesseltouch/delivery.py. Connected to a pvserver, VesselCenterline runs on the server ranks
// while the session proxy is client-only (processes="client" in its XML): its loop thread, the
// device, the agent cone and mouse tracing stay beside the user's hand, as Mark et al. decoupled
// the servo loop from the application on a second machine (cited by Yi & Hayward section 2.3),
// with the Q-skeleton as the small intermediate representation. The ranks' polylines are appended
// on rank 0 (ParaView's ReductionFilter, vtkAppendPolyData) and moved to the client
// (ClientServerMoveData); the mover's client-side output is the session's input.
//
// Built in (one process) nothing is needed: port() is the centerline itself. The two proxies are
// not registered (plumbing, not pipeline items) and are updated on every process together
// (vtkSMSourceProxy::UpdatePipeline) before the client's session reads them.
#ifndef pqVesselTouchCenterlineDelivery_h
#define pqVesselTouchCenterlineDelivery_h

#include "vtkSmartPointer.h"

class pqServer;
class vtkSMProxy;
class vtkSMSourceProxy;

class pqVesselTouchCenterlineDelivery
{
public:
  /// True when `server` is a separate pvserver (client/server mode).
  static bool isRemote(pqServer* server);

  /// Delivers output `port` of `centerline` to the client and returns the proxy whose output 0
  /// the session takes as input: the centerline itself built in (and `port` unchanged), the
  /// mover (port 0) connected to a pvserver. Re-delivers when called again (a new extraction).
  vtkSMProxy* deliver(pqServer* server, vtkSMProxy* centerline, unsigned int& port);

  /// Gathers and moves the current centerline again (every process takes part).
  void update();

  /// Drops the helper proxies (a built-in session, or the session gone).
  void clear();

private:
  vtkSmartPointer<vtkSMSourceProxy> Reducer;
  vtkSmartPointer<vtkSMSourceProxy> Mover;
};

#endif
