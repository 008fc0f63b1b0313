"""The tracing agent over a cached MIP in a ParaView render view.

The MIP of a large volume costs about half a second per frame on a CPU-only machine, while the agent
moves at the GUI rate (~60 Hz). ``AgentOverlay`` keeps the agent out of the ParaView pipeline and
re-renders the volume only when the scene changed::

    overlay = vesseltouch.AgentOverlay(view)
    overlay.MoveAgent(position_mm, direction, roll_deg, state="tracing")   # ~2-20 ms, not 500 ms

How it works (see Docs/RENDERING.md):

* The agent (a cone, red apex and sides, blue base, a white stripe that shows the roll, and a yellow
  cursor sphere for the exploring state) lives in an overlay ``vtkRenderer`` on a new top layer of
  the view's render window. It shares the view's camera and is not interactive, so picking and
  camera interaction still go to ParaView's renderers. Moving it only changes a vtkMatrix4x4.
* Whenever ParaView renders the view (any normal render: camera, data or transfer function
  change), the overlay's StartEvent fires after every lower layer has been drawn; the overlay copies
  the colour buffer (MIP + annotations, without the agent) into its background texture.
* An agent-only frame turns drawing off for every other renderer of the window, lets the overlay
  clear to that texture and draw the agent, and renders the VTK window directly: no proxy, no
  pipeline update, no volume ray casting.
* Before an agent-only frame the cache is checked: a changed camera, window size, a view that
  needs an update (modified representation, data, transfer function) or ``Invalidate()`` forces a
  normal ParaView render, which re-captures.

Only VTK calls run per frame; ParaView's own view is used for the full renders only.
"""

import math

from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonMath import vtkMatrix4x4
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
from vtkmodules.vtkFiltersSources import vtkConeSource, vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer, vtkTexture

from .vectors import cross, unit

#: Agent colours (RGB 0-255): apex and sides, base, roll stripe, exploring cursor.
SIDE_RGB = (230, 20, 20)
BASE_RGB = (20, 40, 235)
STRIPE_RGB = (255, 255, 255)
CURSOR_RGB = (255, 215, 0)

#: Agent states, as the haptic session publishes them.
STATES = ("hidden", "exploring", "tracing")

_RESOLUTION = 32  # cone facets


def _cone_polydata(resolution=_RESOLUTION):
    """A unit-height cone along +Z centred on the origin (apex at z=+0.5, base at z=-0.5, base
    radius 0.35) with per-cell colours: blue base, red sides, a white stripe at +X for the roll."""
    cone = vtkConeSource()
    cone.SetResolution(resolution)
    cone.SetHeight(1.0)
    cone.SetRadius(0.35)
    cone.SetCenter(0.0, 0.0, 0.0)
    cone.SetDirection(0.0, 0.0, 1.0)
    cone.CappingOn()
    cone.Update()
    poly = cone.GetOutput()
    colours = vtkUnsignedCharArray()
    colours.SetName("AgentColours")
    colours.SetNumberOfComponents(3)
    points = poly.GetPoints()
    for cell_id in range(poly.GetNumberOfCells()):
        ids = poly.GetCell(cell_id).GetPointIds()
        if ids.GetNumberOfIds() > 3:  # the base polygon
            colours.InsertNextTuple3(*BASE_RGB)
            continue
        # The side facet whose base edge midpoint lies closest to +X marks the roll.
        xs = [points.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
        base = [p for p in xs if p[2] < 0.0]
        mid = [sum(c) / len(base) for c in zip(*base)] if base else (0.0, 0.0, 0.0)
        angle = math.degrees(math.atan2(mid[1], mid[0]))
        stripe = abs(angle) < 360.0 / resolution  # two facets: visible, red still dominates
        colours.InsertNextTuple3(*(STRIPE_RGB if stripe else SIDE_RGB))
    poly.GetCellData().SetScalars(colours)
    normals = vtkPolyDataNormals()  # smooth sides, a flat base
    normals.SetInputData(poly)
    normals.SetFeatureAngle(45.0)
    normals.SplittingOn()
    normals.ComputeCellNormalsOff()
    normals.Update()
    return normals.GetOutput()


def _unit(v):
    return unit(v, ValueError("AgentOverlay: the agent direction must be a non-zero finite vector"))


def agent_matrix(position_mm, direction, roll_deg, size_mm):
    """The 4x4 (row-major list of 16) that places the unit cone: its axis (apex) along
    ``direction``, its centre at ``position_mm``, its height ``size_mm``, and its stripe rolled by
    ``roll_deg`` about the axis from a reference that is world +Z (or +X when the axis is near Z)
    made perpendicular to the axis."""
    d = _unit(direction)
    reference = [0.0, 0.0, 1.0] if abs(d[2]) < 0.9 else [1.0, 0.0, 0.0]
    dot = sum(r * c for r, c in zip(reference, d))
    u0 = _unit([r - dot * c for r, c in zip(reference, d)])
    v0 = cross(d, u0)
    c, s = math.cos(math.radians(roll_deg)), math.sin(math.radians(roll_deg))
    u = [c * a + s * b for a, b in zip(u0, v0)]
    v = cross(d, u)
    k = float(size_mm)
    m = [0.0] * 16
    for row in range(3):
        m[4 * row + 0] = k * u[row]
        m[4 * row + 1] = k * v[row]
        m[4 * row + 2] = k * d[row]
        m[4 * row + 3] = float(position_mm[row])
    m[15] = 1.0
    return m


class AgentOverlay:
    """The agent and the cached MIP in ParaView render ``view`` (builtin session).

    ``mip_rep`` is optional and only informative (the representation whose MIP is cached); any
    representation change marks the view as needing an update, which forces a full render.
    ``size_mm`` is the cone height in millimetres (default 6 mm)."""

    def __init__(self, view, mip_rep=None, size_mm=6.0):
        if servermanager.ActiveConnection is None or servermanager.ActiveConnection.IsRemote():
            raise RuntimeError("AgentOverlay needs the builtin session (a local render window)")
        self.view = view
        self.mip_rep = mip_rep
        self.size_mm = float(size_mm)
        self.use_cache = True
        self.full_renders = 0  # frames in which ParaView drew the scene (the volume)
        self.cached_frames = 0  # agent-only frames drawn over the cached image
        self.captures = 0
        self.last_frame_cached = False
        self._window = view.GetRenderWindow()
        self._scene = view.GetRenderer()
        self._valid = False
        self._stamp = None
        self._build_actors()
        self._build_overlay()
        self._state = "hidden"
        self.SetState("hidden")

    # ---- set-up -------------------------------------------------------------------------------
    def _build_actors(self):
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(_cone_polydata())
        mapper.SetScalarModeToUseCellData()
        mapper.SetColorModeToDirectScalars()
        self.cone = vtkActor()
        self.cone.SetMapper(mapper)
        self.cone.PickableOff()
        prop = self.cone.GetProperty()
        prop.SetAmbient(0.35)
        prop.SetDiffuse(0.65)
        prop.SetSpecular(0.1)
        sphere = vtkSphereSource()
        sphere.SetRadius(0.25)
        sphere.SetThetaResolution(24)
        sphere.SetPhiResolution(16)
        cursor_mapper = vtkPolyDataMapper()
        cursor_mapper.SetInputConnection(sphere.GetOutputPort())
        self.cursor = vtkActor()
        self.cursor.SetMapper(cursor_mapper)
        self.cursor.PickableOff()
        self.cursor.GetProperty().SetColor(*[c / 255.0 for c in CURSOR_RGB])
        self.cursor.GetProperty().SetAmbient(0.4)
        self._matrix = vtkMatrix4x4()
        self.cone.SetUserMatrix(self._matrix)
        self.cursor.SetUserMatrix(self._matrix)

    def _build_overlay(self):
        window = self._window
        self._layer = window.GetNumberOfLayers()
        window.SetNumberOfLayers(self._layer + 1)
        overlay = vtkRenderer()
        overlay.SetLayer(self._layer)
        overlay.SetPreserveColorBuffer(1)  # full frames: draw the agent over ParaView's image
        overlay.SetPreserveDepthBuffer(0)  # the agent is always on top of the MIP
        overlay.InteractiveOff()  # picking and camera interaction stay with ParaView
        overlay.SetActiveCamera(self._scene.GetActiveCamera())
        overlay.AddActor(self.cone)
        overlay.AddActor(self.cursor)
        window.AddRenderer(overlay)
        self.overlay = overlay
        self._pixels = vtkUnsignedCharArray()
        self._image = vtkImageData()
        self._texture = vtkTexture()
        self._texture.InterpolateOff()
        self._texture.SetInputData(self._image)
        self._observers = [overlay.AddObserver("StartEvent", self._on_overlay_start),
                           overlay.AddObserver("EndEvent", self._on_overlay_end)]

    def Remove(self):
        """Takes the agent and its layer out of the view; ParaView renders as before."""
        if self.overlay is None:
            return
        for observer in self._observers:
            self.overlay.RemoveObserver(observer)
        self._window.RemoveRenderer(self.overlay)
        if self._window.GetNumberOfLayers() == self._layer + 1:
            self._window.SetNumberOfLayers(self._layer)
        self.overlay = None

    # ---- the cache ----------------------------------------------------------------------------
    def _scene_stamp(self):
        """What the cached image depends on: the camera, the window size, and the last change of
        anything a visible prop of the scene renders (mapper, input, transfer functions: the
        props' redraw time, which a transfer-function edit moves at once)."""
        camera = self._scene.GetActiveCamera()
        props = self._scene.GetViewProps()
        props.InitTraversal()
        redraw = 0
        for _ in range(props.GetNumberOfItems()):
            prop = props.GetNextProp()
            if prop.GetVisibility():
                redraw = max(redraw, prop.GetRedrawMTime())
        return (camera.GetMTime(), tuple(self._window.GetSize()), camera.__this__, redraw)

    def _on_overlay_start(self, _overlay, _event):
        """Every lower layer has been drawn. In a ParaView (full) frame, copy it as the cache."""
        if not self._scene.GetDraw():
            return  # an agent-only frame: the background is the cached texture
        camera = self._scene.GetActiveCamera()
        if self.overlay.GetActiveCamera().__this__ != camera.__this__:  # ParaView swapped it
            self.overlay.SetActiveCamera(camera)
        if self._scene.GetSelector() is not None:
            # A hardware-selection pass (ParaView picking): the buffer holds ids, not an image to
            # keep, and the agent must not write colours over them.
            self.cone.VisibilityOff()
            self.cursor.VisibilityOff()
            return
        self.full_renders += 1
        width, height = self._window.GetSize()
        if width <= 0 or height <= 0:
            return
        self._window.GetRGBACharPixelData(0, 0, width - 1, height - 1, 0, self._pixels)
        self._image.SetDimensions(width, height, 1)
        self._image.GetPointData().SetScalars(self._pixels)
        self._image.Modified()
        self.captures += 1
        self._stamp = self._scene_stamp()
        self._valid = True

    def _on_overlay_end(self, _overlay, _event):
        self.SetState(self._state)  # visibility back after a selection pass

    def Invalidate(self):
        """Forces the next frame to re-render the scene (the volume) through ParaView."""
        self._valid = False

    def IsCacheValid(self):
        """True when the next agent frame can reuse the last MIP image: it exists, and neither
        the camera, the window size nor the view's representations changed since."""
        return (self._valid and self._stamp == self._scene_stamp()
                and not self.view.SMProxy.GetNeedsUpdate())

    # ---- the agent ----------------------------------------------------------------------------
    def SetState(self, state):
        """'hidden', 'exploring' (a yellow cursor sphere at the position) or 'tracing' (the
        cone). Integers 0, 1, 2 are accepted too."""
        if isinstance(state, int):
            state = STATES[state]
        if state not in STATES:
            raise ValueError("AgentOverlay: state must be one of %s, got %r" % (STATES, state))
        self._state = state
        self.cone.SetVisibility(state == "tracing")
        self.cursor.SetVisibility(state == "exploring")

    def SetAgentPose(self, position_mm, direction=(0.0, 0.0, 1.0), roll_deg=0.0, size_mm=None):
        """Places the agent (no rendering): centre, apex direction, roll about it, height."""
        if size_mm is not None:
            self.size_mm = float(size_mm)
        self._matrix.DeepCopy(agent_matrix(position_mm, direction, roll_deg, self.size_mm))

    def MoveAgent(self, position_mm, direction=(0.0, 0.0, 1.0), roll_deg=0.0, state="tracing"):
        """Places the agent and renders one frame; returns True when it reused the cached MIP."""
        self.SetAgentPose(position_mm, direction, roll_deg)  # validates before any change shows
        self.SetState(state)
        return self.Render()

    def Render(self):
        """Renders one frame: over the cached MIP when it is valid (and ``use_cache``), else a
        normal ParaView render that re-renders the volume and refreshes the cache. Returns True
        when the frame reused the cache (also in ``last_frame_cached``)."""
        if self.overlay is None:
            raise RuntimeError("AgentOverlay: removed")
        if self.use_cache and self.IsCacheValid():
            self._render_cached()
            self.last_frame_cached = True
        else:
            self.view.StillRender()
            self.last_frame_cached = False
        return self.last_frame_cached

    def _render_cached(self):
        others = []
        renderers = self._window.GetRenderers()
        renderers.InitTraversal()
        for _ in range(renderers.GetNumberOfItems()):
            renderer = renderers.GetNextItem()
            if renderer is not self.overlay and renderer.GetDraw():
                others.append(renderer)
                renderer.DrawOff()
        overlay = self.overlay
        overlay.SetPreserveColorBuffer(0)
        overlay.SetBackgroundTexture(self._texture)
        overlay.TexturedBackgroundOn()
        try:
            self._window.Render()
        finally:
            overlay.TexturedBackgroundOff()
            overlay.SetPreserveColorBuffer(1)
            for renderer in others:
                renderer.DrawOn()
        self.cached_frames += 1

    # ---- helpers for tests and the GUI --------------------------------------------------------
    def ProjectToDisplay(self, point_mm):
        """Display (pixel) coordinates (x from the left, y from the bottom) of a world point."""
        self._scene.SetWorldPoint(point_mm[0], point_mm[1], point_mm[2], 1.0)
        self._scene.WorldToDisplay()
        x, y, _ = self._scene.GetDisplayPoint()
        return x, y

    def CaptureWindow(self):
        """The last rendered frame as a NumPy array (height, width, 3), row 0 at the top."""
        from vtkmodules.util.numpy_support import vtk_to_numpy
        width, height = self._window.GetSize()
        pixels = vtkUnsignedCharArray()
        self._window.GetRGBACharPixelData(0, 0, width - 1, height - 1, 0, pixels)
        return vtk_to_numpy(pixels).reshape(height, width, 4)[::-1, :, :3].copy()
