// Gives ParaView's Volume representation a truthful "Blend Mode" list (issue 20, item 11).
// ParaView 5.11 names only Composite (0), Isosurface (5) and Slice (6) in the property's
// enumeration domain, although the volume mapper also renders maximum intensity (1). VesselTouch's
// MIP sets blend mode 1, so the Properties panel showed "Composite" (the first entry) and choosing
// anything there lost the MIP for good. Naming blend mode 1 "Maximum Intensity" in the domain makes
// the panel show the truth and lets a user come back to the MIP from the same combo box.
#ifndef pqVesselTouchBlendModeNames_h
#define pqVesselTouchBlendModeNames_h

class vtkSMProxy;

class pqVesselTouchBlendModeNames
{
public:
  static constexpr int MaximumIntensity = 1;

  // Adds the "Maximum Intensity" entry to REPRESENTATION's BlendMode enumeration when it has one
  // without it; returns whether the representation now names blend mode 1. Safe on any proxy.
  static bool nameMaximumIntensity(vtkSMProxy* representation);
};

#endif
