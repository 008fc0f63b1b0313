// The props of the tracing agent, built once and moved by writing numbers (no pipeline update per
// frame): the 3D cone (red apex and sides, blue base, a white stripe that shows the roll), a 2D
// yellow cursor marker for the exploring state and a 2D force arrow for pseudo-haptics.
// Colours and cone proportions match vesseltouch.agent_view (the Python AgentOverlay).
#ifndef pqVesselTouchAgentActors_h
#define pqVesselTouchAgentActors_h

#include "vtkNew.h"

#include <array>

class vtkActor;
class vtkActor2D;
class vtkMatrix4x4;
class vtkPoints;
class vtkPolyData;
class vtkRenderer;

class pqVesselTouchAgentActors
{
public:
  /// Agent colours, RGB 0-255: apex and sides, base, roll stripe, cursor, force arrow.
  static constexpr std::array<unsigned char, 3> SideRgb{ { 230, 20, 20 } };
  static constexpr std::array<unsigned char, 3> BaseRgb{ { 20, 40, 235 } };
  static constexpr std::array<unsigned char, 3> StripeRgb{ { 255, 255, 255 } };
  static constexpr std::array<unsigned char, 3> CursorRgb{ { 255, 215, 0 } };
  static constexpr std::array<unsigned char, 3> ArrowRgb{ { 40, 230, 90 } };

  pqVesselTouchAgentActors();
  ~pqVesselTouchAgentActors();

  /// Adds (removes) every prop to (from) `renderer`.
  void addTo(vtkRenderer* renderer);
  void removeFrom(vtkRenderer* renderer);

  /// The cone's model matrix (row-major, 16 values: vtouch::agentConeMatrix).
  void setConeMatrix(const std::array<double, 16>& matrix);
  void setConeVisible(bool visible);
  /// The exploring cursor, centred at display pixel (x, y), bottom-left origin.
  void setCursor(bool visible, double x_px, double y_px);
  /// The force arrow from `from` to `to`, display pixels; hidden when shorter than 2 px.
  void setForceArrow(bool visible, const double from_px[2], const double to_px[2]);

  /// Hides every prop, remembering what was visible (a hardware-selection pass must not see
  /// them); restoreVisibility() brings them back.
  void hideForSelection();
  void restoreVisibility();

  vtkActor* cone() const { return this->Cone; }

private:
  pqVesselTouchAgentActors(const pqVesselTouchAgentActors&) = delete;
  void operator=(const pqVesselTouchAgentActors&) = delete;

  void buildCone();
  void buildCursor();
  void buildArrow();

  vtkNew<vtkActor> Cone;
  vtkNew<vtkMatrix4x4> ConeMatrix;
  vtkNew<vtkActor2D> Cursor;
  vtkNew<vtkActor2D> Arrow;
  vtkNew<vtkPoints> ArrowPoints;
  vtkNew<vtkPolyData> ArrowPolyData;
  std::array<bool, 3> SavedVisibility{ { false, false, false } };
  bool Hidden = false;
};

#endif
