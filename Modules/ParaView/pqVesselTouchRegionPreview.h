// The panel's Preview: the candidate vessel region, what Extract would code from the same seed and
// range (VesselCandidateRegion's mask: the estimated range, the seed's network, tubes only),
// drawn over the MIP as a translucent magenta surface before any extraction, with the range it
// used. It is computed on a thread of its own (pqVesselTouchVolumeJob: a private
// vtkVesselTouchCandidateRegionFilter and an isosurface of its mask), so a large volume does not
// freeze the GUI, and it never enters the pipeline: no source in the Pipeline Browser, nothing in
// state files. It needs the volume's voxels in this process (the builtin session).
#ifndef pqVesselTouchRegionPreview_h
#define pqVesselTouchRegionPreview_h

#include <QObject>
#include <QPointer>
#include <QString>

class pqPipelineSource;
class pqVesselTouchCenterlineOverlay;
class pqVesselTouchVolumeJob;
class pqView;

struct pqVesselTouchPreviewResult
{
  /// Voxels of the candidate region (0 when the filter found none: `message` says why).
  qulonglong voxels = 0;
  double rangeUsed[2] = { 0.0, 0.0 };
  bool rangeAutomatic = false;
  QString message;
  /// What the shading correction did (pqVesselTouchShadingNote), "" when it corrected nothing.
  QString shading;
};

class pqVesselTouchRegionPreview : public QObject
{
  Q_OBJECT
public:
  /// Draws into `overlay`'s layer (which must outlive this object).
  explicit pqVesselTouchRegionPreview(pqVesselTouchCenterlineOverlay* overlay,
    QObject* parent = nullptr);
  ~pqVesselTouchRegionPreview() override;

  /// Why `volume` cannot be previewed ("" when it can): its voxels are on a remote server.
  static QString unavailableReason(pqPipelineSource* volume);

  /// Starts computing the region of `volume` at `seed_mm` (world mm) in [lower, upper] or the
  /// automatic range, replacing any preview; shown() or failed() or cancelled() follows.
  /// False (nothing started) when unavailableReason() says why.
  bool show(pqPipelineSource* volume,
    const double seed_mm[3],
    bool automatic,
    double lower,
    double upper,
    pqView* view);
  /// Stops a computation (at once for the caller: its end is dropped) and removes the region
  /// from the view.
  void hide();
  bool isRunning() const;
  bool isShown() const;
  const pqVesselTouchPreviewResult& result() const { return this->Result; }

Q_SIGNALS:
  void progress(int percent);
  /// The region is drawn (result() says what it holds).
  void shown();
  /// The filter found no region: `reason` is its message.
  void failed(const QString& reason);
  /// The computation stopped by itself: its volume changed or went away.
  void cancelled(const QString& reason);

private:
  void onJobFinished(pqVesselTouchVolumeJob* job);

  pqVesselTouchCenterlineOverlay* Overlay;
  QPointer<pqVesselTouchVolumeJob> Job;
  QPointer<pqPipelineSource> Volume;
  QPointer<pqView> View;
  pqVesselTouchPreviewResult Result;
  Q_DISABLE_COPY(pqVesselTouchRegionPreview)
};

#endif
