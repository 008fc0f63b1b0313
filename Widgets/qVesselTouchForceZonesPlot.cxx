#include "qVesselTouchForceZonesPlot.h"

#include "qVesselTouchForceZonesWidget.h"

#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QtGlobal>

#include <algorithm>
#include <cmath>

namespace
{
// Room for the axis labels around the curve, pixels.
constexpr int kLeftMargin = 34;
constexpr int kRightMargin = 8;
constexpr int kTopMargin = 8;
constexpr int kBottomMargin = 20;
} // namespace

class qVesselTouchForceZonesPlotPrivate
{
public:
  // The force zones' defaults: the table's (vtouchHapticParameters.def).
  double ZeroBelow = vtouch::hapticParameter(vtouch::HapticParameterId::ZoneZeroBelow).defaultValue;
  double SaturateAbove =
    vtouch::hapticParameter(vtouch::HapticParameterId::ZoneSaturateAbove).defaultValue;
  double Gain_N = vtouch::hapticParameter(vtouch::HapticParameterId::ZoneGain).defaultValue;
  double LivePressure = -1.0; // < 0: no dot
  qVesselTouchForceZonesPlot::Handle Dragged = qVesselTouchForceZonesPlot::NoHandle;
};

qVesselTouchForceZonesPlot::qVesselTouchForceZonesPlot(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchForceZonesPlotPrivate)
{
  this->setMouseTracking(true); // the cursor changes shape over a handle
  this->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

qVesselTouchForceZonesPlot::~qVesselTouchForceZonesPlot() = default;

void qVesselTouchForceZonesPlot::setZones(double zeroBelow, double saturateAbove, double gain_N)
{
  Q_D(qVesselTouchForceZonesPlot);
  d->ZeroBelow = zeroBelow;
  d->SaturateAbove = saturateAbove;
  d->Gain_N = gain_N;
  this->update();
}

double qVesselTouchForceZonesPlot::zeroBelow() const
{
  Q_D(const qVesselTouchForceZonesPlot);
  return d->ZeroBelow;
}

double qVesselTouchForceZonesPlot::saturateAbove() const
{
  Q_D(const qVesselTouchForceZonesPlot);
  return d->SaturateAbove;
}

double qVesselTouchForceZonesPlot::gain_N() const
{
  Q_D(const qVesselTouchForceZonesPlot);
  return d->Gain_N;
}

void qVesselTouchForceZonesPlot::setLivePressure(double pressure)
{
  Q_D(qVesselTouchForceZonesPlot);
  d->LivePressure = std::isfinite(pressure) && pressure >= 0.0 ? std::min(pressure, 1.0) : -1.0;
  this->update();
}

double qVesselTouchForceZonesPlot::livePressure() const
{
  Q_D(const qVesselTouchForceZonesPlot);
  return d->LivePressure;
}

bool qVesselTouchForceZonesPlot::hasLivePressure() const
{
  Q_D(const qVesselTouchForceZonesPlot);
  return d->LivePressure >= 0.0;
}

QRect qVesselTouchForceZonesPlot::plotRect() const
{
  return this->rect().adjusted(kLeftMargin, kTopMargin, -kRightMargin, -kBottomMargin);
}

double qVesselTouchForceZonesPlot::axisMaximum_N() const
{
  Q_D(const qVesselTouchForceZonesPlot);
  // Headroom above the saturation level so the flat top is visible; never a zero-height axis.
  return d->Gain_N > 0.0 ? 1.15 * d->Gain_N : 1.0;
}

int qVesselTouchForceZonesPlot::pixelForPressure(double pressure) const
{
  const QRect r = this->plotRect();
  return r.left() + qRound(std::clamp(pressure, 0.0, 1.0) * (r.width() - 1));
}

double qVesselTouchForceZonesPlot::pressureForPixel(int x) const
{
  const QRect r = this->plotRect();
  if (r.width() <= 1)
  {
    return 0.0;
  }
  return std::clamp(double(x - r.left()) / double(r.width() - 1), 0.0, 1.0);
}

int qVesselTouchForceZonesPlot::pixelForGain(double gain_N) const
{
  const QRect r = this->plotRect();
  const double fraction = std::clamp(gain_N / this->axisMaximum_N(), 0.0, 1.0);
  return r.bottom() - qRound(fraction * (r.height() - 1));
}

qVesselTouchForceZonesPlot::Handle qVesselTouchForceZonesPlot::handleAt(int x) const
{
  Q_D(const qVesselTouchForceZonesPlot);
  const int dZero = std::abs(x - this->pixelForPressure(d->ZeroBelow));
  const int dSaturate = std::abs(x - this->pixelForPressure(d->SaturateAbove));
  if (std::min(dZero, dSaturate) > kGrabDistance_px)
  {
    return NoHandle;
  }
  // On a tie (handles drawn on top of each other) prefer the one that can still move toward x.
  if (dZero == dSaturate)
  {
    return x < this->pixelForPressure(d->ZeroBelow) ? ZeroBelowHandle : SaturateAboveHandle;
  }
  return dZero < dSaturate ? ZeroBelowHandle : SaturateAboveHandle;
}

qVesselTouchForceZonesPlot::Handle qVesselTouchForceZonesPlot::draggedHandle() const
{
  Q_D(const qVesselTouchForceZonesPlot);
  return d->Dragged;
}

QSize qVesselTouchForceZonesPlot::sizeHint() const
{
  return QSize(260, 140);
}

QSize qVesselTouchForceZonesPlot::minimumSizeHint() const
{
  return QSize(160, 90);
}

void qVesselTouchForceZonesPlot::paintEvent(QPaintEvent*)
{
  Q_D(qVesselTouchForceZonesPlot);
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  const QRect r = this->plotRect();
  const int x0 = this->pixelForPressure(d->ZeroBelow);
  const int x1 = this->pixelForPressure(d->SaturateAbove);

  // Zone backgrounds: zero (grey), proportional (blue), saturation (orange).
  painter.fillRect(QRect(QPoint(r.left(), r.top()), QPoint(x0, r.bottom())), QColor(225, 225, 225));
  painter.fillRect(QRect(QPoint(x0, r.top()), QPoint(x1, r.bottom())), QColor(214, 230, 250));
  painter.fillRect(
    QRect(QPoint(x1, r.top()), QPoint(r.right(), r.bottom())), QColor(252, 228, 200));
  painter.setPen(this->palette().color(QPalette::WindowText));
  painter.drawRect(r.adjusted(0, 0, -1, -1));

  // The curve itself, one segment per zone.
  QPainterPath curve;
  curve.moveTo(r.left(), this->pixelForGain(0.0));
  curve.lineTo(x0, this->pixelForGain(0.0));
  curve.lineTo(x1, this->pixelForGain(d->Gain_N));
  curve.lineTo(r.right(), this->pixelForGain(d->Gain_N));
  painter.setPen(QPen(QColor(20, 60, 160), 2));
  painter.drawPath(curve);

  // Threshold handles: dashed lines with a grip at the top.
  for (const Handle handle : { ZeroBelowHandle, SaturateAboveHandle })
  {
    const int x = handle == ZeroBelowHandle ? x0 : x1;
    const bool active = handle == d->Dragged;
    painter.setPen(
      QPen(active ? QColor(200, 0, 0) : QColor(60, 60, 60), active ? 2 : 1, Qt::DashLine));
    painter.drawLine(x, r.top(), x, r.bottom());
    painter.setPen(Qt::NoPen);
    painter.setBrush(active ? QColor(200, 0, 0) : QColor(60, 60, 60));
    painter.drawRect(x - 3, r.top(), 7, 7);
  }

  // Axis labels: P on x, k(P) in newtons on y.
  painter.setPen(this->palette().color(QPalette::WindowText));
  const QFontMetrics metrics(painter.font());
  painter.drawText(QRect(r.left(), r.bottom() + 2, r.width(), kBottomMargin - 2),
    Qt::AlignLeft | Qt::AlignTop,
    QStringLiteral("0"));
  painter.drawText(QRect(r.left(), r.bottom() + 2, r.width(), kBottomMargin - 2),
    Qt::AlignHCenter | Qt::AlignTop,
    tr("pressure P"));
  painter.drawText(QRect(r.left(), r.bottom() + 2, r.width(), kBottomMargin - 2),
    Qt::AlignRight | Qt::AlignTop,
    QStringLiteral("1"));
  const int yGain = this->pixelForGain(d->Gain_N);
  painter.drawText(QRect(0, yGain - metrics.height() / 2, kLeftMargin - 3, metrics.height()),
    Qt::AlignRight | Qt::AlignVCenter,
    QString::number(d->Gain_N, 'g', 3));
  painter.drawText(QRect(0, r.bottom() - metrics.height(), kLeftMargin - 3, metrics.height()),
    Qt::AlignRight | Qt::AlignBottom,
    tr("0 N"));

  // The live (P, k(P)) dot.
  if (this->hasLivePressure())
  {
    const double k = qVesselTouchForceZonesWidget::zoneGain(
      d->LivePressure, d->ZeroBelow, d->SaturateAbove, d->Gain_N);
    painter.setPen(QPen(Qt::white, 1.5));
    painter.setBrush(QColor(220, 0, 0));
    painter.drawEllipse(
      QPoint(this->pixelForPressure(d->LivePressure), this->pixelForGain(k)), 5, 5);
  }
}

void qVesselTouchForceZonesPlot::mousePressEvent(QMouseEvent* event)
{
  Q_D(qVesselTouchForceZonesPlot);
  if (event->button() != Qt::LeftButton)
  {
    QWidget::mousePressEvent(event);
    return;
  }
  d->Dragged = this->handleAt(event->pos().x());
  if (d->Dragged != NoHandle)
  {
    event->accept();
    this->update();
  }
}

void qVesselTouchForceZonesPlot::mouseMoveEvent(QMouseEvent* event)
{
  Q_D(qVesselTouchForceZonesPlot);
  if (d->Dragged == NoHandle)
  {
    this->setCursor(
      this->handleAt(event->pos().x()) == NoHandle ? Qt::ArrowCursor : Qt::SizeHorCursor);
    return;
  }
  const double p = this->pressureForPixel(event->pos().x());
  double zeroBelow = d->ZeroBelow;
  double saturateAbove = d->SaturateAbove;
  if (d->Dragged == ZeroBelowHandle)
  {
    zeroBelow = std::clamp(p, 0.0, std::max(0.0, saturateAbove - kMinimumGap));
  }
  else
  {
    saturateAbove = std::clamp(p, std::min(1.0, zeroBelow + kMinimumGap), 1.0);
  }
  event->accept();
  if (zeroBelow != d->ZeroBelow || saturateAbove != d->SaturateAbove)
  {
    emit this->thresholdsEdited(zeroBelow, saturateAbove);
  }
}

void qVesselTouchForceZonesPlot::mouseReleaseEvent(QMouseEvent* event)
{
  Q_D(qVesselTouchForceZonesPlot);
  if (d->Dragged != NoHandle && event->button() == Qt::LeftButton)
  {
    d->Dragged = NoHandle;
    this->update();
    event->accept();
    return;
  }
  QWidget::mouseReleaseEvent(event);
}
