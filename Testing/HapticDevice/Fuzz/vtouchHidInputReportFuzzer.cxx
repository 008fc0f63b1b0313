// libFuzzer target: input-report decoding. The first byte picks a real device descriptor (0
// OpenFFBoard, 1 SHIELD/SideWinder layout, 2 HID-spec mouse) and the rest is the report; any other
// first byte means [2-byte little-endian descriptor length][descriptor][report].
#include "vtouchHidInputDecoder.h"
#include "vtouchHidPidLayout.h"
#include "vtouchHidReportDescriptor.h"
#include "vtouchHidTestDescriptors.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace
{
struct Prepared
{
  vtouch::HidReportDescriptor descriptor;
  vtouch::HidPidLayout layout;
  vtouch::HidInputDecoder decoder;
  bool ok = false;
};

Prepared prepare(const std::vector<std::uint8_t>& bytes)
{
  Prepared p;
  p.ok = p.descriptor.parse(bytes.data(), bytes.size());
  if (p.ok)
  {
    p.layout = vtouch::HidPidLayout::find(p.descriptor);
    p.ok = p.decoder.configure(p.descriptor, p.layout);
  }
  return p;
}

const Prepared& known(int which)
{
  static const Prepared devices[3] = {
    prepare(vtouch::test::hexBytes(vtouch::test::kOpenFfboard2Axis)),
    prepare(vtouch::test::hexBytes(vtouch::test::kShieldPidSegmentGamepad)),
    prepare(vtouch::test::hexBytes(vtouch::test::kHidSpecMouse)),
  };
  return devices[which];
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  vtouch::HidInputSample sample;
  if (data[0] < 3)
  {
    const Prepared& p = known(data[0]);
    if (p.ok)
    {
      p.decoder.decode(data + 1, size - 1, sample);
    }
    return 0;
  }
  if (size < 3)
  {
    return 0;
  }
  const std::size_t length =
    static_cast<std::size_t>(data[1]) | (static_cast<std::size_t>(data[2]) << 8);
  if (3 + length > size)
  {
    return 0;
  }
  const Prepared p = prepare(std::vector<std::uint8_t>(data + 3, data + 3 + length));
  if (p.ok)
  {
    p.decoder.decode(data + 3 + length, size - 3 - length, sample);
  }
  return 0;
}
