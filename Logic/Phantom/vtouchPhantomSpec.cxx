#include "vtouchPhantomSpec.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace vtouch
{

const char* toString(PhantomShape shape)
{
  switch (shape)
  {
    case PhantomShape::Circle:
      return "Circle";
    case PhantomShape::WindingLine:
      return "WindingLine";
    case PhantomShape::Helix:
      return "Helix";
    case PhantomShape::StraightTube:
      return "StraightTube";
    case PhantomShape::YBifurcation:
      return "YBifurcation";
    case PhantomShape::Tree:
      return "Tree";
    case PhantomShape::LoopNetwork:
      return "LoopNetwork";
    case PhantomShape::Column:
      return "Column";
    case PhantomShape::RawAngiogram:
      return "RawAngiogram";
  }
  return "Unknown";
}

double PhantomSpec::referenceLength_mm() const
{
  double n = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    n = std::min(n, (this->dimensions[a] - 1) * this->spacing_mm[a]);
  }
  return n;
}

std::string PhantomSpec::validate() const
{
  std::ostringstream msg;
  const int shapeValue = static_cast<int>(this->shape);
  if (shapeValue < 0 || shapeValue > static_cast<int>(PhantomShape::RawAngiogram))
  {
    msg << "unknown phantom shape " << shapeValue;
    return msg.str();
  }
  double voxelCount = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (this->dimensions[a] < 3)
    {
      msg << "dimension " << a << " is " << this->dimensions[a]
          << " voxels; a 3D phantom needs at least 3 voxels on every axis";
      return msg.str();
    }
    if (!std::isfinite(this->spacing_mm[a]) || this->spacing_mm[a] <= 0.0)
    {
      msg << "spacing " << a << " is " << this->spacing_mm[a] << " mm; it must be finite and > 0";
      return msg.str();
    }
    if (!std::isfinite(this->origin_mm[a]))
    {
      msg << "origin " << a << " is not finite";
      return msg.str();
    }
    voxelCount *= this->dimensions[a];
  }
  // 2^31 voxels is 8 GiB of float: far beyond any angiogram this phantom stands in for.
  if (voxelCount > 2147483647.0)
  {
    msg << "the volume has " << voxelCount << " voxels; at most 2^31 - 1 are supported";
    return msg.str();
  }
  const double minSpacing =
    std::min({ this->spacing_mm[0], this->spacing_mm[1], this->spacing_mm[2] });
  const double n = this->referenceLength_mm();
  if (!std::isfinite(this->radiusFraction) || this->radiusFraction <= 0.0 ||
      this->radiusFraction > 0.25)
  {
    msg << "radius fraction " << this->radiusFraction
        << " must be in (0, 0.25] of the smallest volume side (a larger vessel does not fit)";
    return msg.str();
  }
  if (this->shape != PhantomShape::Column && this->radiusFraction * n < 0.5 * minSpacing)
  {
    msg << "vessel radius " << this->radiusFraction * n << " mm is below half a voxel ("
        << 0.5 * minSpacing << " mm): the vessel would not be sampled";
    return msg.str();
  }
  if (!std::isfinite(this->taperRatio) || this->taperRatio <= 0.0 || this->taperRatio > 10.0)
  {
    msg << "taper ratio " << this->taperRatio << " must be in (0, 10]";
    return msg.str();
  }
  if (!std::isfinite(this->helixRadiusFraction) || this->helixRadiusFraction <= 0.0 ||
      this->helixRadiusFraction > 0.45 || !std::isfinite(this->helixPitchFraction) ||
      this->helixPitchFraction <= 0.0 || !std::isfinite(this->helixTurns) ||
      this->helixTurns <= 0.0 || this->helixTurns > 100.0 ||
      this->helixPitchFraction * this->helixTurns > 0.95)
  {
    msg << "helix parameters (radius " << this->helixRadiusFraction << ", pitch "
        << this->helixPitchFraction << ", turns " << this->helixTurns
        << ") do not fit the volume: radius in (0, 0.45], pitch > 0, pitch x turns <= 0.95";
    return msg.str();
  }
  if (!std::isfinite(this->windingAmplitudeFraction) || this->windingAmplitudeFraction <= 0.0 ||
      this->windingAmplitudeFraction > 0.45 || !std::isfinite(this->windingPeriods) ||
      this->windingPeriods <= 0.0 || this->windingPeriods > 20.0)
  {
    msg << "winding line parameters (amplitude " << this->windingAmplitudeFraction << ", periods "
        << this->windingPeriods
        << ") do not fit the volume: amplitude in (0, 0.45], periods in (0, 20]";
    return msg.str();
  }
  if (this->treeDepth < 1 || this->treeDepth > 6)
  {
    msg << "tree depth " << this->treeDepth << " must be in 1..6";
    return msg.str();
  }
  if (!std::isfinite(this->treeRadiusRatio) || this->treeRadiusRatio <= 0.0 ||
      this->treeRadiusRatio > 1.0)
  {
    msg << "tree radius ratio " << this->treeRadiusRatio << " must be in (0, 1]";
    return msg.str();
  }
  for (double f : this->treeRadiusFractions)
  {
    if (!std::isfinite(f) || f <= 0.0 || f > 0.25)
    {
      msg << "tree radius fraction " << f << " must be in (0, 0.25]";
      return msg.str();
    }
  }
  const int profileValue = static_cast<int>(this->profile);
  if (profileValue < 0 || profileValue > static_cast<int>(Profile::Flat))
  {
    msg << "unknown intensity profile " << profileValue;
    return msg.str();
  }
  if (!std::isfinite(this->backgroundIntensity) || !std::isfinite(this->peakIntensity) ||
      this->backgroundIntensity < 0.0 || this->peakIntensity > 65535.0)
  {
    msg << "intensities (background " << this->backgroundIntensity << ", peak "
        << this->peakIntensity << ") must be finite and within [0, 65535]";
    return msg.str();
  }
  if (!std::isfinite(this->noiseStdDev) || this->noiseStdDev < 0.0)
  {
    msg << "noise standard deviation " << this->noiseStdDev << " must be finite and >= 0";
    return msg.str();
  }
  if (!std::isfinite(this->wallRoughness) || this->wallRoughness < 0.0 || this->wallRoughness > 0.5)
  {
    msg << "wall roughness " << this->wallRoughness << " must be in [0, 0.5]";
    return msg.str();
  }
  return this->validateAngiogram();
}

std::string PhantomSpec::validateAngiogram() const
{
  std::ostringstream msg;
  if (this->angiogramSegments < 1 || this->angiogramSegments > 2000)
  {
    msg << "angiogram segment count " << this->angiogramSegments << " must be in 1..2000";
    return msg.str();
  }
  if (!std::isfinite(this->angiogramSmallestRadius_vox) ||
      this->angiogramSmallestRadius_vox < 0.25 ||
      !std::isfinite(this->angiogramLargestRadius_vox) ||
      this->angiogramLargestRadius_vox < this->angiogramSmallestRadius_vox ||
      this->angiogramLargestRadius_vox > 20.0)
  {
    msg << "angiogram radii (smallest " << this->angiogramSmallestRadius_vox << ", largest "
        << this->angiogramLargestRadius_vox
        << " voxels) must satisfy 0.25 <= smallest <= largest <= 20";
    return msg.str();
  }
  if (this->shape == PhantomShape::RawAngiogram)
  {
    const double minSide =
      std::min({ this->dimensions[0], this->dimensions[1], this->dimensions[2] });
    if (minSide < 8.0 * this->angiogramLargestRadius_vox + 8.0)
    {
      msg << "a raw angiogram with a root of radius " << this->angiogramLargestRadius_vox
          << " voxels needs at least " << 8.0 * this->angiogramLargestRadius_vox + 8.0
          << " voxels on every axis";
      return msg.str();
    }
  }
  const int noise = static_cast<int>(this->noiseModel);
  if (noise < 0 || noise > static_cast<int>(NoiseModel::Rician))
  {
    msg << "unknown noise model " << noise << " (0 Gaussian, 1 Rician)";
    return msg.str();
  }
  if (!std::isfinite(this->biasAmplitude) || this->biasAmplitude < 0.0 || this->biasAmplitude > 0.9)
  {
    msg << "bias amplitude " << this->biasAmplitude << " must be in [0, 0.9]";
    return msg.str();
  }
  if (this->clutterCount < 0 || this->clutterCount > 200)
  {
    msg << "clutter count " << this->clutterCount << " must be in 0..200";
    return msg.str();
  }
  if (!std::isfinite(this->tissueIntensity) || this->tissueIntensity < 0.0 ||
      this->tissueIntensity > 65535.0)
  {
    msg << "tissue intensity " << this->tissueIntensity << " must be within [0, 65535]";
    return msg.str();
  }
  return {};
}

} // namespace vtouch
