#include "qVesselTouchInfoWidget.h"

#include "ui_qVesselTouchInfoWidget.h"

#include <QFormLayout>
#include <QLabel>
#include <QMap>

class qVesselTouchInfoWidgetPrivate
{
public:
  Ui::qVesselTouchInfoWidget Ui;
  QMap<QString, QLabel*> VersionLabels;
  QStringList Order;
};

qVesselTouchInfoWidget::qVesselTouchInfoWidget(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchInfoWidgetPrivate)
{
  Q_D(qVesselTouchInfoWidget);
  d->Ui.setupUi(this);
  this->setVersion("Qt", QString::fromLatin1(qVersion()));
}

qVesselTouchInfoWidget::~qVesselTouchInfoWidget() = default;

void qVesselTouchInfoWidget::setDatasetName(const QString& name)
{
  Q_D(qVesselTouchInfoWidget);
  d->Ui.datasetNameValue->setText(name.isEmpty() ? tr("(none)") : name);
}

QString qVesselTouchInfoWidget::datasetName() const
{
  Q_D(const qVesselTouchInfoWidget);
  const QString text = d->Ui.datasetNameValue->text();
  return text == tr("(none)") ? QString() : text;
}

void qVesselTouchInfoWidget::setDatasetSummary(const QString& summary)
{
  Q_D(qVesselTouchInfoWidget);
  d->Ui.datasetSummaryValue->setText(summary.isEmpty() ? QStringLiteral("-") : summary);
}

QString qVesselTouchInfoWidget::datasetSummary() const
{
  Q_D(const qVesselTouchInfoWidget);
  return d->Ui.datasetSummaryValue->text();
}

void qVesselTouchInfoWidget::setVersion(const QString& component, const QString& version)
{
  Q_D(qVesselTouchInfoWidget);
  QLabel* label = d->VersionLabels.value(component, nullptr);
  if (!label)
  {
    label = new QLabel(this);
    label->setObjectName(QStringLiteral("version_") + component);
    label->setTextInteractionFlags(Qt::TextSelectableByMouse);
    d->Ui.versionLayout->addRow(component + QStringLiteral(":"), label);
    d->VersionLabels.insert(component, label);
    d->Order.append(component);
  }
  label->setText(version);
}

QString qVesselTouchInfoWidget::version(const QString& component) const
{
  Q_D(const qVesselTouchInfoWidget);
  const QLabel* label = d->VersionLabels.value(component, nullptr);
  return label ? label->text() : QString();
}

QStringList qVesselTouchInfoWidget::versionComponents() const
{
  Q_D(const qVesselTouchInfoWidget);
  return d->Order;
}
