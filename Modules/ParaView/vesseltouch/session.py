"""The VesselTouch haptic session from ParaView's Python shell and pvpython.

A thin, documented layer over the ``VesselTouchHapticSession`` proxy (the VTK class
``vtkVesselTouchHapticSession``, which owns the C++ ``vtouch::HapticSession``). Load the plugin
first, then::

    from paraview.simple import *
    LoadPlugin("/path/to/VesselTouch.so", ns=globals())
    import vesseltouch

    phantom = VesselPhantom(Shape="Helix")
    s = vesseltouch.HapticSession(phantom)          # a VesselPhantom: its centerline (port 1)
    s.ResetCamera(direction=(0, 1, 0), view_up=(0, 0, 1))  # the helix seen from the side
    s.SetDevice("simulated")
    s.SetForceLaw("LDGF", k=0.3, lambda_mm=0.005)
    s.SetZoom(1.0)
    s.SetHandSweep(path=0, speed_mm_per_s=100.0)    # a scripted hand following the vessel
    s.RunOffline(6.0, rate_Hz=1000.0)               # deterministic, simulated time
    log = s.GetLog()                                # dict of NumPy arrays
    print(log["time"].shape, log["force"].max(), s.GetAgentState()["state"])

``vesseltouch.logic()`` returns the session the GUI panel shows (like
``slicer.modules.<name>.logic()``): the proxy registered as "VesselTouchSession", adopted if the
panel (C++) or a script created it, created and registered otherwise, replaced if deleted.
``vesseltouch.ExtractCenterlines(volume)`` gives it a centerline from the voxels.

Units: millimetres, newtons, seconds, pixels (screen origin at the bottom-left corner).
Errors (no centerline, an unusable camera, a device that does not open) raise ``RuntimeError``
with the session's reason; the C++ side also reports them with vtkErrorMacro.
"""

import math

from paraview import servermanager, simple

from .delivery import CenterlineDelivery, is_remote
from .haptic_parameters import HapticParameterAccess, _key

__all__ = ["HapticSession", "logic", "SESSION_NAME", "FORCE_LAW_ALIASES", "DEVICES"]

#: Short names accepted by :meth:`HapticSession.SetForceLaw` beside the labels of the
#: ``ForceLaw`` property's choices (which come from the parameter table through the proxy).
FORCE_LAW_ALIASES = {"coh": "changeofheight", "lateral": "lateralgradient",
                     "proxy": "constraintproxy"}
#: Device names accepted by :meth:`HapticSession.SetDevice` -> the ``DeviceType`` value.
DEVICES = {"simulated": 0, "pointer": 1, "mouse": 1, "replay": 2, "hid": 3}

_STATISTICS = ("nominal_rate_Hz", "achieved_rate_Hz", "ticks", "overruns", "skipped_deadlines",
               "period_error_p50_us", "period_error_p99_us", "period_error_p999_us",
               "period_error_max_us", "tick_cost_p50_us", "tick_cost_p99_us", "tick_cost_max_us")
_LOG_COLUMNS = {"Time": "time", "Hand": "hand", "Cursor": "cursor", "State": "state",
                "Path": "path", "Point": "point", "Position": "position",
                "TargetForce": "target_force", "Force": "force"}


def _given(**values):
    """The keyword arguments that were given (not None)."""
    return {name: v for name, v in values.items() if v is not None}


def _first(value):
    """An information property's single value (servermanager gives a scalar or a list)."""
    return value[0] if isinstance(value, (list, tuple)) else value


def _normalized(v):
    n = math.sqrt(sum(c * c for c in v))
    if n == 0.0 or not math.isfinite(n):
        raise RuntimeError("the session's camera is degenerate")
    return [c / n for c in v]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _centerline_port(centerline):
    """A proxy or output port (servermanager.OutputPort) -> the port carrying the centerline."""
    if centerline is None:
        return None
    if getattr(centerline, "Port", 0) == 0 and centerline.GetXMLName() == "VesselPhantom":
        return servermanager.OutputPort(centerline, 1)  # port 1: the analytic centerline
    return centerline


class HapticSession(HapticParameterAccess):
    """One haptic session: centerline + camera + device + force law + zones + zoom.

    ``centerline``: a VesselCenterline proxy, a VesselPhantom proxy (its port 1 is used) or any
    output port producing the centerline polydata; may be given later with SetCenterline().
    ``view``: a render view whose camera and size the session copies (SetCameraFromView);
    without one the camera looks at the centerline along -z (ResetCamera).
    ``proxy``: wrap an existing VesselTouchHapticSession proxy instead of creating one.
    """

    def __init__(self, centerline=None, view=None, proxy=None, registrationName=None):
        self._delivery = None
        if proxy is None:
            proxy = self._create_proxy(self._delivered(centerline), registrationName)
        self.proxy = proxy
        if centerline is not None:
            if view is not None:
                self.SetCameraFromView(view)
            else:
                self.ResetCamera()

    @staticmethod
    def _create_proxy(port, registrationName):
        pxm = servermanager.ProxyManager()
        if not pxm.SMProxyManager.GetProxyDefinitionManager().HasDefinition(
                "filters", "VesselTouchHapticSession"):
            raise RuntimeError("The VesselTouch plugin is not loaded (LoadPlugin first).")
        # Python names proxies by their XML label ("Haptic Session").
        create = simple._create_func("HapticSession", servermanager.filters)
        active = simple.GetActiveSource()
        simple.SetActiveSource(None)  # never adopt an unrelated active source as the input
        try:
            params = {"registrationName": registrationName or "HapticSession"}
            if port is not None:
                params["Input"] = port
            return create(**params)
        finally:
            simple.SetActiveSource(active)

    def _delivered(self, centerline):
        """The port the session takes as input: the centerline itself built in; connected to a
        pvserver, its copy delivered to the client, where the session lives (delivery.py)."""
        port = _centerline_port(centerline)
        if port is None or not is_remote():
            self._delivery = None
            return port
        self._delivery = CenterlineDelivery(port)
        return self._delivery.port

    # --- helpers ---------------------------------------------------------------------------
    def _set(self, **properties):
        """Sets several properties and pushes them in ONE UpdateVTKObjects, so the session's
        ApplyProperties (the proxy's post_push) publishes them to the haptic thread together:
        a camera's position, focal point and view up never arrive apart. A haptic parameter the
        session refuses (out of its range: the C++ session checks every value against the
        parameter table) raises ValueError with the session's message; it keeps its old value."""
        smproxy = self.proxy.SMProxy
        for name, value in properties.items():
            prop = smproxy.GetProperty(name)
            if prop is None or not hasattr(prop, "SetElement") or isinstance(value, str):
                self.proxy.SetPropertyWithName(name, value)  # inputs, strings: as ParaView does
                continue
            values = list(value) if isinstance(value, (list, tuple)) else [value]
            if prop.GetClassName() == "vtkSMIntVectorProperty":
                values = [self._whole(name, v) for v in values]
            prop.SetNumberOfElements(len(values))
            for i, v in enumerate(values):
                prop.SetElement(i, v)
        smproxy.UpdateVTKObjects()
        requested = {n: float(v) for n, v in properties.items()
                     if n in self.HapticParameterNames() and not isinstance(v, (list, tuple, str))}
        if requested:
            self._check_refused(requested)

    def _info(self, name):
        self.proxy.UpdatePropertyInformation()
        return self.proxy.GetProperty(name).GetData()

    def _check(self, what):
        error = self.GetLastError()
        if error:
            raise RuntimeError("%s: %s" % (what, error))

    # --- scene -----------------------------------------------------------------------------
    def SetCenterline(self, centerline):
        """Uses this centerline (VesselCenterline, VesselPhantom or an output port)."""
        self._set(Input=self._delivered(centerline))

    def Bind(self, centerline, view=None):
        """SetCenterline(), then the camera of ``view`` (SetCameraFromView) or, without a view,
        ResetCamera(), and reads the centerline into the session. Returns self."""
        self.SetCenterline(centerline)
        if view is not None:
            self.SetCameraFromView(view)
        else:
            self.ResetCamera()
        self.proxy.UpdatePipeline()  # the session reads the centerline: ready to Start()
        return self

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
        port = self.proxy.Input
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

    # --- device ----------------------------------------------------------------------------
    def SetDevice(self, kind="simulated", path=None, mass_kg=None, damping_N_s_per_m=None,
                  max_force_N=None):
        """'simulated' (mass_kg, damping_N_s_per_m, max_force_N), 'pointer', 'replay' (path of a
        CSV) or 'hid' (hidapi path). The device opens at Start()/RunOffline(), inside the safety
        layer."""
        try:
            props = {"DeviceType": DEVICES[_key(kind)]}
        except KeyError:
            raise ValueError("unknown device %r (one of %s)" % (kind, ", ".join(DEVICES)))
        if path is not None:
            props["ReplayFileName" if props["DeviceType"] == 2 else "HidPath"] = str(path)
        if mass_kg is not None:
            props["SimulatedMass"] = mass_kg
        if damping_N_s_per_m is not None:
            props["SimulatedDamping"] = damping_N_s_per_m
        if max_force_N is not None:
            props["SimulatedMaxForce"] = max_force_N
        self._set(**props)

    def SetHandSweep(self, path=0, speed_mm_per_s=50.0, pressure=1.0):
        """Simulated hand: approach the first point of ``path`` from 20 mm to the right in
        0.3 s, then follow its screen projection at ``speed_mm_per_s`` (device mm)."""
        self._set(HandScript=1, SweepPath=int(path), SweepSpeed=speed_mm_per_s,
                  HandPressure=pressure)

    def SetHandTrajectory(self, times, xs, ys, cursor_start=None, pressure=1.0):
        """Simulated hand positions (device mm) at ``times`` (s, increasing from 0), linearly
        interpolated. ``cursor_start``: cursor (px) at the first sample (default: the centre)."""
        times, xs, ys = list(times), list(xs), list(ys)
        if not (len(times) == len(xs) == len(ys)) or not times:
            raise ValueError("times, xs and ys must be non-empty and of one length")
        samples = []
        previous = -math.inf
        for t, x, y in zip(times, xs, ys):
            t, x, y = float(t), float(x), float(y)
            if not (math.isfinite(t) and math.isfinite(x) and math.isfinite(y)) or t <= previous:
                raise ValueError("hand samples need finite values and increasing times")
            previous = t
            samples.extend((t, x, y))
        cursor = [-1.0, -1.0] if cursor_start is None else [float(v) for v in cursor_start]
        self._set(HandScript=2, HandSamples=samples, InitialCursor=cursor, HandPressure=pressure)

    def SetPointer(self, x_mm, y_mm, pressed=None):
        """Pointer device: the mouse position in device mm (and the pressure modifier)."""
        self._set(PointerPosition=[x_mm, y_mm])
        if pressed is not None:
            self._set(PointerPressed=1 if pressed else 0)

    # --- force -----------------------------------------------------------------------------
    def SetForceLaw(self, law, k=None, lambda_mm=None, z_max_mm=None, probe_px=None, k_c=None,
                    b_c=None, tau_t=None, snap_N=None, tangent_drag=None, snap_drag=None,
                    z_max_counts=None):
        """'LDGF', 'ChangeOfHeight', 'LateralGradient', 'ConstraintProxy' or 'None' (the labels
        of the ForceLaw property's choices, or the short names of FORCE_LAW_ALIASES), with the
        law's parameters: ``k`` (N, the force-zone gain k(P) in the saturation zone),
        ``lambda_mm`` (LDGF / change of height), ``z_max_mm`` (change of height, Hayward & Yi
        eq. 8; 0 = ``z_max_counts`` counts of the device's resolution), ``probe_px`` (lateral
        gradient), ``k_c`` (N/m), ``b_c`` (N s/m), ``tau_t``, ``snap_N`` (N), ``tangent_drag``, ``snap_drag``
        (constraint proxy). Switching is crossfaded (no force jump). Every other haptic
        parameter: SetHapticParameters(); defaults, ranges and meanings:
        DescribeHapticParameters()."""
        choices = self._choices("ForceLaw")
        key = _key(law)
        value = choices.get(FORCE_LAW_ALIASES.get(key, key))
        if value is None:
            raise ValueError("unknown force law %r (one of %s)"
                             % (law, ", ".join(list(choices) + list(FORCE_LAW_ALIASES))))
        props = {"ForceLaw": value}
        if k is not None:
            props["ZoneGain"] = k
        if lambda_mm is not None:
            props["ChangeOfHeightLambda" if value == 1 else "LdgfLambda"] = lambda_mm
        optional = (("ChangeOfHeightZMax", z_max_mm),
                    ("ChangeOfHeightZMaxPerResolution", z_max_counts),
                    ("LateralProbe", probe_px), ("ProxyStiffness", k_c), ("ProxyDamping", b_c),
                    ("ProxyTangentThreshold", tau_t), ("ProxySnapThreshold", snap_N))
        for name, v in optional:
            if v is not None:
                props[name] = v
        if tangent_drag is not None:
            props["ProxyTangentDrag"] = 1 if tangent_drag else 0
        if snap_drag is not None:
            props["ProxySnapDrag"] = 1 if snap_drag else 0
        self._set(**props)

    def SetContact(self, dwell_s=None, approach_at_start=None):
        """When the exploring cursor captures the agent (Yi & Hayward section 3.2): after
        ``dwell_s`` within the capture radius (0 = at once), and, with
        ``approach_at_start``, only once the cursor has come from outside every capture radius
        after Start. After a click it always must leave the vessel first."""
        props = {}
        if dwell_s is not None:
            props["ContactDwell"] = float(dwell_s)
        if approach_at_start is not None:
            props["ContactApproachAtStart"] = 1 if approach_at_start else 0
        self._set(**props)

    def SetTracerRule(self, rule=None, movement_threshold_px=None, junction_window_px=None,
                      junction_margin_px=None):
        """``rule``: 'offset' or 'movement' (Yi & Hayward section 3.2.1 as written: the labels of
        the TracerRule property's choices); ``movement_threshold_px``: the movement rule's
        threshold; ``junction_window_px`` / ``junction_margin_px``: within that screen arc of the
        last junction the branch choice follows the hand's movement since the junction,
        re-routing when another branch's residual is smaller by the margin (a window of 0 makes
        the choice at the junction final). Defaults and ranges: DescribeHapticParameters()."""
        props = _given(TracerMovementThreshold=movement_threshold_px,
                       TracerJunctionWindow=junction_window_px,
                       TracerJunctionMargin=junction_margin_px)
        if rule is not None:
            rules = self._choices("TracerRule")
            key = _key(rule)
            if key not in rules:
                raise ValueError("unknown tracer rule %r (one of %s)" % (rule, ", ".join(rules)))
            props["TracerRule"] = rules[key]
        self.SetHapticParameters(**props)

    def SetForceSmoothing(self, max_rate_N_per_s=None, per_axis=None, slope_force_budget=None):
        """Yi & Hayward section 4.2: force steps spread over several ticks, at most
        ``max_rate_N_per_s`` (a Euclidean bound on the increment, or with ``per_axis`` Fig. 5 as
        printed: a per-axis threshold and n equal steps). Section 4.1: ``slope_force_budget``,
        the fraction of the device's force limit the slope laws may reach where a vessel runs
        along the view direction (0 keeps lambda as set)."""
        self.SetHapticParameters(**_given(MaxForceRate=max_rate_N_per_s,
                                          ForceInterpolationPerAxis=per_axis,
                                          SlopeForceBudget=slope_force_budget))

    _TANGENT_RULES = {"free": (0, 0), "drag": (1, 0), "snap": (0, 1)}
    _NORMAL_RULES = {"rigid": (0, 0), "unilateral": (0, 1), "popover": (1, 0)}

    def SetConstraintProxy(self, tangent_rule=None, normal_rule=None, threshold_from_data=None,
                           friction=None, tick_spacing_mm=None, tick_force_N=None,
                           tick_at_bifurcations=None, field_force=None, kappa_low=None,
                           kappa_high=None):
        """The constraint proxy's rules (Ikits et al.): ``tangent_rule`` 'free' (eq. 9), 'drag'
        (eq. 8) or 'snap' (eq. 11); ``normal_rule`` 'rigid', 'unilateral' (eq. 10) or 'popover';
        ``threshold_from_data`` (eq. 16), ``friction``, tick marks every ``tick_spacing_mm`` (0:
        none) of ``tick_force_N`` and ``tick_at_bifurcations``, ``field_force`` (Yi & Hayward eq.
        2 along the vessel), ``kappa_low`` / ``kappa_high`` (eq. 12's knees). The Proxy* haptic
        parameters: DescribeHapticParameters() gives their defaults, ranges and meanings."""
        props = _given(ProxyThresholdFromData=threshold_from_data, ProxyFriction=friction,
                       ProxyTickSpacing=tick_spacing_mm, ProxyTickForce=tick_force_N,
                       ProxyTickAtBifurcations=tick_at_bifurcations, ProxyFieldForce=field_force,
                       ProxyKappaLow=kappa_low, ProxyKappaHigh=kappa_high)
        for rule, rules, names in ((tangent_rule, self._TANGENT_RULES,
                                    ("ProxyTangentDrag", "ProxyTangentSnap")),
                                   (normal_rule, self._NORMAL_RULES,
                                    ("ProxySnapDrag", "ProxyNormalUnilateral"))):
            if rule is not None:
                if _key(rule) not in rules:
                    raise ValueError("unknown rule %r (one of %s)" % (rule, ", ".join(rules)))
                props.update(zip(names, rules[_key(rule)]))
        self.SetHapticParameters(**props)

    def SetIdleGate(self, radius_mm=None, dwell_s=None, ramp_s=None):
        """The zero-force zone of devices without pressure (Yi & Hayward section 5.2): a handle
        resting within ``radius_mm`` for ``dwell_s`` (0: never) is silenced over ``ramp_s``;
        moving out of the radius restores the force."""
        self.SetHapticParameters(**_given(IdleRadius=radius_mm, IdleDwell=dwell_s,
                                          IdleRamp=ramp_s))

    def SetZoom(self, r):
        """Haptic zoom r = cursor movement / hand movement (a value out of the Zoom parameter's
        range raises ValueError)."""
        self._set(Zoom=float(r))

    def SetForceZones(self, gain_N=None, zero_below=None, saturate_above=None):
        """k(P): zero below ``zero_below``, proportional, then ``gain_N`` above
        ``saturate_above`` (normalized pressure)."""
        props = {}
        if gain_N is not None:
            props["ZoneGain"] = gain_N
        if zero_below is not None:
            props["ZoneZeroBelow"] = zero_below
        if saturate_above is not None:
            props["ZoneSaturateAbove"] = saturate_above
        self._set(**props)

    def SetMaxForce(self, force_N):
        """Safety layer: the largest force sent, N (also limited by the device)."""
        self._set(MaxForce=force_N)

    # --- running ---------------------------------------------------------------------------
    def Start(self, rate_Hz=None):
        """Starts the real-time loop on its own thread (opens the device)."""
        if rate_Hz is not None:
            self._set(LoopRate=rate_Hz)
        self.proxy.InvokeCommand("Start")
        self._check("Start")
        if not self.IsRunning():
            raise RuntimeError("Start: the loop did not start")

    def Stop(self):
        """Stops the loop (zero force first) and closes the device."""
        self.proxy.InvokeCommand("Stop")

    def IsRunning(self):
        return bool(self.GetStatus()["running"])

    def RunOffline(self, seconds, rate_Hz=1000.0):
        """Deterministic scripted run with the simulated device (simulated time): a fresh handle
        and hand script, the agent back to exploring, the log cleared. Returns GetLog()."""
        self._set(OfflineDuration=float(seconds), OfflineRate=float(rate_Hz))
        self.proxy.InvokeCommand("RunOffline")
        self._check("RunOffline")
        return self.GetLog()

    def PlayTrajectory(self, times, xs, ys, rate_Hz=1000.0, cursor_start=None):
        """SetHandTrajectory() then RunOffline() until the last sample. Returns GetLog()."""
        self.SetHandTrajectory(times, xs, ys, cursor_start=cursor_start)
        return self.RunOffline(float(list(times)[-1]), rate_Hz)

    def ClearFault(self):
        self.proxy.InvokeCommand("ClearFault")

    # --- results ---------------------------------------------------------------------------
    def GetLog(self):
        """The recorded log as NumPy arrays: time (s), hand (N x 2, device mm), cursor (N x 2,
        px), state (0 exploring, 1 tracing), path, point, position (N x 3, world mm),
        target_force and force (N x 2, N; force as sent to the device)."""
        from paraview.vtk.util.numpy_support import vtk_to_numpy
        if self._delivery is not None:
            self._delivery.update()  # every process, before the client's session reads it
        self.proxy.UpdatePipeline()
        # The session's output is in this process in both modes (the proxy is client-side).
        table = self.proxy.GetClientSideObject().GetOutputDataObject(0)
        log = {}
        for column, key in _LOG_COLUMNS.items():
            array = table.GetColumnByName(column) if table is not None else None
            log[key] = vtk_to_numpy(array).copy() if array is not None else None
        return log

    def GetStatistics(self):
        """Real-time loop statistics (rates in Hz, period error and tick cost in us)."""
        return dict(zip(_STATISTICS, self._info("StatisticsInfo")))

    def GetAgentState(self):
        """The agent as last published by the haptic thread (or the last offline tick).
        ``torsion_angle`` is the cone's roll about its apex: a rotation-minimising frame carried
        along the agent's path, rolled by the integrated torsion (Yi & Hayward section 7)."""
        v = list(self._info("AgentStateInfo"))
        state, at = {}, 0
        # The layout comes from the session (vtouchAgentStateLayout.h), not from a copy here.
        for field in str(self._info("AgentStateLayoutInfo")).split():
            name, components, kind = field.split(":")
            n = int(components)
            values = [int(x) for x in v[at:at + n]] if kind == "i" else v[at:at + n]
            state[name] = values[0] if n == 1 else values
            at += n
        return state

    def GetStatus(self):
        """running, fault code and text, log length, dropped log entries, skeleton size."""
        v = list(self._info("SessionStatusInfo"))
        return {"running": bool(v[0]), "fault": int(v[1]), "log_entries": int(v[2]),
                "dropped_log_entries": int(v[3]), "paths": int(v[4]), "points": int(v[5]),
                "fault_text": self._info("FaultInfo"),
                "scheduler": self._info("SchedulerNoticeInfo"),
                "realtime_scheduling": _first(self._info("RealTimeSchedulingInfo")) == 1}

    def GetDeviceCapabilities(self):
        """What the open device can do, or None when no device is open (before Start, after
        Stop): name, sensed/actuated DOF, workspace (mm), largest continuous force (N), largest
        stable stiffness (N/m), fastest update rate (Hz), pressure input, position resolution
        (mm), buttons."""
        v = list(self._info("DeviceCapabilitiesInfo"))
        if not v or v[0] < 0.5:
            return None
        return {"name": self._info("DeviceNameInfo") or "", "sensed_dof": int(v[1]),
                "actuated_dof": int(v[2]), "workspace_mm": v[3:6],
                "max_continuous_force_N": v[6], "max_stiffness_N_per_m": v[7],
                "max_update_rate_Hz": v[8], "has_pressure": v[9] > 0.5,
                "position_resolution_mm": v[10], "buttons": int(v[11])}

    def GetLastError(self):
        """The last error of the session ("" when none)."""
        return self._info("LastErrorInfo") or ""

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
        right = _normalized(_cross(forward, list(p.GetProperty("CameraViewUp").GetData())))
        return position, right, _cross(right, forward), forward

    def GetTraceMeasures(self, log=None, window_s=0.01):
        """What a person feels along a trace, from a log (default: GetLog()) and the session's
        camera: a dict of NumPy arrays ``time`` (s), ``tracing`` (bool), ``force_magnitude`` (N),
        ``force_along_travel`` (N, the force projected on the agent's on-screen direction of
        travel over ``window_s``: negative pushes back, positive pulls on; 0 where the agent
        does not move) and ``depth_mm`` (the agent's distance along the viewing direction:
        larger is farther from the viewer)."""
        import numpy
        log = log if log is not None else self.GetLog()
        position, right, up, forward = (numpy.asarray(v, dtype=float)
                                        for v in self.GetCameraFrame())
        time = numpy.asarray(log["time"], dtype=float)
        agent = numpy.asarray(log["position"], dtype=float)
        force = numpy.asarray(log["force"], dtype=float)
        tracing = numpy.asarray(log["state"]) == 1
        depth = (agent - position) @ forward
        screen = numpy.stack([agent @ right, agent @ up], axis=1)
        step = max(1, int(round(window_s / (time[1] - time[0])))) if len(time) > 1 else 1
        travel = numpy.zeros_like(screen)
        if len(time) > step:
            travel[step:] = screen[step:] - screen[:-step]
            travel[:step] = travel[step]
        length = numpy.linalg.norm(travel, axis=1)
        moving = tracing & (length > 1e-6)
        along = numpy.zeros(len(time))
        along[moving] = (force[moving] * travel[moving]).sum(axis=1) / length[moving]
        return {"time": time, "tracing": tracing, "force_magnitude": numpy.linalg.norm(force, axis=1),
                "force_along_travel": along, "depth_mm": depth}

    def SaveLog(self, filename, log=None):
        """Writes a log (default: GetLog()) and its GetTraceMeasures() to ``filename``: a NumPy
        ``.npz`` (one array per key; vectors keep their columns) or a ``.csv`` (one row per
        tick, vector columns split as name_0, name_1, ...). Returns the file name."""
        import numpy
        log = log if log is not None else self.GetLog()
        data = {k: numpy.asarray(v) for k, v in log.items() if v is not None}
        data.update(self.GetTraceMeasures(log))
        if str(filename).endswith(".csv"):
            names, columns = [], []
            for key, value in data.items():
                value = value.reshape(len(value), -1).astype(float)
                for c in range(value.shape[1]):
                    names.append(key if value.shape[1] == 1 else "%s_%d" % (key, c))
                    columns.append(value[:, c])
            numpy.savetxt(filename, numpy.stack(columns, axis=1), delimiter=",",
                          header=",".join(names), comments="", fmt="%.9g")
        else:
            numpy.savez(filename, **data)
        return filename


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
