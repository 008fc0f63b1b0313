"""The centerline delivered to the haptic session in the client (issue 19, item 1).

Built in (one process), the session reads the centerline filter's output directly. Connected to
a pvserver (``Connect``), the volume and VesselCenterline stay on the server ranks while the
haptic session, its loop thread and the device live in the client process (the session proxy is
declared ``processes="client"``): Mark et al.'s decoupling of the servo loop from the application
on a second machine (cited by Yi & Hayward section 2.3), with the Q-skeleton as the small
intermediate representation. The skeleton crosses once per extraction: the ranks' polylines are
appended on rank 0 (ParaView's ReductionFilter with vtkAppendPolyData) and moved to the client
(ClientServerMoveData), whose client-side output is the session's input.

The two helper proxies are not registered: they are the session's plumbing, not pipeline items.
They must be updated on every process together (``update()``: ParaView's UpdatePipeline on the
proxy does that) before the client's session reads them; the client alone would wait for a
server that is not sending.
"""

from paraview import servermanager

from .connection import is_remote

__all__ = ["is_remote", "CenterlineDelivery"]

_VTK_POLY_DATA = 0


class CenterlineDelivery:
    """The server's centerline (an output port or proxy) as polydata in the client."""

    def __init__(self, port):
        self.source = port
        self.reducer = servermanager.filters.ReductionFilter(Input=port)
        self.reducer.PostGatherHelperName = "vtkAppendPolyData"
        self.mover = servermanager.filters.ClientServerMoveData(Input=self.reducer)
        self.mover.OutputDataType = _VTK_POLY_DATA
        self.update()

    def update(self):
        """Gathers and moves the current centerline (every process takes part)."""
        self.reducer.UpdatePipeline()
        self.mover.UpdatePipeline()

    def client_copy(self):
        """The delivered polydata in this (client) process."""
        return self.mover.GetClientSideObject().GetOutputDataObject(0)

    @property
    def port(self):
        """What the client-side session takes as its Input."""
        return self.mover
