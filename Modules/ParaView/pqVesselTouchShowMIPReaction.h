// "Show as MIP": shows the active image in the active render view as a maximum-intensity
// projection (Volume representation, BlendMode 1, grey transfer function).
#ifndef pqVesselTouchShowMIPReaction_h
#define pqVesselTouchShowMIPReaction_h

#include "pqReaction.h"

class pqPipelineSource;
class pqView;

class pqVesselTouchShowMIPReaction : public pqReaction
{
  Q_OBJECT
  typedef pqReaction Superclass;

public:
  explicit pqVesselTouchShowMIPReaction(QAction* parent);

  /// Shows output port 0 of `source` in `view` as a MIP. Returns false (with a qWarning naming
  /// the reason) when the source is not an image or the view is not a render view.
  static bool showAsMIP(pqPipelineSource* source, pqView* view);

protected Q_SLOTS:
  void updateEnableState() override;

protected:
  void onTriggered() override;

private:
  Q_DISABLE_COPY(pqVesselTouchShowMIPReaction)
};

#endif
