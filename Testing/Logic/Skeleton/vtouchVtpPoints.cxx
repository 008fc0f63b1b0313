#include "vtouchVtpPoints.h"

#include <zlib.h>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace vtouch
{
namespace test
{

namespace
{
std::string attribute(const std::string& tag, const std::string& name)
{
  const std::string key = name + "=\"";
  const std::size_t a = tag.find(key);
  if (a == std::string::npos)
  {
    return {};
  }
  const std::size_t b = tag.find('"', a + key.size());
  return tag.substr(a + key.size(), b - a - key.size());
}

std::vector<unsigned char> base64(const std::string& text, std::size_t& consumed, std::size_t limit)
{
  static const std::string alphabet =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  unsigned int buffer = 0;
  int bits = 0;
  std::size_t i = consumed;
  for (; i < text.size() && out.size() < limit; ++i)
  {
    const char c = text[i];
    if (c == '=')
    {
      break; // padding ends one base64 block
    }
    const std::size_t v = alphabet.find(c);
    if (v == std::string::npos)
    {
      continue; // whitespace
    }
    buffer = (buffer << 6) | static_cast<unsigned int>(v);
    bits += 6;
    if (bits >= 8)
    {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((buffer >> bits) & 0xFF));
    }
  }
  while (i < text.size() && (text[i] == '=' || std::isspace(static_cast<unsigned char>(text[i]))))
  {
    ++i;
  }
  consumed = i;
  return out;
}

template<typename T>
T readAs(const unsigned char* p)
{
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}
} // namespace

bool readVtpPoints(const std::string& fileName, std::vector<Vec3>& points, std::string& error)
{
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    error = "cannot open " + fileName;
    return false;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string xml = ss.str();
  const std::size_t fileTag = xml.find("<VTKFile");
  const std::string vtkFile = xml.substr(fileTag, xml.find('>', fileTag) - fileTag);
  const bool compressed = vtkFile.find("vtkZLibDataCompressor") != std::string::npos;
  const bool header64 = attribute(vtkFile, "header_type") == "UInt64";
  const std::size_t pointsTag = xml.find("Name=\"Points\"");
  if (pointsTag == std::string::npos)
  {
    error = "no Points array";
    return false;
  }
  const std::size_t tagStart = xml.rfind("<DataArray", pointsTag);
  const std::size_t tagEnd = xml.find('>', pointsTag);
  const std::string tag = xml.substr(tagStart, tagEnd - tagStart);
  if (attribute(tag, "format") != "binary")
  {
    error = "only inline binary arrays are supported";
    return false;
  }
  const std::string type = attribute(tag, "type");
  const std::size_t dataEnd = xml.find("</DataArray>", tagEnd);
  const std::string text = xml.substr(tagEnd + 1, dataEnd - tagEnd - 1);
  const std::size_t hsize = header64 ? 8 : 4;
  std::size_t pos = 0;
  std::vector<unsigned char> raw;
  const auto headerValue = [&](const std::vector<unsigned char>& h, std::size_t k)
  {
    return header64 ? static_cast<std::size_t>(readAs<std::uint64_t>(&h[k * 8]))
                    : static_cast<std::size_t>(readAs<std::uint32_t>(&h[k * 4]));
  };
  if (compressed)
  {
    // Header (base64 on its own): blocks, block size, last block size, compressed sizes.
    std::size_t probe = pos;
    const std::vector<unsigned char> first = base64(text, probe, 3 * hsize);
    const std::size_t blocks = headerValue(first, 0);
    std::vector<unsigned char> header = base64(text, pos, (3 + blocks) * hsize);
    const std::size_t blockSize = headerValue(header, 1);
    const std::size_t lastSize = headerValue(header, 2);
    std::vector<unsigned char> data = base64(text, pos, static_cast<std::size_t>(-1));
    std::size_t offset = 0;
    for (std::size_t b = 0; b < blocks; ++b)
    {
      const std::size_t csize = headerValue(header, 3 + b);
      uLongf usize = static_cast<uLongf>(b + 1 == blocks && lastSize ? lastSize : blockSize);
      std::vector<unsigned char> block(usize);
      if (offset + csize > data.size() ||
          uncompress(block.data(), &usize, &data[offset], static_cast<uLong>(csize)) != Z_OK)
      {
        error = "zlib block " + std::to_string(b) + " does not inflate";
        return false;
      }
      raw.insert(raw.end(), block.begin(), block.begin() + static_cast<std::ptrdiff_t>(usize));
      offset += csize;
    }
  }
  else
  {
    std::vector<unsigned char> all = base64(text, pos, static_cast<std::size_t>(-1));
    const std::size_t bytes = headerValue(all, 0);
    raw.assign(all.begin() + static_cast<std::ptrdiff_t>(hsize),
      all.begin() + static_cast<std::ptrdiff_t>(hsize + bytes));
  }
  const std::size_t width = type == "Float64" ? 8 : 4;
  points.clear();
  for (std::size_t i = 0; i + 3 * width <= raw.size(); i += 3 * width)
  {
    double v[3];
    for (int a = 0; a < 3; ++a)
    {
      v[a] = width == 8 ? readAs<double>(&raw[i + a * 8]) : readAs<float>(&raw[i + a * 4]);
    }
    points.push_back({ v[0], v[1], v[2] });
  }
  return true;
}

} // namespace test
} // namespace vtouch
