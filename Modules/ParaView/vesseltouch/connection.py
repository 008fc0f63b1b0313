"""The connection VesselTouch runs on: built in, or a client connected to a pvserver (issue 19).

Connected to a pvserver, VesselTouch's server-side filters (VesselCenterline, VesselPhantom, the
readers) are defined only when the plugin was loaded on the server too (``LoadPlugin(path,
remote=True)``): a plugin loaded in the client alone gives the client-side session but no
VesselCenterline, and Python would only report a missing attribute. ``require_server_plugin``
refuses first, with the reason and what to do (issue 19, item 6).
"""

from paraview import servermanager

__all__ = ["is_remote", "server_has_plugin", "require_server_plugin"]

PLUGIN_NAME = "VesselTouch"


def is_remote():
    """True when the active connection is to a separate pvserver (client/server mode)."""
    connection = servermanager.ActiveConnection
    return connection is not None and bool(connection.IsRemote())


def server_has_plugin():
    """True built in, or when the pvserver has loaded the VesselTouch plugin."""
    if not is_remote():
        return True
    manager = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager()
    info = manager.GetRemoteInformation(servermanager.ActiveConnection.Session)
    return any(info.GetPluginName(i) == PLUGIN_NAME and info.GetPluginLoaded(i)
               for i in range(info.GetNumberOfPlugins()))


def require_server_plugin(what):
    """Raises RuntimeError, before anything is created on the server, when it lacks the plugin."""
    if not server_has_plugin():
        raise RuntimeError(
            "%s: the pvserver this client is connected to (%s) has not loaded the VesselTouch "
            "plugin. Load it on the server side too: LoadPlugin(path, remote=True) in Python, or "
            "Tools > Manage Plugins > Remote Plugins in the GUI (the same file as the client's)."
            % (what, servermanager.ActiveConnection.GetURI()))
