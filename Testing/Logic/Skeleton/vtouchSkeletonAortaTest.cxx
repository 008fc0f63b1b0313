// Real data: the VMTK aorta level set against VMTK's reference centerline, and the raw CTA.
#include "vtouchBranchEntry.h"
#include "vtouchRawSkeletonRefinement.h"
#include "vtouchVesselCandidateRegion.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtouchSkeletonTestSupport.h"
#include "vtouchVtpPoints.h"

#include <itkImageFileReader.h>
#include <itkMetaImageIOFactory.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>

namespace vtouch
{
namespace
{
using test::FloatImage;
using Filter = VoxelCodingSkeletonFilter<FloatImage>;

const std::string kDir = std::string(VTOUCH_SHARED_DATA_DIR) + "/vmtk-aorta/";

FloatImage::Pointer readImage(const std::string& name)
{
  itk::MetaImageIOFactory::RegisterOneFactory();
  auto reader = itk::ImageFileReader<FloatImage>::New();
  reader->SetFileName(kDir + name);
  reader->Update();
  return reader->GetOutput();
}

/// The reference centerline's frame flips both in-plane axes of the MetaImage world frame
/// (see ../shared/data/README.md): reference = (-x, -y, z).
Vec3 toReferenceFrame(const Vec3& p)
{
  return { -p.x, -p.y, p.z };
}

struct Comparison
{
  double mean_mm = 0.0;
  double p95_mm = 0.0;
  double coveredWithin1mm = 0.0;
};

Comparison compare(const QSkeleton& skeleton, const std::vector<Vec3>& reference)
{
  QSkeleton mapped = skeleton;
  for (SkeletonPath& path : mapped.paths)
  {
    for (SkeletonPoint& q : path.points)
    {
      q.position_World_mm = toReferenceFrame(q.position_World_mm);
    }
  }
  // Reference polylines: consecutive points closer than 3 mm belong to one line.
  QSkeleton ref;
  for (std::size_t i = 0; i < reference.size(); ++i)
  {
    if (i == 0 || (reference[i] - reference[i - 1]).norm() > 3.0)
    {
      ref.paths.emplace_back();
      ref.paths.back().id = static_cast<int>(ref.paths.size()) - 1;
    }
    SkeletonPoint q;
    q.position_World_mm = reference[i];
    ref.paths.back().points.push_back(q);
  }
  if (const char* dir = std::getenv("VTOUCH_SKELETON_DUMP"))
  {
    std::ofstream f(std::string(dir) + "/aorta.csv", std::ios::app);
    for (const SkeletonPath& path : mapped.paths)
      for (const SkeletonPoint& q : path.points)
        f << "out," << path.id << "," << q.position_World_mm.x << "," << q.position_World_mm.y
          << "," << q.position_World_mm.z << "," << q.radius_mm << "\n";
    for (const SkeletonPath& path : ref.paths)
      for (const SkeletonPoint& q : path.points)
        f << "ref," << path.id << "," << q.position_World_mm.x << "," << q.position_World_mm.y
          << "," << q.position_World_mm.z << ",0\n";
  }
  Comparison c;
  std::vector<double> d;
  for (const SkeletonPath& path : mapped.paths)
  {
    for (const SkeletonPoint& q : path.points)
    {
      d.push_back(test::distanceToSkeleton(ref, q.position_World_mm));
    }
  }
  c.mean_mm = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  std::sort(d.begin(), d.end());
  c.p95_mm = d[static_cast<std::size_t>(0.95 * d.size())];
  std::size_t covered = 0;
  for (const Vec3& p : reference)
  {
    covered += test::distanceToSkeleton(mapped, p) <= 1.0 ? 1 : 0;
  }
  c.coveredWithin1mm = static_cast<double>(covered) / static_cast<double>(reference.size());
  return c;
}

std::vector<Vec3> referenceCenterline()
{
  std::vector<Vec3> points;
  std::string error;
  EXPECT_TRUE(test::readVtpPoints(kDir + "aorta-centerline.vtp", points, error)) << error;
  return points;
}

TEST(VoxelCodingSkeletonFilter, AortaLevelSetMatchesVmtkCenterline)
{
  const std::vector<Vec3> reference = referenceCenterline();
  ASSERT_EQ(reference.size(), 409U);
  auto image = readImage("aorta-final-levelset.mha");
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(-1e30);
  filter->SetUpperThreshold(-1e-9); // the vessel is where the level set is negative
  filter->Update();
  const QSkeleton& s = filter->GetSkeleton();
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(filter->GetNumberOfVesselVoxels(), 11590U);
  const test::Topology t = test::topology(s, 5.0);
  const Comparison c = compare(s, reference);
  std::cout << "aorta level set: paths " << s.paths.size() << ", ends " << t.endPoints
            << ", bifurcations " << t.bifurcations << ", loops " << t.loops << "; mean "
            << c.mean_mm << " mm, p95 " << c.p95_mm << " mm, reference within 1 mm "
            << c.coveredWithin1mm << "\n";
  EXPECT_EQ(t.endPoints, 3);
  EXPECT_EQ(t.bifurcations, 1);
  EXPECT_EQ(t.loops, 0);
  EXPECT_LE(c.mean_mm, 0.5);
  // Regression guard at the level reached (0.973 since through paths are straightened beyond
  // their junctions): the remaining misses are at the iliac ends (VMTK stops at the base of the
  // flattened end cap, we at the medial-axis end, 1 radius from it) and at the aorta's top end.
  EXPECT_GE(c.coveredWithin1mm, 0.97);
}

// Issue 3 target (0.973 reached): see Docs/CENTERLINES.md.
TEST(VoxelCodingSkeletonFilter, AortaLevelSetCoversVmtkReferenceWithin1mm)
{
  const std::vector<Vec3> reference = referenceCenterline();
  auto image = readImage("aorta-final-levelset.mha");
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(-1e30);
  filter->SetUpperThreshold(-1e-9);
  filter->Update();
  EXPECT_GE(compare(filter->GetSkeleton(), reference).coveredWithin1mm, 0.95);
}

TEST(VoxelCodingSkeletonFilter, RawAortaCtaFromASeedAloneCoversTheVmtkReference)
{
  // The raw CTA with only a seed: VesselCandidateRegion estimates the range from the seed's
  // neighbourhood, grows the network and cuts non-tubular parts; the coder codes that mask.
  const std::vector<Vec3> reference = referenceCenterline();
  auto image = readImage("aorta.mha");
  Filter::PointType seed;
  const Vec3 p = toReferenceFrame(reference.front());
  seed[0] = p.x;
  seed[1] = p.y;
  seed[2] = p.z;
  FloatImage::IndexType seedIndex;
  ASSERT_TRUE(image->TransformPhysicalPointToIndex(seed, seedIndex));
  VolumeView<float> view;
  view.voxels = image->GetBufferPointer();
  const auto size = image->GetLargestPossibleRegion().GetSize();
  view.dims = { static_cast<std::int64_t>(size[0]),
    static_cast<std::int64_t>(size[1]),
    static_cast<std::int64_t>(size[2]) };
  for (unsigned a = 0; a < 3; ++a)
  {
    view.spacing_mm[a] = image->GetSpacing()[a];
  }
  VesselCandidateRegion::Settings settings;
  settings.useSeed = true;
  settings.seed = { seedIndex[0], seedIndex[1], seedIndex[2] };
  VesselCandidateRegion::Result region = VesselCandidateRegion::extract(view, settings);
  ASSERT_TRUE(region.ok) << region.message;
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetVesselMask(std::make_shared<const SparseVesselMask>(std::move(region.mask)));
  FloatImage::IndexType start{ { region.seed[0], region.seed[1], region.seed[2] } };
  image->TransformIndexToPhysicalPoint(start, seed);
  filter->SetSeedPoint(seed);
  filter->Update();
  // What VesselCenterline does after coding on the raw path: the tube's own sections re-trace
  // or cut the stretches clutter touches, then non-tube-like paths go (on the volume in range).
  QSkeleton s = filter->GetSkeleton();
  SectionGeometry geometry;
  for (unsigned r = 0; r < 3; ++r)
  {
    geometry.origin_mm[r] = image->GetOrigin()[r];
    geometry.spacing_mm[r] = image->GetSpacing()[r];
    for (unsigned c = 0; c < 3; ++c)
    {
      geometry.direction[3 * r + c] = image->GetDirection()[r][c];
    }
  }
  const float* voxels = image->GetBufferPointer();
  const double lower = region.range.lower, upper = region.range.upper;
  const SectionForeground inRange{ view.dims, [voxels, lower, upper](std::uint64_t lin) {
                                    return voxels[lin] >= lower && voxels[lin] <= upper;
                                  } };
  // Then free ends turned onto one dim noise voxel lose it (the intensities, the range's B and S).
  TurnedDimTipTrimmer::Evidence tips;
  tips.intensity = { view.dims, [voxels](std::uint64_t lin) { return double(voxels[lin]); } };
  tips.lower = lower;
  tips.background = region.range.background;
  tips.backgroundNoise = region.range.backgroundNoise;
  const RawSkeletonRefinement refined =
    RawSkeletonRefinement::apply(s, inRange, geometry, 0.0, &tips);
  // Last, each branch's entry into its parent on its own axis (placeBranchEntries).
  const BranchEntryReport entries = placeBranchEntries(s);
  EXPECT_EQ(s.validate(), "");
  const test::Topology t = test::topology(s, 5.0);
  const Comparison c = compare(s, reference);
  std::cout << "raw CTA from a seed, range [" << region.range.lower << ", " << region.range.upper
            << "]: vessel voxels " << filter->GetNumberOfVesselVoxels() << ", paths "
            << s.paths.size() << ", ends " << t.endPoints << ", bifurcations " << t.bifurcations
            << "; re-traced " << refined.tracked.stretchesTracked << ", cut "
            << refined.tracked.stretchesCut << ", removed " << refined.pruned.pathsRemoved
            << ", turned dim tips " << refined.tips.tipsTrimmed << ", branch entries placed "
            << entries.junctionsMoved << "; reference within 1 mm " << c.coveredWithin1mm << "\n";
  // Issue 16 asks 0.95 within 1 mm. Without the branch entries 0.9169: over the aorta's lowest
  // centimetre above the iliac carina the lumen is one flattened lobe, the coder's band there is
  // one cluster, and the left iliac's path crossed it sideways to the trunk 3 rows above the
  // carina while VMTK's line runs on along the iliac's axis to the aorta's (28 reference points
  // 1-3 mm off; Utilities/bench/cta_bifurcation_sections.py). With the iliac's axis carried on to
  // the aorta's: 0.985; the misses left are the seed's own end and the reference's cut ends
  // (1.0-1.3 mm). See Docs/CENTERLINES.md, "Raw angiograms", step 7.
  EXPECT_GE(c.coveredWithin1mm, 0.95);
  EXPECT_GE(entries.junctionsMoved, 1u);
  EXPECT_EQ(t.loops, 0); // a tree: no false ring through tissue at vessel intensity
}

} // namespace
} // namespace vtouch
