#include "vtouchVolumeIO.h"

#include "vtouchTestVolumes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using vtouch::test::TestGeometry;

namespace
{
class VolumeIO : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    Dir = fs::temp_directory_path() /
          ("vtouchVolumeIOTest-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
    fs::remove_all(Dir);
    fs::create_directories(Dir);
  }
  void TearDown() override { fs::remove_all(Dir); }
  std::string path(const std::string& name) const { return (Dir / name).string(); }

  fs::path Dir;
};

std::vector<std::int16_t> readAll(vtouch::VolumeSource& source)
{
  std::vector<std::int16_t> voxels(source.header().geometry.voxelCount());
  EXPECT_EQ(source.header().voxelType, vtouch::VoxelType::Int16);
  EXPECT_TRUE(source.read(voxels.data(), voxels.size() * sizeof(std::int16_t), nullptr));
  return voxels;
}

void expectGeometry(const vtouch::VolumeGeometry& got, const TestGeometry& want, double tol)
{
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_EQ(got.dimensions[a], want.size[a]) << "axis " << a;
    EXPECT_NEAR(got.spacing_mm[a], want.spacing_mm[a], tol) << "axis " << a;
    EXPECT_NEAR(got.origin_mm[a], want.origin_LPS_mm[a], tol) << "axis " << a;
  }
  for (int e = 0; e < 9; ++e)
  {
    EXPECT_NEAR(got.direction[e], want.direction[e], tol) << "direction element " << e;
  }
}

void expectVoxels(const std::vector<std::int16_t>& voxels, const TestGeometry& g)
{
  for (unsigned k = 0; k < g.size[2]; ++k)
    for (unsigned j = 0; j < g.size[1]; ++j)
      for (unsigned i = 0; i < g.size[0]; ++i)
      {
        const std::size_t at = i + g.size[0] * (j + g.size[1] * k);
        ASSERT_EQ(voxels[at], vtouch::test::testVoxelValue(i, j, k)) << i << " " << j << " " << k;
      }
}

std::string errorOf(const std::string& path, const vtouch::VolumeOpenOptions& options = {})
{
  try
  {
    auto source = vtouch::openVolume(path, options);
    std::vector<char> buffer(source->header().byteCount());
    source->read(buffer.data(), buffer.size(), nullptr);
  }
  catch (const vtouch::VolumeIOError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(VolumeGeometry, WorldPositionAppliesDirectionToScaledIndex)
{
  vtouch::VolumeGeometry g;
  g.spacing_mm = { { 2.0, 3.0, 4.0 } };
  g.origin_mm = { { 10.0, 20.0, 30.0 } };
  g.direction = { { 0, -1, 0, 1, 0, 0, 0, 0, 1 } }; // axis i -> +y, axis j -> -x
  const auto p = g.worldPosition(1, 1, 1);
  EXPECT_DOUBLE_EQ(p[0], 10.0 - 3.0);
  EXPECT_DOUBLE_EQ(p[1], 20.0 + 2.0);
  EXPECT_DOUBLE_EQ(p[2], 30.0 + 4.0);
}

TEST(VolumeGeometry, RasFrameNegatesXAndYOfPointsAndDirections)
{
  vtouch::VolumeGeometry g;
  g.origin_mm = { { -156.445, -24.6094, 0.0 } };
  g.direction = { { -1, 0, 0, 0, -1, 0, 0, 0, 1 } };
  g.spacing_mm = { { 0.878906, 0.878906, 1.50009 } };
  const auto ras = g.inFrame(vtouch::WorldFrame::RAS);
  const auto p = ras.worldPosition(10, 20, 3);
  // The VMTK aorta's reference frame (shared/data/README.md).
  EXPECT_NEAR(p[0], 156.445 + 0.878906 * 10, 1e-9);
  EXPECT_NEAR(p[1], 24.6094 + 0.878906 * 20, 1e-9);
  EXPECT_NEAR(p[2], 1.50009 * 3, 1e-9);
}

TEST_F(VolumeIO, ObliqueAnisotropicVolumeKeepsGeometryInEveryFormat)
{
  const TestGeometry g = vtouch::test::obliqueGeometry();
  for (const char* name : { "v.nrrd", "v.nhdr", "v.nii", "v.nii.gz", "v.mha", "v.mhd" })
  {
    SCOPED_TRACE(name);
    vtouch::test::writeVolume(path(name), g);
    auto source = vtouch::openVolume(path(name));
    // NIfTI stores its matrices in float32.
    expectGeometry(source->header().geometry, g, 1e-4);
    expectVoxels(readAll(*source), g);
  }
}

TEST_F(VolumeIO, VoxelTypesAreKept)
{
  const TestGeometry g;
  const std::pair<const char*, vtouch::VoxelType> types[] = { { "int8", vtouch::VoxelType::Int8 },
    { "uint8", vtouch::VoxelType::UInt8 },
    { "int16", vtouch::VoxelType::Int16 },
    { "uint16", vtouch::VoxelType::UInt16 },
    { "int32", vtouch::VoxelType::Int32 },
    { "uint32", vtouch::VoxelType::UInt32 },
    { "float", vtouch::VoxelType::Float32 },
    { "double", vtouch::VoxelType::Float64 } };
  for (const auto& [pixel, type] : types)
  {
    SCOPED_TRACE(pixel);
    const std::string file = path(std::string(pixel) + ".nrrd");
    vtouch::test::writeVolume(file, g, pixel);
    auto source = vtouch::openVolume(file);
    EXPECT_EQ(source->header().voxelType, type);
    std::vector<char> buffer(source->header().byteCount());
    ASSERT_TRUE(source->read(buffer.data(), buffer.size(), nullptr));
    if (type == vtouch::VoxelType::Float64)
    {
      double last;
      std::memcpy(&last, buffer.data() + buffer.size() - sizeof(double), sizeof(double));
      EXPECT_EQ(last, vtouch::test::testVoxelValue(5, 4, 3));
    }
  }
}

TEST_F(VolumeIO, DicomSeriesIsOrderedByPositionNotFileName)
{
  const TestGeometry g = vtouch::test::obliqueGeometry();
  vtouch::test::writeDicomSeries(path("series"), g, "1.2.826.0.1.3680043.2.1125.7.1");
  for (const std::string& input : { path("series"), path("series/IM0002") })
  {
    SCOPED_TRACE(input);
    auto source = vtouch::openVolume(input);
    EXPECT_EQ(source->header().format, "DICOM series");
    expectGeometry(source->header().geometry, g, 1e-4);
    expectVoxels(readAll(*source), g);
  }
}

TEST_F(VolumeIO, DicomFolderWithTwoSeriesReadsTheLargestOrTheOneAsked)
{
  TestGeometry big;
  TestGeometry small;
  small.size = { { 6, 5, 3 } };
  small.origin_LPS_mm = { { 0.0, 0.0, -40.0 } };
  vtouch::test::writeDicomSeries(path("mixed"), big, "1.2.826.0.1.3680043.2.1125.7.2", -1, "A");
  vtouch::test::writeDicomSeries(path("mixed"), small, "1.2.826.0.1.3680043.2.1125.7.3", -1, "B");
  const auto list = vtouch::listDicomSeries(path("mixed"));
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].seriesInstanceUID, "1.2.826.0.1.3680043.2.1125.7.2");
  EXPECT_EQ(list[0].fileCount, 4u);

  auto largest = vtouch::openVolume(path("mixed"));
  EXPECT_EQ(largest->header().geometry.dimensions[2], 4u);
  ASSERT_EQ(largest->header().warnings.size(), 1u);
  EXPECT_NE(largest->header().warnings[0].find("2 DICOM series"), std::string::npos);

  vtouch::VolumeOpenOptions options;
  options.seriesInstanceUID = "1.2.826.0.1.3680043.2.1125.7.3";
  auto asked = vtouch::openVolume(path("mixed"), options);
  expectGeometry(asked->header().geometry, small, 1e-6);
  expectVoxels(readAll(*asked), small);

  // A file of the small series selects the small series.
  auto byFile = vtouch::openVolume(path("mixed/B0000"));
  EXPECT_EQ(byFile->header().geometry.dimensions[2], 3u);

  options.seriesInstanceUID = "1.2.3.4";
  EXPECT_NE(errorOf(path("mixed"), options).find("is not in"), std::string::npos);
}

TEST_F(VolumeIO, DicomSeriesWithAMissingSliceIsReportedNotStitched)
{
  TestGeometry g;
  g.size = { { 6, 5, 6 } };
  vtouch::test::writeDicomSeries(path("gap"), g, "1.2.826.0.1.3680043.2.1125.7.4", 3);
  const std::string error = errorOf(path("gap"));
  EXPECT_NE(error.find("about 1 missing slice"), std::string::npos) << error;
}

TEST_F(VolumeIO, DicomSeriesWithTwoSlicesAtOnePositionIsRejected)
{
  TestGeometry g;
  vtouch::test::writeDicomSeries(path("dup"), g, "1.2.826.0.1.3680043.2.1125.7.5", -1, "A");
  vtouch::test::writeDicomSeries(path("dup"), g, "1.2.826.0.1.3680043.2.1125.7.5", -1, "B");
  const std::string error = errorOf(path("dup"));
  EXPECT_NE(error.find("same position"), std::string::npos) << error;
}

TEST_F(VolumeIO, DicomSeriesMixingOrientationsIsRejected)
{
  TestGeometry axial;
  TestGeometry oblique = vtouch::test::obliqueGeometry();
  oblique.origin_LPS_mm = { { 0.0, 0.0, -60.0 } };
  vtouch::test::writeDicomSeries(path("mix"), axial, "1.2.826.0.1.3680043.2.1125.7.7", -1, "A");
  vtouch::test::writeDicomSeries(path("mix"), oblique, "1.2.826.0.1.3680043.2.1125.7.7", -1, "B");
  const std::string error = errorOf(path("mix"));
  EXPECT_NE(error.find("mixes slice orientations"), std::string::npos) << error;
}

TEST_F(VolumeIO, DicomSeriesOfOneSliceIsA2DImage)
{
  TestGeometry g;
  g.size = { { 6, 5, 1 } };
  vtouch::test::writeDicomSeries(path("one"), g, "1.2.826.0.1.3680043.2.1125.7.8");
  const std::string error = errorOf(path("one"));
  EXPECT_NE(error.find("single 2D slice"), std::string::npos) << error;
}

TEST_F(VolumeIO, BadInputGivesAClearError)
{
  vtouch::test::write2D(path("flat.mha"));
  EXPECT_NE(errorOf(path("flat.mha")).find("2D image"), std::string::npos);
  vtouch::test::write4D(path("time.nrrd"));
  EXPECT_NE(errorOf(path("time.nrrd")).find("4D image"), std::string::npos);
  vtouch::test::writeVector(path("vector.mha"));
  EXPECT_NE(errorOf(path("vector.mha")).find("3 components"), std::string::npos);
  vtouch::test::writeVolume(path("big.nrrd"), TestGeometry(), "int64");
  EXPECT_NE(errorOf(path("big.nrrd")).find("unsupported pixel type"), std::string::npos);
  EXPECT_NE(errorOf(path("none.nii.gz")).find("does not exist"), std::string::npos);
  {
    std::ofstream(path("junk.nrrd")) << "this is not a NRRD header\n";
  }
  EXPECT_FALSE(errorOf(path("junk.nrrd")).empty());
  {
    std::ofstream(path("notes.txt")) << "hello\n";
  }
  EXPECT_NE(errorOf(path("notes.txt")).find("neither a DICOM"), std::string::npos);
}

TEST_F(VolumeIO, TruncatedFilesGiveAnErrorInEveryFormat)
{
  TestGeometry g;
  g.size = { { 32, 32, 16 } };
  for (const char* name : { "t.nrrd", "t.mha", "t.nii", "t.nii.gz" })
  {
    SCOPED_TRACE(name);
    vtouch::test::writeVolume(path(name), g);
    fs::resize_file(path(name), fs::file_size(path(name)) * 2 / 3);
    EXPECT_FALSE(errorOf(path(name)).empty());
  }
  vtouch::test::writeDicomSeries(path("cut"), g, "1.2.826.0.1.3680043.2.1125.7.6");
  fs::resize_file(path("cut/IM0005"), fs::file_size(path("cut/IM0005")) / 2);
  EXPECT_FALSE(errorOf(path("cut")).empty());
}
