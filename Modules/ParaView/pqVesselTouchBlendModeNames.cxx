#include "pqVesselTouchBlendModeNames.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPVPluginTracker.h"
#include "vtkPVXMLElement.h"
#include "vtkSMEnumerationDomain.h"
#include "vtkSMProperty.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyDefinitionManager.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"

#include <cstring>
#include <string>

namespace
{
/// The representation whose BlendMode property carries the enumeration (the composite
/// representations expose it from this sub-proxy).
constexpr const char* kVolumeRepresentation = "UniformGridVolumeRepresentation";

void nameInActiveSession(vtkObject*, unsigned long, void*, void*)
{
  if (vtkSMProxyManager::IsInitialized())
  {
    pqVesselTouchBlendModeNames::nameMaximumIntensityInDefinitions(
      vtkSMProxyManager::GetProxyManager()->GetActiveSessionProxyManager());
  }
}

/// Installed when the plugin's library is loaded (GUI, pvpython's LoadPlugin, pvbatch alike): when
/// a plugin registers (this one, right after) and when another session becomes active, the active
/// session's Volume representation definition names blend mode 1.
class DefinitionNaming
{
public:
  DefinitionNaming()
  {
    this->Callback->SetCallback(&nameInActiveSession);
    vtkPVPluginTracker::GetInstance()->AddObserver(vtkCommand::RegisterEvent, this->Callback);
  }
  // Called once the proxy manager exists (it does when a plugin registers in a session).
  void watchSessions()
  {
    if (!this->WatchingSessions && vtkSMProxyManager::IsInitialized())
    {
      this->WatchingSessions = true;
      vtkSMProxyManager::GetProxyManager()->AddObserver(
        vtkSMProxyManager::ActiveSessionChanged, this->Callback);
    }
  }

private:
  vtkNew<vtkCallbackCommand> Callback;
  bool WatchingSessions = false;
};

DefinitionNaming& definitionNaming()
{
  static DefinitionNaming naming;
  return naming;
}
// The library's load installs it.
[[maybe_unused]] const bool kDefinitionNamingInstalled = (definitionNaming(), true);
} // namespace

bool pqVesselTouchBlendModeNames::nameMaximumIntensityInDefinitions(vtkSMSessionProxyManager* pxm)
{
  definitionNaming().watchSessions();
  vtkSMProxyDefinitionManager* definitions = pxm ? pxm->GetProxyDefinitionManager() : nullptr;
  vtkPVXMLElement* definition =
    definitions ? definitions->GetProxyDefinition("representations", kVolumeRepresentation, false)
                : nullptr;
  if (!definition)
  {
    return false;
  }
  for (unsigned int i = 0; i < definition->GetNumberOfNestedElements(); ++i)
  {
    vtkPVXMLElement* property = definition->GetNestedElement(i);
    const char* name = property->GetAttribute("name");
    vtkPVXMLElement* domain = name && std::strcmp(name, "BlendMode") == 0
                                ? property->FindNestedElementByName("EnumerationDomain")
                                : nullptr;
    if (!domain)
    {
      continue;
    }
    const std::string value = std::to_string(MaximumIntensity);
    for (unsigned int e = 0; e < domain->GetNumberOfNestedElements(); ++e)
    {
      const char* entryValue = domain->GetNestedElement(e)->GetAttribute("value");
      if (entryValue && value == entryValue)
      {
        return true;
      }
    }
    vtkNew<vtkPVXMLElement> entry;
    entry->SetName("Entry");
    entry->AddAttribute("text", "Maximum Intensity");
    entry->AddAttribute("value", value.c_str());
    domain->AddNestedElement(entry);
    return true;
  }
  return false;
}

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
