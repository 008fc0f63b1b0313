// "Extract": creates (once per volume) or updates a VesselCenterline filter on the chosen volume
// with the picked seed and the vessel intensity range (the filter's own estimate when automatic),
// runs it, reports progress (pqProgressManager's progress while the filter updates) and the
// result, and shows it at once in the render view: the new centerlines drawn as tubes in a colour
// that stands out on a grey MIP, or nothing left on screen when the extraction found none.
#ifndef pqVesselTouchCenterlineExtraction_h
#define pqVesselTouchCenterlineExtraction_h

#include <QObject>
#include <QPointer>
#include <QString>

class pqPipelineSource;
class pqVesselTouchCenterlineOverlay;
class pqView;

struct pqVesselTouchExtractionResult
{
  /// Polylines in the output (0: none found).
  int paths = 0;
  /// The intensity range the filter used (its field data IntensityRangeUsed), when it says.
  bool rangeKnown = false;
  double rangeUsed[2] = { 0.0, 0.0 };
  bool rangeAutomatic = false;
  /// The filter's own words about the run (field data ExtractionMessage), "" when none.
  QString message;
};

class pqVesselTouchCenterlineExtraction : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchCenterlineExtraction(QObject* parent = nullptr);
  ~pqVesselTouchCenterlineExtraction() override;

  /// Runs VesselCenterline on `volume` with UseSeedPoint on at `seed_mm` (world mm), the
  /// filter's automatic intensity range when `automatic` (and the filter has one), else
  /// [lower, upper]. Reuses the filter of an earlier run on the same volume, shows its output in
  /// `view` (when not null) and renders. Returns the filter (null on failure, with failed()
  /// emitted).
  pqPipelineSource* extract(pqPipelineSource* volume,
    const double seed_mm[3],
    bool automatic,
    double lowerThreshold,
    double upperThreshold,
    pqView* view);

  /// The filter of the last run, null before.
  pqPipelineSource* centerline() const;
  /// Takes `filter` (a VesselCenterline, e.g. from a loaded state file) as the last run's.
  void setCenterline(pqPipelineSource* filter);
  /// What the last run found.
  const pqVesselTouchExtractionResult& result() const;
  /// Reads what `filter` (updated) found into result(): paths, range used, message.
  const pqVesselTouchExtractionResult& readResult(pqPipelineSource* filter);

  /// The filter's output drawn in `view` as tubes in a colour visible on a grey MIP, over the
  /// MIP (pqVesselTouchCenterlineOverlay), when `visible`; hidden otherwise; the view rendered.
  void showInView(pqPipelineSource* centerline, pqView* view, bool visible);
  /// Whether the overlay draws centerlines now.
  bool isShowingCenterline() const;
  /// The overlay, which also marks the seed.
  pqVesselTouchCenterlineOverlay* overlay() const { return this->Overlay; }

Q_SIGNALS:
  /// Progress of the running filter, percent [0, 100].
  void progress(int percent);
  /// The filter updated: its output has `paths` polylines.
  void finished(pqPipelineSource* centerline, int paths);
  void failed(const QString& reason);

private:
  pqPipelineSource* filterFor(pqPipelineSource* volume);

  QPointer<pqPipelineSource> Centerline;
  pqVesselTouchCenterlineOverlay* Overlay = nullptr;
  pqVesselTouchExtractionResult Result;
  Q_DISABLE_COPY(pqVesselTouchCenterlineExtraction)
};

#endif
