// Runs when the plugin loads into the ParaView GUI: makes VesselTouch's oriented readers the
// default File > Open choice for NIfTI, NRRD, MetaImage and DICOM files, and names blend mode 1
// "Maximum Intensity" in every representation's Blend Mode list (pqVesselTouchBlendModeNames) and
// leaves the haptic session proxy out of the Pipeline Browser (state files still save it).
#ifndef pqVesselTouchAutoStart_h
#define pqVesselTouchAutoStart_h

#include <QObject>

class pqVesselTouchAutoStart : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchAutoStart(QObject* parent = nullptr);
  ~pqVesselTouchAutoStart() override = default;

  void startup();
  void shutdown() {}

private:
  Q_DISABLE_COPY(pqVesselTouchAutoStart)
};

#endif
