// The custom-painted k(P) curve of the force zones, with two thresholds the mouse can drag.
// Pure Qt: qVesselTouchForceZonesWidget owns it and keeps it in sync with its spin boxes.
#ifndef qVesselTouchForceZonesPlot_h
#define qVesselTouchForceZonesPlot_h

#include <QScopedPointer>
#include <QWidget>

class qVesselTouchForceZonesPlotPrivate;

/// Plots k(P) for P in [0, 1]: the zero-force zone (grey), the proportional zone (blue) and the
/// saturation zone (orange), the two thresholds as vertical handles, and the live (P, k(P)) as a
/// dot. Dragging a handle emits thresholdsEdited(); the owner decides what to keep.
class qVesselTouchForceZonesPlot : public QWidget
{
  Q_OBJECT
public:
  enum Handle
  {
    NoHandle = -1,
    ZeroBelowHandle = 0,     ///< the end of the zero-force zone
    SaturateAboveHandle = 1, ///< the start of the saturation zone
  };
  Q_ENUM(Handle)

  explicit qVesselTouchForceZonesPlot(QWidget* parent = nullptr);
  ~qVesselTouchForceZonesPlot() override;

  /// The curve to draw: thresholds in normalized pressure, gain in newtons.
  void setZones(double zeroBelow, double saturateAbove, double gain_N);
  double zeroBelow() const;
  double saturateAbove() const;
  double gain_N() const;

  /// The live pressure drawn as a dot on the curve; a negative or non-finite value hides it.
  void setLivePressure(double pressure);
  double livePressure() const;
  bool hasLivePressure() const;

  /// Smallest distance kept between the two thresholds while dragging. 0.01.
  static constexpr double kMinimumGap = 0.01;
  /// How close (pixels) a press must be to a handle to grab it. 6 px.
  static constexpr int kGrabDistance_px = 6;

  /// Pixel column of pressure P (P in [0, 1]) in the current geometry, and back (clamped to [0,
  /// 1]).
  int pixelForPressure(double pressure) const;
  double pressureForPixel(int x) const;
  /// Pixel row of a gain k (newtons) in the current geometry.
  int pixelForGain(double gain_N) const;
  /// The handle under pixel column x, or NoHandle.
  Handle handleAt(int x) const;
  /// The handle being dragged, or NoHandle.
  Handle draggedHandle() const;

  QSize sizeHint() const override;
  QSize minimumSizeHint() const override;

signals:
  /// The user dragged a threshold; values are already clamped and ordered.
  void thresholdsEdited(double zeroBelow, double saturateAbove);

protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;

private:
  QRect plotRect() const;
  double axisMaximum_N() const;

  QScopedPointer<qVesselTouchForceZonesPlotPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchForceZonesPlot);
  Q_DISABLE_COPY(qVesselTouchForceZonesPlot);
};

#endif
