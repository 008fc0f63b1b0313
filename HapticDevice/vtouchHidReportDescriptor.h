// A HID report descriptor parser (HID 1.11, section 6.2.2): items, global and local state,
// collections, report IDs, field bit offsets and sizes, logical and physical ranges.
#pragma once

#include "vtouchHidField.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vtouch
{

/// A usage is page << 16 | id, as in the HID Usage Tables.
constexpr std::uint32_t hidUsage(std::uint16_t page, std::uint16_t id)
{
  return (static_cast<std::uint32_t>(page) << 16) | id;
}

/// A collection (Physical, Application, Logical, ...) and where it sits in the tree.
struct HidCollection
{
  std::uint32_t usage = 0; ///< the usage that opened it (0 when none)
  std::uint8_t type = 0;   ///< 0 physical, 1 application, 2 logical, ...
  int parent = -1;         ///< enclosing collection, -1 at top level
};

/// Inclusive range of usages; a single usage has minimum == maximum.
struct HidUsageRange
{
  std::uint32_t minimum = 0;
  std::uint32_t maximum = 0;
};

/// Parses a descriptor once (control thread; it allocates) into an immutable table of fields that
/// the real-time path reads without allocating. Every malformed input is rejected with a reason,
/// never read out of bounds: the parser is fuzzed.
class HidReportDescriptor
{
public:
  /// Limits that keep hostile descriptors from exhausting memory.
  static constexpr std::size_t kMaxDescriptorBytes = 64 * 1024;
  static constexpr std::size_t kMaxFields = 4096;
  static constexpr std::size_t kMaxCollections = 4096;
  static constexpr std::size_t kMaxUsageRanges = 65536;
  static constexpr int kMaxCollectionDepth = 32;
  static constexpr int kMaxPushDepth = 8;
  static constexpr std::uint32_t kMaxReportCount = 4096;
  static constexpr std::uint32_t kMaxReportSize = 256;
  static constexpr std::uint32_t kMaxReportBits = 8 * 4096;

  /// Parses `size` bytes. Returns false (and keeps nothing) on malformed input; error() says why.
  bool parse(const std::uint8_t* data, std::size_t size);

  /// Why the last parse failed ("" after success). A static string.
  const char* error() const { return this->Error; }
  /// Byte offset of the item that failed.
  std::size_t errorOffset() const { return this->ErrorOffset; }

  const std::vector<HidField>& fields() const { return this->Fields; }
  const std::vector<HidCollection>& collections() const { return this->Collections; }
  const std::vector<HidUsageRange>& usageRanges() const { return this->UsageRanges; }
  /// True when at least one Report ID item appeared: every report then starts with its id byte.
  bool usesReportIds() const { return this->UsesReportIds; }

  /// Number of usages a field lists (sum of its ranges).
  std::uint64_t usageCount(const HidField& field) const;
  /// Usage of item `index`: for a variable field the usage of element `index` (the last usage
  /// repeats, as the HID spec says); for an array field the usage selected by value
  /// logicalMinimum + index. Returns 0 when the field has no usage.
  std::uint32_t usageAt(const HidField& field, std::uint64_t index) const;
  /// Index of `usage` in the field's list, or -1.
  std::int64_t indexOfUsage(const HidField& field, std::uint32_t usage) const;

  /// True when `collection` or one of its ancestors was opened with `usage`.
  bool insideCollection(int collection, std::uint32_t usage) const;
  /// The nearest enclosing collection (from `collection` upward) opened with `usage`, or -1.
  int enclosingCollection(int collection, std::uint32_t usage) const;

  /// Payload bytes (without the report-id byte) of a report; 0 when the report does not exist.
  std::size_t payloadBytes(HidReportType type, std::uint8_t reportId) const;
  /// Whole report bytes as sent or received through hidapi (payload plus the id byte when
  /// usesReportIds()).
  std::size_t reportBytes(HidReportType type, std::uint8_t reportId) const;
  /// Largest reportBytes() of a type.
  std::size_t maxReportBytes(HidReportType type) const;

private:
  bool fail(const char* reason, std::size_t offset);
  void clear();

  std::vector<HidField> Fields;
  std::vector<HidCollection> Collections;
  std::vector<HidUsageRange> UsageRanges;
  std::array<std::uint32_t, 3 * 256> ReportBits{};
  bool UsesReportIds = false;
  const char* Error = "not parsed";
  std::size_t ErrorOffset = 0;
};

} // namespace vtouch
