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

  // --- haptic parameters (force law, zones, zoom, tracer, proxy, ...) ---
  /// Sets the haptic parameter `name` (a row of Logic/Haptics/vtouchHapticParameters.def, e.g.
  /// "LdgfLambda", "ProxyStiffness", "Zoom"; the proxy's properties of the same names call this
  /// through their initial_string). A value out of the row's range, not a whole number where one
  /// is needed, or an unknown name is refused: vtkErrorMacro (also GetLastErrorMessage) naming
  /// the parameter, the value, the range and the unit, and the old value stays. ApplyProperties()
  /// publishes it to the haptic thread.
  void SetHapticParameter(const char* name, double value);
  /// The value set for `name` (the table's default until set); NaN and vtkErrorMacro for an
  /// unknown name.
  double GetHapticParameter(const char* name);
  /// The parameters the haptic session holds now (what the haptic thread reads after
  /// ApplyProperties), as text: "Name=value" per parameter in table order, separated by spaces,
  /// values with 17 significant digits.
  const char* GetAppliedHapticParameters();

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
  /// Clears a latched fault (forces re-engage softly). After a lost connection the skeleton
  /// stays the one held (the input is no longer updated); Start() is allowed again on it.
  void ClearFault();
  /// The fault code GetSessionStatus() reports after ReportConnectionLost(), beside
  /// vtouch::SessionFault's codes (1-3).
  static constexpr int CONNECTION_LOST_FAULT = 4;
  /// The client lost its pvserver (issue 19, item 6). Zero force at once: the loop stops (zero
  /// force first) and the device closes, as Stop(); then the fault is latched with `message`
  /// (GetFaultMessage; CONNECTION_LOST_FAULT in GetSessionStatus) until ClearFault(), Start()
  /// refuses meanwhile. The skeleton the session holds is kept and never re-read from the input
  /// (its producer lived on the lost server), so RunOffline() and, after ClearFault(), Start()
  /// trace on it without touching the network. A control-thread call (the GUI's main thread, or
  /// Python, whose calls into VTK hold the interpreter lock). The haptic thread never touches the
  /// network: detection is the host's (pqServer's signal, vesseltouch.connection_watch).
  void ReportConnectionLost(const char* message);
  /// 1 after ReportConnectionLost() (the skeleton is held, the input detached), else 0.
  int GetConnectionLost();
  /// Connected to a pvserver, the centerline arrives through the delivery's ClientServerMoveData
  /// (vesseltouch/delivery.py, pqVesselTouchCenterlineDelivery): plumbing, not a pipeline item.
  /// It is connected here (the proxy's DeliveredCenterline property) rather than through Input,
  /// whose proxies ParaView's GUI expects to be registered pipeline sources ("Some proxy is added
  /// as input but was not registered" otherwise). nullptr detaches a producer set here, and only
  /// that one (a built-in Input set since is kept).
  void SetDeliveredCenterline(vtkAlgorithm* producer);

  // --- information ---
  /// nominal rate, achieved rate (Hz), ticks, overruns, skipped deadlines, period error p50, p99,
  /// p99.9, max (us), tick cost p50, p99, max (us).
  double* GetStatistics() VTK_SIZEHINT(12);
  /// The agent as the haptic thread last published it, laid out by vtouchAgentStateLayout.h
  /// (vtouch::AgentStateIndex): time (s), tick, state (0 exploring, 1 tracing), force law, path,
  /// point, cursor x y (px), position x y z (world mm), tangent x y z, direction of travel, cone
  /// roll (rad: a rotation-minimising frame rolled by the integrated torsion), k(P) (N), force x y
  /// (N), target force x y (N), hand x y (device mm).
  double* GetAgentState() VTK_SIZEHINT(23);
  /// The same layout as text for scripting hosts: "name:components:i|f" per field, in order.
  const char* GetAgentStateLayout();
  /// 1 when the running loop got real-time scheduling (SCHED_FIFO), else 0.
  int GetRealTimeScheduling();
  /// View models built so far (each camera, capture-radius, stencil or centerline change).
  vtkIdType GetViewModelBuilds();
  /// The force last sent to the device, x y z (N, device frame, after the safety layer); zero
  /// when no device is open, and after Stop() (which zeroes the force before closing).
  double* GetDeviceForce() VTK_SIZEHINT(3);
  /// What the open device can do (vtouch::DeviceCapabilities): open (0/1), sensed DOF, actuated
  /// DOF, workspace x y z (mm), largest continuous force (N), largest stable stiffness at 1 kHz
  /// (N/m), fastest update rate (Hz), pressure input (0/1), position resolution (mm), buttons.
  /// All zero when no device is open (before Start, after Stop).
  double* GetDeviceCapabilities() VTK_SIZEHINT(12);
  /// The raw-axis calibration the open device applies (vtouch::DeviceAxisCalibration): the number
  /// of calibrated axes (0: none, e.g. the simulated handle, the mouse, a replay, a HID mouse),
  /// then per axis x, y, z: raw minimum, raw maximum (device units), position at each (mm). All
  /// zero when no device is open.
  double* GetDeviceCalibration() VTK_SIZEHINT(13);
  /// The open device's product name ("" when none is open).
  const char* GetDeviceName();
  /// running (0/1), fault code (0 none), log entries, dropped log entries, skeleton paths,
  /// skeleton points.
  int* GetSessionStatus() VTK_SIZEHINT(6);
  /// The last error (configuration, device, camera), "" when none.
  const char* GetLastErrorMessage();
  /// The fault as text ("none" when none) and the real-time scheduling notice.
  const char* GetFaultMessage();
  const char* GetSchedulerNotice();

  /// Publishes every parameter, and the camera when it changed, to the haptic session if any
  /// property changed since the last call: a running session feels them at its next tick, and
  /// a camera change rebuilds the view model once. ParaView calls it once after each push of the
  /// proxy's properties (the XML's post_push), so a camera whose eight properties change together
  /// reaches the haptic thread whole. Start() and RunOffline() call it too; a C++ host that sets
  /// properties on a running session calls it after the set.
  void ApplyProperties();

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
  vtkMTimeType AppliedTime = 0;
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

  double LoopRate = 1000.0;
  int LogCapacity = 60000;
  double OfflineDuration = 5.0;
  double OfflineRate = 1000.0;

  double Statistics[12] = {};
  double AgentState[23] = {};
  double DeviceCapabilities[12] = {};
  double DeviceCalibration[13] = {};
  double DeviceForce[3] = {};
  int SessionStatus[6] = {};
};

#endif
