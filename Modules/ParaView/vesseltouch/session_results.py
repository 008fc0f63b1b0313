"""What a :class:`vesseltouch.HapticSession` reports: its log as NumPy arrays, loop statistics,
agent state, status, the open device's capabilities, the last error, and the measures of a trace
(force along the direction of travel, depth), saved as .npz or .csv. A mixin: the session
provides ``proxy``, ``_info`` and GetCameraFrame()."""


_STATISTICS = ("nominal_rate_Hz", "achieved_rate_Hz", "ticks", "overruns", "skipped_deadlines",
               "period_error_p50_us", "period_error_p99_us", "period_error_p999_us",
               "period_error_max_us", "tick_cost_p50_us", "tick_cost_p99_us", "tick_cost_max_us")
_LOG_COLUMNS = {"Time": "time", "Hand": "hand", "Cursor": "cursor", "State": "state",
                "Path": "path", "Point": "point", "Position": "position",
                "TargetForce": "target_force", "Force": "force"}


def _first(value):
    """An information property's single value (servermanager gives a scalar or a list)."""
    return value[0] if isinstance(value, (list, tuple)) else value


class SessionResults:
    """Read-out methods of HapticSession (units: s, mm, px, N)."""

    def GetLog(self):
        """The recorded log as NumPy arrays: time (s), hand (N x 2, device mm), cursor (N x 2,
        px), state (0 exploring, 1 tracing), path, point, position (N x 3, world mm),
        target_force and force (N x 2, N; force as sent to the device)."""
        from paraview.vtk.util.numpy_support import vtk_to_numpy
        delivery = getattr(self, "_delivery", None)
        if delivery is not None and not self.GetStatus()["connection_lost"]:
            delivery.update()  # every process, before the client's session reads it
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
        """running, fault code and text, log length, dropped log entries, skeleton size, and
        whether the pvserver was lost (fault 4, CONNECTION_LOST_FAULT: its text says what to do)."""
        v = list(self._info("SessionStatusInfo"))
        return {"running": bool(v[0]), "fault": int(v[1]), "log_entries": int(v[2]),
                "dropped_log_entries": int(v[3]), "paths": int(v[4]), "points": int(v[5]),
                "fault_text": self._info("FaultInfo"),
                "scheduler": self._info("SchedulerNoticeInfo"),
                "realtime_scheduling": _first(self._info("RealTimeSchedulingInfo")) == 1,
                # The pvserver was lost (fault 4 until ClearFault; the skeleton stays held).
                "connection_lost": _first(self._info("ConnectionLostInfo")) == 1}

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

    def GetDeviceCalibration(self):
        """The raw-axis calibration the open device applies, or None when no device is open or
        it calibrates no raw axes (the simulated handle, the mouse, a replay, a HID mouse): one
        dict per axis, x first, with raw_minimum and raw_maximum (device units, e.g. HID logical
        values) and minimum_mm and maximum_mm (the positions at those readings)."""
        v = list(self._info("DeviceCalibrationInfo"))
        count = int(v[0]) if v else 0
        return [{"raw_minimum": v[1 + 4 * i], "raw_maximum": v[2 + 4 * i],
                 "minimum_mm": v[3 + 4 * i], "maximum_mm": v[4 + 4 * i]}
                for i in range(count)] or None

    def GetLastError(self):
        """The last error of the session ("" when none)."""
        return self._info("LastErrorInfo") or ""

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
