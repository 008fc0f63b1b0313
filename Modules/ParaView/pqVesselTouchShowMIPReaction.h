// "Show as MIP": shows the active image in the active render view as a maximum-intensity
// projection (Volume representation, BlendMode 1, grey transfer function) on a black background;
// a patient image (VesselTouch's readers) opens in the radiological axial view. Disabled, with the
// reason in its tooltip, unless the active source is a 3D volume (pqVesselTouchVolumeCheck).
#ifndef pqVesselTouchShowMIPReaction_h
#define pqVesselTouchShowMIPReaction_h

#include "pqReaction.h"

#include <QPointer>

class pqPipelineSource;
class pqView;
class vtkSMProxy;

class pqVesselTouchShowMIPReaction : public pqReaction
{
  Q_OBJECT
  typedef pqReaction Superclass;

public:
  explicit pqVesselTouchShowMIPReaction(QAction* parent);

  /// Shows output port 0 of `source` in `view` as a MIP. Returns false (with a qWarning naming
  /// the reason) when the source is not a 3D volume or the view is not a render view.
  static bool showAsMIP(pqPipelineSource* source, pqView* view);

protected Q_SLOTS:
  void updateEnableState() override;

protected:
  void onTriggered() override;

private:
  /// Patient images open in the radiological axial view (seen from the feet, anterior up).
  static void setRadiologicalCamera(pqPipelineSource* source, vtkSMProxy* viewProxy);
  /// The active source whose data updates re-check the action (a 2D image disables it).
  QPointer<pqPipelineSource> Watched;
  Q_DISABLE_COPY(pqVesselTouchShowMIPReaction)
};

#endif
