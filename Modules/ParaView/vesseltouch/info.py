"""Versions of this VesselTouch build and of what it was built against."""

from paraview import servermanager

_COMPONENTS = ("VesselTouch", "VTK", "ITK", "hidapi")


def build_info():
    """A dict of component -> version: VesselTouch, ParaView, VTK, ITK and hidapi, as compiled
    into the loaded plugin (read from the server, where the plugin's classes live)."""
    proxy = servermanager.CreateProxy("misc", "VesselTouchVersion")
    if proxy is None:
        raise RuntimeError("the VesselTouch plugin is not loaded")
    proxy.UpdatePropertyInformation()
    info = {name: proxy.GetProperty(name + "Version").GetElement(0) for name in _COMPONENTS}
    info["ParaView"] = servermanager.vtkSMProxyManager.GetParaViewSourceVersion()
    return info


def version():
    """VesselTouch's version string, e.g. '0.1.0'."""
    return build_info()["VesselTouch"]
