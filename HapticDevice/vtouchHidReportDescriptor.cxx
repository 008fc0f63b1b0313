#include "vtouchHidReportDescriptor.h"

#include <algorithm>

namespace vtouch
{

namespace
{
// Item types and tags (HID 1.11, 6.2.2.4 - 6.2.2.8).
enum : std::uint8_t
{
  kTypeMain = 0,
  kTypeGlobal = 1,
  kTypeLocal = 2
};
enum : std::uint8_t
{
  kMainInput = 0x8,
  kMainOutput = 0x9,
  kMainCollection = 0xA,
  kMainFeature = 0xB,
  kMainEndCollection = 0xC
};
enum : std::uint8_t
{
  kGlobalUsagePage = 0x0,
  kGlobalLogicalMinimum = 0x1,
  kGlobalLogicalMaximum = 0x2,
  kGlobalPhysicalMinimum = 0x3,
  kGlobalPhysicalMaximum = 0x4,
  kGlobalUnitExponent = 0x5,
  kGlobalUnit = 0x6,
  kGlobalReportSize = 0x7,
  kGlobalReportId = 0x8,
  kGlobalReportCount = 0x9,
  kGlobalPush = 0xA,
  kGlobalPop = 0xB
};
enum : std::uint8_t
{
  kLocalUsage = 0x0,
  kLocalUsageMinimum = 0x1,
  kLocalUsageMaximum = 0x2
};

struct GlobalState
{
  std::uint32_t usagePage = 0;
  std::int64_t logicalMinimum = 0;
  std::int64_t logicalMaximum = 0;
  std::uint32_t logicalMaximumUnsigned = 0;
  int logicalMaximumSize = 0;
  std::int64_t physicalMinimum = 0;
  std::int64_t physicalMaximum = 0;
  std::int32_t unitExponent = 0;
  std::uint32_t unit = 0;
  std::uint32_t reportSize = 0;
  std::uint32_t reportCount = 0;
  std::uint8_t reportId = 0;
};

std::int64_t signedValue(std::uint32_t raw, int size)
{
  switch (size)
  {
    case 1:
      return static_cast<std::int8_t>(raw & 0xFFu);
    case 2:
      return static_cast<std::int16_t>(raw & 0xFFFFu);
    case 4:
      return static_cast<std::int32_t>(raw);
    default:
      return 0;
  }
}

// Usages of one or two bytes take the current usage page; four-byte usages carry their own.
std::uint32_t extendedUsage(std::uint32_t raw, int size, std::uint32_t page)
{
  return size == 4 ? raw : ((page << 16) | (raw & 0xFFFFu));
}

std::size_t slot(HidReportType type, std::uint8_t id)
{
  return static_cast<std::size_t>(type) * 256 + id;
}
} // namespace

void HidReportDescriptor::clear()
{
  this->Fields.clear();
  this->Collections.clear();
  this->UsageRanges.clear();
  this->ReportBits.fill(0);
  this->UsesReportIds = false;
}

bool HidReportDescriptor::fail(const char* reason, std::size_t offset)
{
  this->clear();
  this->Error = reason;
  this->ErrorOffset = offset;
  return false;
}

bool HidReportDescriptor::parse(const std::uint8_t* data, std::size_t size)
{
  this->clear();
  this->Error = "";
  this->ErrorOffset = 0;
  if (!data || size == 0)
  {
    return this->fail("empty report descriptor", 0);
  }
  if (size > kMaxDescriptorBytes)
  {
    return this->fail("report descriptor too large", 0);
  }

  GlobalState global;
  std::array<GlobalState, kMaxPushDepth> stack{};
  int stackDepth = 0;
  std::vector<HidUsageRange> localUsages;
  bool haveMinimum = false, haveMaximum = false;
  std::uint32_t usageMinimum = 0, usageMaximum = 0;
  int current = -1; // innermost open collection
  int depth = 0;

  auto clearLocal = [&]()
  {
    localUsages.clear();
    haveMinimum = haveMaximum = false;
  };
  auto flushRange = [&]() -> bool
  {
    if (haveMinimum && haveMaximum)
    {
      localUsages.push_back(HidUsageRange{
        std::min(usageMinimum, usageMaximum), std::max(usageMinimum, usageMaximum) });
      haveMinimum = haveMaximum = false;
    }
    return localUsages.size() <= kMaxUsageRanges;
  };

  std::size_t pos = 0;
  while (pos < size)
  {
    const std::size_t itemOffset = pos;
    const std::uint8_t prefix = data[pos++];
    if (prefix == 0xFE) // long item: size, tag, data; reserved, skipped
    {
      if (pos + 2 > size)
      {
        return this->fail("truncated long item", itemOffset);
      }
      const std::size_t longSize = data[pos];
      pos += 2;
      if (pos + longSize > size)
      {
        return this->fail("truncated long item", itemOffset);
      }
      pos += longSize;
      continue;
    }
    const int dataSize = (prefix & 3) == 3 ? 4 : (prefix & 3);
    const std::uint8_t type = (prefix >> 2) & 3;
    const std::uint8_t tag = prefix >> 4;
    if (pos + static_cast<std::size_t>(dataSize) > size)
    {
      return this->fail("truncated item", itemOffset);
    }
    std::uint32_t raw = 0;
    for (int i = 0; i < dataSize; ++i)
    {
      raw |= static_cast<std::uint32_t>(data[pos + i]) << (8 * i);
    }
    pos += static_cast<std::size_t>(dataSize);

    if (type == kTypeMain)
    {
      if (!flushRange())
      {
        return this->fail("too many usages", itemOffset);
      }
      if (tag == kMainInput || tag == kMainOutput || tag == kMainFeature)
      {
        const HidReportType reportType = tag == kMainInput    ? HidReportType::Input
                                         : tag == kMainOutput ? HidReportType::Output
                                                              : HidReportType::Feature;
        if (global.reportSize > kMaxReportSize || global.reportCount > kMaxReportCount)
        {
          return this->fail("report size or count out of range", itemOffset);
        }
        std::uint32_t& bits = this->ReportBits[slot(reportType, global.reportId)];
        const std::uint64_t length =
          static_cast<std::uint64_t>(global.reportSize) * global.reportCount;
        if (bits + length > kMaxReportBits)
        {
          return this->fail("report too long", itemOffset);
        }
        if (length > 0)
        {
          if (this->Fields.size() >= kMaxFields ||
              this->UsageRanges.size() + localUsages.size() > kMaxUsageRanges)
          {
            return this->fail("too many fields", itemOffset);
          }
          HidField field;
          field.type = reportType;
          field.reportId = global.reportId;
          field.bitOffset = bits;
          field.reportSize = global.reportSize;
          field.reportCount = global.reportCount;
          field.flags = raw;
          field.logicalMinimum = global.logicalMinimum;
          // A maximum that reads negative while the minimum is not is an unsigned value
          // (e.g. 0x25 0xFF with minimum 0 means 255).
          field.logicalMaximum = (global.logicalMinimum >= 0 && global.logicalMaximum < 0)
                                   ? static_cast<std::int64_t>(global.logicalMaximumUnsigned)
                                   : global.logicalMaximum;
          field.physicalMinimum = global.physicalMinimum;
          field.physicalMaximum = global.physicalMaximum;
          if (field.physicalMinimum == 0 && field.physicalMaximum == 0)
          {
            field.physicalMinimum = field.logicalMinimum;
            field.physicalMaximum = field.logicalMaximum;
          }
          field.unit = global.unit;
          field.unitExponent = global.unitExponent;
          field.collection = current;
          field.firstUsageRange = static_cast<std::uint32_t>(this->UsageRanges.size());
          field.usageRangeCount = static_cast<std::uint32_t>(localUsages.size());
          this->UsageRanges.insert(this->UsageRanges.end(), localUsages.begin(), localUsages.end());
          this->Fields.push_back(field);
          bits += static_cast<std::uint32_t>(length);
        }
        clearLocal();
      }
      else if (tag == kMainCollection)
      {
        if (depth >= kMaxCollectionDepth || this->Collections.size() >= kMaxCollections)
        {
          return this->fail("collections nested too deep or too many", itemOffset);
        }
        HidCollection collection;
        collection.usage = localUsages.empty() ? 0 : localUsages.front().minimum;
        collection.type = static_cast<std::uint8_t>(raw & 0xFF);
        collection.parent = current;
        this->Collections.push_back(collection);
        current = static_cast<int>(this->Collections.size()) - 1;
        ++depth;
        clearLocal();
      }
      else if (tag == kMainEndCollection)
      {
        if (depth == 0)
        {
          return this->fail("End Collection without Collection", itemOffset);
        }
        current = this->Collections[static_cast<std::size_t>(current)].parent;
        --depth;
        clearLocal();
      }
      else
      {
        return this->fail("unknown main item", itemOffset);
      }
    }
    else if (type == kTypeGlobal)
    {
      switch (tag)
      {
        case kGlobalUsagePage:
          global.usagePage = raw & 0xFFFFu;
          break;
        case kGlobalLogicalMinimum:
          global.logicalMinimum = signedValue(raw, dataSize);
          break;
        case kGlobalLogicalMaximum:
          global.logicalMaximum = signedValue(raw, dataSize);
          global.logicalMaximumUnsigned = raw;
          global.logicalMaximumSize = dataSize;
          break;
        case kGlobalPhysicalMinimum:
          global.physicalMinimum = signedValue(raw, dataSize);
          break;
        case kGlobalPhysicalMaximum:
          global.physicalMaximum = signedValue(raw, dataSize);
          if (global.physicalMinimum >= 0 && global.physicalMaximum < 0)
          {
            global.physicalMaximum = static_cast<std::int64_t>(raw);
          }
          break;
        case kGlobalUnitExponent:
          // Four-bit two's complement nibble (HID 1.11, 6.2.2.7), larger sizes as signed.
          global.unitExponent = dataSize == 1 && raw <= 0xF
                                  ? static_cast<std::int32_t>(
                                      raw >= 8 ? static_cast<int>(raw) - 16 : static_cast<int>(raw))
                                  : static_cast<std::int32_t>(signedValue(raw, dataSize));
          break;
        case kGlobalUnit:
          global.unit = raw;
          break;
        case kGlobalReportSize:
          global.reportSize = raw;
          break;
        case kGlobalReportId:
          if (raw == 0 || raw > 0xFF)
          {
            return this->fail("invalid report ID", itemOffset);
          }
          global.reportId = static_cast<std::uint8_t>(raw);
          this->UsesReportIds = true;
          break;
        case kGlobalReportCount:
          global.reportCount = raw;
          break;
        case kGlobalPush:
          if (stackDepth >= kMaxPushDepth)
          {
            return this->fail("Push stack overflow", itemOffset);
          }
          stack[static_cast<std::size_t>(stackDepth++)] = global;
          break;
        case kGlobalPop:
          if (stackDepth == 0)
          {
            return this->fail("Pop without Push", itemOffset);
          }
          global = stack[static_cast<std::size_t>(--stackDepth)];
          break;
        default:
          return this->fail("unknown global item", itemOffset);
      }
    }
    else if (type == kTypeLocal)
    {
      switch (tag)
      {
        case kLocalUsage:
          localUsages.push_back(HidUsageRange{ extendedUsage(raw, dataSize, global.usagePage),
            extendedUsage(raw, dataSize, global.usagePage) });
          break;
        case kLocalUsageMinimum:
          usageMinimum = extendedUsage(raw, dataSize, global.usagePage);
          haveMinimum = true;
          break;
        case kLocalUsageMaximum:
          usageMaximum = extendedUsage(raw, dataSize, global.usagePage);
          haveMaximum = true;
          break;
        default:
          break; // designators, strings and delimiters carry nothing we use
      }
      if (!flushRange())
      {
        return this->fail("too many usages", itemOffset);
      }
    }
    else
    {
      return this->fail("reserved item type", itemOffset);
    }
  }
  if (depth != 0)
  {
    return this->fail("unbalanced collections at end of descriptor", size);
  }
  if (this->Fields.empty())
  {
    return this->fail("descriptor declares no report field", size);
  }
  return true;
}

std::uint64_t HidReportDescriptor::usageCount(const HidField& field) const
{
  std::uint64_t count = 0;
  for (std::uint32_t i = 0; i < field.usageRangeCount; ++i)
  {
    const HidUsageRange& r = this->UsageRanges[field.firstUsageRange + i];
    count += static_cast<std::uint64_t>(r.maximum) - r.minimum + 1;
  }
  return count;
}

std::uint32_t HidReportDescriptor::usageAt(const HidField& field, std::uint64_t index) const
{
  if (field.usageRangeCount == 0)
  {
    return 0;
  }
  const std::uint64_t count = this->usageCount(field);
  if (index >= count)
  {
    if (field.isArray())
    {
      return 0;
    }
    index = count - 1; // variable fields repeat the last usage
  }
  for (std::uint32_t i = 0; i < field.usageRangeCount; ++i)
  {
    const HidUsageRange& r = this->UsageRanges[field.firstUsageRange + i];
    const std::uint64_t n = static_cast<std::uint64_t>(r.maximum) - r.minimum + 1;
    if (index < n)
    {
      return static_cast<std::uint32_t>(r.minimum + index);
    }
    index -= n;
  }
  return 0;
}

std::int64_t HidReportDescriptor::indexOfUsage(const HidField& field, std::uint32_t usage) const
{
  std::uint64_t base = 0;
  for (std::uint32_t i = 0; i < field.usageRangeCount; ++i)
  {
    const HidUsageRange& r = this->UsageRanges[field.firstUsageRange + i];
    if (usage >= r.minimum && usage <= r.maximum)
    {
      return static_cast<std::int64_t>(base + (usage - r.minimum));
    }
    base += static_cast<std::uint64_t>(r.maximum) - r.minimum + 1;
  }
  return -1;
}

bool HidReportDescriptor::insideCollection(int collection, std::uint32_t usage) const
{
  return this->enclosingCollection(collection, usage) >= 0;
}

int HidReportDescriptor::enclosingCollection(int collection, std::uint32_t usage) const
{
  int guard = 0;
  while (collection >= 0 && static_cast<std::size_t>(collection) < this->Collections.size() &&
         guard++ <= kMaxCollectionDepth)
  {
    if (this->Collections[static_cast<std::size_t>(collection)].usage == usage)
    {
      return collection;
    }
    collection = this->Collections[static_cast<std::size_t>(collection)].parent;
  }
  return -1;
}

std::size_t HidReportDescriptor::payloadBytes(HidReportType type, std::uint8_t reportId) const
{
  return (this->ReportBits[slot(type, reportId)] + 7) / 8;
}

std::size_t HidReportDescriptor::reportBytes(HidReportType type, std::uint8_t reportId) const
{
  const std::size_t payload = this->payloadBytes(type, reportId);
  return payload == 0 ? 0 : payload + (this->UsesReportIds ? 1 : 0);
}

std::size_t HidReportDescriptor::maxReportBytes(HidReportType type) const
{
  std::size_t largest = 0;
  for (int id = 0; id < 256; ++id)
  {
    largest = std::max(largest, this->reportBytes(type, static_cast<std::uint8_t>(id)));
  }
  return largest;
}

} // namespace vtouch
