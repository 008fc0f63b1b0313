// Keeps a combo box listing the pipeline sources whose first output is a vtkImageData (the
// volumes a centerline can be extracted from), and selects the active source when it is one.
#ifndef pqVesselTouchVolumeChooser_h
#define pqVesselTouchVolumeChooser_h

#include <QObject>
#include <QPointer>

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

Q_SIGNALS:
  void currentVolumeChanged(pqPipelineSource* volume);

public Q_SLOTS:
  /// Rebuilds the list, keeping the choice when it is still a volume.
  void refresh();

private Q_SLOTS:
  void onActiveSourceChanged(pqPipelineSource* source);
  void onSourceAdded(pqPipelineSource* source);

private:
  static bool isVolume(pqPipelineSource* source);

  QPointer<QComboBox> Combo;
  Q_DISABLE_COPY(pqVesselTouchVolumeChooser)
};

#endif
