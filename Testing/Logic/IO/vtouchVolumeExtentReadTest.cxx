// Parts of a volume read alone (issue 19, "readers that stream"): every format gives the same
// voxels for a box as the whole read does, uncompressed files and DICOM series read no more than
// the box needs, compressed files say that they are decoded whole, and hand-written headers with
// the formats' less common layouts (big-endian voxels, byte and line skips, detached data) read
// right.
#include "vtouchVolumeIO.h"

#include "vtouchTestExtents.h"
#include "vtouchTestVolumes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using vtouch::VoxelExtent;
using vtouch::test::box;
using vtouch::test::TestGeometry;

namespace
{
class VolumeExtentRead : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    Dir = fs::temp_directory_path() / ("vtouchVolumeExtentReadTest-" + std::string(info->name()) +
                                        "-" + std::to_string(::getpid()));
    fs::remove_all(Dir);
    fs::create_directories(Dir);
  }
  void TearDown() override { fs::remove_all(Dir); }
  std::string path(const std::string& name) const { return (Dir / name).string(); }

  fs::path Dir;
};

/// The boxes a parallel reader asks for: a corner, whole rows, whole slices, one voxel, the whole.
std::vector<VoxelExtent> testBoxes(const TestGeometry& g)
{
  const std::size_t nx = g.size[0];
  const std::size_t ny = g.size[1];
  const std::size_t nz = g.size[2];
  return { box(1, 3, 2, 3, 1, 2),
    box(0, nx - 1, 1, 3, 0, 1),
    box(0, nx - 1, 0, ny - 1, 2, nz - 1),
    box(4, 4, 0, 0, 3, 3),
    box(0, nx - 1, 0, ny - 1, 0, nz - 1) };
}

template<typename T>
void expectBoxValues(const std::vector<T>& voxels, const VoxelExtent& e, double scale = 1.0)
{
  std::size_t at = 0;
  for (std::size_t k = e.first[2]; k <= e.last[2]; ++k)
    for (std::size_t j = e.first[1]; j <= e.last[1]; ++j)
      for (std::size_t i = e.first[0]; i <= e.last[0]; ++i, ++at)
      {
        const double want =
          scale * vtouch::test::testVoxelValue(
                    static_cast<unsigned>(i), static_cast<unsigned>(j), static_cast<unsigned>(k));
        ASSERT_EQ(static_cast<double>(voxels[at]), want) << i << " " << j << " " << k;
      }
  EXPECT_EQ(at, voxels.size());
}

std::vector<std::int16_t> readBox(vtouch::VolumeSource& source, const VoxelExtent& e)
{
  std::vector<std::int16_t> voxels(e.voxelCount());
  EXPECT_TRUE(source.readExtent(e, voxels.data(), voxels.size() * sizeof(std::int16_t), nullptr));
  return voxels;
}

std::string extentError(vtouch::VolumeSource& source, const VoxelExtent& e)
{
  std::vector<char> buffer(source.header().byteCount());
  try
  {
    source.readExtent(e, buffer.data(), buffer.size(), nullptr);
  }
  catch (const vtouch::VolumeIOError& error)
  {
    return error.what();
  }
  return "";
}

/// Big-endian int16 bytes of the test volume, x fastest.
std::string bigEndianVoxels(const TestGeometry& g)
{
  std::string bytes;
  for (unsigned k = 0; k < g.size[2]; ++k)
    for (unsigned j = 0; j < g.size[1]; ++j)
      for (unsigned i = 0; i < g.size[0]; ++i)
      {
        const auto v = static_cast<std::uint16_t>(vtouch::test::testVoxelValue(i, j, k));
        bytes.push_back(static_cast<char>(v >> 8));
        bytes.push_back(static_cast<char>(v & 0xff));
      }
  return bytes;
}
} // namespace

TEST_F(VolumeExtentRead, EveryFormatGivesTheWholeReadsVoxelsForABox)
{
  const TestGeometry g = vtouch::test::obliqueGeometry();
  for (const char* name : { "v.nrrd", "v.nhdr", "v.nii", "v.nii.gz", "v.mha", "v.mhd" })
  {
    SCOPED_TRACE(name);
    vtouch::test::writeVolume(path(name), g);
    auto source = vtouch::openVolume(path(name));
    for (const VoxelExtent& e : testBoxes(g))
    {
      expectBoxValues(readBox(*source, e), e);
    }
  }
}

TEST_F(VolumeExtentRead, UncompressedFilesReadOnlyTheBoxesBytes)
{
  const TestGeometry g = vtouch::test::obliqueGeometry();
  for (const char* name : { "v.nrrd", "v.nhdr", "v.nii", "v.mha", "v.mhd" })
  {
    SCOPED_TRACE(name);
    vtouch::test::writeVolume(path(name), g);
    auto source = vtouch::openVolume(path(name));
    EXPECT_TRUE(source->readsExtentsAlone());
    for (const VoxelExtent& e : testBoxes(g))
    {
      readBox(*source, e);
      EXPECT_EQ(source->lastReadStatistics().bytesRead, e.voxelCount() * sizeof(std::int16_t));
    }
  }
}

TEST_F(VolumeExtentRead, CompressedFilesSayTheyAreDecodedWhole)
{
  const TestGeometry g;
  vtouch::test::writeVolume(path("v.nii.gz"), g);
  auto source = vtouch::openVolume(path("v.nii.gz"));
  EXPECT_FALSE(source->readsExtentsAlone());
  const VoxelExtent e = box(0, 2, 0, 2, 1, 1);
  expectBoxValues(readBox(*source, e), e);
  EXPECT_EQ(source->lastReadStatistics().bytesRead, source->header().byteCount());
}

TEST_F(VolumeExtentRead, DicomSeriesOpensOnlyTheFilesOfTheBoxesSlices)
{
  const TestGeometry g;
  vtouch::test::writeDicomSeries(Dir.string(), g, "1.2.826.0.1.3680043.2.1125.77");
  auto source = vtouch::openVolume(Dir.string());
  EXPECT_TRUE(source->readsExtentsAlone());
  for (const VoxelExtent& e : testBoxes(g))
  {
    expectBoxValues(readBox(*source, e), e);
    EXPECT_EQ(source->lastReadStatistics().filesRead, e.size()[2]);
  }
}

TEST_F(VolumeExtentRead, BoxOutsideTheVolumeIsAClearError)
{
  const TestGeometry g;
  vtouch::test::writeVolume(path("v.nrrd"), g);
  auto source = vtouch::openVolume(path("v.nrrd"));
  EXPECT_NE(
    extentError(*source, box(0, g.size[0], 0, 0, 0, 0)).find("not inside"), std::string::npos);
  EXPECT_NE(extentError(*source, box(2, 1, 0, 0, 0, 0)).find("not inside"), std::string::npos);
}

TEST_F(VolumeExtentRead, BigEndianNrrdWithLineAndByteSkipsReadsRight)
{
  const TestGeometry g;
  const std::string voxels = bigEndianVoxels(g);
  {
    std::ofstream raw(path("data.raw"), std::ios::binary);
    raw << "a comment line\nanother\n" << std::string(7, 'x') << voxels;
  }
  {
    std::ofstream nhdr(path("v.nhdr"), std::ios::binary);
    nhdr << "NRRD0004\ntype: short\ndimension: 3\nspace: left-posterior-superior\nsizes: "
         << g.size[0] << " " << g.size[1] << " " << g.size[2]
         << "\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\nendian: big\n"
            "line skip: 2\nbyte skip: 7\ndata file: data.raw\n\n";
  }
  {
    std::ofstream nrrd(path("tail.nrrd"), std::ios::binary);
    nrrd << "NRRD0004\ntype: short\ndimension: 3\nsizes: " << g.size[0] << " " << g.size[1] << " "
         << g.size[2] << "\nencoding: raw\nendian: big\nbyte skip: -1\n\n"
         << "padding before the voxels" << voxels;
  }
  for (const char* name : { "v.nhdr", "tail.nrrd" })
  {
    SCOPED_TRACE(name);
    auto source = vtouch::openVolume(path(name));
    EXPECT_TRUE(source->readsExtentsAlone());
    for (const VoxelExtent& e : testBoxes(g))
    {
      expectBoxValues(readBox(*source, e), e);
    }
  }
}

TEST_F(VolumeExtentRead, MetaImageWithADetachedFileAndHeaderSizeReadsRight)
{
  const TestGeometry g;
  {
    std::ofstream raw(path("v.raw"), std::ios::binary);
    raw << std::string(16, '\0') << bigEndianVoxels(g);
  }
  {
    std::ofstream mhd(path("v.mhd"), std::ios::binary);
    mhd << "ObjectType = Image\nNDims = 3\nDimSize = " << g.size[0] << " " << g.size[1] << " "
        << g.size[2]
        << "\nElementType = MET_SHORT\nBinaryData = True\nBinaryDataByteOrderMSB = True\n"
           "CompressedData = False\nHeaderSize = 16\nElementDataFile = v.raw\n";
  }
  auto source = vtouch::openVolume(path("v.mhd"));
  EXPECT_TRUE(source->readsExtentsAlone());
  for (const VoxelExtent& e : testBoxes(g))
  {
    expectBoxValues(readBox(*source, e), e);
  }
}

TEST_F(VolumeExtentRead, NiftiWithIntensityScalingIsReadThroughITK)
{
  // scl_slope = 2: ITK converts the voxels to float and scales them, so there is no raw layout;
  // a box must still carry the scaled values.
  const TestGeometry g;
  vtouch::test::writeVolume(path("v.nii"), g);
  {
    std::fstream nii(path("v.nii"), std::ios::in | std::ios::out | std::ios::binary);
    const float slope = 2.0F;
    nii.seekp(112);
    nii.write(reinterpret_cast<const char*>(&slope), sizeof(slope));
  }
  auto source = vtouch::openVolume(path("v.nii"));
  ASSERT_EQ(source->header().voxelType, vtouch::VoxelType::Float32);
  EXPECT_FALSE(source->readsExtentsAlone());
  const VoxelExtent e = box(1, 4, 0, 2, 1, 3);
  std::vector<float> voxels(e.voxelCount());
  ASSERT_TRUE(source->readExtent(e, voxels.data(), voxels.size() * sizeof(float), nullptr));
  expectBoxValues(voxels, e, 2.0);
}
