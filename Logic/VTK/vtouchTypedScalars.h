// The scalar-type dispatch of the VTK-facing extraction runs: a run templated on the voxel type
// is called with the volume's own type where it is instantiated for it, else with one float copy.
// One place for the switch that the candidate region's runner (vtouchCandidateRegionRunner.h) and
// the distributed raw region (vtouchDistributedRawRegion.cxx) each carried (duplicates --change;
// branch hdup).
#pragma once

#include "vtkDataArray.h"
#include "vtkType.h"

#include <cstddef>
#include <vector>

namespace vtouch
{

/// Calls `run(voxels)` with the first component of `scalars` (one component a tuple, one tuple a
/// voxel) as `const T*` for T float, double, unsigned char, short and unsigned short, and as a
/// float copy, kept for the call, for every other type; returns what `run` returns.
template<class Run>
auto withTypedScalars(vtkDataArray* scalars, Run&& run)
  -> decltype(run(static_cast<const float*>(nullptr)))
{
  const void* data = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    case VTK_FLOAT:
      return run(static_cast<const float*>(data));
    case VTK_DOUBLE:
      return run(static_cast<const double*>(data));
    case VTK_UNSIGNED_CHAR:
      return run(static_cast<const unsigned char*>(data));
    case VTK_SHORT:
      return run(static_cast<const short*>(data));
    case VTK_UNSIGNED_SHORT:
      return run(static_cast<const unsigned short*>(data));
    default:
    {
      std::vector<float> copy(static_cast<std::size_t>(scalars->GetNumberOfTuples()));
      for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
      {
        copy[static_cast<std::size_t>(i)] = static_cast<float>(scalars->GetComponent(i, 0));
      }
      return run(static_cast<const float*>(copy.data()));
    }
  }
}

} // namespace vtouch
