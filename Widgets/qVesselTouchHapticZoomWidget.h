// Haptic zoom: the graphic/haptic ratio r = cursor movement / hand movement, on a logarithmic
// slider from 0.1 to 10 (r = 1 at the middle) with a numeric spin box kept in sync both ways.
// Pure Qt: the module glue forwards ratioChanged() to the haptic session.
#ifndef qVesselTouchHapticZoomWidget_h
#define qVesselTouchHapticZoomWidget_h

#include "vtouchHapticParameterTable.h"

#include <QScopedPointer>
#include <QWidget>

class qVesselTouchHapticZoomWidgetPrivate;

class qVesselTouchHapticZoomWidget : public QWidget
{
  Q_OBJECT
  Q_PROPERTY(double ratio READ ratio WRITE setRatio NOTIFY ratioChanged)
public:
  explicit qVesselTouchHapticZoomWidget(QWidget* parent = nullptr);
  ~qVesselTouchHapticZoomWidget() override;

  /// Graphic/haptic ratio r (dimensionless): cursor movement on the screen per unit of hand
  /// movement. r > 1 magnifies the hand, r < 1 gives fine control. Default, range and meaning:
  /// the Zoom row of vtouchHapticParameters.def (1, [0.1, 10]); resolution 0.001 (values are
  /// clamped and rounded).
  double ratio() const;

  static constexpr double kMinimumRatio =
    vtouch::hapticParameter(vtouch::HapticParameterId::Zoom).minimum;
  static constexpr double kMaximumRatio =
    vtouch::hapticParameter(vtouch::HapticParameterId::Zoom).maximum;
  /// Slider positions span [0, kSliderSteps]; the middle (kSliderSteps / 2) is r = 1.
  static constexpr int kSliderSteps = 1000;

  /// r = 10^(2 position / kSliderSteps - 1), so 0 -> 0.1, kSliderSteps / 2 -> 1, kSliderSteps
  /// -> 10.
  static double sliderPositionToRatio(int position);
  /// The nearest slider position of r (clamped to the range).
  static int ratioToSliderPosition(double ratio);

public slots:
  /// Sets r (clamped to [0.1, 10], rounded to 0.001); emits ratioChanged() only when it changes.
  void setRatio(double ratio);
  /// Back to r = 1.
  void resetRatio();

signals:
  /// r changed, from the slider, the spin box, the reset button or setRatio().
  void ratioChanged(double ratio);

private:
  QScopedPointer<qVesselTouchHapticZoomWidgetPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchHapticZoomWidget);
  Q_DISABLE_COPY(qVesselTouchHapticZoomWidget);
};

#endif
