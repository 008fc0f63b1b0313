"""GUI test (issue 19, item 6): the panel connected to a pvserver that did not load the plugin.

The real ParaView with the plugin (client side only) starts on an empty scene; a 2-rank pvserver
starts on 127.0.0.1 with a free port (vtouch_pvserver.ParallelServer: every wait timed out, the
process group ended, the port checked free), and the GUI's Python connects to it as File > Connect
would. The panel (pqVesselTouchServerCheck) must then say what is missing and how to fix it:
Extract disabled, its tool tip and the message beside it naming the server, the missing plugin and
the menu (Tools > Manage Plugins, Remote Plugins) or the command (LoadPlugin(path, remote=True)).
Doing what it says (the plugin loaded on the server) enables Extract again and clears the message.
A screenshot of the panel with the message is kept (<build>/Testing/gui-cs-no-plugin).
Runs with Debian's python3 under vtouch-xvfb-run.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.join(os.path.dirname(HERE), "clientserver"), os.path.dirname(HERE)]
from gui_driver import GuiDriver  # noqa: E402
from vtouch_pvserver import ParallelServer, port_is_free, wait_until  # noqa: E402
from vtouch_testing import Check  # noqa: E402

CHECK = Check('GUI server without the plugin')
check = CHECK.true


def extract_button(state):
    return state.get("widgets", {}).get("extractButton", {})


def main():
    server = ParallelServer(ranks=2)
    server.start()
    port = server.port
    gui = GuiDriver("gui-cs-no-plugin", "empty", check)
    try:
        if not gui.wait_for_scene():
            return
        gui.python("from paraview.simple import Connect\nConnect('127.0.0.1', %d)\n" % port)
        refused = gui.wait_until(
            lambda s: not extract_button(s).get("enabled", True)
            and "VesselTouch plugin" in extract_button(s).get("tooltip", ""), seconds=60)
        button = gui.widget("extractButton")
        message = gui.widget("extractMessage").get("text", "")
        print("Extract: enabled %s, tool tip %r" % (button.get("enabled"), button.get("tooltip")))
        print("message: %r" % message)
        check(refused, "connected to a server without the plugin, Extract is disabled with the "
                       "reason as its tool tip (%s)" % button)
        check("127.0.0.1:%d" % port in message and "has not loaded the VesselTouch plugin"
              in message, "the message beside Extract names the server and what is missing "
                          "(%r)" % message)
        check("Tools > Manage Plugins" in message and "remote=True" in message,
              "the message says how to fix it: the menu and the command (%r)" % message)
        gui.screenshot(os.path.join(gui.work, "server_without_plugin.png"))

        # Doing what it says: the plugin loaded on the server enables Extract again.
        plugin = os.environ["VESSELTOUCH_PLUGIN"]
        gui.python("from paraview.simple import LoadPlugin\nLoadPlugin(%r, remote=True)\n"
                   % plugin)
        fixed = gui.wait_until(lambda s: extract_button(s).get("enabled", False), seconds=60)
        after = gui.widget("extractMessage").get("text", "")
        check(fixed, "with the plugin loaded on the server, Extract is enabled again (%s)"
              % gui.widget("extractButton"))
        check("VesselTouch plugin" not in after,
              "the message is gone once the server has the plugin (%r)" % after)
    finally:
        gui.finish()  # ParaView ends: the server sees its client leave
        code = server.stop()
        check(code is not None, "the server exited")
        check(wait_until(lambda: port_is_free(port), 10.0), "port %d is free again" % port)


main()
CHECK.finish()
