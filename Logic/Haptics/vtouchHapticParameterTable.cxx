#include "vtouchHapticParameterTable.h"

#include <cmath>
#include <cstring>
#include <sstream>

namespace vtouch
{

namespace
{
// Every default must pass its own check: a table row that contradicts itself fails to compile.
constexpr bool defaultsWithinRanges()
{
  for (const HapticParameterDescriptor& d : kHapticParameterDescriptors)
  {
    if (!(d.minimum <= d.defaultValue && d.defaultValue <= d.maximum))
    {
      return false;
    }
    if (d.get(HapticParameters{}) != d.defaultValue)
    {
      return false;
    }
  }
  return true;
}
static_assert(defaultsWithinRanges(),
  "a default of vtouchHapticParameters.def is out of its range");

std::string withUnit(double value, const char* unit)
{
  std::ostringstream text;
  text.precision(10);
  text << value;
  if (unit && *unit)
  {
    text << ' ' << unit;
  }
  return text.str();
}
} // namespace

const HapticParameterDescriptor* findHapticParameter(const char* name)
{
  if (!name)
  {
    return nullptr;
  }
  for (const HapticParameterDescriptor& d : kHapticParameterDescriptors)
  {
    if (std::strcmp(d.name, name) == 0)
    {
      return &d;
    }
  }
  return nullptr;
}

std::string checkHapticParameter(const HapticParameterDescriptor& d, double value)
{
  const std::string range =
    "[" + withUnit(d.minimum, "") + ", " + withUnit(d.maximum, d.unit) + "]";
  const std::string what = std::string(d.name) + " = " + withUnit(value, d.unit);
  if (!std::isfinite(value) || value < d.minimum || value > d.maximum)
  {
    return what + " is out of range: " + d.label + " must be in " + range;
  }
  if (d.kind != HapticParameterKind::Real && value != std::floor(value))
  {
    return what + " is not a whole number: " + d.label + " is an integer in " + range;
  }
  return std::string();
}

} // namespace vtouch
