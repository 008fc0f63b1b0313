// Patient orientation letters (L/R, A/P, S/I) at the middle of the four edges of a render view,
// drawn by the plugin as 2D text in the view's renderer: a view annotation, not pipeline sources
// (issue 20, item 10). Each letter names the patient direction that points toward that edge of the
// screen, from the camera (direction of projection x view up) and the image's world frame (LPS or
// RAS, VesselTouch's readers' OutputFrame); an oblique edge lists up to three letters, strongest
// first (e.g. "LA"), as radiology viewers do. Recomputed before every render, so it follows the
// camera; hidden while the labelled image is hidden in the view or deleted.
#ifndef pqVesselTouchOrientationLabels_h
#define pqVesselTouchOrientationLabels_h

#include <QObject>
#include <QPointer>
#include <QString>

#include <memory>

class pqPipelineSource;
class pqRenderView;

class pqVesselTouchOrientationLabels : public QObject
{
  Q_OBJECT
public:
  enum Edge
  {
    Top = 0,
    Bottom,
    Left,
    Right
  };

  /// Shows the labels for SOURCE (a VesselTouch reader: world frame LPS, or RAS when its
  /// OutputFrame is 1) in VIEW, creating them once per view; returns the view's labels.
  static pqVesselTouchOrientationLabels* show(pqPipelineSource* source, pqRenderView* view);

  /// The letters for a world direction (unit vector) in frame LPS (ras false) or RAS.
  static QString letters(const double direction_World[3], bool ras);

  /// The letters currently drawn at EDGE (empty when hidden).
  QString text(Edge edge) const;

  ~pqVesselTouchOrientationLabels() override;

private:
  explicit pqVesselTouchOrientationLabels(pqRenderView* view);
  void update();

  struct Internals;
  std::unique_ptr<Internals> Internal;
  QPointer<pqRenderView> View;
  QPointer<pqPipelineSource> Source;
  bool Ras = false;
  Q_DISABLE_COPY(pqVesselTouchOrientationLabels)
};

#endif
