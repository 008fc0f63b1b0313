// Yi & Hayward's force zones k(P): a plot of the gain versus the pressure/z input with draggable
// thresholds, spin boxes for the thresholds and the gain, and the live (P, k(P)) as a moving dot.
// Pure Qt: the module glue forwards thresholdsChanged()/gainChanged() to the haptic session and
// feeds setLivePressure() from the agent state at the GUI rate.
#ifndef qVesselTouchForceZonesWidget_h
#define qVesselTouchForceZonesWidget_h

#include "vtouchHapticParameterTable.h"

#include <QScopedPointer>
#include <QWidget>

class qVesselTouchForceZonesPlot;
class qVesselTouchForceZonesWidgetPrivate;

/// k(P) = 0                                              for P <  zeroBelow     (zero-force zone)
///      = gain * (P - zeroBelow) / (saturateAbove - zeroBelow)   in between     (proportional zone)
///      = gain                                           for P >= saturateAbove (saturation zone)
/// P is the device's normalized pressure (or z) in [0, 1].
class qVesselTouchForceZonesWidget : public QWidget
{
  Q_OBJECT
  Q_PROPERTY(double zeroBelow READ zeroBelow WRITE setZeroBelow NOTIFY thresholdsChanged)
  Q_PROPERTY(
    double saturateAbove READ saturateAbove WRITE setSaturateAbove NOTIFY thresholdsChanged)
  Q_PROPERTY(double gain_N READ gain_N WRITE setGain_N NOTIFY gainChanged)
  Q_PROPERTY(double livePressure READ livePressure WRITE setLivePressure)
public:
  explicit qVesselTouchForceZonesWidget(QWidget* parent = nullptr);
  ~qVesselTouchForceZonesWidget() override;

  /// k(P) in newtons for the zones above. Pure function, never throws: a non-finite P gives 0,
  /// P is clamped to [0, 1], and saturateAbove <= zeroBelow degenerates to a step at zeroBelow.
  static double zoneGain(double pressure, double zeroBelow, double saturateAbove, double gain_N);

  /// Upper end of the zero-force zone (device unattended), normalized pressure in [0, 1 - gap].
  /// Default: ZoneZeroBelow's (vtouchHapticParameters.def). Values are rounded to 0.001 and kept at
  /// least kMinimumGap below saturateAbove.
  double zeroBelow() const;
  /// Start of the saturation zone, normalized pressure in [gap, 1]. Default: ZoneSaturateAbove's.
  double saturateAbove() const;
  /// Sets both thresholds at once (ordered, clamped, rounded to 0.001); emits once if changed.
  void setThresholds(double zeroBelow, double saturateAbove);

  /// Gain k reached in the saturation zone, newtons per unit slope. Default and range: ZoneGain's.
  double gain_N() const;

  /// The live pressure last given to setLivePressure(), or -1 when none is shown.
  double livePressure() const;
  /// k(livePressure) in newtons, 0 when no live pressure is shown.
  double liveGain_N() const;
  /// Shows (default) or hides the gain's spin box: a host that edits k elsewhere (the force law's
  /// gain) hides it, so one value has one field; the plot still shows k.
  void setGainEditable(bool editable);

  /// Smallest distance kept between the two thresholds, normalized pressure. 0.01.
  static constexpr double kMinimumGap = 0.01;
  /// Largest gain the spin box accepts, newtons: ZoneGain's maximum (vtouchHapticParameters.def).
  static constexpr double kMaximumGain_N =
    vtouch::hapticParameter(vtouch::HapticParameterId::ZoneGain).maximum;

  /// The plot, for hosts that want to resize it and for tests that drag its handles.
  qVesselTouchForceZonesPlot* plot() const;

public slots:
  void setZeroBelow(double zeroBelow);
  void setSaturateAbove(double saturateAbove);
  void setGain_N(double gain_N);
  /// Moves the live dot to (P, k(P)); a negative or non-finite P hides it. Cheap: call at GUI rate.
  void setLivePressure(double pressure);
  /// Hides the live dot (no device, or a device without pressure input).
  void clearLivePressure();

signals:
  /// A threshold changed, from a drag, a spin box or a setter.
  void thresholdsChanged(double zeroBelow, double saturateAbove);
  /// The gain changed, newtons.
  void gainChanged(double gain_N);
  /// Any of the three parameters changed (after thresholdsChanged or gainChanged).
  void parametersChanged();

private:
  QScopedPointer<qVesselTouchForceZonesWidgetPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchForceZonesWidget);
  Q_DISABLE_COPY(qVesselTouchForceZonesWidget);
};

#endif
