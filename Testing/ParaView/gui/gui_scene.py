"""Scene of the driven GUI tests (gui_driver.py), run by the real ParaView as
``paraview --script=...``. VESSELTOUCH_SCENE chooses it:
  empty     nothing (ParaView as the user finds it)
  phantom   a VesselPhantom tree ("Phantom") shown as a MIP, active (the clinician's start)
  volume+2d the phantom, plus a 2D image ("Flat", a 64 x 64 x 1 wavelet) and, if
            VESSELTOUCH_SCENE_PNG names a file, that PNG opened by ParaView's reader ("Png")
  tracing   the phantom, and vesseltouch.logic() on its analytic centerline with the pointer
            device (the mouse), started
  angiogram a raw-angiogram VesselPhantom ("Angio": a random tree, noise, plates and blobs) of
            VESSELTOUCH_SCENE_SIZE^3 voxels (default 256) shown as a MIP, active; no "Phantom"
Otherwise no session is created: the panel does what the user asks. Writes "ok" (or the error) to
$VESSELTOUCH_DONE_FLAG.
"""

import os
import traceback


def main():
    from paraview import simple
    import vesseltouch

    scene = os.environ.get("VESSELTOUCH_SCENE", "phantom")
    view = simple.GetActiveViewOrCreate("RenderView")
    if scene == "empty":
        return
    if scene == "angiogram":
        size = int(os.environ.get("VESSELTOUCH_SCENE_SIZE", "256"))
        angio = simple.VesselPhantom(registrationName="Angio", Shape="Raw angiogram",
                                     Dimensions=[size] * 3, Seed=1, NoiseStandardDeviation=50)
        vesseltouch.ShowAsMIP(angio, view)
        view.OrientationAxesVisibility = 0
        simple.SetActiveSource(angio)
        simple.Render(view)
        return
    phantom = simple.VesselPhantom(registrationName="Phantom", Shape="Tree",
                                   Dimensions=[64, 64, 64])
    vesseltouch.ShowAsMIP(phantom, view)
    view.OrientationAxesVisibility = 0  # its white letters would be the brightest "vessel"
    if scene == "volume+2d":
        flat = simple.Wavelet(registrationName="Flat", WholeExtent=[0, 63, 0, 63, 0, 0])
        flat.UpdatePipeline()
        png = os.environ.get("VESSELTOUCH_SCENE_PNG")
        if png:
            simple.PNGSeriesReader(registrationName="Png", FileNames=[png]).UpdatePipeline()
    if scene == "tracing":
        # The session on the phantom's analytic centerline with the mouse as its device, running.
        session = vesseltouch.logic()
        session.SetCenterline(phantom)  # port 1: the analytic centerline
        session.SetCameraFromView(view)
        session.SetDevice("pointer")
        session.Start()
    simple.SetActiveSource(phantom)
    simple.Render(view)


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
