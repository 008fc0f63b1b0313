#include "pqVesselTouchBlendModeNames.h"

#include "vtkCommand.h"
#include "vtkSMEnumerationDomain.h"
#include "vtkSMProperty.h"
#include "vtkSMProxy.h"

bool pqVesselTouchBlendModeNames::nameMaximumIntensity(vtkSMProxy* representation)
{
  vtkSMProperty* property = representation ? representation->GetProperty("BlendMode") : nullptr;
  auto* domain = property ? property->FindDomain<vtkSMEnumerationDomain>() : nullptr;
  if (!domain)
  {
    return false;
  }
  for (unsigned int i = 0; i < domain->GetNumberOfEntries(); ++i)
  {
    if (domain->GetEntryValue(i) == MaximumIntensity)
    {
      return true;
    }
  }
  domain->AddEntry("Maximum Intensity", MaximumIntensity);
  // pqComboBoxDomain (the panel's combo box) refills its items on this event.
  domain->InvokeEvent(vtkCommand::DomainModifiedEvent, nullptr);
  return true;
}
