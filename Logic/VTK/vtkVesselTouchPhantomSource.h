// VesselPhantom: a synthetic angiogram (port 0, vtkImageData) and its analytic centerline
// (port 1, vtkPolyData: one polyline per vessel, point array "Radius" in mm).
#ifndef vtkVesselTouchPhantomSource_h
#define vtkVesselTouchPhantomSource_h

#include "vtkImageAlgorithm.h"
#include "vtkVesselTouchLogicModule.h" // for export macro

class VTKVESSELTOUCHLOGIC_EXPORT vtkVesselTouchPhantomSource : public vtkImageAlgorithm
{
public:
  static vtkVesselTouchPhantomSource* New();
  vtkTypeMacro(vtkVesselTouchPhantomSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Vessel shape, a vtouch::PhantomShape: 0 Circle, 1 WindingLine, 2 Helix, 3 StraightTube,
  /// 4 YBifurcation, 5 Tree (default), 6 LoopNetwork, 7 Column, 8 RawAngiogram (a random
  /// vascular tree with partial volume, tissue, clutter, bias and noise; port 1 holds the tree
  /// only, its first point is on the root: the place to seed an extraction).
  vtkSetMacro(Shape, int);
  vtkGetMacro(Shape, int);

  /// Voxels per axis (default 128 128 128; each >= 3).
  vtkSetVector3Macro(Dimensions, int);
  vtkGetVector3Macro(Dimensions, int);

  /// Voxel size in mm per axis (default 1 1 1; anisotropic allowed).
  vtkSetVector3Macro(Spacing, double);
  vtkGetVector3Macro(Spacing, double);

  /// World position of voxel (0,0,0) in mm (default 0 0 0).
  vtkSetVector3Macro(Origin, double);
  vtkGetVector3Macro(Origin, double);

  /// Vessel radius as a fraction of the smallest physical side N (default 0.05).
  vtkSetMacro(RadiusFraction, double);
  vtkGetMacro(RadiusFraction, double);

  /// End radius / start radius of each vessel (default 1: no taper).
  vtkSetMacro(TaperRatio, double);
  vtkGetMacro(TaperRatio, double);

  /// Helix coil radius and pitch as fractions of N, and number of turns (0.3, 0.25, 3).
  vtkSetMacro(HelixRadiusFraction, double);
  vtkGetMacro(HelixRadiusFraction, double);
  vtkSetMacro(HelixPitchFraction, double);
  vtkGetMacro(HelixPitchFraction, double);
  vtkSetMacro(HelixTurns, double);
  vtkGetMacro(HelixTurns, double);

  /// Winding line: oscillation amplitude as a fraction of N (0.2) and number of periods (2).
  /// The defaults fold the tube at its crests (see vtouchPhantomSpec.h); 0.1 and 1 give a
  /// sinuous vessel.
  vtkSetMacro(WindingAmplitudeFraction, double);
  vtkGetMacro(WindingAmplitudeFraction, double);
  vtkSetMacro(WindingPeriods, double);
  vtkGetMacro(WindingPeriods, double);

  /// Tree generations (default 3: seven segments) and child/parent radius ratio (0.8).
  vtkSetMacro(TreeDepth, int);
  vtkGetMacro(TreeDepth, int);
  vtkSetMacro(TreeRadiusRatio, double);
  vtkGetMacro(TreeRadiusRatio, double);

  /// Cross-section: 0 Gaussian (default), 1 flat lumen with a partial-volume edge.
  vtkSetMacro(Profile, int);
  vtkGetMacro(Profile, int);

  /// Intensities of the background and of the vessel axis (100, 1000), noise sigma (10),
  /// noise seed (1) and wall roughness as a fraction of the radius (0).
  vtkSetMacro(BackgroundIntensity, double);
  vtkGetMacro(BackgroundIntensity, double);
  vtkSetMacro(PeakIntensity, double);
  vtkGetMacro(PeakIntensity, double);
  vtkSetMacro(NoiseStandardDeviation, double);
  vtkGetMacro(NoiseStandardDeviation, double);
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  vtkSetMacro(WallRoughness, double);
  vtkGetMacro(WallRoughness, double);

  /// RawAngiogram: target number of tree segments (200), root and smallest radii in voxels
  /// (4, 0.5), noise model (0 Gaussian, 1 Rician), multiplicative bias amplitude (0.1), number of
  /// bone-like plates and blobs touching the vessels (8) and tissue intensity (400). The vessel
  /// intensity is PeakIntensity; BackgroundIntensity is not used (the background is tissue).
  vtkSetMacro(AngiogramSegments, int);
  vtkGetMacro(AngiogramSegments, int);
  vtkSetMacro(AngiogramLargestRadius, double);
  vtkGetMacro(AngiogramLargestRadius, double);
  vtkSetMacro(AngiogramSmallestRadius, double);
  vtkGetMacro(AngiogramSmallestRadius, double);
  vtkSetMacro(NoiseModel, int);
  vtkGetMacro(NoiseModel, int);
  vtkSetMacro(BiasAmplitude, double);
  vtkGetMacro(BiasAmplitude, double);
  vtkSetMacro(ClutterCount, int);
  vtkGetMacro(ClutterCount, int);
  vtkSetMacro(TissueIntensity, double);
  vtkGetMacro(TissueIntensity, double);

  /// VTK_UNSIGNED_SHORT (default) or VTK_FLOAT.
  vtkSetMacro(OutputScalarType, int);
  vtkGetMacro(OutputScalarType, int);

protected:
  vtkVesselTouchPhantomSource();
  ~vtkVesselTouchPhantomSource() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkVesselTouchPhantomSource(const vtkVesselTouchPhantomSource&) = delete;
  void operator=(const vtkVesselTouchPhantomSource&) = delete;

  /// Empty when the parameters are usable, else the reason.
  std::string Validate() const;

  int Shape = 5;
  int Dimensions[3] = { 128, 128, 128 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double RadiusFraction = 0.05;
  double TaperRatio = 1.0;
  double HelixRadiusFraction = 0.3;
  double HelixPitchFraction = 0.25;
  double WindingAmplitudeFraction = 0.2;
  double WindingPeriods = 2.0;
  double HelixTurns = 3.0;
  int TreeDepth = 3;
  double TreeRadiusRatio = 0.8;
  int Profile = 0;
  double BackgroundIntensity = 100.0;
  double PeakIntensity = 1000.0;
  double NoiseStandardDeviation = 10.0;
  int Seed = 1;
  double WallRoughness = 0.0;
  int AngiogramSegments = 200;
  double AngiogramLargestRadius = 4.0;
  double AngiogramSmallestRadius = 0.5;
  int NoiseModel = 0;
  double BiasAmplitude = 0.1;
  int ClutterCount = 8;
  double TissueIntensity = 400.0;
  int OutputScalarType = VTK_UNSIGNED_SHORT;
};

#endif
