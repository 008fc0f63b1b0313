// A VTK pipeline run on a thread of its own on a volume's voxels, so the GUI keeps rendering and
// answering while it runs (Extract and Preview in the panel; issue 16 item 6). ParaView 5.11
// updates its pipeline on the GUI thread and blocks user input meanwhile (pqProgressManager), so
// the job runs private copies of VesselTouch's filters instead, on a shallow copy of the volume's
// output in this process (the builtin session): the copy holds the voxels' array, so a source that
// re-executes meanwhile allocates a new one, and deleting the volume frees nothing the thread
// reads. Nothing else is shared with the GUI thread: the job's filters, their executives and
// outputs are the thread's until finished() (after which the GUI thread owns them again).
//
// Cancel: the head filter reads cancelFlag() at its check points (SetCancelFlag) and stops within
// milliseconds of work. The job cancels itself when its volume is deleted or re-executes with new
// voxels (its result would be stale). Errors and warnings of the job's filters are collected
// (errorText()), never written to ParaView's output window from the thread.
#ifndef pqVesselTouchVolumeJob_h
#define pqVesselTouchVolumeJob_h

#include <QObject>
#include <QPointer>
#include <QString>
#include <QTimer>

#include "pqPipelineSource.h" // for QPointer<pqPipelineSource>

#include "vtkAlgorithm.h" // for head() and tail()
#include "vtkImageData.h" // for the thread's copy of the volume
#include "vtkSmartPointer.h"

#include <atomic>
#include <mutex>
#include <string>
#include <thread>

class pqVesselTouchVolumeJob : public QObject
{
  Q_OBJECT
public:
  /// The volume's output image in this process (builtin session); null when the data lives on a
  /// remote server (client/server: the panel then runs the pipeline's filter as before).
  static vtkImageData* localImage(pqPipelineSource* volume);

  /// `head` takes a shallow copy of the volume's image as its input; `tail` (the end of the
  /// private pipeline from `head`, may be `head`) is updated on the thread. Call start() after
  /// giving `head` the cancel flag.
  pqVesselTouchVolumeJob(pqPipelineSource* volume,
    vtkAlgorithm* head,
    vtkAlgorithm* tail,
    QObject* parent = nullptr);
  /// Cancels and joins the thread (at the head's next check point).
  ~pqVesselTouchVolumeJob() override;

  /// The flag `head` reads (vtkVesselTouch*Filter::SetCancelFlag).
  const std::atomic<bool>* cancelFlag() const { return &this->CancelFlag; }
  /// Starts the thread; false (and finished() soon after) when the volume has no local image.
  bool start();
  /// Asks the run to stop; finished() follows with wasCancelled() true. `reason` (may be empty)
  /// is what cancelReason() says.
  void cancel(const QString& reason = QString());

  bool isRunning() const { return this->Thread.joinable(); }
  bool wasCancelled() const { return this->CancelFlag.load(); }
  QString cancelReason() const { return this->CancelReason; }
  /// The job's volume, null once it is deleted.
  pqPipelineSource* volume() const { return this->Volume; }
  vtkAlgorithm* head() const { return this->Head; }
  vtkAlgorithm* tail() const { return this->Tail; }
  /// Errors and warnings the job's filters reported (after finished()).
  QString errorText() const { return this->ErrorText; }
  /// Fraction done of the head filter, percent.
  int percent() const { return this->Permille.load() / 10; }

Q_SIGNALS:
  void progress(int percent);
  /// The thread ended and was joined (on the GUI thread): the output is the GUI's to read.
  void finished();

private:
  void poll();
  void onVolumeDataUpdated();
  void run();
  /// The volume's scalars now (array and point data modification time): a change means new
  /// voxels.
  std::string voxelsSignature() const;

  QPointer<pqPipelineSource> Volume;
  vtkSmartPointer<vtkAlgorithm> Head;
  vtkSmartPointer<vtkAlgorithm> Tail;
  vtkSmartPointer<vtkImageData> Input;
  std::string StartSignature;
  std::atomic<bool> CancelFlag{ false };
  std::atomic<bool> Done{ false };
  std::atomic<int> Permille{ 0 };
  std::thread Thread;
  std::mutex ErrorMutex;
  std::string Errors; // written by the thread (under ErrorMutex), read after the join
  QString ErrorText;
  QString CancelReason;
  QTimer Poll;
  bool Finished = false;
  int LastPercent = -1;
  Q_DISABLE_COPY(pqVesselTouchVolumeJob)
};

#endif
