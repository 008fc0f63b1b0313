// HapticSession: the scriptable haptic session (vtouch::HapticSession) as a VTK filter, so that
// ParaView's Python shell, pvpython and the GUI drive one session through a proxy.
//
// Input: the centerline vtkPolyData (VesselCenterline, or VesselPhantom port 1), converted to a
// Q-skeleton with its junctions (vtouch::PolyDataToQSkeleton) whenever the input changes.
// Output: vtkTable, the session log, one row per tick: Time (s), Hand (2, device mm), Cursor
// (2, px, bottom-left origin), State (0 exploring, 1 tracing), Path, Point, Position (3, world
// mm), TargetForce (2, N, the force law's output) and Force (2, N, as sent to the device).
// Every setter reaches a running session at once (parameters are published without locks);
// camera changes rebuild the view model. Bad input or a device that fails to open: vtkErrorMacro,
// zero force, nothing crashes.
#ifndef vtkVesselTouchHapticSession_h
#define vtkVesselTouchHapticSession_h

#include "vtkTableAlgorithm.h"
#include "vtkVesselTouchLogicModule.h" // for export macro

#include <memory> // for std::unique_ptr

class vtkMatrix4x4;

class VTKVESSELTOUCHLOGIC_EXPORT vtkVesselTouchHapticSession : public vtkTableAlgorithm
{
public:
  static vtkVesselTouchHapticSession* New();
  vtkTypeMacro(vtkVesselTouchHapticSession, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum DeviceTypes
  {
    SIMULATED = 0, ///< a mass-damper handle held by a scripted hand (deterministic offline)
    POINTER = 1,   ///< the mouse, with pseudo-haptic feedback (fed by SetPointerPosition)
    REPLAY = 2,    ///< positions replayed from ReplayFileName (CSV)
    HID = 3        ///< a HID PID force-feedback device at HidPath (hidapi)
  };
  enum HandScripts
  {
    HAND_NONE = 0,      ///< the hand does nothing: the handle moves only under the force
    HAND_SWEEP = 1,     ///< built-in: approach the first point of SweepPath, then follow it
    HAND_TRAJECTORY = 2 ///< the samples given by AddHandSample (time, x, y in device mm)
  };

  // --- camera (the host's view of the centerline) ---
  /// Camera position, focal point (world mm) and view up. Defaults (0,0,1), (0,0,0), (0,1,0).
  vtkSetVector3Macro(CameraPosition, double);
  vtkGetVector3Macro(CameraPosition, double);
  vtkSetVector3Macro(CameraFocalPoint, double);
  vtkGetVector3Macro(CameraFocalPoint, double);
  vtkSetVector3Macro(CameraViewUp, double);
  vtkGetVector3Macro(CameraViewUp, double);
  /// Parallel (orthographic, as for a MIP) projection. Default on.
  vtkSetMacro(CameraParallelProjection, bool);
  vtkGetMacro(CameraParallelProjection, bool);
  vtkBooleanMacro(CameraParallelProjection, bool);
  /// Half the view height, mm (vtkCamera::ParallelScale); <= 0 fits the centerline. Default 0.
  vtkSetMacro(CameraParallelScale, double);
  vtkGetMacro(CameraParallelScale, double);
  /// Vertical view angle of a perspective camera, degrees. Default 30.
  vtkSetMacro(CameraViewAngle, double);
  vtkGetMacro(CameraViewAngle, double);
  /// Viewport width and height, pixels. Default 800 x 600.
  vtkSetVector2Macro(ViewportSize, int);
  vtkGetVector2Macro(ViewportSize, int);
  /// Use ViewMatrix/ProjectionMatrix instead of the camera parameters above. Default off.
  vtkSetMacro(UseExplicitMatrices, bool);
  vtkGetMacro(UseExplicitMatrices, bool);
  vtkBooleanMacro(UseExplicitMatrices, bool);
  /// World -> eye and eye -> clip matrices, ROW-major as vtkMatrix4x4 stores them
  /// (vtkCamera::GetModelViewTransformMatrix, GetProjectionTransformMatrix(aspect, -1, 1)).
  /// Defaults identity.
  vtkSetVectorMacro(ViewMatrix, double, 16);
  vtkGetVectorMacro(ViewMatrix, double, 16);
  vtkSetVectorMacro(ProjectionMatrix, double, 16);
  vtkGetVectorMacro(ProjectionMatrix, double, 16);
  /// Copies both matrices and turns UseExplicitMatrices on (null matrices: error, no change).
  void SetCameraMatrices(vtkMatrix4x4* view, vtkMatrix4x4* projection);
  /// Capture radius of the contact map, px. Default 12.
  vtkSetMacro(CaptureRadius, double);
  vtkGetMacro(CaptureRadius, double);
  /// 3D arc length of the dz/dl stencil, mm. Default 1.
  vtkSetMacro(SlopeWindow, double);
  vtkGetMacro(SlopeWindow, double);

  // --- device ---
  /// One of DeviceTypes. Default SIMULATED. Changing it applies at the next Start/RunOffline.
  vtkSetClampMacro(DeviceType, int, SIMULATED, HID);
  vtkGetMacro(DeviceType, int);
  /// Simulated handle: moving mass (kg, default 0.05), damping (N s/m, default 0.5), largest force
  /// (N, default 3).
  vtkSetMacro(SimulatedMass, double);
  vtkGetMacro(SimulatedMass, double);
  vtkSetMacro(SimulatedDamping, double);
  vtkGetMacro(SimulatedDamping, double);
  vtkSetMacro(SimulatedMaxForce, double);
  vtkGetMacro(SimulatedMaxForce, double);
  /// The simulated hand: one of HandScripts. Default HAND_SWEEP.
  vtkSetClampMacro(HandScript, int, HAND_NONE, HAND_TRAJECTORY);
  vtkGetMacro(HandScript, int);
  /// Grip of the scripted hand: stiffness (N/m, default 3000) and damping (N s/m, default 10).
  vtkSetMacro(HandStiffness, double);
  vtkGetMacro(HandStiffness, double);
  vtkSetMacro(HandDamping, double);
  vtkGetMacro(HandDamping, double);
  /// Pressure the scripted hand reports, [0, 1] (selects the force zone). Default 1.
  vtkSetClampMacro(HandPressure, double, 0.0, 1.0);
  vtkGetMacro(HandPressure, double);
  /// HAND_SWEEP: path followed (default 0) and hand speed along it, device mm/s (default 50).
  /// The hand starts 20 mm right of the path's first point, reaches it in 0.3 s, then follows the
  /// path's screen projection; the cursor starts under the hand.
  vtkSetMacro(SweepPath, int);
  vtkGetMacro(SweepPath, int);
  vtkSetMacro(SweepSpeed, double);
  vtkGetMacro(SweepSpeed, double);
  /// HAND_TRAJECTORY: samples (time s, increasing; x, y device mm), linearly interpolated and
  /// held after the last one.
  void AddHandSample(double time_s, double x_mm, double y_mm);
  void ClearHandSamples();
  int GetNumberOfHandSamples() const;
  /// HAND_TRAJECTORY: cursor position at the first sample, px (bottom-left origin); negative
  /// components: the viewport centre. Default (-1, -1).
  vtkSetVector2Macro(InitialCursor, double);
  vtkGetVector2Macro(InitialCursor, double);
  /// REPLAY: the CSV file (time_s, x_mm, y_mm[, pressure, buttons]). Default empty.
  vtkSetStringMacro(ReplayFileName);
  vtkGetStringMacro(ReplayFileName);
  /// HID: the hidapi path of the device (vesseltouch-devices lists them). Default empty.
  vtkSetStringMacro(HidPath);
  vtkGetStringMacro(HidPath);
  /// POINTER: the mouse in device mm (from the view binding) and the pressure modifier.
  void SetPointerPosition(double x_mm, double y_mm);
  void SetPointerPressed(bool pressed);
  /// POINTER: the mouse buttons, bit i for button i (a press of bit 0 returns from tracing to
  /// exploring; bit 1 held re-indexes). Default 0.
  void SetPointerButtons(int buttons);
  /// Safety layer: largest force sent, N (also limited by the device). Default 3.
  vtkSetMacro(MaxForce, double);
  vtkGetMacro(MaxForce, double);

  // --- force law, zones, zoom ---
  /// 0 LDGF (default), 1 change of height, 2 lateral gradient, 3 constraint proxy, 4 none.
  vtkSetClampMacro(ForceLaw, int, 0, 4);
  vtkGetMacro(ForceLaw, int);
  /// LDGF lambda, mm. Default 0.005.
  vtkSetMacro(LdgfLambda, double);
  vtkGetMacro(LdgfLambda, double);
  /// Change of height: lambda (mm, 0.005), z_max (mm, 1), forgetting time (s, 0.1).
  vtkSetMacro(ChangeOfHeightLambda, double);
  vtkGetMacro(ChangeOfHeightLambda, double);
  vtkSetMacro(ChangeOfHeightZMax, double);
  vtkGetMacro(ChangeOfHeightZMax, double);
  vtkSetMacro(ChangeOfHeightForgetTime, double);
  vtkGetMacro(ChangeOfHeightForgetTime, double);
  /// Lateral gradient central-difference half width, px. Default 2.
  vtkSetMacro(LateralProbe, double);
  vtkGetMacro(LateralProbe, double);
  /// Constraint proxy coupler: k_c (N/m, 200), b_c (N s/m, 0.1), drag threshold tau_t (N, 0.3,
  /// used when ProxyTangentDrag is on, default off), snap threshold (N, 1.5, ProxySnapDrag, off).
  vtkSetMacro(ProxyStiffness, double);
  vtkGetMacro(ProxyStiffness, double);
  vtkSetMacro(ProxyDamping, double);
  vtkGetMacro(ProxyDamping, double);
  vtkSetMacro(ProxyTangentDrag, bool);
  vtkGetMacro(ProxyTangentDrag, bool);
  vtkSetMacro(ProxyTangentThreshold, double);
  vtkGetMacro(ProxyTangentThreshold, double);
  vtkSetMacro(ProxySnapDrag, bool);
  vtkGetMacro(ProxySnapDrag, bool);
  vtkSetMacro(ProxySnapThreshold, double);
  vtkGetMacro(ProxySnapThreshold, double);
  /// Force zones k(P): gain (N, default 1), end of the zero zone and start of the saturation zone
  /// (normalized pressure, 0.05 and 0.5).
  vtkSetMacro(ZoneGain, double);
  vtkGetMacro(ZoneGain, double);
  vtkSetMacro(ZoneZeroBelow, double);
  vtkGetMacro(ZoneZeroBelow, double);
  vtkSetMacro(ZoneSaturateAbove, double);
  vtkGetMacro(ZoneSaturateAbove, double);
  /// Haptic zoom r = cursor movement / hand movement, [0.1, 10]. Default 1.
  vtkSetClampMacro(Zoom, double, 0.1, 10.0);
  vtkGetMacro(Zoom, double);
  /// Cursor pixels per hand millimetre at zoom 1. Default 4.
  vtkSetMacro(PixelsPerDeviceMm, double);
  vtkGetMacro(PixelsPerDeviceMm, double);
  /// Time-domain interpolation bound, N/s (default 100); law crossfade, s (default 0.005).
  vtkSetMacro(MaxForceRate, double);
  vtkGetMacro(MaxForceRate, double);
  vtkSetMacro(Crossfade, double);
  vtkGetMacro(Crossfade, double);
  /// Contact (Yi & Hayward 3.2, vtouch::ContactGate): dwell within the capture radius before the
  /// agent is captured, s (default 0.05; 0 = immediate); whether the cursor must first come from
  /// outside every capture radius after Start (default on). After a click it always must.
  vtkSetMacro(ContactDwell, double);
  vtkGetMacro(ContactDwell, double);
  vtkSetMacro(ContactApproachAtStart, bool);
  vtkGetMacro(ContactApproachAtStart, bool);
  /// Tracing rule: 0 offset (default), 1 the paper's per-tick movement rule (3.2.1).
  vtkSetClampMacro(TracerRule, int, 0, 1);
  vtkGetMacro(TracerRule, int);
  /// Fraction of the device's force limit the slope laws may reach where dl -> 0 (lambda sized
  /// from it, 4.1); 0 = lambda as set. Default 0.9.
  vtkSetMacro(SlopeForceBudget, double);
  vtkGetMacro(SlopeForceBudget, double);

  // --- the tick's options (issue 17; vtouch::HapticParameters, Docs/HAPTICS.md) ---
  /// Movement rule: per-tick projections below this leave the agent still, px. Default 0.01.
  vtkSetMacro(TracerMovementThreshold, double);
  vtkGetMacro(TracerMovementThreshold, double);
  /// Both rules: within this screen arc of the last junction the branch choice follows the hand's
  /// movement, px (0: the choice at the junction is final). Default 24.
  vtkSetMacro(TracerJunctionWindow, double);
  vtkGetMacro(TracerJunctionWindow, double);
  /// ...re-routing when another branch's residual is smaller by this, px. Default 1.
  vtkSetMacro(TracerJunctionMargin, double);
  vtkGetMacro(TracerJunctionMargin, double);
  /// Time-domain smoothing as Fig. 5 prints it (per-axis threshold, n equal steps) instead of the
  /// Euclidean bound on the increment. Default off.
  vtkSetMacro(ForceInterpolationPerAxis, bool);
  vtkGetMacro(ForceInterpolationPerAxis, bool);
  vtkBooleanMacro(ForceInterpolationPerAxis, bool);
  /// Change of height: z_max in counts of the device's position resolution when
  /// ChangeOfHeightZMax is 0 (Hayward & Yi App. A). Default 2.
  vtkSetMacro(ChangeOfHeightZMaxPerResolution, double);
  vtkGetMacro(ChangeOfHeightZMaxPerResolution, double);
  /// Constraint proxy, Ikits: tangent rule snap-drag (eq. 11, steps of tau; wins over
  /// ProxyTangentDrag), normal rule unilateral (eq. 10; ProxySnapDrag, the pop-over, wins), the
  /// pop-over threshold times the frame strength (eq. 16), friction mu in the constraint
  /// subspace, tick marks every ProxyTickSpacing mm of arc (0: none) of ProxyTickForce N and at
  /// bifurcations, the depth slope of eq. 2 added as a field force, and the stiffness transfer
  /// function's knees on the frame strength (eq. 12). Defaults off, off, off, 0, 0 mm, 0.3 N, off,
  /// off, 0.15, 0.5.
  vtkSetMacro(ProxyTangentSnap, bool);
  vtkGetMacro(ProxyTangentSnap, bool);
  vtkSetMacro(ProxyNormalUnilateral, bool);
  vtkGetMacro(ProxyNormalUnilateral, bool);
  vtkSetMacro(ProxyThresholdFromData, bool);
  vtkGetMacro(ProxyThresholdFromData, bool);
  vtkSetMacro(ProxyFriction, double);
  vtkGetMacro(ProxyFriction, double);
  vtkSetMacro(ProxyTickSpacing, double);
  vtkGetMacro(ProxyTickSpacing, double);
  vtkSetMacro(ProxyTickForce, double);
  vtkGetMacro(ProxyTickForce, double);
  vtkSetMacro(ProxyTickAtBifurcations, bool);
  vtkGetMacro(ProxyTickAtBifurcations, bool);
  vtkSetMacro(ProxyFieldForce, bool);
  vtkGetMacro(ProxyFieldForce, bool);
  vtkSetMacro(ProxyKappaLow, double);
  vtkGetMacro(ProxyKappaLow, double);
  vtkSetMacro(ProxyKappaHigh, double);
  vtkGetMacro(ProxyKappaHigh, double);
  /// Idle gate (devices without pressure, Yi & Hayward 5.2's zero-force zone): a handle resting
  /// within IdleRadius mm for IdleDwell s (0: never) is silenced over IdleRamp s. Defaults 1 mm,
  /// 1.5 s, 0.05 s.
  vtkSetMacro(IdleRadius, double);
  vtkGetMacro(IdleRadius, double);
  vtkSetMacro(IdleDwell, double);
  vtkGetMacro(IdleDwell, double);
  vtkSetMacro(IdleRamp, double);
  vtkGetMacro(IdleRamp, double);

  // --- running ---
  /// Real-time loop rate, Hz, [100, 10000]. Default 1000.
  vtkSetClampMacro(LoopRate, double, 100.0, 10000.0);
  vtkGetMacro(LoopRate, double);
  /// Log entries kept by a real-time run (0: no log; at most 2e6). Default 60000 (one minute at
  /// 1 kHz).
  vtkSetClampMacro(LogCapacity, int, 0, 2000000);
  vtkGetMacro(LogCapacity, int);
  /// Offline run length (s, default 5) and rate (Hz, default 1000) used by RunOffline().
  vtkSetMacro(OfflineDuration, double);
  vtkGetMacro(OfflineDuration, double);
  vtkSetMacro(OfflineRate, double);
  vtkGetMacro(OfflineRate, double);

  /// Starts the real-time loop on its own thread (opens the device). False + vtkErrorMacro when
  /// the centerline, camera or device is unusable.
  bool Start();
  /// Stops the loop (zero force first) and closes the device. The log output is refreshed.
  void Stop();
  bool IsRunning() const;
  /// Deterministic run with the simulated device: a fresh handle and hand script, the agent back
  /// to exploring, the log cleared, then `duration_s` of simulated time at `rate_Hz`.
  bool RunOffline(double duration_s, double rate_Hz);
  /// RunOffline(OfflineDuration, OfflineRate) (the proxy's button).
  bool RunOffline();
  /// Clears a latched fault (forces re-engage softly).
  void ClearFault();

  // --- information ---
  /// nominal rate, achieved rate (Hz), ticks, overruns, skipped deadlines, period error p50, p99,
  /// p99.9, max (us), tick cost p50, p99, max (us).
  double* GetStatistics() VTK_SIZEHINT(12);
  /// time (s), tick, state (0 exploring, 1 tracing), force law, path, point, cursor x y (px),
  /// position x y z (world mm), tangent x y z, direction of travel, cone roll (rad: the roll to
  /// pass vtouch::agentConeMatrix, a rotation-minimising frame rolled by the integrated torsion),
  /// k(P) (N), force x y (N), target force x y (N), hand x y (device mm).
  double* GetAgentState() VTK_SIZEHINT(23);
  /// The force last sent to the device, x y z (N, device frame, after the safety layer); zero
  /// when no device is open, and after Stop() (which zeroes the force before closing).
  double* GetDeviceForce() VTK_SIZEHINT(3);
  /// running (0/1), fault code (0 none), log entries, dropped log entries, skeleton paths,
  /// skeleton points.
  int* GetSessionStatus() VTK_SIZEHINT(6);
  /// The tick's options as the haptic pipeline holds them (vtouch::HapticParameters, after
  /// Modified()), in this order: tracer rule, movement threshold (px), junction window (px),
  /// junction margin (px), contact dwell (s), contact approach at start, slope force budget,
  /// per-axis interpolation, max force rate (N/s), z_max per resolution, proxy tangent drag,
  /// tangent snap, pop-over, unilateral, threshold from data, friction, tick spacing (mm), tick
  /// force (N), ticks at bifurcations, field force, kappa low, kappa high, idle radius (mm),
  /// idle dwell (s), idle ramp (s).
  double* GetTickOptions() VTK_SIZEHINT(25);
  /// The last error (configuration, device, camera), "" when none.
  const char* GetLastErrorMessage();
  /// The fault as text ("none" when none) and the real-time scheduling notice.
  const char* GetFaultMessage();
  const char* GetSchedulerNotice();

  /// Pushes every parameter (and a changed camera) to the session: a running session feels it at
  /// the next tick.
  void Modified() override;

protected:
  vtkVesselTouchHapticSession();
  ~vtkVesselTouchHapticSession() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkVesselTouchHapticSession(const vtkVesselTouchHapticSession&) = delete;
  void operator=(const vtkVesselTouchHapticSession&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;

  vtkDataObject* UpdateInput();
  bool UpdateSkeleton(vtkDataObject* data);
  bool ApplyCamera();
  void PushParameters();
  bool BuildDevice(bool offline);
  void Fail(const std::string& message);
  bool ReserveLog(int entries);

  double CameraPosition[3] = { 0.0, 0.0, 1.0 };
  double CameraFocalPoint[3] = { 0.0, 0.0, 0.0 };
  double CameraViewUp[3] = { 0.0, 1.0, 0.0 };
  bool CameraParallelProjection = true;
  double CameraParallelScale = 0.0;
  double CameraViewAngle = 30.0;
  int ViewportSize[2] = { 800, 600 };
  bool UseExplicitMatrices = false;
  double ViewMatrix[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  double ProjectionMatrix[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  double CaptureRadius = 12.0;
  double SlopeWindow = 1.0;

  int DeviceType = SIMULATED;
  double SimulatedMass = 0.05;
  double SimulatedDamping = 0.5;
  double SimulatedMaxForce = 3.0;
  int HandScript = HAND_SWEEP;
  double HandStiffness = 3000.0;
  double HandDamping = 10.0;
  double HandPressure = 1.0;
  int SweepPath = 0;
  double SweepSpeed = 50.0;
  double InitialCursor[2] = { -1.0, -1.0 };
  char* ReplayFileName = nullptr;
  char* HidPath = nullptr;
  double MaxForce = 3.0;

  int ForceLaw = 0;
  double LdgfLambda = 0.005;
  double ChangeOfHeightLambda = 0.005;
  double ChangeOfHeightZMax = 0.0;       // 0: 2 counts of the device's position resolution
  double ChangeOfHeightForgetTime = 0.1; // ignored (eqs. 8-9 have none); old state files set it
  double LateralProbe = 2.0;
  double ProxyStiffness = 200.0;
  double ProxyDamping = 0.1;
  bool ProxyTangentDrag = false;
  double ProxyTangentThreshold = 0.3;
  bool ProxySnapDrag = false;
  double ProxySnapThreshold = 1.5;
  double ZoneGain = 1.0;
  double ZoneZeroBelow = 0.05;
  double ZoneSaturateAbove = 0.5;
  double Zoom = 1.0;
  double PixelsPerDeviceMm = 4.0;
  double MaxForceRate = 100.0;
  double ContactDwell = 0.05;
  bool ContactApproachAtStart = true;
  int TracerRule = 0;
  double SlopeForceBudget = 0.9;
  double TracerMovementThreshold = 0.01;
  double TracerJunctionWindow = 24.0;
  double TracerJunctionMargin = 1.0;
  bool ForceInterpolationPerAxis = false;
  double ChangeOfHeightZMaxPerResolution = 2.0;
  bool ProxyTangentSnap = false;
  bool ProxyNormalUnilateral = false;
  bool ProxyThresholdFromData = false;
  double ProxyFriction = 0.0;
  double ProxyTickSpacing = 0.0;
  double ProxyTickForce = 0.3;
  bool ProxyTickAtBifurcations = false;
  bool ProxyFieldForce = false;
  double ProxyKappaLow = 0.15;
  double ProxyKappaHigh = 0.5;
  double IdleRadius = 1.0;
  double IdleDwell = 1.5;
  double IdleRamp = 0.05;
  double Crossfade = 0.005;

  double LoopRate = 1000.0;
  int LogCapacity = 60000;
  double OfflineDuration = 5.0;
  double OfflineRate = 1000.0;

  double Statistics[12] = {};
  double AgentState[23] = {};
  double DeviceForce[3] = {};
  int SessionStatus[6] = {};
  double TickOptions[25] = {};
};

#endif
