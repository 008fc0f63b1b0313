"""The camera of a :class:`vesseltouch.HapticSession`: copied from a render view once or
continuously, reset to fit the centerline, given as vtkCamera values or explicit matrices, and read
back as a frame of unit vectors. A mixin: the session provides ``proxy`` and ``_set``."""

import math

from paraview import simple

from .vectors import cross, unit


def _normalized(v):
    return unit(v, RuntimeError("the session's camera is degenerate"))


class SessionCamera:
    """Camera methods of HapticSession (world mm, viewport px)."""

    def FollowView(self, view=None):
        """Copies the camera of ``view`` (default: the active view) now and after every change of
        it (a vtkCamera observer), so the haptic scene matches what is shown. FollowView(None)
        after FollowView(view) keeps following the active view; UnfollowView() stops."""
        view = view or simple.GetActiveView()
        if view is None:
            raise RuntimeError("FollowView: no render view")
        self.UnfollowView()
        camera = view.GetActiveCamera()
        state = {"last": None}

        def follow(*_):
            current = (tuple(view.CameraPosition), tuple(view.CameraFocalPoint),
                       tuple(view.CameraViewUp), view.CameraParallelScale,
                       int(view.CameraParallelProjection), tuple(view.ViewSize))
            if current != state["last"]:
                state["last"] = current
                self.SetCameraFromView(view)

        self._follow = (camera, camera.AddObserver("ModifiedEvent", follow))
        follow()

    def ResetCamera(self, direction=(0.0, 0.0, -1.0), view_up=(0.0, 1.0, 0.0), size=None):
        """An orthographic camera looking at the centerline's centre along ``direction`` (the
        direction of projection), fitting the whole centerline. ``size``: (width, height) px."""
        port = self.centerline_source()
        if port is None:
            raise RuntimeError("ResetCamera: no centerline")
        port.UpdatePipeline()
        bounds = port.GetDataInformation().GetBounds()
        if bounds[0] > bounds[1]:
            raise RuntimeError("ResetCamera: the centerline is empty")
        centre = [0.5 * (bounds[2 * i] + bounds[2 * i + 1]) for i in range(3)]
        radius = 0.5 * math.sqrt(sum((bounds[2 * i + 1] - bounds[2 * i]) ** 2 for i in range(3)))
        norm = math.sqrt(sum(d * d for d in direction)) or 1.0
        distance = 2.0 * radius + 1.0
        position = [centre[i] - direction[i] / norm * distance for i in range(3)]
        self.SetCamera(position=position, focal_point=centre, view_up=view_up, parallel=True,
                       parallel_scale=0.0, size=size)

    def SetCamera(self, position=None, focal_point=None, view_up=None, parallel=None,
                  parallel_scale=None, view_angle=None, size=None):
        """Camera in world mm (like vtkCamera); ``parallel_scale`` 0 fits the centerline;
        ``size`` = (width, height) of the viewport in pixels. Rebuilds the view model."""
        props = {}
        if position is not None:
            props["CameraPosition"] = list(position)
        if focal_point is not None:
            props["CameraFocalPoint"] = list(focal_point)
        if view_up is not None:
            props["CameraViewUp"] = list(view_up)
        if parallel is not None:
            props["CameraParallelProjection"] = 1 if parallel else 0
        if parallel_scale is not None:
            props["CameraParallelScale"] = parallel_scale
        if view_angle is not None:
            props["CameraViewAngle"] = view_angle
        if size is not None:
            props["ViewportSize"] = [int(size[0]), int(size[1])]
        props["UseExplicitMatrices"] = 0
        self._set(**props)

    def SetCameraFromView(self, view=None):
        """Copies the camera and size of a render view (default: the active view)."""
        view = view or simple.GetActiveView()
        if view is None:
            raise RuntimeError("SetCameraFromView: no render view")
        if hasattr(view.SMProxy, "SynchronizeCameraProperties"):
            view.SMProxy.SynchronizeCameraProperties()  # the vtkCamera may have moved since
        self.SetCamera(position=view.CameraPosition, focal_point=view.CameraFocalPoint,
                       view_up=view.CameraViewUp, parallel=bool(view.CameraParallelProjection),
                       parallel_scale=view.CameraParallelScale, view_angle=view.CameraViewAngle,
                       size=view.ViewSize)

    def SetCameraMatrices(self, view_matrix, projection_matrix, size=None):
        """World->eye and eye->clip matrices, row-major (16 values or vtkMatrix4x4)."""
        def flat(m):
            if hasattr(m, "GetElement"):
                return [m.GetElement(r, c) for r in range(4) for c in range(4)]
            return [float(v) for v in m]
        props = {"ViewMatrix": flat(view_matrix), "ProjectionMatrix": flat(projection_matrix),
                 "UseExplicitMatrices": 1}
        if size is not None:
            props["ViewportSize"] = [int(size[0]), int(size[1])]
        self._set(**props)

    def UnfollowView(self):
        """Stops FollowView()."""
        follow = getattr(self, "_follow", None)
        if follow is not None:
            follow[0].RemoveObserver(follow[1])
        self._follow = None

    def GetCameraFrame(self):
        """The session's camera as (position, right, up, forward) unit vectors in world mm:
        ``right``/``up`` are the screen (= device) x/y axes, ``forward`` the viewing direction."""
        p = self.proxy
        if p.GetProperty("UseExplicitMatrices").GetData():
            m = list(p.GetProperty("ViewMatrix").GetData())  # row-major world -> eye
            right, up, back = m[0:3], m[4:7], m[8:11]
            rotation_t = [[m[4 * c + r] for c in range(3)] for r in range(3)]
            t = [m[3], m[7], m[11]]
            position = [-sum(rotation_t[r][c] * t[c] for c in range(3)) for r in range(3)]
            return position, _normalized(right), _normalized(up), _normalized([-v for v in back])
        position = list(p.GetProperty("CameraPosition").GetData())
        focal = list(p.GetProperty("CameraFocalPoint").GetData())
        forward = _normalized([f - q for f, q in zip(focal, position)])
        right = _normalized(cross(forward, list(p.GetProperty("CameraViewUp").GetData())))
        return position, right, cross(right, forward), forward
