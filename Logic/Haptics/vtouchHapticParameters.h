// Every run-time setting of the haptic pipeline in one trivially copyable struct, so the GUI can
// publish it to the haptic thread through a SeqLock.
//
// The members, their defaults, units, ranges and meanings are generated from ONE table,
// vtouchHapticParameters.def (read it for each member's meaning); vtouchHapticParameterTable.h
// describes them to hosts (names, ranges, setters), the facade validates against it, and the
// session proxy's properties are generated from it.
#pragma once

#include "vtouchForceLaw.h"

#include <cstdint>

namespace vtouch
{

struct HapticParameters
{
// Only the leading columns matter here; the rest (range, labels, meaning, laws) is the table's.
#define VTOUCH_HAPTIC_PARAMETER(Type, member, Property, Kind, label, unit, defaultValue, ...)      \
  Type member = static_cast<Type>(defaultValue);
#include "vtouchHapticParameters.def"
#undef VTOUCH_HAPTIC_PARAMETER
};

} // namespace vtouch
