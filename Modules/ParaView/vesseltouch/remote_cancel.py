"""Cancel a VesselCenterline run on a pvserver from the client (issue 19 item 1, issue 16 item 6).

While the server runs the filter, the client's connection is busy with the update: the client
waits for its reply and nothing it sends there is read before the run ends. So each rank of the
server listens on a socket of its own for the run (vtouch::RemoteCancelListener), the first names
its port in the filter's progress text and tells the others when it hears the token. The port
travels in the progress text, which ParaView sends to the client during the update; this module
reads the port from the progress events and sends the filter's token there::

    import vesseltouch
    cancel = vesseltouch.RemoteCancel(centerline)  # before the update: the token, the progress
    threading.Timer(5.0, cancel.cancel).start()   # from any thread, or from a progress callback
    centerline.UpdatePipeline()            # returns early: empty output, "Cancelled."
    cancel.close()

Built in there is nothing to do (the panel's Extract runs in the background with its own Cancel).

Threads: this VTK is built without VTK_PYTHON_FULL_THREADSAFE, so a wrapped call (UpdatePipeline)
keeps Python's interpreter lock while it waits for the server; another Python thread runs only
while the main thread runs Python code, i.e. in the progress observer, which therefore yields the
lock once per progress event (``time.sleep(0)``) and also sends a cancel asked before the port was
known. ParaView sends the first rank's progress at most once a second (vtkPVProgressHandler's
server interval), so a cancel from another thread takes effect within about a second of a progress
event; a cancel from a progress callback (``on_progress``) at once.
"""

import re
import secrets
import socket
import threading
import time

from paraview import servermanager

PORT_TEXT = re.compile(r"VesselCenterline: cancel port (\d+)")
# Project rule: the connection to the cancel socket and its answer may take this long (a server on
# a LAN answers in milliseconds; a cancel that cannot be delivered must not hang the client).
SEND_TIMEOUT_S = 5.0


def server_host(connection=None):
    """The host the client connected to (the pvserver's data server), from the session's URI
    ("cs://host:port"); None built in."""
    connection = connection or servermanager.ActiveConnection
    if connection is None or not connection.IsRemote():
        return None
    match = re.match(r"^\w+://([^:/]+)", connection.GetURI())
    return match.group(1) if match else None


class RemoteCancel:
    """The client's side of a remote cancel for one VesselCenterline proxy.

    ``centerline``: the proxy. ``on_progress(fraction, text)``: optional, called on the main
    thread at each progress event of the server during an update (return True to cancel).
    """

    def __init__(self, centerline, on_progress=None, connection=None):
        self.centerline = centerline
        self.on_progress = on_progress
        self.connection = connection or servermanager.ActiveConnection
        self.host = server_host(self.connection)
        self.port = None
        self.progress = 0.0
        self.answer = None      # the server's answer to the cancel ("cancelling", ...)
        self.error = None       # why a cancel could not be sent
        self.sent_at = None     # time.monotonic() when the token was sent
        self._wanted = threading.Event()
        self._lock = threading.Lock()
        token = centerline.GetProperty("RemoteCancelToken").GetElement(0)
        if not token:
            # One token per proxy (project rule: it is not a parameter of the output, so it is
            # set once and never forces a re-execution).
            token = secrets.token_hex(16)
            centerline.GetProperty("RemoteCancelToken").SetElement(0, token)
            centerline.UpdateVTKObjects()
        self.token = token
        self._handler = self.connection.Session.GetProgressHandler()
        self._tag = self._handler.AddObserver("ProgressEvent", self._on_progress_event)

    def close(self):
        """Stops watching the progress (the token stays on the proxy)."""
        if self._tag is not None:
            self._handler.RemoveObserver(self._tag)
            self._tag = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def cancel(self):
        """Asks the running extraction to stop (any thread). Sent at once when the port is known,
        else at the next progress event that names it."""
        self._wanted.set()
        if self.port is not None:
            self._send()

    def cancelled(self):
        """Whether the server acknowledged the cancel."""
        return self.answer == "cancelling"

    def _on_progress_event(self, handler, event):
        text = handler.GetLastProgressText() or ""
        match = PORT_TEXT.search(text)
        if match:
            self.port = int(match.group(1))
        self.progress = handler.GetLastProgress() / 100.0
        if self.on_progress is not None and self.on_progress(self.progress, text):
            self._wanted.set()
        if self._wanted.is_set() and self.port is not None:
            self._send()
        time.sleep(0)  # another Python thread (a timer's cancel) may run now

    def _send(self):
        with self._lock:
            if self.answer is not None or self.host is None:
                if self.host is None:
                    self.error = "not connected to a pvserver"
                return
            try:
                with socket.create_connection((self.host, self.port), SEND_TIMEOUT_S) as s:
                    s.settimeout(SEND_TIMEOUT_S)
                    self.sent_at = time.monotonic()
                    s.sendall((self.token + "\n").encode())
                    self.answer = s.makefile().readline().strip()
            except OSError as e:
                self.error = "the cancel could not reach %s:%s: %s" % (self.host, self.port, e)
                self.answer = ""
