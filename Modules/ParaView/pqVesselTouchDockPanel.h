// The "VesselTouch" dock panel: hosts the VesselTouch widgets and binds them to ParaView's active
// objects. Later widgets (force law, zoom, zones, device, loop statistics) join it here.
#ifndef pqVesselTouchDockPanel_h
#define pqVesselTouchDockPanel_h

#include <QDockWidget>
#include <QPointer>

class pqPipelineSource;
class qVesselTouchInfoWidget;

class pqVesselTouchDockPanel : public QDockWidget
{
  Q_OBJECT
public:
  explicit pqVesselTouchDockPanel(QWidget* parent = nullptr);
  ~pqVesselTouchDockPanel() override;

protected:
  void showEvent(QShowEvent* event) override;

private Q_SLOTS:
  void setActiveSource(pqPipelineSource* source);
  void updateDatasetInformation();
  /// Shows the panel; the first time a dataset is active, then never again on its own.
  void revealOnce();

private:
  /// When VESSELTOUCH_GUI_REPORT names a file, writes what the panel shows there as JSON, so
  /// GUI tests can check the real widget state of a running ParaView.
  void writeReportIfRequested() const;

  qVesselTouchInfoWidget* Info = nullptr;
  QPointer<pqPipelineSource> Source;
  bool Revealed = false;
  Q_DISABLE_COPY(pqVesselTouchDockPanel)
};

#endif
