// The haptic tick's options of issue 17 for the panel's Advanced section: the tracing rule and its
// movement threshold, the junction re-decision, contact dwell and approach, the slope force
// budget, Fig. 5's per-axis smoothing, change of height's z_max in resolution counts, the
// constraint proxy's snap-drag / unilateral rules, threshold from the data, friction, tick marks
// and field force, and the idle gate. Pure Qt: the names and defaults follow Logic/Haptics
// (vtouch::HapticParameters, Docs/HAPTICS.md) so the module glue copies fields one to one.
#ifndef qVesselTouchTickOptionsWidget_h
#define qVesselTouchTickOptionsWidget_h

#include <QScopedPointer>
#include <QWidget>

/// Every option the widget edits, with Logic's defaults.
struct qVesselTouchTickOptions
{
  int tracerRule = 0;                       ///< 0 offset (default), 1 movement (3.2.1)
  double tracerMovementThreshold_px = 0.01; ///< movement rule threshold, px
  double tracerJunctionWindow_px = 24.0;    ///< junction re-decision window, px (0 off)
  double tracerJunctionMargin_px = 1.0;     ///< junction re-decision margin, px
  double contactDwell_s = 0.05;             ///< contact dwell, s (0 at once)
  bool contactApproachAtStart = true;       ///< contact waits for an approach after Start
  double slopeForceBudget = 0.9;            ///< lambda sized to this fraction of F_max (0 off)
  bool forceInterpolationPerAxis = false;   ///< Fig. 5 as printed instead of the Euclidean bound
  double cohZMaxPerResolution = 2.0;        ///< change of height z_max, resolution counts
  bool proxyTangentSnap = false;            ///< Ikits eq. 11 snap-drag steps
  bool proxyNormalUnilateral = false;       ///< Ikits eq. 10 unilateral normal
  bool proxyThresholdFromData = false;      ///< Ikits eq. 16
  double proxyFriction = 0.0;               ///< mu in the constraint subspace
  double proxyTickSpacing_mm = 0.0;         ///< tick marks every ... mm (0 none)
  double proxyTickForce_N = 0.3;            ///< tick marks' peak force, N
  bool proxyTickAtBifurcations = false;     ///< a tick mark where a branch joins
  bool proxyFieldForce = false;             ///< the depth slope added to the coupler
  double idleRadius_mm = 1.0;               ///< idle gate radius, mm
  double idleDwell_s = 1.5;                 ///< idle gate dwell, s (0 never)
  double idleRamp_s = 0.05;                 ///< idle gate fade, s

  bool operator==(const qVesselTouchTickOptions& other) const;
  bool operator!=(const qVesselTouchTickOptions& other) const { return !(*this == other); }
};

class qVesselTouchTickOptionsWidgetPrivate;

class qVesselTouchTickOptionsWidget : public QWidget
{
  Q_OBJECT
public:
  explicit qVesselTouchTickOptionsWidget(QWidget* parent = nullptr);
  ~qVesselTouchTickOptionsWidget() override;

  /// The options as shown (clamped to each control's range and rounded to its decimals).
  qVesselTouchTickOptions options() const;

public slots:
  /// Shows `options` (clamped and rounded); emits optionsChanged() only when they change.
  void setOptions(const qVesselTouchTickOptions& options);

signals:
  /// An option changed, from a control or setOptions().
  void optionsChanged();

private:
  QScopedPointer<qVesselTouchTickOptionsWidgetPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchTickOptionsWidget);
  Q_DISABLE_COPY(qVesselTouchTickOptionsWidget);
};

#endif
