// The raw path's shading correction on VTK scalars (vtouch::ShadingField; issue 16 item 1,
// Docs/CENTERLINES.md "Shading"), shared by VesselCenterline and VesselCandidateRegion so that
// the preview shows the region the extraction codes. Header only, not a wrapped class.
#pragma once

#include "vtouchCandidateRegionRunner.h"
#include "vtouchIntensityRangeEstimator.h"
#include "vtouchShadingField.h"
#include "vtouchTypedScalars.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkSmartPointer.h"

#include <string>
#include <type_traits>
#include <utility>

namespace vtouch
{

struct ShadingCorrection
{
  ShadingField field;
  /// The corrected scalars (the input's type; float for other types), or null when the field
  /// is not active (no shading to correct, a binary mask, a single intensity).
  vtkSmartPointer<vtkDataArray> scalars;
  std::string summary;
};

/// Runs `run(view)` with `scalars` seen as a VolumeView of `dims` voxels of its own type (the
/// types withTypedScalars wraps; one float copy for the others).
template<typename Run>
void withVolumeView(vtkDataArray* scalars, const std::array<std::int64_t, 3>& dims, Run&& run)
{
  withTypedScalars(scalars,
    [&](const auto* voxels)
    {
      VolumeView<std::remove_const_t<std::remove_pointer_t<decltype(voxels)>>> view;
      view.voxels = voxels;
      view.dims = dims;
      run(view);
      return 0;
    });
}

/// The voxel type of a VolumeView (withVolumeView's argument).
template<typename View>
using ViewVoxel = std::remove_const_t<std::remove_pointer_t<decltype(std::declval<View>().voxels)>>;

/// `scalars` (one component, a piece of `dims` voxels whose first voxel is whole-volume voxel
/// `origin`) corrected by `field`: the input's type (float for the types withTypedScalars copies).
inline vtkSmartPointer<vtkDataArray> correctedScalars(const ShadingField& field,
  vtkDataArray* scalars,
  const std::array<std::int64_t, 3>& dims,
  const std::array<std::int64_t, 3>& origin)
{
  vtkSmartPointer<vtkDataArray> corrected;
  const int type = scalars->GetDataType();
  if (type == VTK_FLOAT || type == VTK_DOUBLE || type == VTK_UNSIGNED_CHAR || type == VTK_SHORT ||
      type == VTK_UNSIGNED_SHORT)
  {
    corrected.TakeReference(scalars->NewInstance());
  }
  else
  {
    corrected = vtkSmartPointer<vtkFloatArray>::New();
  }
  corrected->SetNumberOfComponents(1);
  corrected->SetNumberOfTuples(scalars->GetNumberOfTuples());
  corrected->SetName(scalars->GetName());
  withVolumeView(scalars,
    dims,
    [&](const auto& view)
    {
      using T = ViewVoxel<decltype(view)>;
      field.correct(view, origin, static_cast<T*>(corrected->GetVoidPointer(0)));
    });
  return corrected;
}

/// The field of `image`'s `scalars` (one component; `image` indexed from 0, the whole volume),
/// referenced to the seed's voxel when `useSeed` and the seed is inside, and the corrected
/// scalars when the gate is met.
inline ShadingCorrection correctShading(vtkImageData* image,
  vtkDataArray* scalars,
  bool useSeed,
  const double seed_World_mm[3])
{
  ShadingCorrection out;
  int d[3];
  image->GetDimensions(d);
  const std::array<std::int64_t, 3> dims{ d[0], d[1], d[2] };
  const std::array<std::int64_t, 3> seed =
    useSeed ? worldToIndex(image, seed_World_mm) : std::array<std::int64_t, 3>{ -1, -1, -1 };
  withVolumeView(scalars,
    dims,
    [&](const auto& view)
    {
      // fromVolume's sample lattice: no pass over the whole volume unless there is shading.
      const std::uint64_t stride = IntensityRangeEstimator::sampleStride(view.size());
      out.field = ShadingField::fit(dims, stride, ShadingField::sampleOf(view, stride));
      if (useSeed && view.inside(seed[0], seed[1], seed[2]))
      {
        out.field.setReference(seed);
      }
    });
  out.summary = out.field.summary();
  if (out.field.active())
  {
    out.scalars = correctedScalars(out.field, scalars, dims, { 0, 0, 0 });
  }
  return out;
}

/// ShadingCorrected (0/1), ShadingGainSpan (lowest, highest gain relative to the seed; 1 1 when
/// not corrected) and ShadingMessage (what the field did).
inline void addShadingFieldData(vtkFieldData* fd, const ShadingCorrection& c)
{
  vtkNew<vtkIntArray> corrected;
  corrected->SetName("ShadingCorrected");
  corrected->InsertNextValue(c.scalars ? 1 : 0);
  fd->AddArray(corrected);
  vtkNew<vtkDoubleArray> span;
  span->SetName("ShadingGainSpan");
  const std::array<double, 2> g =
    c.scalars ? c.field.gainSpan() : std::array<double, 2>{ 1.0, 1.0 };
  span->InsertNextValue(g[0]);
  span->InsertNextValue(g[1]);
  fd->AddArray(span);
  vtkNew<vtkStringArray> text;
  text->SetName("ShadingMessage");
  text->InsertNextValue(c.summary);
  fd->AddArray(text);
}

} // namespace vtouch
