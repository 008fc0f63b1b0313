// A raw angiogram's smooth multiplicative shading (issue 16 item 1; Docs/CENTERLINES.md,
// "Shading"): an MR coil's sensitivity, a CE-MRA's or a CTA's intensity falling along the body,
// the phantom's bias field. The seed's range (IntensityRangeEstimator) holds where it was
// estimated; where the whole image is darker by a factor of 3 the vessel falls below it and the
// network stops there (the raw CTA's abdominal aorta above the renal arteries), where it is
// brighter the tissue rises into it (false vessels).
//
// Yi & Hayward §3.1 extract "from raw intensity volume images with linear operations" and give
// no rule for shading; the rule here is the product's (a named departure, Docs/CENTERLINES.md):
//  - model: I(x) = g(x) I0(x), g smooth and positive, for images whose zero is their own (an MR
//    magnitude, a CTA stored with air at 0, the phantom). A volume with negative values (a CT in
//    Hounsfield units, a subtraction image) is left as it is: its zero is not its darkest
//    tissue's, and its shading (a CT's cupping) is not a gain. (The code keeps m = 0 as the
//    model's zero, Minimum.)
//  - evidence: the background level of blocks of the volume (16 voxels a side, more when the
//    sample is sparse), each the median of the volume's sample lattice in the block
//    (IntensityRangeEstimator::sampleStride, the lattice fromVolume draws): vessels fill well
//    under half of a block, as of the seed's cube. Blocks at the model's zero (padding) or under
//    a quarter of the typical block's level (air, lung) are not shading and take no part;
//  - fit: log(B_block - m) by a quadratic polynomial of the block's centre (10 terms; only the
//    terms an axis with enough block layers supports), least squares weighted by the block's
//    samples, blocks farther than Parameters::rejectSigmas robust sigmas from the fit dropped and
//    the fit redone (another tissue, bone, a block filled by a vessel are not shading);
//  - gate: the shading is corrected only when the fitted gain spans at least
//    Parameters::minimumGainRatio (1.1) between the 5th and 95th percentiles of the blocks. The
//    phantom family's bias (+/- 10 %) fits 1.03-1.04, and correcting it moved recall both ways
//    by up to 0.5 %: the fit's own error. A scene with no more shading than that needs no model;
//  - correction: I'(x) = I(x) / g(x), g = 1 at the seed (the range estimated there is
//    the range of the corrected volume), or at the blocks' median without a seed; g is held
//    within the span the blocks' centres support (no extrapolation of the quadratic to the
//    volume's corners).
// Every quantity is the sample's order statistics and a fit of them: a distributed run that
// gathers the same sample gets the same field (ShadingField::fit takes the sample, not a volume).
#pragma once

#include "vtouchShadingBlocks.h"
#include "vtouchVolumeView.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace vtouch
{

struct ShadingFieldParameters
{
  std::int64_t minimumBlockEdge_voxels = 16;
  std::uint64_t minimumSamplesPerBlock = 64;
  double minimumGainRatio = 1.1; ///< the gate: P95 / P5 of the blocks' fitted gain
  double rejectSigmas = 3.0;
  int fitIterations = 4;
};

class ShadingField
{
public:
  using Parameters = ShadingFieldParameters;
  /// One voxel of the sample: its linear index in the whole volume and its intensity.
  using Sample = ShadingBlocks::Sample;

  /// The field fitted to `samples` (any order; sorted here) of a volume of `wholeDims`, drawn on
  /// the lattice of `stride`. Inactive (and summary() says why) for a sample of at most two values
  /// (a mask), with a negative value (a CT in Hounsfield units), when too few blocks hold enough
  /// samples above zero, or when the gate is not met.
  static ShadingField fit(const std::array<std::int64_t, 3>& wholeDims,
    std::uint64_t stride,
    std::vector<Sample> samples,
    const Parameters& p = Parameters{});

  /// The sample of a whole volume on the lattice of `stride` (fromVolume's).
  template<typename T>
  static std::vector<Sample> sampleOf(const VolumeView<T>& volume, std::uint64_t stride);

  bool active() const { return this->Active; }
  /// P95 / P5 of the blocks' fitted gain (1 when no fit).
  double gainRatio() const { return this->GainRatio; }
  int blocksUsed() const { return this->BlocksUsed; }
  double minimum() const { return this->Minimum; }
  /// The gain at whole-volume voxel (i, j, k), relative to the reference (1 there).
  double gain(double i, double j, double k) const;
  /// Makes the gain 1 at whole-volume voxel `c` (the seed).
  void setReference(const std::array<std::int64_t, 3>& c);
  /// Lowest and highest gain over the volume's block centres (after setReference).
  std::array<double, 2> gainSpan() const { return { this->SpanLow, this->SpanHigh }; }
  /// What the field did, for the filters' messages and field data.
  std::string summary() const;

  /// Writes the corrected piece: `out[n] = m + (in[n] - m) / gain` for every voxel of `piece`,
  /// whose voxel (0, 0, 0) is whole-volume voxel `pieceOrigin`. Integer types are rounded and
  /// clamped to the type's range.
  template<typename T>
  void correct(const VolumeView<T>& piece,
    const std::array<std::int64_t, 3>& pieceOrigin,
    T* out) const;

private:
  static constexpr int kTerms = 10;
  /// The gain along a row of the whole volume from i = 0: gain(i) = exp(a + b i + c i^2) (no
  /// span clamp; 1 when inactive), advanced by step().
  struct RowRecurrence
  {
    double gain = 1.0, ratio = 1.0, ratioStep = 1.0;
    void step()
    {
      this->gain *= this->ratio;
      this->ratio *= this->ratioStep;
    }
  };
  RowRecurrence rowRecurrence(std::int64_t j, std::int64_t k) const;
  /// Why `samples` cannot show a shading ("" when they can); drops the values that are not
  /// finite or lie outside the volume.
  static std::string sampleVerdict(std::vector<Sample>& samples,
    const std::array<std::int64_t, 3>& wholeDims);
  /// Sets Used to the terms the kept blocks' layers support; returns their number.
  int chooseTerms(const std::vector<ShadingBlock>& blocks);
  /// Weighted least squares of the kept blocks' log levels (false: fewer than `minimumBlocks`,
  /// or singular).
  bool leastSquares(const std::vector<ShadingBlock>& blocks, int minimumBlocks);
  /// The fit, the far blocks dropped and the fit redone (Parameters::fitIterations at most).
  bool fitRobustly(std::vector<ShadingBlock>& blocks, const Parameters& p);
  /// The polynomial's terms at normalised position u (each axis in [-1, 1] over the volume).
  void terms(const double u[3], double t[kTerms]) const;
  double logGain(double i, double j, double k) const;

  bool Active = false;
  std::string Why;   ///< why the field is inactive before its gate ("" when fitted)
  double Gate = 0.0; ///< Parameters::minimumGainRatio of the fit
  double GainRatio = 1.0;
  int BlocksUsed = 0;
  double Minimum = 0.0;
  double Reference = 0.0; ///< the log gain subtracted (setReference)
  double SpanLow = 1.0, SpanHigh = 1.0;
  std::array<double, 3> Centre{ 0.0, 0.0, 0.0 }, HalfExtent{ 1.0, 1.0, 1.0 };
  std::array<bool, kTerms> Used{};
  std::array<double, kTerms> Coefficients{};
  std::vector<std::array<double, 3>> BlockCentres; ///< the blocks the fit kept
};

template<typename T>
std::vector<ShadingField::Sample> ShadingField::sampleOf(const VolumeView<T>& volume,
  std::uint64_t stride)
{
  std::vector<Sample> s;
  const std::uint64_t n = volume.size();
  stride = stride == 0 ? 1 : stride;
  s.reserve(static_cast<std::size_t>(n / stride + 1));
  for (std::uint64_t i = 0; i < n; i += stride)
  {
    s.push_back({ i, static_cast<double>(volume.voxels[i]) });
  }
  return s;
}

template<typename T>
void ShadingField::correct(const VolumeView<T>& piece,
  const std::array<std::int64_t, 3>& pieceOrigin,
  T* out) const
{
  const double lowest = static_cast<double>(std::numeric_limits<T>::lowest());
  const double highest = static_cast<double>(std::numeric_limits<T>::max());
  const std::int64_t first = pieceOrigin[0], last = pieceOrigin[0] + piece.dims[0] - 1;
  for (std::int64_t k = 0; k < piece.dims[2]; ++k)
    for (std::int64_t j = 0; j < piece.dims[1]; ++j)
    {
      // Along a row the log gain is a quadratic of the whole volume's i: the gain by a product
      // recurrence from i = 0 (two multiplications a voxel instead of an exp; every piece that
      // holds the voxel runs the same recurrence from the same start, so a distributed rank
      // gets the single run's value bit for bit).
      RowRecurrence row = this->rowRecurrence(j + pieceOrigin[1], k + pieceOrigin[2]);
      for (std::int64_t i = 0; i < first; ++i)
      {
        row.step();
      }
      const T* in = piece.voxels + piece.linear(0, j, k);
      T* to = out + piece.linear(0, j, k);
      for (std::int64_t i = first; i <= last; ++i, row.step())
      {
        const double g = std::min(this->SpanHigh, std::max(this->SpanLow, row.gain));
        double v = this->Minimum + (static_cast<double>(in[i - first]) - this->Minimum) / g;
        if constexpr (std::is_integral_v<T>)
        {
          v = std::min(highest, std::max(lowest, std::round(v)));
        }
        to[i - first] = static_cast<T>(v);
      }
    }
}

} // namespace vtouch
