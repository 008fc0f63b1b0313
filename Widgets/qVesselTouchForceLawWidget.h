// Chooses the force law (LDGF, change of height, lateral surface gradient, constraint proxy) and
// edits its parameters on one stacked page per law, with per-law presets and device limits on the
// virtual coupler. Pure Qt: the module glue forwards forceLawChanged()/parametersChanged() to the
// haptic session and calls setDeviceLimits() from the chosen device's capabilities.
#ifndef qVesselTouchForceLawWidget_h
#define qVesselTouchForceLawWidget_h

#include "qVesselTouchForceLawParameters.h"

#include <QScopedPointer>
#include <QStringList>
#include <QWidget>

class qVesselTouchForceLawWidgetPrivate;

class qVesselTouchForceLawWidget : public QWidget
{
  Q_OBJECT
  Q_PROPERTY(ForceLaw forceLaw READ forceLaw WRITE setForceLaw NOTIFY forceLawChanged)
  Q_PROPERTY(QString presetName READ presetName)
public:
  /// The laws; values equal vtouch::ForceLawId so the glue can cast one to the other.
  enum ForceLaw
  {
    Ldgf = 0,            ///< Yi & Hayward lateral depth gradient force (default)
    ChangeOfHeight = 1,  ///< Hayward & Yi change of height with the robust mu
    LateralGradient = 2, ///< classic lateral surface gradient baseline
    ConstraintProxy = 3, ///< Ikits et al. proxy with a virtual coupler
  };
  Q_ENUM(ForceLaw)
  static constexpr int kForceLawCount = 4;

  explicit qVesselTouchForceLawWidget(QWidget* parent = nullptr);
  ~qVesselTouchForceLawWidget() override;

  /// The chosen law. Default Ldgf.
  ForceLaw forceLaw() const;

  /// All parameters (every law's, not only the shown one), after the device limits.
  qVesselTouchForceLawParameters parameters() const;
  /// Sets all parameters (clamped to their ranges and the device limits); emits
  /// parametersChanged() once if anything changed.
  void setParameters(const qVesselTouchForceLawParameters& parameters);

  /// Bounds the coupler of the constraint proxy: k_c <= maxStiffness_N_per_m (N/m) and
  /// b_c <= maxDamping_N_s_per_m (N·s/m). A value <= 0 or non-finite removes that bound. Current
  /// values above a bound are lowered to it (parametersChanged() is emitted). Default: no bounds.
  void setDeviceLimits(double maxStiffness_N_per_m, double maxDamping_N_s_per_m);
  /// The bounds in force, 0 when unbounded.
  double maxStiffness_N_per_m() const;
  double maxDamping_N_s_per_m() const;

  /// Preset names, the same for every law, gentlest first: "Gentle", "Default", "Firm".
  static QStringList presetNames();
  /// Writes preset `name` of `law` into that law's fields of `parameters` (other laws' fields are
  /// left alone). False, and nothing written, for an unknown name.
  static bool presetParameters(ForceLaw law,
    const QString& name,
    qVesselTouchForceLawParameters& parameters);
  /// The preset of the current law the current parameters match, or "Custom".
  QString presetName() const;
  /// Human-readable name of a law, as the combo shows it.
  static QString forceLawLabel(ForceLaw law);

public slots:
  /// Shows `law`'s page; emits forceLawChanged() when it changes.
  void setForceLaw(ForceLaw law);
  /// Same, from an integer (vtouch::ForceLawId value); out-of-range values are ignored.
  void setForceLaw(int law);
  /// Applies preset `name` to the current law. False for an unknown name.
  bool applyPreset(const QString& name);

signals:
  /// The law changed; the argument is a ForceLaw value.
  void forceLawChanged(int law);
  /// Any parameter changed (from the user, a preset, setParameters() or the device limits).
  void parametersChanged();

private:
  QScopedPointer<qVesselTouchForceLawWidgetPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchForceLawWidget);
  Q_DISABLE_COPY(qVesselTouchForceLawWidget);
};

#endif
