// A form of haptic parameters built from the parameter table (vtouchHapticParameters.def): given a
// list of parameter names, one row per parameter with the descriptor's label, unit, range and
// meaning (tooltip): a spin box for Real and Integer rows, a check box for Boolean rows, a combo
// box for Choice rows. It reads and writes a vtouch::HapticParameters through the descriptors'
// get/set, so no default, range or label is written here. Used for the panel's Advanced section.
// Rows whose parameter does not act on the chosen force law (the table's "laws" column) are greyed
// out.
#ifndef qVesselTouchHapticParameterForm_h
#define qVesselTouchHapticParameterForm_h

#include "vtouchHapticParameters.h"

#include <QScopedPointer>
#include <QStringList>
#include <QWidget>

class QWidget;
class qVesselTouchHapticParameterFormPrivate;

class qVesselTouchHapticParameterForm : public QWidget
{
  Q_OBJECT
public:
  explicit qVesselTouchHapticParameterForm(QWidget* parent = nullptr);
  ~qVesselTouchHapticParameterForm() override;

  /// Builds one row per name (property names of the table, in this order); an unknown name is
  /// skipped with a warning. The rows show the current parameters.
  void setParameterNames(const QStringList& names);
  /// The names of the rows, in order.
  QStringList parameterNames() const;

  /// The parameters: those last set, with the form's rows as shown (clamped to the table's range
  /// and rounded to the control's decimals).
  vtouch::HapticParameters parameters() const;
  /// Writes the form's rows into `p` (other members untouched).
  void writeTo(vtouch::HapticParameters& p) const;

  /// The control of a row (QDoubleSpinBox, QSpinBox, QCheckBox or QComboBox), or nullptr.
  QWidget* editor(const QString& name) const;

  /// The force law the rows are greyed out for (a ForceLaw value). Default 0 (LDGF).
  int forceLaw() const;

public slots:
  /// Shows `p` (clamped to the ranges); emits parametersChanged() only when a row changes.
  void setParameters(const vtouch::HapticParameters& p);
  /// Enables the rows whose parameter acts on `law` (a ForceLaw value, e.g. the force-law
  /// widget's forceLawChanged()) and greys out the others; their values are kept.
  void setForceLaw(int law);

signals:
  /// A row's value changed, from its control or setParameters().
  void parametersChanged();

private:
  QScopedPointer<qVesselTouchHapticParameterFormPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchHapticParameterForm);
  Q_DISABLE_COPY(qVesselTouchHapticParameterForm);
};

#endif
