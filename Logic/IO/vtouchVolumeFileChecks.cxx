#include "vtouchVolumeFileChecks.h"

#include "vtouchVolumeIO.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gdcmExplicitDataElement.h>
#include <gdcmImplicitDataElement.h>
#include <gdcmReader.h>
#include <gdcmTag.h>
#include <zlib.h>

namespace vtouch
{
namespace
{
namespace fs = std::filesystem;

std::uintmax_t fileSize(const std::string& path)
{
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  return ec ? 0 : size;
}

[[noreturn]] void truncated(const std::string& path, std::uintmax_t have, std::uintmax_t want)
{
  std::ostringstream msg;
  msg << "'" << path << "' is truncated: it holds " << have << " bytes where its header "
      << "announces " << want;
  throw VolumeIOError(msg.str());
}

template<class T>
T swapped(T value)
{
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  std::reverse(bytes, bytes + sizeof(T));
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

bool endsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}
} // namespace

void checkNiftiComplete(const std::string& path)
{
  const bool gz = endsWith(path, ".nii.gz");
  if (!gz && !endsWith(path, ".nii"))
  {
    return;
  }
  // The NIfTI-1 header: sizeof_hdr (int32 at 0), dim (int16[8] at 40), bitpix (int16 at 72),
  // vox_offset (float32 at 108).
  unsigned char header[348];
  int got = 0;
  if (gz)
  {
    gzFile file = gzopen(path.c_str(), "rb");
    got = file ? gzread(file, header, sizeof(header)) : 0;
    if (file)
    {
      gzclose(file);
    }
  }
  else
  {
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(header), sizeof(header));
    got = static_cast<int>(in.gcount());
  }
  if (got != static_cast<int>(sizeof(header)))
  {
    truncated(path, static_cast<std::uintmax_t>(std::max(got, 0)), sizeof(header));
  }
  std::int32_t sizeofHdr;
  std::memcpy(&sizeofHdr, header, 4);
  const bool swap = sizeofHdr != 348;
  std::int16_t dim[8];
  std::int16_t bitpix;
  float voxOffset;
  std::memcpy(dim, header + 40, sizeof(dim));
  std::memcpy(&bitpix, header + 72, 2);
  std::memcpy(&voxOffset, header + 108, 4);
  if (swap)
  {
    for (auto& d : dim)
    {
      d = swapped(d);
    }
    bitpix = swapped(bitpix);
    voxOffset = swapped(voxOffset);
  }
  std::uintmax_t voxels = 1;
  for (int a = 1; a <= std::min<int>(dim[0], 7); ++a)
  {
    voxels *= static_cast<std::uintmax_t>(std::max<int>(dim[a], 1));
  }
  const std::uintmax_t want = static_cast<std::uintmax_t>(voxOffset) + voxels * (bitpix / 8);
  if (!gz)
  {
    if (fileSize(path) < want)
    {
      truncated(path, fileSize(path), want);
    }
    return;
  }
  // gzip: the trailer's ISIZE is the uncompressed size modulo 2^32 (little endian). A truncated
  // file ends elsewhere, so its last four bytes are not that size.
  const std::uintmax_t size = fileSize(path);
  std::ifstream in(path, std::ios::binary);
  unsigned char trailer[4] = { 0, 0, 0, 0 };
  in.seekg(static_cast<std::streamoff>(size - 4));
  in.read(reinterpret_cast<char*>(trailer), 4);
  const std::uint32_t isize =
    static_cast<std::uint32_t>(trailer[0]) | (static_cast<std::uint32_t>(trailer[1]) << 8) |
    (static_cast<std::uint32_t>(trailer[2]) << 16) | (static_cast<std::uint32_t>(trailer[3]) << 24);
  if (isize != static_cast<std::uint32_t>(want & 0xffffffffu))
  {
    std::ostringstream msg;
    msg << "'" << path << "' is truncated or corrupt: its gzip stream does not end with the "
        << want << " bytes its NIfTI header announces";
    throw VolumeIOError(msg.str());
  }
}

void checkMetaImageComplete(const std::string& path, std::size_t rawBytes)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::string dataFile;
  bool compressed = false;
  while (std::getline(in, line))
  {
    const auto eq = line.find('=');
    if (eq == std::string::npos)
    {
      continue;
    }
    const std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    if (key == "CompressedData")
    {
      compressed = value == "True" || value == "true";
    }
    if (key == "ElementDataFile")
    {
      dataFile = value;
      break; // the last header field
    }
  }
  if (compressed || dataFile.empty())
  {
    return;
  }
  if (dataFile == "LOCAL")
  {
    const std::uintmax_t headerEnd = static_cast<std::uintmax_t>(in.tellg());
    const std::uintmax_t have = fileSize(path) - std::min(fileSize(path), headerEnd);
    if (have < rawBytes)
    {
      truncated(path, have, rawBytes);
    }
    return;
  }
  if (dataFile.find(' ') != std::string::npos || dataFile == "LIST")
  {
    return; // a file pattern or a list of slice files: not checked
  }
  const fs::path data = fs::path(path).parent_path() / dataFile;
  if (fileSize(data.string()) < rawBytes)
  {
    truncated(data.string(), fileSize(data.string()), rawBytes);
  }
}

void checkDicomSliceComplete(const std::string& path)
{
  // GDCM parses a short file leniently ("Incomplete Pixel Data found") and keeps the declared
  // lengths: the file must then be shorter than its preamble + meta header + data set.
  gdcm::Reader reader;
  reader.SetFileName(path.c_str());
  if (!reader.Read())
  {
    throw VolumeIOError("'" + path + "' is not a readable DICOM file (truncated or corrupt?)");
  }
  const gdcm::FileMetaInformation& meta = reader.GetFile().GetHeader();
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  const bool implicit =
    meta.GetDataSetTransferSyntax().GetNegociatedType() == gdcm::TransferSyntax::Implicit;
  const std::uintmax_t dataSetBytes =
    implicit ? static_cast<std::uintmax_t>(ds.GetLength<gdcm::ImplicitDataElement>())
             : static_cast<std::uintmax_t>(ds.GetLength<gdcm::ExplicitDataElement>());
  const std::uintmax_t want = static_cast<std::uintmax_t>(meta.GetFullLength()) + dataSetBytes;
  // A few bytes of slack for odd-length padding the parser may count differently.
  constexpr std::uintmax_t slack = 8;
  if (fileSize(path) + slack < want)
  {
    truncated(path, fileSize(path), want);
  }
}

} // namespace vtouch
