// A snapshot of the haptic session proxy's information properties (StatisticsInfo,
// AgentStateInfo, SessionStatusInfo, DeviceForceInfo, DeviceCapabilitiesInfo, DeviceNameInfo,
// DeviceCalibrationInfo, LastErrorInfo, FaultInfo, SchedulerNoticeInfo), read by the panel's
// ~10 Hz timer and by the panel self-test.
#ifndef pqVesselTouchSessionStatus_h
#define pqVesselTouchSessionStatus_h

#include "qVesselTouchDeviceCalibration.h"
#include "qVesselTouchDeviceCapabilities.h"
#include "qVesselTouchLoopStats.h"

#include <QString>

class vtkSMProxy;

struct pqVesselTouchSessionStatus
{
  /// The loop runs. Default false.
  bool running = false;
  /// Fault code (0 none) and its text ("none").
  int faultCode = 0;
  QString faultText;
  /// The session's last error ("" when none) and the real-time scheduling notice.
  QString lastError;
  QString schedulerNotice;
  /// Loop statistics and the agent's interaction state, as the loop statistics widget shows them.
  qVesselTouchLoopStats loop;
  /// Skeleton size the session holds (paths, points).
  int skeletonPaths = 0;
  int skeletonPoints = 0;
  /// The force last sent to the device, N (zero after Stop), and the agent's force, N.
  double deviceForce_N[3] = { 0.0, 0.0, 0.0 };
  /// A device is open (the session runs on it); `deviceCapabilities` are then its own.
  bool deviceOpen = false;
  qVesselTouchDeviceCapabilities deviceCapabilities;
  /// The open device calibrates raw axes (HID joysticks); `deviceCalibration` is then what it
  /// applies (DeviceCalibrationInfo).
  bool deviceHasCalibration = false;
  qVesselTouchDeviceCalibration deviceCalibration;
  double agentForce_N[2] = { 0.0, 0.0 };
  /// Agent position, world mm.
  double agentPosition_mm[3] = { 0.0, 0.0, 0.0 };

  /// Pulls the information properties of `session` (UpdatePropertyInformation) and reads them.
  /// A null proxy gives the defaults.
  static pqVesselTouchSessionStatus read(vtkSMProxy* session);
  /// One line for the panel: "Running: tracing path 2, point 14" / "Stopped" / "No session".
  QString summary() const;
  /// Magnitude of deviceForce_N, N.
  double deviceForceMagnitude_N() const;
  /// The fault is the device's or the loop's own (a device error, a non-finite force, a late
  /// loop), not a lost pvserver (vtkVesselTouchHapticSession::CONNECTION_LOST_FAULT).
  bool deviceFault() const;
};

#endif
