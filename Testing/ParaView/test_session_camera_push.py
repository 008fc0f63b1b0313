"""One camera push per view change (issue 18, item 2): the session proxy publishes its properties
to the haptic thread once per push (post_push = ApplyProperties), so a camera whose eight
properties change together rebuilds the view model exactly once and the haptic thread never sees
the new position with the old focal point. The agent state reaches Python through the session's
own layout, and the real-time flag through its own property."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import simple  # noqa: E402

check = Check("SessionCameraPush")
simple.LoadPlugin(plugin_path(), ns=globals())
import vesseltouch  # noqa: E402

phantom = VesselPhantom(Shape="Y bifurcation", Dimensions=[48, 48, 48])  # noqa: F821
view = simple.CreateRenderView()
view.ViewSize = [400, 300]
simple.Show(phantom, view)
simple.ResetCamera(view)
session = vesseltouch.logic()
session.Bind(phantom, view)


def builds():
    info = session._info("ViewModelBuildsInfo")
    return int(info[0] if isinstance(info, (list, tuple)) else info)


def camera_pose(angle):
    """A camera orbiting the volume's centre: every one of the eight values changes."""
    import math
    c = [24.0, 24.0, 24.0]
    return dict(position=[c[0] + 150 * math.cos(angle), c[1] + 150 * math.sin(angle), c[2] + 40],
                focal_point=[c[0] + angle, c[1] - angle, c[2]],
                view_up=[0.0, -math.sin(0.1 * angle), math.cos(0.1 * angle)],
                parallel=True, parallel_scale=30.0 + angle, view_angle=30.0 + angle,
                size=[400 + int(10 * angle), 300])


start = builds()
check.true(start >= 1, "binding to a centerline and a camera builds the view model (%d)" % start)

# Eight camera properties in one push: one rebuild, never one per property.
for i in range(1, 6):
    before = builds()
    session.SetCamera(**camera_pose(0.3 * i))
    check.equal(builds() - before, 1, "camera change %d: exactly one view-model rebuild" % i)

# The same camera again: nothing to rebuild.
before = builds()
session.SetCamera(**camera_pose(1.5))
check.equal(builds() - before, 0, "an unchanged camera rebuilds nothing")

# A parameter that does not touch the view model: no rebuild either.
before = builds()
session.SetZoom(2.0)
check.equal(builds() - before, 0, "a zoom change rebuilds no view model")

# The render view's camera, as the GUI's agent display pushes it: one rebuild per move.
camera = simple.GetActiveCamera()
for i in range(3):
    camera.Azimuth(20.0)
    camera.Elevation(5.0)
    before = builds()
    session.SetCameraFromView(view)
    check.equal(builds() - before, 1, "view rotation %d: exactly one rebuild" % i)

# While the haptic loop runs: every SetCamera still arrives whole (one build each).
session.SetDevice("pointer")
session.Start()
check.true(session.GetStatus()["running"], "the session runs")
before = builds()
for i in range(20):
    session.SetCamera(**camera_pose(2.0 + 0.05 * i))
check.equal(builds() - before, 20, "20 camera changes on a running session: 20 rebuilds")
status = session.GetStatus()
check.true(status["realtime_scheduling"] in (True, False),
           "the real-time flag is a boolean of its own (%r)" % status["realtime_scheduling"])
check.true(not status["realtime_scheduling"] or "SCHED_FIFO" in status["scheduler"],
           "the real-time flag agrees with the notice (%r, %r)"
           % (status["realtime_scheduling"], status["scheduler"]))
session.Stop()

# The agent state through the session's layout.
state = session.GetAgentState()
expected = {"time": 1, "tick": 1, "state": 1, "force_law": 1, "path": 1, "point": 1, "cursor": 2,
            "position": 3, "tangent": 3, "direction": 1, "torsion_angle": 1, "zone_gain": 1,
            "force": 2, "target_force": 2, "hand": 2}
check.equal(sorted(state.keys()), sorted(expected.keys()), "agent-state fields")
for name, n in expected.items():
    value = state.get(name)
    size = len(value) if isinstance(value, list) else 1
    check.equal(size, n, "agent-state field %s has %d component(s)" % (name, n))
check.true(isinstance(state["tick"], int) and isinstance(state["state"], int),
           "counts and states are integers")
check.true(state["tick"] > 0, "the loop ran ticks (%r)" % state["tick"])
check.finish()
