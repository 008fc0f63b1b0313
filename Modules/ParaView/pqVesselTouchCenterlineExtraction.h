// "Extract centerlines": creates (once per volume) or updates a VesselCenterline filter on the
// chosen volume with the picked seed and the vessel thresholds, runs it, and reports progress
// (pqProgressManager's progress while the filter updates) and the result.
#ifndef pqVesselTouchCenterlineExtraction_h
#define pqVesselTouchCenterlineExtraction_h

#include <QObject>
#include <QPointer>

class pqPipelineSource;

class pqVesselTouchCenterlineExtraction : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchCenterlineExtraction(QObject* parent = nullptr);
  ~pqVesselTouchCenterlineExtraction() override;

  /// Runs VesselCenterline on `volume` with UseSeedPoint on at `seed_mm` (world mm) and the
  /// vessel intensity range [lower, upper]. Reuses the filter of an earlier run on the same
  /// volume. Returns the filter (null on failure, with failed() emitted).
  pqPipelineSource* extract(pqPipelineSource* volume,
    const double seed_mm[3],
    double lowerThreshold,
    double upperThreshold);

  /// The filter of the last run, null before.
  pqPipelineSource* centerline() const;

Q_SIGNALS:
  /// Progress of the running filter, percent [0, 100].
  void progress(int percent);
  /// The filter updated: its output has `paths` polylines.
  void finished(pqPipelineSource* centerline, int paths);
  void failed(const QString& reason);

private:
  pqPipelineSource* filterFor(pqPipelineSource* volume);

  QPointer<pqPipelineSource> Centerline;
  Q_DISABLE_COPY(pqVesselTouchCenterlineExtraction)
};

#endif
