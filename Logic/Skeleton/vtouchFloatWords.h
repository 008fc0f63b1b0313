#ifndef vtouchFloatWords_h
#define vtouchFloatWords_h

#include <cstdint>
#include <cstring>

namespace vtouch
{
/// A float's 32 bits as one int64 word of the ranks' exchanges (RankCollectives carries int64
/// words), and back. Exact for every float (an SS code, an intensity), so a value gathered from
/// another rank is the value that rank holds; for non-negative floats the words order as the
/// values do (IEEE 754), so a word compares as its value.
inline std::int64_t floatToWord(float value)
{
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return static_cast<std::int64_t>(bits);
}

/// The float whose bits are the low 32 bits of `word` (floatToWord's inverse).
inline float wordToFloat(std::int64_t word)
{
  const auto bits = static_cast<std::uint32_t>(static_cast<std::uint64_t>(word) & 0xffffffffU);
  float value = 0.0F;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}
} // namespace vtouch

#endif
