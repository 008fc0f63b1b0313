"""``vesseltouch.logic()``: the one session shared by the GUI panel and the Python console, the
proxy registered as SESSION_NAME, adopted, created or replaced as sessions come and go (state
files, Reset Session, a new connection)."""

from paraview import servermanager, simple

#: Name under which the module-wide session is registered (group "sources"); the VesselTouch
#: panel binds to the proxy of this name, whichever side (C++ panel or Python) created it.
SESSION_NAME = "VesselTouchSession"

_LOGIC = None


def _registered_sessions():
    """The VesselTouchHapticSession proxies registered as SESSION_NAME in the active connection's
    proxy manager, oldest first (ParaView keeps them in registration order)."""
    if servermanager.ActiveConnection is None:
        return []
    pxm = servermanager.ProxyManager()
    proxies = pxm.GetProxies("sources", SESSION_NAME) or []
    return [p for p in proxies if p.GetXMLName() == "VesselTouchHapticSession"]


def _registered_session():
    """The newest VesselTouchHapticSession proxy registered as SESSION_NAME, or None."""
    sessions = _registered_sessions()
    return sessions[-1] if sessions else None


def _same(a, b):
    return a is not None and b is not None and a.SMProxy.__this__ == b.SMProxy.__this__


def _stop(proxy):
    try:
        proxy.InvokeCommand("Stop")
    except Exception:  # a proxy half gone (its connection closing): nothing runs any more
        pass


_WATCHED = {}


def _watch_registrations():
    """Stops an older session as soon as a newer one is registered as SESSION_NAME (a state file
    loaded with LoadState while a session runs: ParaView adds the state's proxies beside the
    existing ones), so the old loop zeroes its force at once, also in pvpython where no panel
    watches. One observer per proxy manager; logic() drops the stopped one afterwards."""
    if servermanager.ActiveConnection is None:
        return
    pxm = servermanager.ProxyManager().SMProxyManager
    key = pxm.__this__
    if key in _WATCHED:
        return

    def on_register(*_):
        sessions = _registered_sessions()
        for old in sessions[:-1]:
            _stop(old)

    _WATCHED.clear()  # an earlier connection's proxy manager is gone
    _WATCHED[key] = pxm.AddObserver("RegisterEvent", on_register)


def logic():
    """The module-level session shared by the GUI panel and the Python console.

    If a proxy registered as ``"VesselTouchSession"`` exists (the panel may create it from C++,
    or the main job's start-up script from Python), that proxy is adopted; otherwise a new one is
    created and registered under that name. A session whose proxy was deleted (``Delete``,
    ``ResetSession()``, a new connection) is replaced by a new one, so ``logic()`` always returns
    the session the panel shows.

    One session at a time: a state file loaded while a session exists (``LoadState``, File > Load
    State) registers its own ``"VesselTouchSession"`` beside it. The loaded (newest) one is the
    session from then on: the old one is stopped as soon as the new one is registered (force to
    zero) and deleted here (the GUI panel deletes it at once), so exactly one stays registered.
    The loaded session does not start by itself."""
    from .session import HapticSession  # session.py imports this module: import when called

    global _LOGIC
    _watch_registrations()
    sessions = _registered_sessions()
    for old in sessions[:-1]:
        _stop(old)
        simple.Delete(old)
    registered = sessions[-1] if sessions else None
    if registered is not None:
        if _LOGIC is None or not _same(_LOGIC.proxy, registered):
            if _LOGIC is not None:
                _LOGIC.UnfollowView()
            _LOGIC = HapticSession(proxy=registered)
        return _LOGIC
    if _LOGIC is not None:
        _LOGIC.UnfollowView()
    _LOGIC = HapticSession(registrationName=SESSION_NAME)
    return _LOGIC
