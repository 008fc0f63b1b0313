"""Noticing at once that the pvserver is gone (issue 19, item 6).

What ParaView 5.11 offers: the client's session (vtkSMSessionClient) fires
``vtkPVSessionBase::ConnectionLost`` when its socket communicator reports an error, that is only
when the client next sends to or receives from the dead server. The GUI learns it sooner because
pqServer watches the socket for server notifications (its ``serverSideDisconnected`` signal; the
panel listens to it, pqVesselTouchConnectionFault). pvpython has no event loop: between two calls
nothing reads the socket, and a haptic session running in the client would keep pushing a force
computed on a skeleton whose server is gone, unnoticed.

``ConnectionWatch`` closes that gap without touching the data stream and without the haptic
thread ever touching the network: a daemon thread polls the data-server socket for the peer's
hang-up (``POLLRDHUP``/``POLLHUP``/``POLLERR``, never ``POLLIN``: it reads nothing, so ParaView's
own messages are left alone), every ``period_s`` (20 ms; a project rule: well under a human
reaction time, and the haptic loop's own safety net, SafeHapticDevice's 30 ms watchdog, is for a
loop that stops writing, not for this). ParaView's ConnectionLost event is observed too. Either
way every HapticSession of that connection gets the fault (``ConnectionLostMessage``: zero force
at once, the fault latched with the message, the skeleton held; vtkVesselTouchHapticSession::
ReportConnectionLost), and the message is printed once.

The watch holds no reference to the session or its socket (it would keep the connection open
after Disconnect): only the descriptor, and it stops when the process module closes the
connection (``ConnectionClosedEvent``), before the descriptor is closed. Its calls into VTK come
from its thread; they hold Python's interpreter lock, as the main thread's do (this VTK is built
without VTK_PYTHON_FULL_THREADSAFE), so they never run inside one of the main thread's calls.
"""

import select
import sys
import threading
import weakref

from paraview import servermanager

__all__ = ["ConnectionWatch", "watch", "lost_message", "CONNECTION_LOST_EVENT"]

#: vtkPVSessionBase::ConnectionLost (not a vtkCommand event, so not in vtkCommand's names).
CONNECTION_LOST_EVENT = 6789
_HANG_UP = select.POLLHUP | select.POLLERR | select.POLLNVAL | getattr(select, "POLLRDHUP", 0x2000)

_WATCHES = {}


def lost_message(uri):
    """What the user reads when the server `uri` is gone: what happened and what to do."""
    return ("the connection to the pvserver %s was lost (the server died or the network went "
            "down): the force is zero and the loop stopped. The skeleton stays in this process: "
            "RunOffline() traces on it, or ClearFault() then Start(). To go on with the volume, "
            "restart the server, Connect() again and re-extract; to keep the skeleton, "
            "SaveSkeleton(\"centerline.vtp\")." % uri)


def _data_server_socket(connection):
    """The descriptor of the client's socket to the data server, or None built in."""
    from paraview.modules.vtkRemotingCore import vtkPVSession
    session = connection.Session
    # vtkSMSessionClient::GetDataServerController is not wrapped; GetController is.
    controller = session.GetController(vtkPVSession.DATA_SERVER)
    communicator = controller.GetCommunicator() if controller else None
    socket = communicator.GetSocket() if communicator and hasattr(communicator, "GetSocket") \
        else None
    return socket.GetSocketDescriptor() if socket else None


class ConnectionWatch:
    """Watches one client/server connection; tells its listeners once when it is lost."""

    def __init__(self, connection, period_s=0.02):
        self.uri = connection.GetURI()
        self.lost = False
        self._listeners = []
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._period_ms = max(1, int(round(period_s * 1000.0)))
        self._fd = _data_server_socket(connection)
        session = connection.Session
        self._session_id = connection.ID
        self._lost_observer = session.AddObserver(
            CONNECTION_LOST_EVENT, lambda *_: self._on_lost("ParaView's ConnectionLost event"))
        module = servermanager.vtkProcessModule.GetProcessModule()
        self._closed_observer = module.AddObserver("ConnectionClosedEvent", self._closed_callback())
        self._thread = None
        if self._fd is not None and self._fd >= 0:
            self._thread = threading.Thread(target=self._run, name="vesseltouch-connection-watch",
                                            daemon=True)
            self._thread.start()

    def add(self, listener):
        """`listener(message)` is called once when the connection is lost (held weakly when it
        is a bound method, so a dropped session is not kept alive)."""
        ref = weakref.WeakMethod(listener) if hasattr(listener, "__self__") else (
            lambda: listener)
        with self._lock:
            self._listeners.append(ref)
            lost = self.lost
        if lost:
            listener(lost_message(self.uri))

    def _run(self):
        poller = select.poll()
        poller.register(self._fd, _HANG_UP)
        while not self._stop.is_set():
            events = poller.poll(self._period_ms)
            if self._stop.is_set():
                return
            if any(mask & _HANG_UP for _, mask in events):
                self._on_lost("the server's socket was closed")
                return

    def _closed_callback(self):
        """vtkProcessModule::UnRegisterSession fires ConnectionClosedEvent with the session's id
        before it releases the session (whose destructor closes the socket): the watch of that
        session stops first. Held weakly: the module outlives every watch."""
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_INT
        me = weakref.ref(self)

        @calldata_type(VTK_INT)
        def on_closed(_module, _event, session_id):
            watch = me()
            if watch is not None and session_id == watch._session_id:
                watch._stop.set()
                _WATCHES.pop(session_id, None)
                _module.RemoveObserver(watch._closed_observer)
        return on_closed

    def _on_lost(self, how):
        with self._lock:
            if self.lost or self._stop.is_set():
                return
            self.lost = True
            listeners = [ref() for ref in self._listeners]
        message = lost_message(self.uri)
        print("VesselTouch: %s [%s]" % (message, how), file=sys.stderr, flush=True)
        for listener in listeners:
            if listener is not None:
                try:
                    listener(message)
                except Exception as e:  # noqa: BLE001 - one failure must not stop the rest
                    print("VesselTouch: a session could not take the fault: %s" % e,
                          file=sys.stderr, flush=True)

    def stop(self):
        self._stop.set()
        if self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=1.0)


#: Set by the VesselTouch panel in the GUI, where pqServer watches the connection and the panel
#: reports the loss on the main thread (a thread of ours would call into the server manager
#: while Qt's main thread uses it: no interpreter lock orders those).
GUI_WATCHES_ENV = "VESSELTOUCH_CONNECTION_WATCHED_IN_GUI"


def _process_env(name):
    """The variable as the process has it now (os.environ is a copy taken when Python started,
    possibly before the panel set it)."""
    import ctypes
    getenv = ctypes.CDLL(None).getenv
    getenv.restype = ctypes.c_char_p
    return getenv(name.encode())


def watch(listener, connection=None):
    """Adds `listener` to the watch of `connection` (the active one by default), started once
    per connection. Returns the watch, or None built in (nothing to lose) and in the GUI (the
    panel watches there)."""
    connection = connection or servermanager.ActiveConnection
    if connection is None or not connection.IsRemote() or _process_env(GUI_WATCHES_ENV):
        return None
    existing = _WATCHES.get(connection.ID)
    if existing is None or existing._stop.is_set():
        existing = _WATCHES[connection.ID] = ConnectionWatch(connection)
    existing.add(listener)
    return existing
