// One main item (Input/Output/Feature) of a HID report descriptor, and how to read and write its
// values inside a report.
#pragma once

#include <cstddef>
#include <cstdint>

namespace vtouch
{

/// The three kinds of HID report.
enum class HidReportType : std::uint8_t
{
  Input = 0,
  Output = 1,
  Feature = 2
};

/// A field: reportCount elements of reportSize bits each, at bitOffset in its report's payload (the
/// report without its leading report-id byte). Usages are kept as ranges in the descriptor; see
/// HidReportDescriptor::usageAt().
struct HidField
{
  /// Main item flags (HID 1.11, 6.2.2.5).
  static constexpr std::uint32_t kConstant = 1u << 0;
  static constexpr std::uint32_t kVariable = 1u << 1;
  static constexpr std::uint32_t kRelative = 1u << 2;
  static constexpr std::uint32_t kNullState = 1u << 6;

  HidReportType type = HidReportType::Input;
  std::uint8_t reportId = 0;     ///< 0 when the descriptor uses no report IDs
  std::uint32_t bitOffset = 0;   ///< first bit of element 0 in the payload
  std::uint32_t reportSize = 0;  ///< bits per element
  std::uint32_t reportCount = 0; ///< number of elements
  std::uint32_t flags = 0;       ///< main item data bits
  std::int64_t logicalMinimum = 0;
  std::int64_t logicalMaximum = 0;
  std::int64_t physicalMinimum = 0;
  std::int64_t physicalMaximum = 0;
  std::uint32_t unit = 0;
  std::int32_t unitExponent = 0;
  int collection = -1;               ///< innermost enclosing collection, -1 for none
  std::uint32_t firstUsageRange = 0; ///< index of the first usage range in the descriptor
  std::uint32_t usageRangeCount = 0; ///< number of usage ranges (0: no usage, e.g. padding)

  bool isConstant() const { return (this->flags & kConstant) != 0; }
  bool isVariable() const { return (this->flags & kVariable) != 0; }
  bool isArray() const { return !this->isVariable(); }
  bool isRelative() const { return (this->flags & kRelative) != 0; }
  bool isSigned() const { return this->logicalMinimum < 0; }

  /// Bits this field occupies.
  std::uint64_t bitLength() const
  {
    return static_cast<std::uint64_t>(this->reportSize) * this->reportCount;
  }

  /// Reads element `element` from `payload` (`size` bytes), sign-extended when the logical
  /// minimum is negative. Only the low 32 bits of wider elements are read. Returns false when the
  /// element lies outside the payload or the field.
  bool read(const std::uint8_t* payload,
    std::size_t size,
    std::uint32_t element,
    std::int64_t& value) const;

  /// Writes `value` (truncated to reportSize bits, at most 32) into element `element`.
  /// Returns false when the element lies outside the payload or the field.
  bool write(std::uint8_t* payload,
    std::size_t size,
    std::uint32_t element,
    std::int64_t value) const;
};

} // namespace vtouch
