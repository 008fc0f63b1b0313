#include "vtouchForceLaw.h"

namespace vtouch
{

const char* toString(ForceLawId id)
{
  switch (id)
  {
    case ForceLawId::Ldgf:
      return "LDGF";
    case ForceLawId::ChangeOfHeight:
      return "ChangeOfHeight";
    case ForceLawId::LateralGradient:
      return "LateralGradient";
    case ForceLawId::ConstraintProxy:
      return "ConstraintProxy";
    case ForceLawId::None:
      return "None";
  }
  return "unknown";
}

} // namespace vtouch
