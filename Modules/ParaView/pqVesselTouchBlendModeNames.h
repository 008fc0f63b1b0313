// Gives ParaView's Volume representation a truthful "Blend Mode" list (issue 20, item 11).
// ParaView 5.11 names only Composite (0), Isosurface (5) and Slice (6) in the property's
// enumeration domain, although the volume mapper also renders maximum intensity (1). VesselTouch's
// MIP sets blend mode 1, so the Properties panel showed "Composite" (the first entry) and choosing
// anything there lost the MIP for good. Naming blend mode 1 "Maximum Intensity" in the domain makes
// the panel show the truth and lets a user come back to the MIP from the same combo box.
#ifndef pqVesselTouchBlendModeNames_h
#define pqVesselTouchBlendModeNames_h

class vtkSMProxy;
class vtkSMSessionProxyManager;

class pqVesselTouchBlendModeNames
{
public:
  static constexpr int MaximumIntensity = 1;

  // Adds the "Maximum Intensity" entry to REPRESENTATION's BlendMode enumeration when it has one
  // without it; returns whether the representation now names blend mode 1. Safe on any proxy.
  static bool nameMaximumIntensity(vtkSMProxy* representation);

  // Adds the same entry to the Volume representation's definition in PXM's session, so every
  // representation created from then on names blend mode 1 without the GUI: a Python state saved
  // from the GUI (`BlendMode = 'Maximum Intensity'`) then loads in a pvpython that loaded the
  // plugin and never ran ShowAsMIP. Runs by itself when the plugin is loaded (into the active
  // session) and for every session that becomes active afterwards. Returns whether it is named.
  static bool nameMaximumIntensityInDefinitions(vtkSMSessionProxyManager* pxm);
};

#endif
