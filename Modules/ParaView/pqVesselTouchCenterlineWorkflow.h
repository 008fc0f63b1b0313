// The panel's "Centerlines" box: the volume combo, "Pick seed" (a one-shot click in the active
// render view, pqVesselTouchSeedPicker), the seed shown in mm, the vessel intensity range
// (defaulting to the upper half of the volume's scalar range), and "Extract centerlines"
// (pqVesselTouchCenterlineExtraction) with its progress bar. The panel feeds the result to the
// session.
#ifndef pqVesselTouchCenterlineWorkflow_h
#define pqVesselTouchCenterlineWorkflow_h

#include <QObject>
#include <QPoint>

class pqPipelineSource;
class pqVesselTouchCenterlineExtraction;
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

  /// The chosen volume, null when no source produces image data.
  pqPipelineSource* currentVolume() const;
  /// The picked seed, world mm; false before any pick.
  bool seed(double seed_mm[3]) const;
  /// The vessel intensity range given to VesselCenterline (the volume's units).
  double lowerThreshold() const;
  double upperThreshold() const;
  /// The VesselCenterline filter of the last extraction, null before.
  pqPipelineSource* centerline() const;

public Q_SLOTS:
  /// What an armed click does, at once at `position` (view widget pixels, top-left origin) in the
  /// active render view and the chosen volume. Returns whether a seed was found.
  bool pickSeedAt(const QPoint& position);
  /// Runs VesselCenterline at the seed with the intensity range; emits centerlineReady() or
  /// message().
  void extract();

Q_SIGNALS:
  /// Centerlines were extracted: `paths` polylines.
  void centerlineReady(pqPipelineSource* centerline, int paths);
  /// An error to show in red, or "" once an action succeeded.
  void message(const QString& text);

private Q_SLOTS:
  void onPickSeedToggled(bool armed);
  void onSeedPicked(double x_mm, double y_mm, double z_mm, double value);
  void onVolumeChanged(pqPipelineSource* volume);
  void onVolumeDataUpdated(pqPipelineSource* volume);

private:
  Ui::pqVesselTouchDockPanel& Ui;
  pqVesselTouchVolumeChooser* Volumes = nullptr;
  pqVesselTouchSeedPicker* Picker = nullptr;
  pqVesselTouchCenterlineExtraction* Extraction = nullptr;
  bool HasSeed = false;
  double Seed_mm[3] = { 0.0, 0.0, 0.0 };
  Q_DISABLE_COPY(pqVesselTouchCenterlineWorkflow)
};

#endif
