// Shows the active dataset and the versions this VesselTouch build runs with.
// Pure Qt: the host module feeds it (dataset name and summary, dependency versions).
#ifndef qVesselTouchInfoWidget_h
#define qVesselTouchInfoWidget_h

#include <QScopedPointer>
#include <QWidget>

class qVesselTouchInfoWidgetPrivate;

class qVesselTouchInfoWidget : public QWidget
{
  Q_OBJECT
public:
  explicit qVesselTouchInfoWidget(QWidget* parent = nullptr);
  ~qVesselTouchInfoWidget() override;

  /// Name of the active dataset as the host shows it; empty shows "(none)".
  void setDatasetName(const QString& name);
  QString datasetName() const;

  /// One line describing the dataset (type, dimensions, spacing, scalar range).
  void setDatasetSummary(const QString& summary);
  QString datasetSummary() const;

  /// Adds or updates one "component: version" row, e.g. ("ITK", "5.2.1").
  void setVersion(const QString& component, const QString& version);
  QString version(const QString& component) const;
  QStringList versionComponents() const;

private:
  QScopedPointer<qVesselTouchInfoWidgetPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchInfoWidget);
  Q_DISABLE_COPY(qVesselTouchInfoWidget);
};

#endif
