"""GUI test: a real TOF-MRA opened with VesselTouch's reader and shown with the toolbar's MIP
action, in the real ParaView (issue 20 item 10): the MIP is on black from the first frame and in
the radiological axial view (seen from the feet: the camera below the volume looking toward
superior, anterior up: view up -y in LPS), the volume is offered by the panel's chooser, and the
view is not blank.
"""

import os
import sys

import numpy
from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_driver import run_test  # noqa: E402

DATA = os.path.join(os.environ.get("VESSELTOUCH_SHARED_DATA", "/work/shared/data"),
                    "tof-mra-willis", "chris_MRA.nii.gz")


def body(gui, check):
    gui.python("from paraview import simple\n"
               "for s in list(simple.GetSources().values()):\n"
               "    simple.Hide(s)\n"
               "mra = simple.OpenDataFile(%r, registrationName='MRA')\n"
               "mra.UpdatePipeline()\n"
               "simple.SetActiveSource(mra)\n" % DATA)
    check(gui.wait_until(lambda s: "MRA" in s["widgets"].get("volumeCombo", {}).get("items", [])),
          "the MRA is offered as a volume (%r)" % gui.widget("volumeCombo").get("items"))
    gui.run("trigger", "actionVesselTouchShowMIP")
    gui.wait_until(lambda s: s.get("camera_view_up", [0, 0, 0])[1] < -0.99, seconds=10)
    up = gui.state.get("camera_view_up", [0, 0, 0])
    position, focal = gui.state["camera_position"], gui.state["camera_focal_point"]
    check(abs(up[0]) < 1e-6 and up[1] < -0.999 and abs(up[2]) < 1e-6,
          "LPS: anterior (-y) is up (%r)" % up)
    check(position[2] < focal[2] and abs(position[0] - focal[0]) < 1e-6
          and abs(position[1] - focal[1]) < 1e-6,
          "seen from the feet: the camera below, looking toward superior (%r -> %r)"
          % (position, focal))
    png = gui.capture("mra_mip.png")
    rgb = numpy.asarray(Image.open(png).convert("RGB")).astype(int) if png else None
    if check(rgb is not None, "the view was captured"):
        check(rgb[2, 2].tolist() == [0, 0, 0], "the background is black (%r)" % rgb[2, 2].tolist())
        check(rgb.max() > 120, "the MIP shows the vessels (max grey %d)" % rgb.max())


run_test("gui_mip_orientation", "phantom", body)
