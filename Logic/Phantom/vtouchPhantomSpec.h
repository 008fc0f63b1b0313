// Parameters of a synthetic angiogram. Every length is in millimetres unless the name says voxels.
#pragma once

#include "vtouchVector.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

/// The vessel shapes of the built-in phantom. Circle, WindingLine and Helix are the three synthetic
/// objects of Yi & Hayward; the others cover bifurcations, trees, loops and a thin column.
enum class PhantomShape : int
{
  Circle = 0, ///< a ring in a plane tilted 60 deg from the view plane (a narrow oval on screen)
  WindingLine = 1,  ///< a line oscillating in the x-z plane (edge-on from +z it shows cusps)
  Helix = 2,        ///< a helix around the volume's z axis
  StraightTube = 3, ///< a straight tube along x
  YBifurcation = 4, ///< one trunk splitting into two branches
  Tree = 5,         ///< a binary tree of depth TreeDepth (>= 3): 2^depth - 1 segments
  LoopNetwork = 6,  ///< a ring with two inflow and two outflow vessels (circle-of-Willis-like)
  Column = 7, ///< a 4x4-voxel square column through the whole z extent (thinning failure case)
  /// A raw angiogram: a seeded random bifurcating tree (Murray's law, curved segments, radii
  /// from angiogramLargestRadius_vox down to angiogramSmallestRadius_vox) rasterised as the
  /// fraction of each voxel inside a vessel, over tissue, with bone-like plates and blobs at
  /// vessel intensity touching the vessels, a smooth bias field and Gaussian or Rician noise.
  /// The centerline (port 1) is the tree only; path 0 is the root, its first point the seed.
  RawAngiogram = 8
};

const char* toString(PhantomShape shape);

/// Everything that defines one phantom. Geometry is placed relative to the volume's physical extent
/// (N = the smallest physical side), so a spec scales with the grid.
struct PhantomSpec
{
  PhantomShape shape = PhantomShape::Helix;
  std::array<int, 3> dimensions{ 96, 96, 96 };       ///< voxels per axis (each >= 3)
  std::array<double, 3> spacing_mm{ 1.0, 1.0, 1.0 }; ///< voxel size per axis (> 0, finite)
  std::array<double, 3> origin_mm{ 0.0, 0.0, 0.0 };  ///< world position of voxel (0,0,0)

  /// Vessel radius as a fraction of N (the smallest physical side). Tree segments scale it down
  /// by TreeRadiusRatio per generation; the helix defaults follow the benchmark of issue 3.
  double radiusFraction = 0.05;
  /// Radius at the far end of a vessel divided by the radius at its start (1 = no taper).
  double taperRatio = 1.0;

  /// Helix: coil radius and pitch (advance per turn) as fractions of N, and number of turns.
  double helixRadiusFraction = 0.3;
  double helixPitchFraction = 0.25;
  double helixTurns = 3.0;

  /// WindingLine: amplitude of the oscillation as a fraction of N, and number of periods over
  /// the line's 0.8 N. The crests bend with a radius of curvature 0.64 N / (amplitude (2 pi
  /// periods)^2): with the defaults 0.02 N, tighter than the default vessel radius, so the tube
  /// folds onto itself at every crest (Yi & Hayward's object shows projection cusps; its mask has
  /// no single medial axis there). Amplitude 0.1 and one period give 0.16 N: a sinuous vessel.
  double windingAmplitudeFraction = 0.2;
  double windingPeriods = 2.0;

  int treeDepth = 3;            ///< Tree generations (1..6); 3 gives seven segments
  double treeRadiusRatio = 0.8; ///< child radius / parent radius in the tree
  /// Optional explicit radius fraction per tree generation (overrides radiusFraction and
  /// treeRadiusRatio when non-empty; e.g. {0.055, 0.045, 0.035}).
  std::vector<double> treeRadiusFractions;

  /// Cross-section profile P(d/r) of a vessel, d = distance to the centerline, r = local radius.
  /// Gaussian: P = 2^-(d/r)^2 (half maximum at the wall d = r, background beyond 3 r).
  /// Flat: a contrast-filled lumen with a partial-volume edge, P = 0.5 erfc((d - r) / (0.5 voxel))
  /// (also half maximum at the wall). Intensity = background + (peak - background) * P + noise.
  enum class Profile : int
  {
    Gaussian = 0,
    Flat = 1
  };
  Profile profile = Profile::Gaussian;
  double backgroundIntensity = 100.0;
  double peakIntensity = 1000.0;
  double noiseStdDev = 0.0;   ///< standard deviation of additive Gaussian noise
  std::uint32_t seed = 1;     ///< noise seed: same seed, same volume
  double wallRoughness = 0.0; ///< radius modulation amplitude as a fraction of the radius

  /// RawAngiogram: tree, tissue, clutter, bias and noise model (see vtouchVascularTreeGenerator.h,
  /// vtouchPhantomClutter.h and vtouchAngiogramRasterizer.h). Radii are in voxels of the
  /// smallest spacing. The intensity is bias * (base + (peak - base) * f) + noise, where f is the
  /// fraction of the voxel inside a vessel or clutter and base is tissueIntensity inside the body
  /// (an ellipsoid filling the volume) and backgroundIntensity outside it (the corners).
  enum class NoiseModel : int
  {
    Gaussian = 0, ///< additive, standard deviation noiseStdDev
    Rician = 1    ///< magnitude of a complex signal with Gaussian noise on both channels (MRA)
  };
  int angiogramSegments = 200;              ///< target number of tree segments (1..2000)
  double angiogramLargestRadius_vox = 4;    ///< root radius
  double angiogramSmallestRadius_vox = 0.5; ///< no vessel is thinner
  NoiseModel noiseModel = NoiseModel::Gaussian;
  double biasAmplitude = 0.1;     ///< multiplicative bias field 1 +/- biasAmplitude (smooth)
  int clutterCount = 8;           ///< bone-like plates and blobs touching the vessels (alternating)
  double tissueIntensity = 400.0; ///< intensity of the soft tissue around the vessels

  /// Returns an empty string when the spec is usable, else a sentence saying what is wrong.
  std::string validate() const;
  /// The RawAngiogram parameters' part of validate().
  std::string validateAngiogram() const;

  /// N: the smallest physical side of the volume in millimetres.
  double referenceLength_mm() const;
};

} // namespace vtouch
