// The table of haptic parameters (vtouchHapticParameters.def) as C++ data: one descriptor per
// HapticParameters member, with its host name, label, unit, default, range, meaning and a getter
// and setter, so that hosts (the VTK facade, the Qt panel, a 3D Slicer parameter node) loop over
// the parameters instead of writing each one out, and check a value in ONE place
// (checkHapticParameter).
#pragma once

#include "vtouchHapticParameters.h"

#include <cstddef>
#include <string>
#include <type_traits>

namespace vtouch
{

/// How a parameter is edited and carried: a real number, a 0/1 switch, an integer, or one of a
/// few named integer values (HapticParameterDescriptor::choices).
enum class HapticParameterKind
{
  Real,
  Boolean,
  Integer,
  Choice
};

struct HapticParameterDescriptor
{
  const char* name;    ///< property name (PascalCase), as the facade, proxy and Python know it
  const char* member;  ///< the HapticParameters member
  const char* label;   ///< short label for a user interface
  const char* unit;    ///< "" for dimensionless values
  double defaultValue; ///< the HapticParameters default
  double minimum;      ///< smallest accepted value
  double maximum;      ///< largest accepted value
  const char* choices; ///< Choice: '|'-separated labels of minimum, minimum + 1, ...; else ""
  const char* meaning; ///< one line, with its paper section or equation
  /// The force laws the parameter acts on: '|'-separated labels of the ForceLaw row's choices,
  /// "" for every law.
  const char* forceLaws;
  HapticParameterKind kind;
  double (*get)(const HapticParameters&); ///< the member as a double
  void (*set)(HapticParameters&, double); ///< stores a value (checked first: checkHapticParameter)
};

namespace detail
{
template<typename T, T HapticParameters::*Member>
constexpr double getHapticParameter(const HapticParameters& p)
{
  if constexpr (std::is_enum_v<T>)
  {
    return static_cast<double>(static_cast<std::underlying_type_t<T>>(p.*Member));
  }
  else
  {
    return static_cast<double>(p.*Member);
  }
}

template<typename T, T HapticParameters::*Member>
constexpr void setHapticParameter(HapticParameters& p, double value)
{
  if constexpr (std::is_same_v<T, bool>)
  {
    p.*Member = value != 0.0;
  }
  else if constexpr (std::is_enum_v<T>)
  {
    p.*Member = static_cast<T>(static_cast<std::underlying_type_t<T>>(value));
  }
  else
  {
    p.*Member = static_cast<T>(value);
  }
}
} // namespace detail

/// Identifies a row of the table: HapticParameterId::Zoom etc., in table order.
enum class HapticParameterId : int
{
#define VTOUCH_HAPTIC_PARAMETER(Type, member, Property, ...) Property,
#include "vtouchHapticParameters.def"
#undef VTOUCH_HAPTIC_PARAMETER
};

/// Every haptic parameter, in table order.
inline constexpr HapticParameterDescriptor kHapticParameterDescriptors[] = {
// clang-format off
#define VTOUCH_HAPTIC_PARAMETER(Type, member, Property, Kind, label, unit, defaultValue, minimum,   \
  maximum, choices, meaning, laws)                                                                 \
  { #Property, #member, label, unit, defaultValue, minimum, maximum, choices, meaning, laws,        \
    HapticParameterKind::Kind,                                                                     \
    &detail::getHapticParameter<Type, &HapticParameters::member>,                                  \
    &detail::setHapticParameter<Type, &HapticParameters::member> },
// clang-format on
#include "vtouchHapticParameters.def"
#undef VTOUCH_HAPTIC_PARAMETER
};

inline constexpr std::size_t kHapticParameterCount =
  sizeof(kHapticParameterDescriptors) / sizeof(kHapticParameterDescriptors[0]);

/// The descriptor of a row.
constexpr const HapticParameterDescriptor& hapticParameter(HapticParameterId id)
{
  return kHapticParameterDescriptors[static_cast<std::size_t>(id)];
}

/// The descriptor called `name` (exact, case-sensitive), or nullptr.
const HapticParameterDescriptor* findHapticParameter(const char* name);

/// Why `value` is not acceptable for `d`, or "" when it is: it must be finite and within
/// [minimum, maximum], an integer for Integer and Choice, 0 or 1 for Boolean. The message names
/// the parameter, the value, the range and the unit.
std::string checkHapticParameter(const HapticParameterDescriptor& d, double value);

} // namespace vtouch
