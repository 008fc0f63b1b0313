#include "pqVesselTouchTestDriver.h"

#include "pqVesselTouchCenterlineWorkflow.h"
#include "pqVesselTouchDockPanel.h"
#include "pqVesselTouchMessageRecorder.h"
#include "pqVesselTouchOrientationLabels.h"
#include "pqVesselTouchSeedPicker.h"
#include "pqVesselTouchSessionBinding.h"
#include "pqVesselTouchSessionStatus.h"
#include "pqVesselTouchVolumeJob.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqPVApplicationCore.h"
#include "pqLoadStateReaction.h"
#include "pqPipelineBrowserWidget.h"
#include "pqPipelineSource.h"
#include "pqPropertyWidget.h"
#include "pqPythonManager.h"
#include "pqRenderView.h"
#include "pqSaveStateReaction.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"

#include "vtkCamera.h"
#include "vtkCollection.h"
#include "vtkNew.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkImageData.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkSMProperty.h"
#include "vtkSMProxy.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSaveScreenshotProxy.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVector.h"
#include "vtkSMViewProxy.h"

#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDialog>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QGroupBox>
#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QProgressBar>
#include <QSaveFile>
#include <QSpinBox>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>

namespace
{
constexpr int kPollPeriod_ms = 100;

QJsonArray screenRect(const QWidget* widget)
{
  const QPoint topLeft = widget->mapToGlobal(QPoint(0, 0));
  return QJsonArray{ topLeft.x(), topLeft.y(), widget->width(), widget->height() };
}

QJsonObject describe(const QWidget* widget)
{
  QJsonObject entry;
  entry.insert("class", widget->metaObject()->className());
  entry.insert("visible", widget->isVisible());
  entry.insert("enabled", widget->isEnabled());
  entry.insert("rect", screenRect(widget));
  entry.insert("minimum_width", widget->minimumSizeHint().width());
  if (!widget->toolTip().isEmpty())
  {
    entry.insert("tooltip", widget->toolTip());
  }
  if (const auto* label = qobject_cast<const QLabel*>(widget))
  {
    entry.insert("text", label->text());
  }
  else if (const auto* button = qobject_cast<const QAbstractButton*>(widget))
  {
    entry.insert("text", button->text());
    entry.insert("checked", button->isChecked());
  }
  else if (const auto* spin = qobject_cast<const QDoubleSpinBox*>(widget))
  {
    entry.insert("value", spin->value());
    entry.insert("minimum", spin->minimum());
    entry.insert("maximum", spin->maximum());
  }
  else if (const auto* intSpin = qobject_cast<const QSpinBox*>(widget))
  {
    entry.insert("value", intSpin->value());
  }
  else if (const auto* combo = qobject_cast<const QComboBox*>(widget))
  {
    entry.insert("text", combo->currentText());
    QJsonArray items;
    for (int i = 0; i < combo->count(); ++i)
    {
      items.append(combo->itemText(i));
    }
    entry.insert("items", items);
  }
  else if (const auto* edit = qobject_cast<const QLineEdit*>(widget))
  {
    entry.insert("text", edit->text());
  }
  else if (const auto* bar = qobject_cast<const QProgressBar*>(widget))
  {
    entry.insert("value", bar->value());
    entry.insert("text", bar->text());
    // How many values strictly between empty and full the bar took since it was first described:
    // a test reads it after an update during which the driver cannot answer (a remote run), and
    // a screenshot may miss a fill that lasts one progress report.
    auto* counted = const_cast<QProgressBar*>(bar);
    if (!counted->property("vtouchTestCounted").toBool())
    {
      counted->setProperty("vtouchTestCounted", true);
      QObject::connect(counted, &QProgressBar::valueChanged, counted, [counted](int value) {
        if (value > counted->minimum() && value < counted->maximum())
        {
          counted->setProperty(
            "vtouchTestPartialValues", counted->property("vtouchTestPartialValues").toInt() + 1);
        }
      });
    }
    entry.insert("partial_values", bar->property("vtouchTestPartialValues").toInt());
  }
  else if (const auto* group = qobject_cast<const QGroupBox*>(widget))
  {
    entry.insert("text", group->title());
    entry.insert("checked", group->isChecked());
  }
  return entry;
}

QWidget* mainWindow()
{
  return pqCoreUtilities::mainWidget();
}

template<typename T>
T* findNamed(const QString& name)
{
  QWidget* window = mainWindow();
  return window ? window->findChild<T*>(name) : nullptr;
}
// The combo box of the Properties panel's widget for the property named XML_NAME (e.g. BlendMode
// of the active representation), preferring a visible one; null when the panel shows none.
QComboBox* propertyCombo(const QString& xmlName)
{
  QWidget* window = mainWindow();
  QComboBox* found = nullptr;
  for (pqPropertyWidget* widget :
    window ? window->findChildren<pqPropertyWidget*>() : QList<pqPropertyWidget*>())
  {
    vtkSMProperty* property = widget->property();
    auto* combo = widget->findChild<QComboBox*>();
    if (!property || !combo || xmlName != property->GetXMLName())
    {
      continue;
    }
    if (combo->isVisible())
    {
      return combo;
    }
    found = found ? found : combo;
  }
  return found;
}
} // namespace

pqVesselTouchTestDriver::pqVesselTouchTestDriver(QWidget* panel, const QString& directory)
  : QObject(panel)
  , Panel(panel)
  , Directory(directory)
{
  pqVesselTouchMessageRecorder::install();
  auto* timer = new QTimer(this);
  timer->setInterval(kPollPeriod_ms);
  QObject::connect(timer, &QTimer::timeout, this, &pqVesselTouchTestDriver::poll);
  timer->start();
}

pqVesselTouchTestDriver::~pqVesselTouchTestDriver() = default;

void pqVesselTouchTestDriver::poll()
{
  if (this->Busy)
  {
    return; // a command's nested event loop (a modal dialog) polls again
  }
  this->Busy = true;
  this->pollOnce();
  this->Busy = false;
}

void pqVesselTouchTestDriver::runAsAction(const std::function<void()>& action)
{
  QTimer::singleShot(0,
    this,
    [this, action]()
    {
      this->InAction = true;
      action();
      this->InAction = false;
    });
}

void pqVesselTouchTestDriver::pollOnce()
{
  const QDir directory(this->Directory);
  QFile command(directory.filePath(QString("cmd-%1.txt").arg(this->Next)));
  if (!command.exists() || !command.open(QIODevice::ReadOnly))
  {
    return;
  }
  const QString line = QString::fromUtf8(command.readAll()).trimmed();
  command.close();
  // While a queued action runs (Edit > Reset Session, a Python state's save), ParaView may turn
  // the event loop inside it (its confirmation dialog, progress while the session is rebuilt):
  // only commands that answer its dialogs run then, the others wait until it is over. A state
  // loaded from inside Reset Session, between the old session's end and the new one's view,
  // crashed ParaView in vtkSMViewLayoutProxy (a user cannot do that; the driver could).
  const QString verb = line.section(' ', 0, 0);
  if (this->InAction && verb != QLatin1String("accept") && verb != QLatin1String("dismiss"))
  {
    return;
  }
  const QString error = this->run(line);
  QJsonObject reply;
  reply.insert("command", line);
  reply.insert("ok", error.isEmpty());
  reply.insert("error", error);
  reply.insert("state", this->state());
  QSaveFile file(directory.filePath(QString("reply-%1.json").arg(this->Next)));
  if (file.open(QIODevice::WriteOnly))
  {
    file.write(QJsonDocument(reply).toJson());
    file.commit();
  }
  ++this->Next;
}

QString pqVesselTouchTestDriver::run(const QString& line)
{
  const QString verb = line.section(' ', 0, 0);
  const QString name = line.section(' ', 1, 1);
  const QString rest = line.section(' ', 2);
  if (verb == "state")
  {
    return QString();
  }
  if (verb == "trigger")
  {
    QAction* action = findNamed<QAction>(name);
    if (!action)
    {
      return QString("no action %1").arg(name);
    }
    if (!action->isEnabled())
    {
      return QString("action %1 is disabled").arg(name);
    }
    // Queued: a confirmation dialog the action opens (Reset Session) must not block the reply;
    // the test answers it through the X server.
    this->runAsAction([action]() { action->trigger(); });
    return QString();
  }
  if (verb == "click" || verb == "check")
  {
    auto* button = findNamed<QAbstractButton>(name);
    QAction* action = button ? nullptr : findNamed<QAction>(name);
    if (verb == "check" && action && action->isCheckable())
    {
      // A toolbar toggle, as its button sets it (queued, like trigger).
      const bool checked = rest.trimmed() == "1";
      QTimer::singleShot(0, action, [action, checked]() { action->setChecked(checked); });
      return QString();
    }
    if (!button)
    {
      return QString("no button %1").arg(name);
    }
    if (!button->isEnabled())
    {
      return QString("button %1 is disabled").arg(name);
    }
    if (verb == "click")
    {
      button->click();
    }
    else if (button->isChecked() != (rest.trimmed() == "1"))
    {
      button->click();
    }
    return QString();
  }
  if (verb == "set")
  {
    QWidget* widget = findNamed<QWidget>(name);
    if (auto* spin = qobject_cast<QDoubleSpinBox*>(widget))
    {
      spin->setValue(rest.toDouble());
      Q_EMIT spin->editingFinished();
    }
    else if (auto* combo = qobject_cast<QComboBox*>(widget))
    {
      const int index = combo->findText(rest);
      if (index < 0)
      {
        return QString("%1 has no item %2").arg(name, rest);
      }
      combo->setCurrentIndex(index);
    }
    else if (auto* edit = qobject_cast<QLineEdit*>(widget))
    {
      edit->setText(rest);
      Q_EMIT edit->editingFinished();
    }
    else
    {
      return QString("no editable widget %1").arg(name);
    }
    return QString();
  }
  if (verb == "setproperty")
  {
    // Picks TEXT in the Properties panel's combo box for property NAME, as a user's click does.
    QComboBox* combo = propertyCombo(name);
    const int index = combo ? combo->findText(rest) : -1;
    if (index < 0)
    {
      return combo ? QString("%1 has no item %2").arg(name, rest)
                   : QString("the Properties panel shows no %1").arg(name);
    }
    combo->setCurrentIndex(index);
    return QString();
  }
  if (verb == "select")
  {
    pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
    pqPipelineSource* source = name.isEmpty() ? nullptr : model->findItem<pqPipelineSource*>(name);
    if (!name.isEmpty() && !source)
    {
      return QString("no source %1").arg(name);
    }
    pqActiveObjects::instance().setActiveSource(source);
    return QString();
  }
  if (verb == "accept")
  {
    // Answers "Yes" (or OK) in the open message box whose title contains TITLE.
    for (QWidget* top : QApplication::topLevelWidgets())
    {
      auto* box = qobject_cast<QMessageBox*>(top);
      if (box && box->isVisible() && box->windowTitle().contains(name))
      {
        QAbstractButton* yes = box->button(QMessageBox::Yes);
        QAbstractButton* ok = box->button(QMessageBox::Ok);
        QTimer::singleShot(0, yes ? yes : ok, &QAbstractButton::click);
        return QString();
      }
    }
    return QString("no message box %1 open").arg(name);
  }
  if (verb == "dismiss")
  {
    // ParaView's welcome dialog (shown a while after start-up) or any other stray dialog.
    int closed = 0;
    for (QWidget* top : QApplication::topLevelWidgets())
    {
      auto* dialog = qobject_cast<QDialog*>(top);
      if (dialog && dialog->isVisible() && dialog->windowTitle().contains(name))
      {
        dialog->reject();
        ++closed;
      }
    }
    return closed > 0 ? QString() : QString("no dialog %1 open").arg(name);
  }
  if (verb == "resize")
  {
    QWidget* window = mainWindow();
    if (!window)
    {
      return QString("no main window");
    }
    window->move(0, 0);
    window->resize(name.toInt(), rest.toInt());
    return QString();
  }
  if (verb == "savestate" || verb == "loadstate")
  {
    // What File > Save State and File > Load State do once the file is chosen (a .pvsm or a
    // Python .py state; ParaView's own reactions).
    if (verb == "savestate" && name.endsWith(".py"))
    {
      // Queued: ParaView may ask for the Python state's options in a dialog, which the test
      // answers (as a user does) and the reply must not wait for.
      this->runAsAction([name]() { pqSaveStateReaction::savePythonState(name); });
      return QString();
    }
    if (verb == "savestate")
    {
      return pqSaveStateReaction::saveState(name) ? QString()
                                                  : QString("could not save %1").arg(name);
    }
    pqLoadStateReaction::loadState(name, false, pqActiveObjects::instance().activeServer());
    return QString();
  }
  if (verb == "seed")
  {
    auto* picker = this->Panel ? this->Panel->findChild<pqVesselTouchSeedPicker*>() : nullptr;
    auto* workflow =
      this->Panel ? this->Panel->findChild<pqVesselTouchCenterlineWorkflow*>() : nullptr;
    const QStringList words = line.split(' ', Qt::SkipEmptyParts);
    if (!picker || !workflow || (words.size() != 4 && words.size() != 5))
    {
      return QString("seed needs X Y Z [VALUE] and the panel's seed picker");
    }
    const double point[3] = { words[1].toDouble(), words[2].toDouble(), words[3].toDouble() };
    if (words.size() == 5)
    {
      // A volume on a pvserver has no voxels here: the test gives the seed's value.
      Q_EMIT picker->seedPicked(point[0], point[1], point[2], words[4].toDouble());
      return QString();
    }
    vtkImageData* image = pqVesselTouchVolumeJob::localImage(workflow->currentVolume());
    const vtkIdType id = image ? image->FindPoint(point[0], point[1], point[2]) : -1;
    if (id < 0 || !image->GetPointData()->GetScalars())
    {
      return QString("no voxel of the chosen volume at the seed");
    }
    Q_EMIT picker->seedPicked(
      point[0], point[1], point[2], image->GetPointData()->GetScalars()->GetComponent(id, 0));
    return QString();
  }
  if (verb == "python")
  {
    // A script file run by ParaView's Python, as the Python Shell's "Run Script" does.
    pqPythonManager* python =
      pqPVApplicationCore::instance() ? pqPVApplicationCore::instance()->pythonManager() : nullptr;
    if (!python || !QFile::exists(name))
    {
      return QString("cannot run the Python script %1").arg(name);
    }
    python->executeScript(name);
    return QString();
  }
  if (verb == "capture" || verb == "render")
  {
    auto* view = qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
    if (!view)
    {
      return QString("no active render view");
    }
    view->forceRender();
    if (verb == "render")
    {
      return QString();
    }
    // What ParaView's File > Save Screenshot captures, at the view's size.
    const QSize size = view->widget() ? view->widget()->size() : QSize(400, 400);
    vtkSmartPointer<vtkImageData> image = vtkSMSaveScreenshotProxy::CaptureImage(
      view->getViewProxy(), vtkVector2i(size.width(), size.height()));
    const int* dimensions = image ? image->GetDimensions() : nullptr;
    vtkUnsignedCharArray* pixels =
      image ? vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars()) : nullptr;
    if (!pixels || pixels->GetNumberOfComponents() < 3)
    {
      return QString("could not capture the view");
    }
    const int components = pixels->GetNumberOfComponents();
    QImage picture(dimensions[0], dimensions[1], QImage::Format_RGB888);
    for (int y = 0; y < dimensions[1]; ++y)
    {
      uchar* row = picture.scanLine(dimensions[1] - 1 - y); // VTK rows go bottom-up
      for (int x = 0; x < dimensions[0]; ++x)
      {
        const unsigned char* pixel =
          pixels->GetPointer(static_cast<vtkIdType>(y * dimensions[0] + x) * components);
        std::copy(pixel, pixel + 3, row + 3 * x);
      }
    }
    return picture.save(name, "PNG") ? QString() : QString("could not write %1").arg(name);
  }
  return QString("unknown verb %1").arg(verb);
}

QJsonObject pqVesselTouchTestDriver::state() const
{
  QJsonObject state;
  QJsonObject widgets;
  QWidget* window = mainWindow();
  QList<QWidget*> roots;
  if (this->Panel)
  {
    roots.append(this->Panel);
  }
  if (window)
  {
    for (QToolBar* bar : window->findChildren<QToolBar*>())
    {
      if (bar->objectName().contains("VesselTouch"))
      {
        roots.append(bar);
      }
    }
  }
  for (QWidget* root : roots)
  {
    widgets.insert(root->objectName(), describe(root));
    for (QWidget* child : root->findChildren<QWidget*>())
    {
      if (!child->objectName().isEmpty() && !child->objectName().startsWith("qt_"))
      {
        widgets.insert(child->objectName(), describe(child));
      }
    }
  }
  state.insert("widgets", widgets);

  QJsonObject properties;
  for (const char* xmlName : { "BlendMode", "Representation" })
  {
    if (QComboBox* combo = propertyCombo(xmlName))
    {
      properties.insert(xmlName, describe(combo));
    }
  }
  state.insert("properties", properties);

  QJsonObject actions;
  if (window)
  {
    for (QAction* action : window->findChildren<QAction*>())
    {
      if (action->objectName().contains("VesselTouch") || action->text().contains("VesselTouch"))
      {
        QJsonObject entry;
        entry.insert("text", action->text());
        entry.insert("enabled", action->isEnabled());
        entry.insert("checked", action->isChecked());
        entry.insert("tooltip", action->toolTip());
        entry.insert("has_icon", !action->icon().isNull());
        // Shown on its toolbar (not hidden in the toolbar's overflow menu).
        bool onToolbar = false;
        for (QToolBar* bar : window->findChildren<QToolBar*>())
        {
          QWidget* button = bar->widgetForAction(action);
          onToolbar = onToolbar || (button && button->isVisible());
        }
        entry.insert("on_toolbar", onToolbar);
        actions.insert(action->objectName(), entry);
      }
    }
  }
  state.insert("actions", actions);

  QJsonArray sources;
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    sources.append(source->getSMName());
  }
  state.insert("sources", sources);
  // The names the Pipeline Browser lists (its filtered model, every level).
  QJsonArray browserRows;
  if (auto* browser = window ? window->findChild<pqPipelineBrowserWidget*>() : nullptr)
  {
    QAbstractItemModel* rows = browser->getModel();
    QList<QModelIndex> pending{ QModelIndex() };
    while (rows && !pending.isEmpty())
    {
      const QModelIndex parent = pending.takeFirst();
      for (int row = 0; row < rows->rowCount(parent); ++row)
      {
        const QModelIndex index = rows->index(row, 0, parent);
        browserRows.append(index.data(Qt::DisplayRole).toString());
        pending.append(index);
      }
    }
  }
  state.insert("pipeline_browser", browserRows);
  pqPipelineSource* active = pqActiveObjects::instance().activeSource();
  state.insert("active_source", active ? active->getSMName() : QString());

  if (auto* view = qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView()))
  {
    if (QWidget* widget = view->widget())
    {
      state.insert("view_rect", screenRect(widget));
    }
    vtkCamera* camera = view->getRenderViewProxy()->GetActiveCamera();
    const double* position = camera->GetPosition();
    const double* up = camera->GetViewUp();
    state.insert("camera_position", QJsonArray{ position[0], position[1], position[2] });
    state.insert("camera_view_up", QJsonArray{ up[0], up[1], up[2] });
    const double* focal = camera->GetFocalPoint();
    state.insert("camera_focal_point", QJsonArray{ focal[0], focal[1], focal[2] });
    if (auto* labels = view->findChild<pqVesselTouchOrientationLabels*>())
    {
      QJsonObject letters;
      letters.insert("top", labels->text(pqVesselTouchOrientationLabels::Top));
      letters.insert("bottom", labels->text(pqVesselTouchOrientationLabels::Bottom));
      letters.insert("left", labels->text(pqVesselTouchOrientationLabels::Left));
      letters.insert("right", labels->text(pqVesselTouchOrientationLabels::Right));
      state.insert("orientation_labels", letters);
    }
  }

  // The session the panel is bound to, and every session registered under the shared name (one
  // is expected; a loaded state must not leave the old one beside it).
  auto* panel = qobject_cast<pqVesselTouchDockPanel*>(this->Panel.data());
  vtkSMProxy* session = panel ? panel->sessionBinding()->proxy() : nullptr;
  const pqVesselTouchSessionStatus status = pqVesselTouchSessionStatus::read(session);
  QJsonArray registered;
  QJsonArray registeredRunning;
  if (pqServer* server = pqActiveObjects::instance().activeServer())
  {
    vtkNew<vtkCollection> sessions;
    server->proxyManager()->GetProxies("sources", "VesselTouchSession", sessions);
    for (int i = 0; i < sessions->GetNumberOfItems(); ++i)
    {
      auto* proxy = vtkSMProxy::SafeDownCast(sessions->GetItemAsObject(i));
      registered.append(static_cast<double>(proxy->GetGlobalID()));
      registeredRunning.append(pqVesselTouchSessionStatus::read(proxy).running);
    }
  }
  auto globalId = [](vtkSMProxy* proxy)
  { return proxy ? static_cast<double>(proxy->GetGlobalID()) : 0.0; };
  QJsonObject sessionState;
  sessionState.insert("exists", session != nullptr);
  sessionState.insert("global_id", globalId(session));
  sessionState.insert("registered", registered);
  sessionState.insert("registered_running", registeredRunning);
  sessionState.insert("input_global_id",
    globalId(session ? vtkSMPropertyHelper(session, "Input", true).GetAsProxy() : nullptr));
  if (panel)
  {
    pqVesselTouchCenterlineWorkflow* workflow = panel->centerlineWorkflow();
    pqPipelineSource* volume = workflow->currentVolume();
    pqPipelineSource* centerline = workflow->centerline();
    state.insert("panel_volume_global_id", globalId(volume ? volume->getProxy() : nullptr));
    state.insert(
      "panel_centerline_global_id", globalId(centerline ? centerline->getProxy() : nullptr));
    state.insert("panel_centerline_input_global_id",
      globalId(
        centerline ? vtkSMPropertyHelper(centerline->getProxy(), "Input").GetAsProxy() : nullptr));
  }
  sessionState.insert("running", status.running);
  sessionState.insert("fault", status.faultCode);
  sessionState.insert("fault_text", status.faultText);
  sessionState.insert("last_error", status.lastError);
  sessionState.insert("ticks", static_cast<double>(status.loop.ticks));
  sessionState.insert("overruns", static_cast<double>(status.loop.overruns));
  sessionState.insert("period_error_max_us", status.loop.periodErrorMax_us);
  sessionState.insert("period_error_p99_us", status.loop.periodErrorP99_us);
  sessionState.insert("tracing", status.loop.tracing);
  sessionState.insert("realtime_scheduling", status.loop.realtimeScheduling);
  sessionState.insert("skeleton_paths", status.skeletonPaths);
  sessionState.insert(
    "agent_force_N", QJsonArray{ status.agentForce_N[0], status.agentForce_N[1] });
  sessionState.insert("agent_position_mm",
    QJsonArray{
      status.agentPosition_mm[0], status.agentPosition_mm[1], status.agentPosition_mm[2] });
  state.insert("session", sessionState);
  state.insert("messages", QJsonArray::fromStringList(pqVesselTouchMessageRecorder::messages()));
  state.insert("output_messages",
    QJsonArray::fromStringList(pqVesselTouchMessageRecorder::displayedMessages()));
  state.insert("output_messages_visible", pqVesselTouchMessageRecorder::outputMessagesVisible());
  return state;
}
