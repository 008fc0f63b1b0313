"""GUI test: the VesselTouch panel survives its volume going away, in the real ParaView.

With the panel open on the phantom (picked seed, extracted centerlines, a session), the user
deletes the volume's tree (the Pipeline Browser's Delete on the volume and its filters), then opens
another volume and runs Edit > Reset Session (the real menu action, "actionDelete_All"), then
opens one more. ParaView must not crash (issue 20 item 1: the volume chooser held freed sources),
the chooser must follow (empty, with a message saying how to get a volume; then the new volume),
and the panel must keep working (a seed picked on the new volume).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_driver import run_test  # noqa: E402


def body(gui, check):
    # The start: the phantom chosen, a seed, centerlines, a session using them.
    gui.run("state")
    check(gui.widget("volumeCombo").get("items") == ["Phantom"],
          "the chooser lists the phantom (%r)" % gui.widget("volumeCombo"))
    gui.python("import vesseltouch\n"
               "from paraview import simple\n"
               "vesseltouch.logic()\n"
               "simple.SetActiveSource(simple.FindSource('Phantom'))\n")
    gui.run("click", "extractButton")  # no seed yet: refused with a message, nothing breaks
    check(gui.alive(), "Extract without a seed leaves ParaView running")

    # Delete the volume and everything built on it, as the Pipeline Browser's Delete does.
    gui.python("from paraview import simple\n"
               "phantom = simple.FindSource('Phantom')\n"
               "for proxy in list(simple.GetSources().values()):\n"
               "    if proxy.GetXMLName() == 'VesselCenterline':\n"
               "        simple.Delete(proxy)\n"
               "simple.Delete(phantom)\n")
    gone = gui.wait_until(lambda s: "Phantom" not in s.get("sources", []), seconds=10)
    check(gone, "the phantom was deleted (%r)" % gui.state.get("sources"))
    check(gui.alive(), "ParaView survives deleting the volume with the panel open")
    gui.run("state")
    check(gui.widget("volumeCombo").get("items") == [],
          "the chooser is empty after the delete (%r)" % gui.widget("volumeCombo").get("items"))
    message = gui.widget("volumeMessage").get("text", "")
    check("volume" in message.lower() and gui.widget("volumeMessage").get("visible"),
          "the panel says there is no volume and how to get one (%r)" % message)

    # Another volume, then the real Edit > Reset Session with the panel open.
    gui.python("from paraview import simple\n"
               "v = simple.VesselPhantom(registrationName='Second', Dimensions=[48, 48, 48])\n"
               "simple.Show(v)\n"
               "simple.SetActiveSource(v)\n"
               "simple.Render()\n")
    check(gui.wait_until(lambda s: s["widgets"].get("volumeCombo", {}).get("items") == ["Second"]),
          "the chooser offers the new volume (%r)" % gui.widget("volumeCombo").get("items"))
    gui.run("trigger", "actionDelete_All")
    check(gui.answer_dialog("Delete All", "Return"), "Reset Session asked for confirmation")
    check(gui.wait_until(lambda s: "Second" not in s.get("sources", []), seconds=15,
                         reply_seconds=120),
          "Reset Session removed the pipeline (%r)" % gui.state.get("sources"))
    check(gui.alive(), "ParaView survives Edit > Reset Session with the panel open")
    gui.run("state")
    check(gui.widget("volumeCombo").get("items") == [], "the chooser is empty after the reset")
    check(gui.state["session"]["exists"] is False, "the session went with the reset")

    # The panel still works: a third volume, a seed picked on it.
    gui.python("from paraview import simple\n"
               "import vesseltouch\n"
               "v = simple.VesselPhantom(registrationName='Third', Dimensions=[48, 48, 48])\n"
               "vesseltouch.ShowAsMIP(v)\n"
               "simple.SetActiveSource(v)\n"
               "simple.Render()\n")
    check(gui.wait_until(lambda s: s["widgets"].get("volumeCombo", {}).get("items") == ["Third"]),
          "the chooser offers the volume opened after the reset")
    gui.run("click", "pickSeedButton")
    rect = gui.state.get("view_rect")
    if check(rect is not None, "a render view after the reset"):
        gui.xdotool("mousemove", rect[0] + rect[2] // 2, rect[1] + rect[3] // 2)
        gui.xdotool("click", 1)
        picked = gui.wait_until(lambda s: "mm" in s["widgets"].get("seedLabel", {}).get("text", ""))
        check(picked, "a seed is picked on the new volume (%r)" % gui.widget("seedLabel"))
    check(gui.alive(), "ParaView is running at the end")


run_test("gui_volume_lifecycle", "phantom", body)
