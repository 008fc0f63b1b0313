// "Extract": creates (once per volume) or updates a VesselCenterline filter on the chosen volume
// with the picked seed and the vessel intensity range (the filter's own estimate when automatic),
// runs it, reports progress (pqProgressManager's progress while the filter updates) and the
// result, and shows it at once in the render view: the new centerlines drawn as tubes in a colour
// that stands out on a grey MIP, or nothing left on screen when the extraction found none.
//
// start() runs the same filter on a thread of its own (pqVesselTouchVolumeJob) when the volume's
// data is in this process, and hands its output to the volume's VesselCenterline proxy, whose
// update then returns it without recomputing (vtkVesselTouchCenterlineFilter's precomputed
// output, keyed on the input's voxels and the parameters): state files, Python and the Pipeline
// Browser see the filter as after extract(). Until then nothing of the pipeline, the view or the
// session changes.
//
// With remote data (a pvserver) the pipeline's filter runs synchronously, as in ParaView, and is
// cancellable (issue 19 item 1): the run's progress reports from the server give progress() and
// remoteProgress() and run the events the panel's Cancel needs (setRemoteUpdateEvents); cancel()
// sends the filter's token over the side channel (pqVesselTouchRemoteCancel). After a cancel the
// filter gets the previous run's parameters back and returns that run's output, which its ranks
// kept (vtkVesselTouchCenterlineFilter's kept output): the previous centerline stays.
#ifndef pqVesselTouchCenterlineExtraction_h
#define pqVesselTouchCenterlineExtraction_h

#include "pqPipelineSource.h" // for QPointer<pqPipelineSource>
#include "pqView.h"           // for QPointer<pqView>

#include <QElapsedTimer>
#include <QObject>
#include <QPointer>
#include <QString>

#include <memory>
#include <string>

class pqVesselTouchCenterlineOverlay;
class pqVesselTouchRemoteCancel;
class pqVesselTouchRemoteUpdateEvents;
class pqVesselTouchVolumeJob;
class vtkObject;
class vtkPolyData;

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
  /// What the shading correction did (pqVesselTouchShadingNote), "" when it corrected nothing.
  QString shading;
  /// The run went on a thread of its own and the pipeline took its output without recomputing.
  bool background = false;
  /// Wall time from Extract to the result, s.
  double seconds = 0.0;
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

  /// As extract(), on a thread of its own when the volume's data is in this process (the
  /// builtin session): returns at once, then progress() and finished(), failed() or cancelled()
  /// on the GUI thread. With remote data (client/server) it runs extract() before it returns.
  /// A start while a run goes on cancels that run (its result is dropped), unless it asks the
  /// same of the same volume: then that run goes on. Returns whether a run goes on now.
  bool start(pqPipelineSource* volume,
    const double seed_mm[3],
    bool automatic,
    double lowerThreshold,
    double upperThreshold,
    pqView* view);
  /// Stops the running start() at its next check point: cancelled() follows; the pipeline, the
  /// view and the session keep the previous centerline. During a remote run (called from a click
  /// that setRemoteUpdateEvents let through): sends the cancel to the server.
  void cancel(const QString& reason = QString());
  bool isRunning() const;
  /// Whether a remote run is under way (the client inside the update).
  bool isRunningRemotely() const { return this->Remote != nullptr; }
  /// Runs the events the panel needs (its Cancel) at each progress report of a remote run; not
  /// owned, null: none (the client answers only after the run).
  void setRemoteUpdateEvents(pqVesselTouchRemoteUpdateEvents* events);

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
  /// A start() was cancelled (Cancel, the volume deleted or changed): `reason` says which.
  void cancelled(const QString& reason);
  /// A remote run began: the client waits in the update until it ends (Cancel works meanwhile).
  void remoteRunStarted();
  /// A progress report of the remote run: percent and the server's text.
  void remoteProgress(int percent, const QString& text);

private:
  struct Request
  {
    QPointer<pqPipelineSource> volume;
    double seed_mm[3] = { 0.0, 0.0, 0.0 };
    bool automatic = true;
    double lower = 0.0, upper = 0.0;
    QPointer<pqView> view;
    static Request of(pqPipelineSource* volume,
      const double seed_mm[3],
      bool automatic,
      double lowerThreshold,
      double upperThreshold,
      pqView* view);
    bool sameAs(const Request& other) const;
  };

  pqPipelineSource* filterFor(pqPipelineSource* volume);
  /// The synchronous run (and the hand-off of a background run's `precomputed` output, whose key
  /// is `key`): the filter's properties, its update, the result shown.
  pqPipelineSource* run(const Request& request, vtkPolyData* precomputed, const std::string& key);
  void onJobFinished(pqVesselTouchVolumeJob* job);
  /// A progress report of the server during a remote run (vtkPVProgressHandler's ProgressEvent).
  void onRemoteProgress(vtkObject* handler);
  /// The remote update, cancellable; true when it was cancelled.
  bool updateRemotely(pqPipelineSource* filter);
  /// After a remote cancel: the previous run's parameters back on `filter` and its kept output.
  void restorePrevious(pqPipelineSource* filter, pqView* view);

  QPointer<pqPipelineSource> Centerline;
  QPointer<pqVesselTouchVolumeJob> Job;
  Request Running;
  /// The filter's run parameters as this run found them (restored after a remote cancel).
  struct Parameters
  {
    QPointer<pqPipelineSource> filter;
    double seed_mm[3] = { 0.0, 0.0, 0.0 };
    int useSeed = 0;
    int automatic = 1;
    double lower = 0.0, upper = 0.0;
    static Parameters of(pqPipelineSource* filter);
    void applyTo(pqPipelineSource* filter) const;
  };
  Parameters Previous;
  /// The filter's last run gave its output (not cancelled, not failed on the input).
  QPointer<pqPipelineSource> Completed;
  std::unique_ptr<pqVesselTouchRemoteCancel> Remote;
  QPointer<pqVesselTouchRemoteUpdateEvents> RemoteEvents;
  QElapsedTimer Clock;
  pqVesselTouchCenterlineOverlay* Overlay = nullptr;
  pqVesselTouchExtractionResult Result;
  Q_DISABLE_COPY(pqVesselTouchCenterlineExtraction)
};

#endif
