// Keeps a combo box listing the pipeline sources whose first output is a usable volume (3D image
// data with scalars, pqVesselTouchVolumeCheck), and selects the active source when it is one. An
// image that is not a usable volume (a PNG, one slice) is left out and its reason reported.
//
// The combo holds each source's global proxy ID, never a pointer: a source deleted from the
// Pipeline Browser or by Edit > Reset Session is looked up as gone instead of dereferenced (a
// QVariant holding a freed QObject pointer crashes on value<>(), which qobject_casts it).
#ifndef pqVesselTouchVolumeChooser_h
#define pqVesselTouchVolumeChooser_h

#include <QObject>
#include <QPointer>
#include <QString>

class QComboBox;
class pqPipelineSource;

class pqVesselTouchVolumeChooser : public QObject
{
  Q_OBJECT
public:
  /// Fills `combo` (owned by the caller) and keeps it up to date.
  explicit pqVesselTouchVolumeChooser(QComboBox* combo, QObject* parent = nullptr);
  ~pqVesselTouchVolumeChooser() override;

  /// The chosen volume, null when the list is empty.
  pqPipelineSource* currentVolume() const;
  /// Selects `source` when it is listed.
  void setCurrentVolume(pqPipelineSource* source);
  /// Why there is no usable volume to choose, or why the active image is not listed ("" when
  /// the active source, if an image, is a usable volume and the list is not empty).
  QString problem() const;

Q_SIGNALS:
  void currentVolumeChanged(pqPipelineSource* volume);
  void problemChanged(const QString& problem);

public Q_SLOTS:
  /// Rebuilds the list, keeping the choice when it is still a volume.
  void refresh();

private Q_SLOTS:
  void onActiveSourceChanged(pqPipelineSource* source);
  void onSourceAdded(pqPipelineSource* source);
  void onSourceAboutToBeRemoved(pqPipelineSource* source);

private:
  void updateProblem();

  QPointer<QComboBox> Combo;
  QString Problem;
  Q_DISABLE_COPY(pqVesselTouchVolumeChooser)
};

#endif
