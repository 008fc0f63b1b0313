#include "pqVesselTouchCenterlineWorkflow.h"
#include "ui_pqVesselTouchDockPanel.h"

#include "pqVesselTouchCenterlineExtraction.h"
#include "pqVesselTouchCenterlineOverlay.h"
#include "pqVesselTouchRegionPreview.h"
#include "pqVesselTouchRemoteUpdateEvents.h"
#include "pqVesselTouchSeedPicker.h"
#include "pqVesselTouchVolumeCheck.h"
#include "pqVesselTouchVolumeChooser.h"
#include "pqVesselTouchVoxelSample.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqServerManagerModel.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"

#include "vtkDataSetAttributes.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkPVXMLElement.h"
#include "vtkSMProperty.h"
#include "vtkSMProxyLocator.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMSourceProxy.h"

#include <QSignalBlocker>
#include <QTimer>

#include <algorithm>
#include <cmath>

using pqVesselTouchVoxelSample::neighbourhoodMedian;
using pqVesselTouchVoxelSample::sampleVoxels;
using pqVesselTouchVoxelSample::VoxelSample;
using pqVesselTouchVoxelSample::voxelValue;

namespace
{
/// A seed is on background unless its value stands this many noise sigmas above the background
/// level: Rose's criterion for a detectable object (the filter's estimator uses the same rule).
constexpr double kRoseContrastToNoise = 5.0;

pqRenderView* activeRenderView()
{
  return qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
}
} // namespace

pqVesselTouchCenterlineWorkflow::pqVesselTouchCenterlineWorkflow(Ui::pqVesselTouchDockPanel& ui,
  QObject* parentObject)
  : QObject(parentObject)
  , Ui(ui)
  , Volumes(new pqVesselTouchVolumeChooser(ui.volumeCombo, this))
  , Picker(new pqVesselTouchSeedPicker(this))
  , Extraction(new pqVesselTouchCenterlineExtraction(this))
  , Preview(new pqVesselTouchRegionPreview(this->Extraction->overlay(), this))
  , PreviewToolTip(ui.previewButton->toolTip())
  , ExtractToolTip(ui.extractButton->toolTip())
{
  QObject::connect(this->Volumes,
    &pqVesselTouchVolumeChooser::currentVolumeChanged,
    this,
    &pqVesselTouchCenterlineWorkflow::onVolumeChanged);
  QObject::connect(this->Volumes,
    &pqVesselTouchVolumeChooser::problemChanged,
    this,
    [this](const QString& problem) { showMessage(this->Ui.volumeMessage, problem, true); });
  QObject::connect(this->Ui.pickSeedButton,
    &QPushButton::toggled,
    this,
    &pqVesselTouchCenterlineWorkflow::onPickSeedToggled);
  QObject::connect(this->Picker,
    &pqVesselTouchSeedPicker::seedPicked,
    this,
    &pqVesselTouchCenterlineWorkflow::onSeedPicked);
  QObject::connect(this->Picker,
    &pqVesselTouchSeedPicker::pickFailed,
    this,
    [this](const QString& why)
    {
      const QSignalBlocker blocker(this->Ui.pickSeedButton);
      this->Ui.pickSeedButton->setChecked(false);
      this->setExtractMessage(why, true);
    });
  QObject::connect(
    this->Ui.extractButton, &QPushButton::clicked, this, &pqVesselTouchCenterlineWorkflow::extract);
  QObject::connect(this->Ui.clearSeedButton,
    &QToolButton::clicked,
    this,
    &pqVesselTouchCenterlineWorkflow::clearSeed);
  QObject::connect(this->Ui.automaticRange,
    &QCheckBox::toggled,
    this,
    &pqVesselTouchCenterlineWorkflow::onAutomaticToggled);
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::progress,
    this->Ui.extractProgress,
    &QProgressBar::setValue);
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::failed,
    this,
    [this](const QString& why)
    {
      this->Ui.extractProgress->setValue(0);
      this->setExtractMessage(why, true);
      this->updateRunState();
    });
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::finished,
    this,
    &pqVesselTouchCenterlineWorkflow::onExtracted);
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::cancelled,
    this,
    &pqVesselTouchCenterlineWorkflow::onRunCancelled);
  QObject::connect(this->Ui.cancelButton,
    &QPushButton::clicked,
    this,
    &pqVesselTouchCenterlineWorkflow::cancelRuns);
  // A remote run (a pvserver's ranks) keeps the client inside the update: at each progress report
  // the panel repaints and its Cancel takes clicks, nothing else (pqVesselTouchRemoteUpdateEvents).
  QWidget* runArea = this->Ui.cancelButton->parentWidget();
  while (runArea && runArea->parentWidget() &&
         !(runArea->isAncestorOf(this->Ui.extractMessage) &&
           runArea->isAncestorOf(this->Ui.extractProgress)))
  {
    runArea = runArea->parentWidget();
  }
  this->Extraction->setRemoteUpdateEvents(
    new pqVesselTouchRemoteUpdateEvents(runArea, this->Ui.cancelButton, this));
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::remoteRunStarted,
    this,
    [this]()
    {
      this->setExtractMessage(
        tr("Extracting on the server: the view waits for it; Cancel stops it."), false);
      this->updateRunState();
    });
  QObject::connect(this->Ui.previewButton,
    &QPushButton::toggled,
    this,
    &pqVesselTouchCenterlineWorkflow::onPreviewToggled);
  QObject::connect(this->Preview,
    &pqVesselTouchRegionPreview::progress,
    this->Ui.extractProgress,
    &QProgressBar::setValue);
  QObject::connect(this->Preview,
    &pqVesselTouchRegionPreview::shown,
    this,
    &pqVesselTouchCenterlineWorkflow::onPreviewShown);
  QObject::connect(this->Preview,
    &pqVesselTouchRegionPreview::failed,
    this,
    [this](const QString& why)
    {
      this->hidePreview();
      this->setExtractMessage(tr("Preview: %1").arg(why), true);
    });
  QObject::connect(this->Preview,
    &pqVesselTouchRegionPreview::cancelled,
    this,
    &pqVesselTouchCenterlineWorkflow::onRunCancelled);
  // A preview shows one seed and range: any change makes it stale.
  for (QDoubleSpinBox* field : { this->Ui.lowerThreshold, this->Ui.upperThreshold })
  {
    QObject::connect(field,
      QOverload<double>::of(&QDoubleSpinBox::valueChanged),
      this,
      &pqVesselTouchCenterlineWorkflow::hidePreview);
  }
  QObject::connect(pqApplicationCore::instance(),
    &pqApplicationCore::stateLoaded,
    this,
    [this]() { QTimer::singleShot(0, this, &pqVesselTouchCenterlineWorkflow::adoptFromState); });
  showMessage(this->Ui.volumeMessage, this->Volumes->problem(), true);
  showMessage(this->Ui.extractMessage, QString(), false);
  this->onAutomaticToggled(this->Ui.automaticRange->isChecked());
  this->onVolumeChanged(this->Volumes->currentVolume());
}

pqVesselTouchCenterlineWorkflow::~pqVesselTouchCenterlineWorkflow() = default;

pqPipelineSource* pqVesselTouchCenterlineWorkflow::currentVolume() const
{
  return this->Volumes->currentVolume();
}

bool pqVesselTouchCenterlineWorkflow::seed(double seed_mm[3]) const
{
  std::copy(this->Seed_mm, this->Seed_mm + 3, seed_mm);
  return this->HasSeed;
}

double pqVesselTouchCenterlineWorkflow::lowerThreshold() const
{
  return this->Ui.lowerThreshold->value();
}

double pqVesselTouchCenterlineWorkflow::upperThreshold() const
{
  return this->Ui.upperThreshold->value();
}

bool pqVesselTouchCenterlineWorkflow::automaticRange() const
{
  return this->Ui.automaticRange->isChecked();
}

pqPipelineSource* pqVesselTouchCenterlineWorkflow::centerline() const
{
  return this->Extraction->centerline();
}

QString pqVesselTouchCenterlineWorkflow::extractMessage() const
{
  return this->Ui.extractMessage->text();
}

bool pqVesselTouchCenterlineWorkflow::isRunning() const
{
  return this->Extraction->isRunning() || this->Preview->isRunning();
}

void pqVesselTouchCenterlineWorkflow::showMessage(QLabel* label, const QString& text, bool error)
{
  label->setText(text);
  label->setStyleSheet(error ? QStringLiteral("color: #c00000;") : QString());
  label->setVisible(!text.isEmpty());
}

void pqVesselTouchCenterlineWorkflow::setExtractMessage(const QString& text, bool error)
{
  showMessage(this->Ui.extractMessage, text, error);
}

void pqVesselTouchCenterlineWorkflow::onPickSeedToggled(bool armed)
{
  if (!armed)
  {
    this->Picker->disarm();
    return;
  }
  pqPipelineSource* volume = this->Volumes->currentVolume();
  if (!volume)
  {
    const QSignalBlocker blocker(this->Ui.pickSeedButton);
    this->Ui.pickSeedButton->setChecked(false);
    this->setExtractMessage(tr("Pick seed: %1").arg(this->Volumes->problem()), true);
    return;
  }
  this->setExtractMessage(tr("Click a vessel in the render view."), false);
  this->Picker->arm(activeRenderView(), volume);
}

bool pqVesselTouchCenterlineWorkflow::pickSeedAt(const QPoint& position)
{
  return this->Picker->pickAt(activeRenderView(), this->Volumes->currentVolume(), position);
}

void pqVesselTouchCenterlineWorkflow::onSeedPicked(double x_mm,
  double y_mm,
  double z_mm,
  double value)
{
  const double seed_mm[3] = { x_mm, y_mm, z_mm };
  this->acceptSeed(seed_mm, value);
}

void pqVesselTouchCenterlineWorkflow::acceptSeed(const double seed_mm[3], double value)
{
  const double x_mm = seed_mm[0];
  const double y_mm = seed_mm[1];
  const double z_mm = seed_mm[2];
  this->HasSeed = true;
  this->SeedVolume = this->Volumes->currentVolume();
  this->Seed_mm[0] = x_mm;
  this->Seed_mm[1] = y_mm;
  this->Seed_mm[2] = z_mm;
  this->SeedValue = value;
  this->Ui.seedLabel->setText(tr("(%1, %2, %3) mm, value %4")
                                .arg(x_mm, 0, 'f', 1)
                                .arg(y_mm, 0, 'f', 1)
                                .arg(z_mm, 0, 'f', 1)
                                .arg(value));
  const QSignalBlocker blocker(this->Ui.pickSeedButton);
  this->Ui.pickSeedButton->setChecked(false);
  this->Ui.clearSeedButton->setEnabled(true);
  this->hidePreview();
  // The marker: a sphere of 1 % of the volume's diagonal (visible, smaller than a vessel).
  double radius_mm = 1.0;
  if (vtkPVDataInformation* data =
        this->SeedVolume ? this->SeedVolume->getOutputPort(0)->getDataInformation() : nullptr)
  {
    const double* b = data->GetBounds();
    radius_mm =
      std::max(0.01 * std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
                                (b[5] - b[4]) * (b[5] - b[4])),
        1e-3);
  }
  this->Extraction->overlay()->showSeed(activeRenderView(), this->Seed_mm, radius_mm);
  // The seed is on background when the voxels around the brightest one under the click (a
  // lumen, or a noise spike) are not brighter than the background by Rose's criterion, or when
  // the ray crossed only the volume's minimum (a zero-filled background).
  double around = value;
  const bool aroundKnown = neighbourhoodMedian(this->SeedVolume, this->Seed_mm, around);
  if (value <= this->DataRange[0] ||
      (this->NoiseKnown && aroundKnown &&
        around < this->Background + kRoseContrastToNoise * this->Noise))
  {
    this->setExtractMessage(tr("The seed is on background (value %1, %2 around it; background "
                               "%3 ± %4): click on a bright vessel.")
                              .arg(value)
                              .arg(around)
                              .arg(this->Background)
                              .arg(this->Noise),
      true);
  }
  else if (!this->automaticRange() && value < this->Ui.lowerThreshold->value())
  {
    this->setExtractMessage(tr("The seed's value %1 is below the vessel range's lower bound %2: "
                               "lower it, or tick Automatic.")
                              .arg(value)
                              .arg(this->Ui.lowerThreshold->value()),
      true);
  }
  else
  {
    this->setExtractMessage(QString(), false);
  }
}

void pqVesselTouchCenterlineWorkflow::adoptFromState()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  // The loaded session's centerlines (a state loaded into a running ParaView leaves the old
  // pipeline beside the loaded one), else the newest extraction.
  pqPipelineSource* filter = nullptr;
  pqPipelineSource* sessionCenterlines = nullptr;
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    const QLatin1String xmlName(source->getProxy()->GetXMLName());
    if (xmlName == QLatin1String("VesselCenterline"))
    {
      filter = source; // the last one: the newest extraction
    }
    else if (xmlName == QLatin1String("VesselTouchHapticSession") &&
             source->getSMName() == QLatin1String("VesselTouchSession"))
    {
      vtkSMProxy* input = vtkSMPropertyHelper(source->getProxy(), "Input", true).GetAsProxy();
      pqPipelineSource* centerlines = input ? model->findItem<pqPipelineSource*>(input) : nullptr;
      if (centerlines && QLatin1String(input->GetXMLName()) == QLatin1String("VesselCenterline"))
      {
        sessionCenterlines = centerlines; // the newest session's
      }
    }
  }
  filter = sessionCenterlines ? sessionCenterlines : filter;
  vtkSMProxy* proxy = filter ? filter->getProxy() : nullptr;
  vtkSMProxy* input = proxy ? vtkSMPropertyHelper(proxy, "Input").GetAsProxy() : nullptr;
  pqPipelineSource* volume = input ? model->findItem<pqPipelineSource*>(input) : nullptr;
  if (!volume)
  {
    return;
  }
  this->Volumes->refresh();
  this->Volumes->setCurrentVolume(volume);
  this->Extraction->setCenterline(filter);
  if (vtkSMProperty* automatic = proxy->GetProperty("AutomaticIntensityRange"))
  {
    this->Ui.automaticRange->setChecked(vtkSMPropertyHelper(automatic).GetAsInt() != 0);
  }
  {
    const QSignalBlocker lowerBlocker(this->Ui.lowerThreshold);
    const QSignalBlocker upperBlocker(this->Ui.upperThreshold);
    this->Ui.lowerThreshold->setValue(vtkSMPropertyHelper(proxy, "LowerThreshold").GetAsDouble());
    this->Ui.upperThreshold->setValue(vtkSMPropertyHelper(proxy, "UpperThreshold").GetAsDouble());
  }
  if (vtkSMPropertyHelper(proxy, "UseSeedPoint").GetAsInt() != 0)
  {
    double seed_mm[3];
    vtkSMPropertyHelper(proxy, "SeedPoint").Get(seed_mm, 3);
    double value = 0.0;
    voxelValue(volume, seed_mm, value);
    this->acceptSeed(seed_mm, value);
  }
  // The state holds the filter's settings; the range an automatic run used is in its output.
  vtkSMSourceProxy::SafeDownCast(proxy)->UpdatePipeline();
  const pqVesselTouchExtractionResult& result = this->Extraction->readResult(filter);
  if (result.rangeKnown)
  {
    const QSignalBlocker lowerBlocker(this->Ui.lowerThreshold);
    const QSignalBlocker upperBlocker(this->Ui.upperThreshold);
    this->Ui.lowerThreshold->setValue(result.rangeUsed[0]);
    this->Ui.upperThreshold->setValue(result.rangeUsed[1]);
  }
  const int paths = result.paths;
  this->Extraction->showInView(filter, activeRenderView(), paths > 0);
  this->setExtractMessage(tr("From the state file: %n centerline path(s).", "", paths), false);
  if (paths > 0)
  {
    Q_EMIT this->centerlineReady(filter, paths);
  }
}

void pqVesselTouchCenterlineWorkflow::clearSeed()
{
  this->hidePreview();
  this->HasSeed = false;
  this->SeedVolume = nullptr;
  this->Ui.seedLabel->setText(tr("No seed"));
  this->Ui.clearSeedButton->setEnabled(false);
  this->Extraction->overlay()->showSeed(activeRenderView(), nullptr, 0.0);
}

void pqVesselTouchCenterlineWorkflow::setDataRange(pqPipelineSource* volume)
{
  vtkPVDataInformation* data = volume ? volume->getOutputPort(0)->getDataInformation() : nullptr;
  vtkPVArrayInformation* scalars =
    data ? data->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS)
         : nullptr;
  QDoubleSpinBox* fields[2] = { this->Ui.lowerThreshold, this->Ui.upperThreshold };
  double range[2] = { 0.0, 0.0 };
  if (scalars)
  {
    scalars->GetComponentRange(0, range);
  }
  const bool known = scalars && range[0] <= range[1];
  this->DataRange[0] = known ? range[0] : 0.0;
  this->DataRange[1] = known ? range[1] : 0.0;
  // Small ranges (a normalised volume) need decimals; intensities in the hundreds do not.
  const int decimals = known && range[1] - range[0] < 10.0 ? 3 : 1;
  const VoxelSample sample = known ? sampleVoxels(volume) : VoxelSample();
  this->NoiseKnown = sample.ok;
  this->Background = sample.background;
  this->Noise = sample.noise;
  // Remote data (no voxels to sample here): the middle of the range.
  const double lower = sample.ok ? sample.tail : 0.5 * (range[0] + range[1]);
  for (QDoubleSpinBox* field : fields)
  {
    const QSignalBlocker blocker(field);
    field->setDecimals(decimals);
    field->setRange(this->DataRange[0], this->DataRange[1]);
    // With no volume the fields show a dash, not a number that means nothing.
    field->setSpecialValueText(known ? QString() : QStringLiteral("–"));
  }
  if (known)
  {
    const QSignalBlocker lowerBlocker(this->Ui.lowerThreshold);
    const QSignalBlocker upperBlocker(this->Ui.upperThreshold);
    this->Ui.lowerThreshold->setValue(std::min(lower, range[1]));
    this->Ui.upperThreshold->setValue(range[1]);
  }
  this->onAutomaticToggled(this->automaticRange());
}

void pqVesselTouchCenterlineWorkflow::onAutomaticToggled(bool automatic)
{
  this->hidePreview();
  const bool hasVolume = this->DataRange[0] < this->DataRange[1];
  this->Ui.lowerThreshold->setEnabled(!automatic && hasVolume);
  this->Ui.upperThreshold->setEnabled(!automatic && hasVolume);
}

void pqVesselTouchCenterlineWorkflow::onVolumeChanged(pqPipelineSource* volume)
{
  // Runs belong to the volume they started on (a deleted volume takes its run with it).
  this->Extraction->cancel(volume ? tr("another volume was chosen.") : QString());
  this->hidePreview();
  // Preview reads the voxels in this process: not with the data on a remote server.
  const QString noPreview = pqVesselTouchRegionPreview::unavailableReason(volume);
  this->Ui.previewButton->setEnabled(!volume || noPreview.isEmpty());
  this->Ui.previewButton->setToolTip(
    volume && !noPreview.isEmpty() ? noPreview : this->PreviewToolTip);
  if (volume != this->SeedVolume || !volume)
  {
    this->clearSeed(); // a seed belongs to the volume it was picked in
  }
  vtkPVDataInformation* data = volume ? volume->getOutputPort(0)->getDataInformation() : nullptr;
  if (volume && (!data || data->GetNumberOfPoints() <= 0))
  {
    // No data yet (a source created a moment ago): try again when it has updated.
    QObject::connect(volume,
      QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated),
      this,
      &pqVesselTouchCenterlineWorkflow::onVolumeDataUpdated,
      Qt::UniqueConnection);
  }
  this->setDataRange(volume);
  this->Ui.extractProgress->setValue(0);
  this->setExtractMessage(this->ServerProblem, !this->ServerProblem.isEmpty());
}

void pqVesselTouchCenterlineWorkflow::onVolumeDataUpdated(pqPipelineSource* volume)
{
  QObject::disconnect(volume, nullptr, this, nullptr);
  if (volume == this->Volumes->currentVolume())
  {
    this->setDataRange(volume);
  }
}

void pqVesselTouchCenterlineWorkflow::setServerProblem(const QString& problem)
{
  const bool had = !this->ServerProblem.isEmpty();
  this->ServerProblem = problem;
  this->Ui.extractButton->setEnabled(problem.isEmpty());
  this->Ui.extractButton->setToolTip(problem.isEmpty() ? this->ExtractToolTip : problem);
  if (!problem.isEmpty())
  {
    this->setExtractMessage(problem, true);
  }
  else if (had)
  {
    this->setExtractMessage(QString(), false);
  }
}

void pqVesselTouchCenterlineWorkflow::extract()
{
  if (!this->ServerProblem.isEmpty())
  {
    this->setExtractMessage(this->ServerProblem, true); // Extract is disabled; a script may call
    return;
  }
  pqPipelineSource* volume = this->Volumes->currentVolume();
  if (!volume)
  {
    this->setExtractMessage(tr("Pick a volume first: %1").arg(this->Volumes->problem()), true);
    return;
  }
  if (!this->HasSeed)
  {
    this->setExtractMessage(
      tr("Pick a seed first: press Pick seed, then click a vessel in the view."), true);
    return;
  }
  this->hidePreview(); // the centerlines replace it
  this->setExtractMessage(tr("Extracting..."), false);
  // In the background when the data is here: the view, the panel and a running session go on
  // (on the previous centerline) until finished(), failed() or cancelled().
  this->Extraction->start(volume,
    this->Seed_mm,
    this->automaticRange(),
    this->Ui.lowerThreshold->value(),
    this->Ui.upperThreshold->value(),
    activeRenderView());
  if (this->Extraction->isRunning())
  {
    this->setExtractMessage(
      tr("Extracting in the background: the view and a running session go on; Cancel stops it."),
      false);
  }
  this->updateRunState();
}

void pqVesselTouchCenterlineWorkflow::onExtracted(pqPipelineSource* centerline, int paths)
{
  this->updateRunState();
  const pqVesselTouchExtractionResult& result = this->Extraction->result();
  QString text = tr("%n centerline path(s)", "", result.paths);
  text += tr(" in %1 s.").arg(result.seconds, 0, 'f', 1);
  if (result.rangeKnown)
  {
    this->showRangeUsed(result.rangeUsed);
    text += tr(" Vessel intensity %1 to %2 (%3).")
              .arg(result.rangeUsed[0])
              .arg(result.rangeUsed[1])
              .arg(result.rangeAutomatic ? tr("automatic") : tr("yours"));
  }
  if (!result.shading.isEmpty())
  {
    text += QLatin1Char(' ') + result.shading;
  }
  if (!result.message.isEmpty())
  {
    text += QLatin1Char(' ') + result.message;
  }
  this->setExtractMessage(text, false);
  Q_EMIT this->centerlineReady(centerline, paths);
}

void pqVesselTouchCenterlineWorkflow::showRangeUsed(const double range[2])
{
  const QSignalBlocker lowerBlocker(this->Ui.lowerThreshold);
  const QSignalBlocker upperBlocker(this->Ui.upperThreshold);
  this->Ui.lowerThreshold->setValue(range[0]);
  this->Ui.upperThreshold->setValue(range[1]);
}

void pqVesselTouchCenterlineWorkflow::cancelRuns()
{
  this->Extraction->cancel(); // cancelled() follows when its thread has stopped
  if (this->Preview->isRunning())
  {
    this->hidePreview(); // stopped for the panel at once
    this->onRunCancelled(QString());
  }
}

void pqVesselTouchCenterlineWorkflow::onRunCancelled(const QString& reason)
{
  this->updateRunState();
  this->Ui.extractProgress->setValue(0);
  this->setExtractMessage(
    reason.isEmpty() ? tr("Cancelled.") : tr("Cancelled: %1").arg(reason), !reason.isEmpty());
}

void pqVesselTouchCenterlineWorkflow::onPreviewToggled(bool on)
{
  if (!on)
  {
    this->hidePreview();
    return;
  }
  pqPipelineSource* volume = this->Volumes->currentVolume();
  QString problem = !volume ? tr("Pick a volume first: %1").arg(this->Volumes->problem())
                    : !this->HasSeed
                      ? tr("Pick a seed first: press Pick seed, then click a vessel in the view.")
                      : pqVesselTouchRegionPreview::unavailableReason(volume);
  if (problem.isEmpty() && !this->Preview->show(volume,
                             this->Seed_mm,
                             this->automaticRange(),
                             this->Ui.lowerThreshold->value(),
                             this->Ui.upperThreshold->value(),
                             activeRenderView()))
  {
    problem = tr("The preview could not start.");
  }
  if (!problem.isEmpty())
  {
    const QSignalBlocker blocker(this->Ui.previewButton);
    this->Ui.previewButton->setChecked(false);
    this->setExtractMessage(problem, true);
    return;
  }
  this->setExtractMessage(tr("Preview: finding the candidate vessel region..."), false);
  this->updateRunState();
}

void pqVesselTouchCenterlineWorkflow::onPreviewShown()
{
  this->updateRunState();
  this->Ui.extractProgress->setValue(100);
  const pqVesselTouchPreviewResult& result = this->Preview->result();
  if (result.rangeAutomatic)
  {
    this->showRangeUsed(result.rangeUsed); // the estimate, before any extraction
  }
  QString text = tr("Preview (magenta): the region Extract would code, %1 voxels; "
                    "vessel intensity %2 to %3 (%4).")
                   .arg(result.voxels)
                   .arg(result.rangeUsed[0])
                   .arg(result.rangeUsed[1])
                   .arg(result.rangeAutomatic ? tr("automatic") : tr("yours"));
  if (!result.shading.isEmpty())
  {
    text += QLatin1Char(' ') + result.shading;
  }
  this->setExtractMessage(text, false);
}

void pqVesselTouchCenterlineWorkflow::hidePreview()
{
  if (this->Preview->isRunning() || this->Preview->isShown())
  {
    this->Preview->hide();
  }
  const QSignalBlocker blocker(this->Ui.previewButton);
  this->Ui.previewButton->setChecked(false);
  this->updateRunState();
}

void pqVesselTouchCenterlineWorkflow::updateRunState()
{
  this->Ui.cancelButton->setEnabled(this->isRunning());
}
