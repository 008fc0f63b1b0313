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

from .connection_watch import watch as watch_connection
from .delivery import CenterlineDelivery, is_remote
from .haptic_parameters import HapticParameterAccess, _key
from .session_camera import SessionCamera
from .session_results import SessionResults, _first

__all__ = ["HapticSession", "logic", "SESSION_NAME", "FORCE_LAW_ALIASES", "DEVICES"]

#: Short names accepted by :meth:`HapticSession.SetForceLaw` beside the labels of the
#: ``ForceLaw`` property's choices (which come from the parameter table through the proxy).
FORCE_LAW_ALIASES = {"coh": "changeofheight", "lateral": "lateralgradient",
                     "proxy": "constraintproxy"}
#: Device names accepted by :meth:`HapticSession.SetDevice` -> the ``DeviceType`` value.
DEVICES = {"simulated": 0, "pointer": 1, "mouse": 1, "replay": 2, "hid": 3}


def _given(**values):
    """The keyword arguments that were given (not None)."""
    return {name: v for name, v in values.items() if v is not None}


def _centerline_port(centerline):
    """A proxy or output port (servermanager.OutputPort) -> the port carrying the centerline."""
    if centerline is None:
        return None
    if getattr(centerline, "Port", 0) == 0 and centerline.GetXMLName() == "VesselPhantom":
        return servermanager.OutputPort(centerline, 1)  # port 1: the analytic centerline
    return centerline


class HapticSession(SessionCamera, SessionResults, HapticParameterAccess):
    """One haptic session: centerline + camera + device + force law + zones + zoom.

    ``centerline``: a VesselCenterline proxy, a VesselPhantom proxy (its port 1 is used) or any
    output port producing the centerline polydata; may be given later with SetCenterline().
    ``view``: a render view whose camera and size the session copies (SetCameraFromView);
    without one the camera looks at the centerline along -z (ResetCamera).
    ``proxy``: wrap an existing VesselTouchHapticSession proxy instead of creating one.

    The camera methods come from :class:`SessionCamera` (session_camera.py), the log, status and
    measures from :class:`SessionResults` (session_results.py), the haptic parameters by name
    from :class:`HapticParameterAccess` (haptic_parameters.py).
    """

    def __init__(self, centerline=None, view=None, proxy=None, registrationName=None):
        self._delivery = None
        if proxy is None:
            name, port = self._delivered(centerline)
            proxy = self._create_proxy(port if name == "Input" else None, registrationName)
            self.proxy = proxy
            if name != "Input":
                self._set_delivered(port)
        self.proxy = proxy
        # Connected to a pvserver: its loss zeroes the force at once (connection_watch.py).
        watch_connection(self._connection_lost)
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
        """(property, port) the session takes the centerline through: Input, the centerline
        itself, built in; connected to a pvserver, DeliveredCenterline, its copy delivered to
        the client where the session lives (delivery.py). The delivery's mover is plumbing, not
        a registered pipeline source, so it never goes on Input (ParaView's GUI reports an
        unregistered proxy on an Input in its Output Messages)."""
        port = _centerline_port(centerline)
        if port is None or not is_remote():
            self._delivery = None
            return "Input", port
        self._delivery = CenterlineDelivery(port)
        return "DeliveredCenterline", self._delivery.port

    def centerline_source(self):
        """The proxy the session reads its centerline from (the delivered copy when connected
        to a pvserver), or None."""
        delivered = self.proxy.SMProxy.GetProperty("DeliveredCenterline")
        if delivered is not None and delivered.GetNumberOfProxies() > 0:
            return self._delivery.port if self._delivery is not None else \
                servermanager._getPyProxy(delivered.GetProxy(0))
        return self.proxy.Input

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

    def _connection_lost(self, message):
        """The pvserver is gone: zero force, the fault latched with `message`, the skeleton held
        (vtkVesselTouchHapticSession::ReportConnectionLost; the proxy lives in this process)."""
        prop = self.proxy.SMProxy.GetProperty("ConnectionLostMessage")
        prop.SetNumberOfElements(1)
        prop.SetElement(0, message)
        self.proxy.SMProxy.UpdateVTKObjects()

    def ConnectionLost(self):
        """True after the pvserver this session's centerline came from was lost."""
        return _first(self._info("ConnectionLostInfo")) == 1

    def SaveSkeleton(self, filename):
        """Writes the skeleton this session traces (the centerline polydata in this process) as
        VTK XML PolyData (.vtp): also after the server was lost, from the copy delivered here."""
        from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
        if self._delivery is not None:
            data = self._delivery.client_copy()
        else:
            self.proxy.UpdatePipeline()
            data = self.proxy.GetClientSideObject().GetInputDataObject(0, 0)
        if data is None or data.GetNumberOfPoints() == 0:
            raise RuntimeError("SaveSkeleton: the session holds no skeleton (Bind a centerline)")
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(str(filename))
        writer.SetInputData(data)
        if not writer.Write():
            raise RuntimeError("SaveSkeleton: cannot write %s" % filename)
        return str(filename)

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
        name, port = self._delivered(centerline)
        if name == "Input":
            self._set(Input=port)
        else:
            self._set_delivered(port)

    def _set_delivered(self, mover):
        """The delivered copy (delivery.py's mover) as the session's centerline."""
        prop = self.proxy.SMProxy.GetProperty("DeliveredCenterline")
        prop.RemoveAllProxies()
        prop.AddProxy(mover.SMProxy)
        self.proxy.SMProxy.UpdateVTKObjects()

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


# logic() and SESSION_NAME live in session_registry.py; imported last, since logic() builds a
# HapticSession (``from vesseltouch.session import logic`` keeps working).
from .session_registry import SESSION_NAME, logic  # noqa: E402
