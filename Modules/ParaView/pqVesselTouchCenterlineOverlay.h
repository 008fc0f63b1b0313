// The extracted centerlines drawn over the MIP. A maximum-intensity projection is composited over
// opaque geometry with the opacity of the brightest voxel on the ray, and a centerline runs
// inside the brightest voxels: drawn as a ParaView representation it is hidden under its own
// vessel. So the centerlines are drawn by a renderer on a layer above the view's 3D renderer that
// shares its camera and clears only depth (the technique of pqVesselTouchAgentOverlay, without
// the cached frames), in a colour that stands out on grey, as tubes. It follows the visibility of
// the filter's representation in the view (the Pipeline Browser's eye).
//
// Attached before the agent overlay (which takes the next layer when tracing starts), the agent
// is drawn over the centerlines and its cached frames include them. The same layer shows the
// seed's marker and Preview's candidate vessel region (a translucent magenta surface).
#ifndef pqVesselTouchCenterlineOverlay_h
#define pqVesselTouchCenterlineOverlay_h

#include <QObject>
#include <QPointer>

#include "vtkNew.h"
#include "vtkSphereSource.h"
#include "vtkWeakPointer.h"

class pqPipelineSource;
class pqView;
class vtkActor;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderWindow;
class vtkRenderer;
class vtkSphereSource;

class pqVesselTouchCenterlineOverlay : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchCenterlineOverlay(QObject* parent = nullptr);
  ~pqVesselTouchCenterlineOverlay() override;

  /// Draws the current output of `centerline` (its client-side polydata) over `view` when
  /// `visible`; hides it otherwise. Renders the view.
  void show(pqPipelineSource* centerline, pqView* view, bool visible);
  /// Whether centerlines are drawn now (attached, visible and not empty).
  bool isShowing() const;
  /// The seed's marker (a sphere of `radius_mm` at `seed_mm`, world mm) over `view`, or none
  /// (`seed_mm` null). Renders the view.
  void showSeed(pqView* view, const double* seed_mm, double radius_mm);
  bool isShowingSeed() const;
  /// The candidate vessel region's surface (world mm) over `view`, or none (`surface` null or
  /// empty). Renders the view.
  void showRegion(pqView* view, vtkPolyData* surface);
  bool isShowingRegion() const;

private Q_SLOTS:
  void followRepresentation();

private:
  bool attach(pqView* view);
  void detach();

  vtkNew<vtkRenderer> Overlay;
  vtkNew<vtkPolyData> Lines;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkSphereSource> SeedSphere;
  vtkNew<vtkPolyDataMapper> SeedMapper;
  vtkNew<vtkActor> SeedActor;
  vtkNew<vtkPolyData> Region;
  vtkNew<vtkPolyDataMapper> RegionMapper;
  vtkNew<vtkActor> RegionActor;
  vtkWeakPointer<vtkRenderWindow> Window;
  QPointer<pqView> View;
  QPointer<pqPipelineSource> Centerline;
  int Layer = -1;
  Q_DISABLE_COPY(pqVesselTouchCenterlineOverlay)
};

#endif
