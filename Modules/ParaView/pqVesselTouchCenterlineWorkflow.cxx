#include "pqVesselTouchCenterlineWorkflow.h"
#include "ui_pqVesselTouchDockPanel.h"

#include "pqVesselTouchCenterlineExtraction.h"
#include "pqVesselTouchCenterlineOverlay.h"
#include "pqVesselTouchSeedPicker.h"
#include "pqVesselTouchVolumeCheck.h"
#include "pqVesselTouchVolumeChooser.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqServerManagerModel.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkPointData.h"
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
#include <vector>

namespace
{
/// The manual range's starting lower bound: the intensity above which this fraction of the voxels
/// lie (the histogram's upper tail). Vessels fill a few percent of an angiogram's field of view;
/// the automatic estimate (the filter's, from the seed's neighbourhood) replaces it after Extract.
constexpr double kVesselTailFraction = 0.03;
/// Voxels sampled for the percentiles (evenly strided).
constexpr vtkIdType kTailSamples = 1 << 18;
/// A seed is on background unless its value stands this many noise sigmas above the background
/// level: Rose's criterion for a detectable object (the filter's estimator uses the same rule).
constexpr double kRoseContrastToNoise = 5.0;

pqRenderView* activeRenderView()
{
  return qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
}

/// Order statistics of an evenly strided sample of the volume's voxels: the upper tail's start
/// and the background (the median: vessels fill far less than half an angiogram) with its noise
/// (P50 - P15.87, one Gaussian sigma from the lower half, which the vessels do not reach).
struct VoxelSample
{
  bool ok = false;
  double tail = 0.0;
  double background = 0.0;
  double noise = 0.0;
};

/// The volume's voxels in this process (builtin session), null otherwise.
vtkImageData* clientImage(pqPipelineSource* volume)
{
  auto* proxy = volume ? vtkSMSourceProxy::SafeDownCast(volume->getProxy()) : nullptr;
  auto* algorithm = proxy ? vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject()) : nullptr;
  return algorithm ? vtkImageData::SafeDownCast(algorithm->GetOutputDataObject(0)) : nullptr;
}

/// Median of the 3x3x3 voxels around the world point `point_mm` (the seed): a vessel's lumen
/// around its brightest voxel, or background around a noise spike. False outside the volume.
bool neighbourhoodMedian(pqPipelineSource* volume, const double point_mm[3], double& median)
{
  vtkImageData* image = clientImage(volume);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars)
  {
    return false;
  }
  int centre[3];
  double pcoords[3];
  if (!image->ComputeStructuredCoordinates(point_mm, centre, pcoords))
  {
    return false;
  }
  const int* extent = image->GetExtent();
  std::vector<double> values;
  for (int k = -1; k <= 1; ++k)
  {
    for (int j = -1; j <= 1; ++j)
    {
      for (int i = -1; i <= 1; ++i)
      {
        int ijk[3] = {
          centre[0] + i + extent[0], centre[1] + j + extent[2], centre[2] + k + extent[4]
        };
        if (ijk[0] <= extent[1] && ijk[1] <= extent[3] && ijk[2] <= extent[5] &&
            ijk[0] >= extent[0] && ijk[1] >= extent[2] && ijk[2] >= extent[4])
        {
          values.push_back(scalars->GetComponent(image->ComputePointId(ijk), 0));
        }
      }
    }
  }
  if (values.empty())
  {
    return false;
  }
  std::nth_element(
    values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  median = values[values.size() / 2];
  return true;
}

/// The voxel value nearest the world point `point_mm`; false outside the volume.
bool voxelValue(pqPipelineSource* volume, const double point_mm[3], double& value)
{
  vtkImageData* image = clientImage(volume);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  const vtkIdType id = scalars ? image->FindPoint(point_mm[0], point_mm[1], point_mm[2]) : -1;
  if (id < 0)
  {
    return false;
  }
  value = scalars->GetComponent(id, 0);
  return true;
}

VoxelSample sampleVoxels(pqPipelineSource* volume)
{
  VoxelSample result;
  vtkImageData* image = clientImage(volume);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  const vtkIdType count = scalars ? scalars->GetNumberOfTuples() : 0;
  if (count <= 0)
  {
    return result;
  }
  const vtkIdType stride = std::max<vtkIdType>(1, count / kTailSamples);
  std::vector<double> samples;
  samples.reserve(static_cast<size_t>(count / stride + 1));
  for (vtkIdType i = 0; i < count; i += stride)
  {
    samples.push_back(scalars->GetComponent(i, 0));
  }
  const auto at = [&samples](double quantile)
  {
    const auto rank =
      static_cast<std::ptrdiff_t>(quantile * static_cast<double>(samples.size() - 1));
    std::nth_element(samples.begin(), samples.begin() + rank, samples.end());
    return samples[static_cast<size_t>(rank)];
  };
  result.tail = at(1.0 - kVesselTailFraction);
  result.background = at(0.5);
  result.noise = result.background - at(0.1587);
  result.ok = true;
  return result;
}
} // namespace

pqVesselTouchCenterlineWorkflow::pqVesselTouchCenterlineWorkflow(Ui::pqVesselTouchDockPanel& ui,
  QObject* parentObject)
  : QObject(parentObject)
  , Ui(ui)
  , Volumes(new pqVesselTouchVolumeChooser(ui.volumeCombo, this))
  , Picker(new pqVesselTouchSeedPicker(this))
  , Extraction(new pqVesselTouchCenterlineExtraction(this))
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
    });
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::finished,
    this,
    &pqVesselTouchCenterlineWorkflow::centerlineReady);
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
  const bool hasVolume = this->DataRange[0] < this->DataRange[1];
  this->Ui.lowerThreshold->setEnabled(!automatic && hasVolume);
  this->Ui.upperThreshold->setEnabled(!automatic && hasVolume);
}

void pqVesselTouchCenterlineWorkflow::onVolumeChanged(pqPipelineSource* volume)
{
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
  this->setExtractMessage(QString(), false);
}

void pqVesselTouchCenterlineWorkflow::onVolumeDataUpdated(pqPipelineSource* volume)
{
  QObject::disconnect(volume, nullptr, this, nullptr);
  if (volume == this->Volumes->currentVolume())
  {
    this->setDataRange(volume);
  }
}

void pqVesselTouchCenterlineWorkflow::extract()
{
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
  this->Ui.extractButton->setEnabled(false);
  this->setExtractMessage(tr("Extracting..."), false);
  pqPipelineSource* filter = this->Extraction->extract(volume,
    this->Seed_mm,
    this->automaticRange(),
    this->Ui.lowerThreshold->value(),
    this->Ui.upperThreshold->value(),
    activeRenderView());
  this->Ui.extractButton->setEnabled(true);
  const pqVesselTouchExtractionResult& result = this->Extraction->result();
  if (!filter || result.paths <= 0)
  {
    return; // failed() showed why
  }
  QString text = tr("%n centerline path(s).", "", result.paths);
  if (result.rangeKnown)
  {
    // The range used, in the fields too: the user's starting point for an override.
    const QSignalBlocker lowerBlocker(this->Ui.lowerThreshold);
    const QSignalBlocker upperBlocker(this->Ui.upperThreshold);
    this->Ui.lowerThreshold->setValue(result.rangeUsed[0]);
    this->Ui.upperThreshold->setValue(result.rangeUsed[1]);
    text += tr(" Vessel intensity %1 to %2 (%3).")
              .arg(result.rangeUsed[0])
              .arg(result.rangeUsed[1])
              .arg(result.rangeAutomatic ? tr("automatic") : tr("yours"));
  }
  if (!result.message.isEmpty())
  {
    text += QLatin1Char(' ') + result.message;
  }
  this->setExtractMessage(text, false);
}
