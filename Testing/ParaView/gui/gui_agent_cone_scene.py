"""Scene of the GUI agent test (Testing/ParaView/gui/gui_agent_cone.py), run by the real ParaView
as ``paraview --script=...``: the helix phantom as a MIP seen from the side, and
``vesseltouch.logic()`` on its centerline with the simulated device and a slow hand sweep (or, with
VESSELTOUCH_SCENE_DEVICE=pointer, the pointer device), started.
The C++ agent display (toolbar "Agent", checked by VESSELTOUCH_GUI_AGENT=1) draws the agent.
Writes "ok" (or the error) to $VESSELTOUCH_DONE_FLAG when the session runs.
"""

import os
import traceback


def main():
    from paraview import simple
    import vesseltouch

    view = simple.GetActiveViewOrCreate("RenderView")
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.OrientationAxesVisibility = 0  # its red X axis next to a blue Z would look like an agent
    phantom = simple.VesselPhantom(registrationName="VesselPhantom1", Shape="Helix",
                                   Dimensions=[96, 96, 96])
    vesseltouch.ShowAsMIP(phantom, view)
    # The helix (axis z) from the side: its front and back halves run toward and away from the
    # viewer, so the blue base of the cone shows on one of them.
    bounds = phantom.GetDataInformation(0).GetBounds()
    centre = [0.5 * (bounds[2 * i] + bounds[2 * i + 1]) for i in range(3)]
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1] - 3.0 * (bounds[3] - bounds[2]), centre[2]]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()
    simple.Render(view)

    session = vesseltouch.logic()
    session.SetCenterline(phantom)  # port 1: the analytic centerline
    session.SetCameraFromView(view)
    session.SetForceLaw("LDGF")
    if os.environ.get("VESSELTOUCH_SCENE_DEVICE") == "pointer":
        session.SetDevice("pointer")  # the mouse (toolbar "Trace with mouse")
    else:
        session.SetDevice("simulated")
        session.SetHandSweep(path=0, speed_mm_per_s=float(
            os.environ.get("VESSELTOUCH_SWEEP_SPEED", "15")))
    session.Start()
    simple.SetActiveSource(phantom)
    if os.environ.get("VESSELTOUCH_SCENE_DEVICE") != "pointer":
        _restart_sweep_when_resized(view, session)


def _restart_sweep_when_resized(view, session, restarts=3, end_restarts=20, still_s=3.0):
    """The sweep's hand track is the path's screen projection at Start. The dock panels appear
    after this script and narrow the view, so restart the sweep (with the renderer's real size)
    when a render shows a new size; the agent display pushes the camera to the session anyway.
    The sweep also restarts when the agent has stood on one point for `still_s` (the path's end:
    on a loaded machine the first screenshots may come after the hand has arrived there, where
    the helix's end runs away from the viewer and the cone's red sides are hidden)."""
    import time
    renderer = view.GetRenderer()
    started = [tuple(renderer.GetSize())]
    still = {"point": None, "since": time.monotonic(), "restarts": 0}

    def at_rest():
        point = session.GetAgentState().get("point")
        now = time.monotonic()
        if point != still["point"]:
            still.update(point=point, since=now)
            return False
        return now - still["since"] > still_s and still["restarts"] < end_restarts

    def on_timer(_interactor, _event):
        # A still agent draws no frame: a twice-a-second timer of the view's (Qt) interactor.
        if session.IsRunning() and at_rest():
            still["restarts"] += 1
            still["since"] = time.monotonic()
            session.Stop()
            session.Start()

    interactor = view.GetInteractor()
    if interactor is not None:
        interactor.AddObserver("TimerEvent", on_timer)
        interactor.CreateRepeatingTimer(500)

    def on_end(_window, _event):
        size = tuple(renderer.GetSize())
        if size == started[0] or len(started) > restarts or min(size) <= 0:
            return
        started[0] = size
        started.append(size)
        camera = renderer.GetActiveCamera()
        session.Stop()
        session.SetCamera(position=camera.GetPosition(), focal_point=camera.GetFocalPoint(),
                          view_up=camera.GetViewUp(), parallel=bool(camera.GetParallelProjection()),
                          parallel_scale=camera.GetParallelScale(),
                          view_angle=camera.GetViewAngle(), size=size)
        session.Start()

    view.GetRenderWindow().AddObserver("EndEvent", on_end)


flag = os.environ.get("VESSELTOUCH_DONE_FLAG")
try:
    main()
    status = "ok\n"
except Exception:  # the runner reports it
    traceback.print_exc()
    status = "error\n" + traceback.format_exc()
if flag:
    with open(flag, "w") as done:
        done.write(status)
