// The warnings and errors the GUI tests check for: every Qt warning/critical/fatal message
// (ParaView's own GUI classes report through Qt, e.g. pqPipelineFilter's "Some proxy is added as
// input but was not registered"), recorded before ParaView's Output Messages window gets them,
// and whether that window is showing. Test code only (the VesselTouchTestDriver plugin).
#ifndef pqVesselTouchMessageRecorder_h
#define pqVesselTouchMessageRecorder_h

#include <QStringList>

class pqVesselTouchMessageRecorder
{
public:
  /// Installs the recorder in front of the current Qt message handler (which still gets every
  /// message) and listens to the Output Messages window. Idempotent.
  static void install();
  /// The messages recorded so far ("critical: text"), at most the last 200.
  static QStringList messages();
  /// What ParaView's Output Messages window displayed since install() (its messageDisplayed
  /// signal: after its own suppression of known harmless messages), at most the last 200.
  static QStringList displayedMessages();
  /// Whether ParaView's Output Messages window (the dock holding pqOutputWidget) is visible.
  static bool outputMessagesVisible();
};

#endif
