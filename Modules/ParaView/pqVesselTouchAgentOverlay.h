// The agent over a cached MIP, in C++: the technique of vesseltouch.AgentOverlay (see
// Docs/RENDERING.md) without Python in the frame loop.
//
// * An overlay vtkRenderer on a new top layer of the view's render window shares the scene's
//   camera, is not interactive, and clears only depth in ParaView's own renders, so the agent is
//   drawn over every normal frame.
// * Its StartEvent fires after every lower layer has been drawn: in a normal frame (not a
//   hardware-selection pass) the colour buffer is copied into the overlay's background texture.
// * An agent-only frame turns drawing off for every other renderer, clears the overlay to that
//   texture, draws the agent and renders the VTK window directly: no volume ray casting.
// * The cache is valid while the camera, the window size and the redraw time of the scene's
//   visible props are those of the capture.
#ifndef pqVesselTouchAgentOverlay_h
#define pqVesselTouchAgentOverlay_h

#include "vtkNew.h"
#include "vtkWeakPointer.h"

#include <array>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkTexture;
class vtkUnsignedCharArray;
class pqVesselTouchAgentActors;

class pqVesselTouchAgentOverlay
{
public:
  explicit pqVesselTouchAgentOverlay(pqVesselTouchAgentActors& actors);
  ~pqVesselTouchAgentOverlay();

  /// Adds the overlay layer to `window` above `scene` (the view's 3D renderer). Detaches first.
  /// False for null arguments.
  bool attach(vtkRenderWindow* window, vtkRenderer* scene);
  /// Removes the layer: the window renders as before.
  void detach();
  bool isAttached() const { return this->Window != nullptr; }

  /// True when an agent-only frame can reuse the last capture.
  bool isCacheValid() const;
  /// Forces the next frame to be a normal (full) render.
  void invalidate() { this->Valid = false; }
  /// Draws the agent over the cached image (call only when isCacheValid()).
  void renderCached();

  /// Normal frames whose image was captured (the scene, i.e. the volume, was drawn).
  long long captures() const { return this->Captures; }
  /// Agent-only frames drawn over the capture.
  long long cachedFrames() const { return this->CachedFrames; }
  /// Mean wall time of an agent-only frame, ms (0 before the first).
  double meanCachedFrame_ms() const
  {
    return this->CachedFrames > 0 ? 1000.0 * this->CachedSeconds / this->CachedFrames : 0.0;
  }
  /// The scene renderer's (the volume's) time in the last captured frame, ms.
  double lastSceneRender_ms() const { return this->LastSceneRender_ms; }
  vtkRenderer* renderer() const { return this->Overlay; }

private:
  pqVesselTouchAgentOverlay(const pqVesselTouchAgentOverlay&) = delete;
  void operator=(const pqVesselTouchAgentOverlay&) = delete;

  using Stamp = std::array<unsigned long long, 5>;
  Stamp sceneStamp() const;
  void onOverlayStart();
  void onOverlayEnd();

  pqVesselTouchAgentActors& Actors;
  vtkWeakPointer<vtkRenderWindow> Window;
  vtkWeakPointer<vtkRenderer> Scene;
  vtkNew<vtkRenderer> Overlay;
  vtkNew<vtkUnsignedCharArray> Pixels;
  vtkNew<vtkImageData> Image;
  vtkNew<vtkTexture> Texture;
  int Layer = -1;
  unsigned long StartObserver = 0;
  unsigned long EndObserver = 0;
  bool Valid = false;
  bool InCachedFrame = false;
  Stamp Captured{};
  long long Captures = 0;
  long long CachedFrames = 0;
  double CachedSeconds = 0.0;
  double LastSceneRender_ms = 0.0;
};

#endif
