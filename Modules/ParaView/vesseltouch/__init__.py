"""VesselTouch from ParaView's Python shell and pvpython.

Load the plugin first (``LoadPlugin(path, ns=globals())`` or the Plugin Manager), then::

    import vesseltouch
    phantom = VesselPhantom(Shape='Helix')
    vesseltouch.ShowAsMIP(phantom)
    centerline = vesseltouch.ExtractCenterlines(phantom)     # VesselCenterline
    session = vesseltouch.logic().Bind(centerline)           # the session the panel shows

On a pvserver, ``vesseltouch.RemoteCancel(centerline)`` before ``UpdatePipeline()`` lets a
progress callback or another thread cancel the run (vesseltouch/remote_cancel.py).
"""

from .mip import ShowAsMIP
from .info import version, build_info
from .orientation import ShowPatientOrientation, HidePatientOrientation
from .scene import OpenDefaultScene, DEFAULT_PHANTOM
from .session import HapticSession, logic, SESSION_NAME
from .centerlines import ExtractCenterlines
from .agent_view import AgentOverlay
from .remote_cancel import RemoteCancel

__all__ = ["ShowAsMIP", "OpenDefaultScene", "DEFAULT_PHANTOM", "ShowPatientOrientation",
           "HidePatientOrientation", "version", "build_info", "AgentOverlay", "HapticSession",
           "logic", "SESSION_NAME", "ExtractCenterlines", "RemoteCancel"]
