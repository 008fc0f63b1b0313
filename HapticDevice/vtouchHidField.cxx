#include "vtouchHidField.h"

#include <algorithm>

namespace vtouch
{

namespace
{
bool locate(const HidField& field,
  std::size_t size,
  std::uint32_t element,
  std::uint64_t& first,
  std::uint32_t& bits)
{
  if (element >= field.reportCount || field.reportSize == 0)
  {
    return false;
  }
  first = field.bitOffset + static_cast<std::uint64_t>(element) * field.reportSize;
  bits = std::min<std::uint32_t>(field.reportSize, 32);
  // The whole element (not only the bits we touch) must be inside the payload.
  return first + field.reportSize <= static_cast<std::uint64_t>(size) * 8;
}
} // namespace

bool HidField::read(const std::uint8_t* payload,
  std::size_t size,
  std::uint32_t element,
  std::int64_t& value) const
{
  std::uint64_t first = 0;
  std::uint32_t bits = 0;
  if (!payload || !locate(*this, size, element, first, bits))
  {
    return false;
  }
  // HID fields are little-endian bit strings: bit i of the value is bit (first + i) of the report.
  std::uint64_t raw = 0;
  for (std::uint32_t i = 0; i < bits; ++i)
  {
    const std::uint64_t bit = first + i;
    raw |= static_cast<std::uint64_t>((payload[bit >> 3] >> (bit & 7u)) & 1u) << i;
  }
  if (this->isSigned() && bits < 64 && (raw >> (bits - 1)) & 1u)
  {
    raw |= ~((std::uint64_t{ 1 } << bits) - 1); // sign-extend
  }
  value = static_cast<std::int64_t>(raw);
  return true;
}

bool HidField::write(std::uint8_t* payload,
  std::size_t size,
  std::uint32_t element,
  std::int64_t value) const
{
  std::uint64_t first = 0;
  std::uint32_t bits = 0;
  if (!payload || !locate(*this, size, element, first, bits))
  {
    return false;
  }
  const std::uint64_t raw = static_cast<std::uint64_t>(value);
  for (std::uint32_t i = 0; i < bits; ++i)
  {
    const std::uint64_t bit = first + i;
    const std::uint8_t mask = static_cast<std::uint8_t>(1u << (bit & 7u));
    if ((raw >> i) & 1u)
    {
      payload[bit >> 3] = static_cast<std::uint8_t>(payload[bit >> 3] | mask);
    }
    else
    {
      payload[bit >> 3] = static_cast<std::uint8_t>(payload[bit >> 3] & ~mask);
    }
  }
  return true;
}

} // namespace vtouch
