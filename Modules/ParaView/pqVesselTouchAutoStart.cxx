#include "pqVesselTouchAutoStart.h"

#include "pqVesselTouchBlendModeNames.h"

#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqPipelineBrowserWidget.h"
#include "pqPipelineSource.h"
#include "pqRepresentation.h"
#include "pqServerManagerModel.h"

#include "vtkSMProxy.h"
#include "vtkSMSettings.h"

#include <QPointer>
#include <QTimer>

namespace
{
// Sources with this annotation are left out of the Pipeline Browser (issue 20, item 13).
constexpr const char* kHiddenInBrowser = "VesselTouch.HiddenInPipelineBrowser";
}

pqVesselTouchAutoStart::pqVesselTouchAutoStart(QObject* parentObject)
  : QObject(parentObject)
{
}

void pqVesselTouchAutoStart::startup()
{
  // ParaView 5.11 has no reader priority: File > Open asks when several readers match, unless a
  // "ReaderDetails" default names one. These defaults sit at priority 0.5, below the user's own
  // settings (priority 1), so a user's choice still wins.
  vtkSMSettings::GetInstance()->AddCollectionFromString(
    R"json({"settings": {"RepresentedArrayListSettings": {"ReaderDetails": [
      "*.nii *.nii.gz", "NIfTI, oriented (VesselTouch)", "AnatomicalNIfTIReader",
      "*.nrrd *.nhdr", "NRRD, oriented (VesselTouch)", "AnatomicalNrrdReader",
      "*.mha *.mhd", "MetaImage, oriented (VesselTouch)", "AnatomicalMetaImageReader",
      "*.dcm", "DICOM series, oriented (VesselTouch)", "AnatomicalDICOMSeriesReader"]}}})json",
    0.5);

  // Every representation, also those a state file brings back, names blend mode 1 "Maximum
  // Intensity" so the Properties panel tells the truth about VesselTouch's MIP (issue 20, item 11).
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model,
    &pqServerManagerModel::representationAdded,
    this,
    [](pqRepresentation* representation)
    { pqVesselTouchBlendModeNames::nameMaximumIntensity(representation->getProxy()); });
  for (pqRepresentation* representation : model->findItems<pqRepresentation*>())
  {
    pqVesselTouchBlendModeNames::nameMaximumIntensity(representation->getProxy());
  }

  // The haptic session is driven from the VesselTouch panel, not a data product: it stays out of
  // the Pipeline Browser (ParaView's annotation filter, non-matching: annotated sources are hidden)
  // while state files still save and restore it as any registered proxy.
  QWidget* window = pqCoreUtilities::mainWidget();
  QPointer<pqPipelineBrowserWidget> browser =
    window ? window->findChild<pqPipelineBrowserWidget*>() : nullptr;
  if (browser)
  {
    browser->enableAnnotationFilter(kHiddenInBrowser);
    browser->setAnnotationFilterMatching(false);
  }
  auto hide = [browser](pqPipelineSource* source)
  {
    vtkSMProxy* proxy = source ? source->getProxy() : nullptr;
    if (proxy && QLatin1String(proxy->GetXMLName()) == QLatin1String("VesselTouchHapticSession") &&
        !proxy->HasAnnotation(kHiddenInBrowser))
    {
      proxy->SetAnnotation(kHiddenInBrowser, "1");
      // The browser filtered the row when it was added, before the annotation: filter again.
      QTimer::singleShot(0,
        browser.data(),
        [browser]()
        {
          if (browser)
          {
            browser->setAnnotationFilterMatching(false);
          }
        });
    }
  };
  QObject::connect(model, &pqServerManagerModel::sourceAdded, this, hide);
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    hide(source);
  }
}
