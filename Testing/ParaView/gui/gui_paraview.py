"""The command line that starts the real ParaView for a GUI test: the VesselTouch plugin and the
tests' VesselTouchTestDriver plugin (Testing/ParaView/driver: the command driver, the panel
self-test and the report files, which the product plugin does not carry), then `script`."""


def paraview_command(env, script):
    return [env["VESSELTOUCH_PARAVIEW"],
            "--plugin-search-paths=" + env["VESSELTOUCH_PLUGIN_DIR"],
            "--plugin-search-paths=" + env["VESSELTOUCH_TEST_DRIVER_DIR"],
            "--plugins=VesselTouch", "--plugins=VesselTouchTestDriver", "--script=" + script]
