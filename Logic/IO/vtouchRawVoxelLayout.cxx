#include "vtouchRawVoxelLayout.h"

#include "vtouchHeaderText.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace vtouch
{
namespace
{
namespace fs = std::filesystem;

bool hostIsLittleEndian()
{
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

/// A data file named in a header: relative names are relative to the header's folder.
std::string besideHeader(const std::string& headerPath, const std::string& name)
{
  const fs::path named(name);
  return named.is_absolute() ? name : (fs::path(headerPath).parent_path() / named).string();
}

/// The layout when `dataFile` holds the whole volume from `offset` on, else nothing.
std::optional<RawVoxelLayout> checked(const std::string& dataFile,
  std::int64_t offset,
  bool fileIsLittleEndian,
  const VolumeHeader& header)
{
  std::error_code ec;
  const std::uintmax_t fileBytes = fs::file_size(dataFile, ec);
  if (ec || offset < 0 ||
      fileBytes <
        static_cast<std::uintmax_t>(offset) + static_cast<std::uintmax_t>(header.byteCount()))
  {
    return std::nullopt; // ITK reads it and the truncation checks say what is wrong
  }
  RawVoxelLayout layout;
  layout.dataFile = dataFile;
  layout.byteOffset = static_cast<std::uint64_t>(offset);
  layout.swapBytes = voxelSize(header.voxelType) > 1 && fileIsLittleEndian != hostIsLittleEndian();
  return layout;
}

bool sameDimensions(const std::vector<long long>& sizes, const VolumeHeader& header)
{
  if (sizes.size() != 3)
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (sizes[a] < 0 || static_cast<std::size_t>(sizes[a]) != header.geometry.dimensions[a])
    {
      return false;
    }
  }
  return true;
}

std::vector<long long> integers(const std::string& text)
{
  std::istringstream in(text);
  std::vector<long long> values;
  long long v = 0;
  while (in >> v)
  {
    values.push_back(v);
  }
  return values;
}

// NIfTI-1 (one .nii file, or an .hdr/.img pair): the 348-byte header gives dim[], bitpix,
// vox_offset and the intensity scaling; ITK rescales scaled voxels itself, so those are not raw.
std::optional<RawVoxelLayout> niftiLayout(const std::string& path, const VolumeHeader& header)
{
  const std::string lower = lowerCase(path);
  std::string headerFile = path;
  std::string dataFile = path;
  if (endsWith(lower, ".hdr"))
  {
    dataFile = path.substr(0, path.size() - 4) + (endsWith(path, ".HDR") ? ".IMG" : ".img");
  }
  else if (endsWith(lower, ".img"))
  {
    headerFile = path.substr(0, path.size() - 4) + (endsWith(path, ".IMG") ? ".HDR" : ".hdr");
  }
  else if (!endsWith(lower, ".nii"))
  {
    return std::nullopt; // .nii.gz, .img.gz: compressed
  }
  unsigned char h[348];
  std::ifstream in(headerFile, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(h), sizeof(h)))
  {
    return std::nullopt;
  }
  const bool hostLittle = hostIsLittleEndian();
  auto field = [&h](std::size_t at, std::size_t n, bool swap, void* out)
  {
    unsigned char bytes[8];
    std::memcpy(bytes, h + at, n);
    if (swap)
    {
      std::reverse(bytes, bytes + n);
    }
    std::memcpy(out, bytes, n);
  };
  std::int32_t sizeofHdr = 0;
  field(0, 4, false, &sizeofHdr);
  bool swap = false;
  if (sizeofHdr != 348)
  {
    field(0, 4, true, &sizeofHdr);
    if (sizeofHdr != 348)
    {
      return std::nullopt; // NIfTI-2 or not NIfTI
    }
    swap = true;
  }
  const bool fileLittle = swap ? !hostLittle : hostLittle;
  std::int16_t dim[8];
  for (int d = 0; d < 8; ++d)
  {
    field(40 + 2 * static_cast<std::size_t>(d), 2, swap, &dim[d]);
  }
  std::int16_t bitpix = 0;
  float voxOffset = 0.0F;
  float slope = 0.0F;
  float intercept = 0.0F;
  field(72, 2, swap, &bitpix);
  field(108, 4, swap, &voxOffset);
  field(112, 4, swap, &slope);
  field(116, 4, swap, &intercept);
  if (dim[0] < 3 || dim[0] > 7)
  {
    return std::nullopt;
  }
  for (int d = 4; d <= dim[0]; ++d)
  {
    if (dim[d] != 1)
    {
      return std::nullopt;
    }
  }
  if (!sameDimensions({ dim[1], dim[2], dim[3] }, header) ||
      bitpix != 8 * static_cast<int>(voxelSize(header.voxelType)))
  {
    return std::nullopt;
  }
  if (slope != 0.0F && (slope != 1.0F || intercept != 0.0F))
  {
    return std::nullopt; // scaled intensities: ITK converts them
  }
  if (!(voxOffset >= 0.0F))
  {
    return std::nullopt;
  }
  return checked(dataFile, static_cast<std::int64_t>(voxOffset), fileLittle, header);
}

// NRRD: "field: value" lines up to a blank line; raw encoding only, data attached after the blank
// line or in one detached file, with line skip and byte skip (-1: the last bytes of the file).
std::optional<RawVoxelLayout> nrrdLayout(const std::string& path, const VolumeHeader& header)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || line.rfind("NRRD", 0) != 0)
  {
    return std::nullopt;
  }
  std::map<std::string, std::string> fields;
  while (std::getline(in, line))
  {
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    if (line.empty())
    {
      break;
    }
    if (line[0] == '#' || line.find(":=") != std::string::npos)
    {
      continue; // comments and key/value pairs
    }
    const auto colon = line.find(": ");
    if (colon != std::string::npos)
    {
      fields[lowerCase(line.substr(0, colon))] = trimmed(line.substr(colon + 2));
    }
  }
  const auto get = [&fields](const char* a, const char* b = "") -> std::string
  {
    auto it = fields.find(a);
    if (it == fields.end() && *b)
    {
      it = fields.find(b);
    }
    return it == fields.end() ? std::string() : it->second;
  };
  if (lowerCase(get("encoding")) != "raw" || trimmed(get("dimension")) != "3" ||
      !sameDimensions(integers(get("sizes")), header))
  {
    return std::nullopt;
  }
  const std::string endian = lowerCase(get("endian"));
  const bool fileLittle = endian.empty() ? hostIsLittleEndian() : endian == "little";
  std::string dataFile = path;
  std::int64_t offset = in ? static_cast<std::int64_t>(in.tellg()) : -1;
  const std::string detached = get("data file", "datafile");
  if (!detached.empty())
  {
    if (detached.find_first_of(" \t%") != std::string::npos || detached.rfind("LIST", 0) == 0)
    {
      return std::nullopt; // several data files
    }
    dataFile = besideHeader(path, detached);
    offset = 0;
  }
  if (offset < 0)
  {
    return std::nullopt;
  }
  const std::vector<long long> lineSkip = integers(get("line skip", "lineskip"));
  const std::vector<long long> byteSkip = integers(get("byte skip", "byteskip"));
  if (!lineSkip.empty() && lineSkip[0] > 0)
  {
    std::ifstream data(dataFile, std::ios::binary);
    data.seekg(offset);
    for (long long n = 0; n < lineSkip[0]; ++n)
    {
      if (!std::getline(data, line))
      {
        return std::nullopt;
      }
    }
    offset = static_cast<std::int64_t>(data.tellg());
  }
  if (!byteSkip.empty() && byteSkip[0] == -1)
  {
    std::error_code ec;
    const std::uintmax_t fileBytes = fs::file_size(dataFile, ec);
    if (ec || fileBytes < header.byteCount())
    {
      return std::nullopt;
    }
    offset = static_cast<std::int64_t>(fileBytes - header.byteCount());
  }
  else if (!byteSkip.empty())
  {
    offset += byteSkip[0];
  }
  return checked(dataFile, offset, fileLittle, header);
}

// MetaImage: "Key = Value" lines ending with ElementDataFile; LOCAL data follows that line, a
// single named file holds it otherwise; HeaderSize skips bytes of a detached file (-1: the last
// bytes of the file).
std::optional<RawVoxelLayout> metaImageLayout(const std::string& path, const VolumeHeader& header)
{
  std::ifstream in(path, std::ios::binary);
  std::map<std::string, std::string> fields;
  std::string line;
  std::string elementDataFile;
  while (std::getline(in, line))
  {
    const auto equals = line.find('=');
    if (equals == std::string::npos)
    {
      continue;
    }
    const std::string key = lowerCase(trimmed(line.substr(0, equals)));
    const std::string value = trimmed(line.substr(equals + 1));
    fields[key] = value;
    if (key == "elementdatafile")
    {
      elementDataFile = value;
      break;
    }
  }
  const auto get = [&fields](const char* key)
  {
    const auto it = fields.find(key);
    return it == fields.end() ? std::string() : lowerCase(it->second);
  };
  if (elementDataFile.empty() || get("compresseddata") == "true" || trimmed(get("ndims")) != "3" ||
      !sameDimensions(integers(get("dimsize")), header) ||
      (!get("elementnumberofchannels").empty() && trimmed(get("elementnumberofchannels")) != "1"))
  {
    return std::nullopt;
  }
  const bool bigEndian =
    get("binarydatabyteordermsb") == "true" || get("elementbyteordermsb") == "true";
  const std::vector<long long> headerSize = integers(get("headersize"));
  std::string dataFile = path;
  std::int64_t offset = 0;
  if (lowerCase(elementDataFile) == "local")
  {
    if (!headerSize.empty() && headerSize[0] != 0)
    {
      return std::nullopt;
    }
    offset = in ? static_cast<std::int64_t>(in.tellg()) : -1;
  }
  else
  {
    if (elementDataFile.find_first_of(" \t%") != std::string::npos ||
        lowerCase(elementDataFile).rfind("list", 0) == 0)
    {
      return std::nullopt; // a list or a pattern of slice files
    }
    dataFile = besideHeader(path, elementDataFile);
    if (!headerSize.empty() && headerSize[0] == -1)
    {
      std::error_code ec;
      const std::uintmax_t fileBytes = fs::file_size(dataFile, ec);
      if (ec || fileBytes < header.byteCount())
      {
        return std::nullopt;
      }
      offset = static_cast<std::int64_t>(fileBytes - header.byteCount());
    }
    else if (!headerSize.empty())
    {
      offset = headerSize[0];
    }
  }
  return checked(dataFile, offset, !bigEndian, header);
}
} // namespace

std::optional<RawVoxelLayout> findRawVoxelLayout(const std::string& path,
  const VolumeHeader& header)
{
  if (header.format == "NIfTI")
  {
    return niftiLayout(path, header);
  }
  if (header.format == "NRRD")
  {
    return nrrdLayout(path, header);
  }
  if (header.format == "MetaImage")
  {
    return metaImageLayout(path, header);
  }
  return std::nullopt;
}

} // namespace vtouch
