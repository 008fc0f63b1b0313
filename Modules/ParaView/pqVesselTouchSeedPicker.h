// "Pick seed": arms a one-shot left click in a render view. The click's ray (unprojected with
// the view's camera) is marched through the chosen volume (its vtkImageData, fetched client-side:
// builtin sessions only) and the brightest voxel along it becomes the 3D seed, world mm: the
// vessel the user sees under the cursor on a maximum-intensity projection.
#ifndef pqVesselTouchSeedPicker_h
#define pqVesselTouchSeedPicker_h

#include <QObject>
#include <QPoint>
#include <QPointer>

#include <array>

class pqPipelineSource;
class pqRenderView;

class pqVesselTouchSeedPicker : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchSeedPicker(QObject* parent = nullptr);
  ~pqVesselTouchSeedPicker() override;

  /// Waits for one left click in `view`, then picks in `volume` (port 0). The click is consumed
  /// (the camera does not move). Re-arming replaces the previous request.
  void arm(pqRenderView* view, pqPipelineSource* volume);
  /// Forgets a pending click (emits nothing).
  void disarm();
  bool isArmed() const;

  /// The pick itself at `position` (widget pixels, top-left origin, as Qt gives them); emits
  /// seedPicked() or pickFailed() and returns whether a seed was found. Public for the GUI tests' driver.
  bool pickAt(pqRenderView* view, pqPipelineSource* volume, const QPoint& position);

Q_SIGNALS:
  /// The seed (world mm) and the voxel value there.
  void seedPicked(double x_mm, double y_mm, double z_mm, double value);
  /// Why no seed was found (no volume data, the ray missed the volume...).
  void pickFailed(const QString& reason);

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  /// The click's ray as two world points (near and far clipping planes), false without a view.
  static bool clickRay(pqRenderView* view,
    const QPoint& position,
    std::array<double, 3>& near_mm,
    std::array<double, 3>& far_mm);

  QPointer<pqRenderView> View;
  QPointer<pqPipelineSource> Volume;
  QPointer<QObject> WatchedWidget;
  QPoint PressPosition;
  Q_DISABLE_COPY(pqVesselTouchSeedPicker)
};

#endif
