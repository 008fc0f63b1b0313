// The VesselTouch toolbar: one-click actions bound to the active render view.
#ifndef pqVesselTouchToolBar_h
#define pqVesselTouchToolBar_h

#include <QToolBar>

class pqVesselTouchToolBar : public QToolBar
{
  Q_OBJECT
public:
  explicit pqVesselTouchToolBar(QWidget* parent = nullptr);

private:
  Q_DISABLE_COPY(pqVesselTouchToolBar)
};

#endif
