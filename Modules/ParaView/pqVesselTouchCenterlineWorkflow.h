// The panel's "Centerlines" section: the volume combo (3D volumes only; why another image is not
// one shows beside it), "Pick seed" (a one-shot click in the active render view,
// pqVesselTouchSeedPicker), the seed shown in mm with a warning when it lies on background, the
// vessel intensity range (the filter's automatic estimate, or the user's, clamped to the data's
// range), "Preview" (pqVesselTouchRegionPreview: the candidate vessel region over the MIP) and
// "Extract" (pqVesselTouchCenterlineExtraction), both in the background with one progress bar,
// one "Cancel" and their message beside them. The panel feeds the result to the session.
#ifndef pqVesselTouchCenterlineWorkflow_h
#define pqVesselTouchCenterlineWorkflow_h

#include <QObject>
#include <QPoint>
#include <QPointer>

class QLabel;
class pqPipelineSource;
class pqVesselTouchCenterlineExtraction;
class pqVesselTouchRegionPreview;
class pqVesselTouchSeedPicker;
class pqVesselTouchVolumeChooser;

namespace Ui
{
class pqVesselTouchDockPanel;
}

class pqVesselTouchCenterlineWorkflow : public QObject
{
  Q_OBJECT
public:
  /// Drives the centerline widgets of `ui` (which must outlive this object).
  pqVesselTouchCenterlineWorkflow(Ui::pqVesselTouchDockPanel& ui, QObject* parent = nullptr);
  ~pqVesselTouchCenterlineWorkflow() override;

  /// The chosen volume, null when no source produces a 3D image.
  pqPipelineSource* currentVolume() const;
  /// The picked seed, world mm; false before any pick (and after the volume changed).
  bool seed(double seed_mm[3]) const;
  /// The vessel intensity range given to VesselCenterline when Automatic is off (the volume's
  /// units).
  double lowerThreshold() const;
  double upperThreshold() const;
  bool automaticRange() const;
  /// The VesselCenterline filter of the last extraction, null before.
  pqPipelineSource* centerline() const;
  /// The message beside Extract ("" when none).
  QString extractMessage() const;
  /// Whether an Extract or a Preview runs now (in the background).
  bool isRunning() const;

public Q_SLOTS:
  /// What an armed click does, at once at `position` (view widget pixels, top-left origin) in the
  /// active render view and the chosen volume. Returns whether a seed was found.
  bool pickSeedAt(const QPoint& position);
  /// Runs VesselCenterline at the seed, in the background when the data is in this process;
  /// centerlineReady() follows, or the reason it did not beside Extract.
  void extract();
  /// Stops a running Extract or Preview ("Cancelled." beside Extract); the previous centerline
  /// stays in the view and in the session.
  void cancelRuns();
  /// Forgets the seed and removes its marker from the view.
  void clearSeed();
  /// After a state file was loaded: the panel shows the state's VesselCenterline (its volume,
  /// seed, intensity range and automatic choice) and feeds it on as the last extraction.
  void adoptFromState();
  /// The active server cannot run VesselTouch's server-side filters (pqVesselTouchServerCheck):
  /// Extract is disabled with `problem` as its tool tip and said beside it; "" enables it again.
  void setServerProblem(const QString& problem);

Q_SIGNALS:
  /// Centerlines were extracted: `paths` polylines.
  void centerlineReady(pqPipelineSource* centerline, int paths);

private Q_SLOTS:
  void onPickSeedToggled(bool armed);
  void onSeedPicked(double x_mm, double y_mm, double z_mm, double value);
  void onVolumeChanged(pqPipelineSource* volume);
  void onVolumeDataUpdated(pqPipelineSource* volume);
  void onAutomaticToggled(bool automatic);
  void onPreviewToggled(bool on);
  void onExtracted(pqPipelineSource* centerline, int paths);
  void onPreviewShown();
  void onRunCancelled(const QString& reason);

private:
  /// Cancel is enabled while a run goes on; Preview is checked while the region is computed or
  /// shown.
  void updateRunState();
  /// Removes the preview (a new seed, range or volume makes it stale, and Extract replaces it).
  void hidePreview();
  /// The range fields show `range` (what a run used: the user's starting point for an override).
  void showRangeUsed(const double range[2]);
  /// Shows `text` in `label` (red when `error`), hidden when empty.
  static void showMessage(QLabel* label, const QString& text, bool error);
  void setExtractMessage(const QString& text, bool error);
  /// The range fields: bounded by the data's range, and their default (the upper tail).
  void setDataRange(pqPipelineSource* volume);
  /// Takes a seed (world mm, the voxel value there) as picked in the current volume.
  void acceptSeed(const double seed_mm[3], double value);

  Ui::pqVesselTouchDockPanel& Ui;
  pqVesselTouchVolumeChooser* Volumes = nullptr;
  pqVesselTouchSeedPicker* Picker = nullptr;
  pqVesselTouchCenterlineExtraction* Extraction = nullptr;
  pqVesselTouchRegionPreview* Preview = nullptr;
  /// Preview's tooltip (replaced by why not, with the data on a remote server).
  QString PreviewToolTip;
  QString ExtractToolTip;
  QString ServerProblem;
  QPointer<pqPipelineSource> SeedVolume;
  bool HasSeed = false;
  double Seed_mm[3] = { 0.0, 0.0, 0.0 };
  double SeedValue = 0.0;
  double DataRange[2] = { 0.0, 0.0 };
  /// The volume's background level and noise (sampled voxels), when known.
  bool NoiseKnown = false;
  double Background = 0.0;
  double Noise = 0.0;
  Q_DISABLE_COPY(pqVesselTouchCenterlineWorkflow)
};

#endif
