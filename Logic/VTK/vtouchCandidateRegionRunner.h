// The raw-angiogram stage shared by VesselCenterline and VesselCandidateRegion (header only, not
// a wrapped class): VTK scalars -> vtouch::VesselCandidateRegion -> the mask the voxel coder codes,
// the range it used and the user-facing message; and the field data both filters publish.
#pragma once

#include "vtouchTypedScalars.h"
#include "vtouchVesselCandidateRegion.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkType.h"

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace vtouch
{

struct CandidateRegionRequest
{
  bool automatic = true;
  double lower = 0.5, upper = 1e300; ///< used when !automatic
  bool useSeed = false;
  double seed_World_mm[3] = { 0.0, 0.0, 0.0 };
  /// The stages' progress and cancel (VesselCandidateRegion::Settings::progress): when it
  /// returns false the run throws vtouch::Cancelled.
  ProgressCallback progress;
};

struct CandidateRegionOutcome
{
  bool ok = false;
  std::string message; ///< empty when ok
  double lower = 0.0, upper = 0.0;
  /// The range estimator's background B and its noise sigma S (automatic runs; 0 otherwise).
  double background = 0.0, backgroundNoise = 0.0;
  bool automatic = true;
  bool binary = false; ///< an automatic run found a two-valued mask: threshold it as before
  std::shared_ptr<const SparseVesselMask> mask;
  std::array<std::int64_t, 3> seedIndex{ -1, -1, -1 }; ///< in `mask`, when seeded
  std::vector<std::pair<std::string, double>> stageSeconds;
};

/// The message for a seed outside the volume: where the seed and the volume are (the click or the
/// Python seed missed it), and what to do. `bounds_mm`: the whole volume's, x0 x1 y0 y1 z0 z1.
inline std::string seedOutsideVolumeMessage(const double seed_World_mm[3],
  const std::array<std::int64_t, 3>& seed,
  const double bounds_mm[6])
{
  char text[400];
  std::snprintf(text,
    sizeof(text),
    "The seed (%g, %g, %g mm; voxel %lld, %lld, %lld) is outside the volume (%g..%g, %g..%g, "
    "%g..%g mm): pick a point on a vessel in the MIP.",
    seed_World_mm[0],
    seed_World_mm[1],
    seed_World_mm[2],
    static_cast<long long>(seed[0]),
    static_cast<long long>(seed[1]),
    static_cast<long long>(seed[2]),
    bounds_mm[0],
    bounds_mm[1],
    bounds_mm[2],
    bounds_mm[3],
    bounds_mm[4],
    bounds_mm[5]);
  return text;
}

/// Voxel index (origin + direction * (index * spacing), nearest) of a world point, as ITK
/// imports the image: from index 0 (the filters hand the runner and the coder an image whose
/// extent starts at 0, DistributedCenterline::pieceFromIndexZero).
inline std::array<std::int64_t, 3> worldToIndex(vtkImageData* image, const double p[3])
{
  double origin[3], spacing[3];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  vtkNew<vtkMatrix3x3> inverse;
  if (vtkMatrix3x3* m = image->GetDirectionMatrix())
  {
    inverse->DeepCopy(m);
  }
  inverse->Invert();
  const double d[3] = { p[0] - origin[0], p[1] - origin[1], p[2] - origin[2] };
  std::array<std::int64_t, 3> index{};
  for (int r = 0; r < 3; ++r)
  {
    const double c = (inverse->GetElement(r, 0) * d[0] + inverse->GetElement(r, 1) * d[1] +
                       inverse->GetElement(r, 2) * d[2]) /
                     spacing[r];
    index[r] = std::isfinite(c) && std::abs(c) < 1e15 ? static_cast<std::int64_t>(std::lround(c))
                                                      : std::int64_t{ -1 };
  }
  return index;
}

template<typename T>
CandidateRegionOutcome runCandidateRegion(vtkImageData* image,
  const T* data,
  const CandidateRegionRequest& request)
{
  VolumeView<T> view;
  view.voxels = data;
  int dims[3];
  image->GetDimensions(dims);
  view.dims = { dims[0], dims[1], dims[2] };
  image->GetSpacing(view.spacing_mm.data());
  VesselCandidateRegion::Settings s;
  s.automatic = request.automatic;
  s.lower = request.lower;
  s.upper = request.upper;
  // The override is the threshold as given: no tube cut (the filters' path before the raw path).
  s.cutNonTubular = request.automatic;
  s.useSeed = request.useSeed;
  s.progress = request.progress;
  if (request.useSeed)
  {
    s.seed = worldToIndex(image, request.seed_World_mm);
  }
  VesselCandidateRegion::Result r = VesselCandidateRegion::extract(view, s);
  if (request.useSeed && !view.inside(s.seed[0], s.seed[1], s.seed[2]))
  {
    double bounds[6];
    image->GetBounds(bounds);
    r.message = seedOutsideVolumeMessage(request.seed_World_mm, s.seed, bounds);
  }
  CandidateRegionOutcome out;
  out.ok = r.ok;
  out.message = r.message;
  out.automatic = request.automatic;
  out.lower = request.automatic ? r.range.lower : request.lower;
  out.upper = request.automatic ? r.range.upper : request.upper;
  out.background = request.automatic ? r.range.background : 0.0;
  out.backgroundNoise = request.automatic ? r.range.backgroundNoise : 0.0;
  out.binary = request.automatic && r.range.binary;
  out.seedIndex = r.seed;
  out.stageSeconds = r.stageSeconds;
  if (r.ok)
  {
    out.mask = std::make_shared<const SparseVesselMask>(std::move(r.mask));
  }
  return out;
}

/// Dispatches on the scalar type (other types: one float copy of the volume).
inline CandidateRegionOutcome runCandidateRegion(vtkImageData* image,
  vtkDataArray* scalars,
  const CandidateRegionRequest& request)
{
  return withTypedScalars(
    scalars, [&](const auto* voxels) { return runCandidateRegion(image, voxels, request); });
}

/// What the filters say when a run was cancelled (ExtractionMessage).
inline const char* cancelledMessage()
{
  return "Cancelled.";
}

/// Whether a filter's run is to stop: another thread set `flag`, or AbortExecute is on.
inline bool cancelRequested(const std::atomic<bool>* flag, vtkAlgorithm* algorithm)
{
  return (flag && flag->load(std::memory_order_relaxed)) || algorithm->GetAbortExecute();
}

/// IntensityRangeUsed (lower, upper), IntensityRangeAutomatic (0/1), ExtractionMessage.
inline void addRangeFieldData(vtkFieldData* fd,
  double lower,
  double upper,
  bool automatic,
  const std::string& message)
{
  vtkNew<vtkDoubleArray> range;
  range->SetName("IntensityRangeUsed");
  range->InsertNextValue(lower);
  range->InsertNextValue(upper);
  fd->AddArray(range);
  vtkNew<vtkIntArray> isAutomatic;
  isAutomatic->SetName("IntensityRangeAutomatic");
  isAutomatic->InsertNextValue(automatic ? 1 : 0);
  fd->AddArray(isAutomatic);
  vtkNew<vtkStringArray> text;
  text->SetName("ExtractionMessage");
  text->InsertNextValue(message);
  fd->AddArray(text);
}

/// One field array per stage of the candidate region, "CandidateRangeSeconds",
/// "CandidateGrowSeconds", "CandidateDepthSeconds", "CandidateTubularitySeconds",
/// "CandidateNecksSeconds" (wall-clock seconds; the stages that ran).
inline void addStageSeconds(vtkFieldData* fd,
  const std::vector<std::pair<std::string, double>>& stageSeconds,
  const std::string& prefix = "Candidate")
{
  // One array per stage, <Prefix><Stage>Seconds; a stage's name keeps its letters and digits,
  // each word capitalised ("trace(all)" -> TraceAllSeconds); a stage met twice adds up.
  for (const auto& [stage, seconds] : stageSeconds)
  {
    std::string name;
    bool wordStart = true;
    for (char c : stage)
    {
      const auto u = static_cast<unsigned char>(c);
      if (!std::isalnum(u))
      {
        wordStart = true;
        continue;
      }
      name += wordStart ? static_cast<char>(std::toupper(u)) : c;
      wordStart = false;
    }
    name = prefix + name + "Seconds";
    if (vtkDataArray* existing = fd->GetArray(name.c_str()))
    {
      existing->SetComponent(0, 0, existing->GetComponent(0, 0) + seconds);
      continue;
    }
    vtkNew<vtkDoubleArray> a;
    a->SetName(name.c_str());
    a->InsertNextValue(seconds);
    fd->AddArray(a);
  }
}

} // namespace vtouch
