// Real, published HID report descriptors replayed by the fake transport. The bytes are data, kept
// as hex text (two digits per byte) so that they read like the sources they come from.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{
namespace test
{

/// "05 01 ..." -> bytes. Anything that is not a hex digit separates bytes.
inline std::vector<std::uint8_t> hexBytes(const char* text)
{
  std::vector<std::uint8_t> bytes;
  int nibbles = 0;
  unsigned value = 0;
  for (const char* c = text; *c; ++c)
  {
    int digit = -1;
    if (*c >= '0' && *c <= '9')
      digit = *c - '0';
    else if (*c >= 'a' && *c <= 'f')
      digit = *c - 'a' + 10;
    else if (*c >= 'A' && *c <= 'F')
      digit = *c - 'A' + 10;
    if (digit < 0)
    {
      nibbles = 0;
      value = 0;
      continue;
    }
    value = (value << 4) | static_cast<unsigned>(digit);
    if (++nibbles == 2)
    {
      bytes.push_back(static_cast<std::uint8_t>(value));
      nibbles = 0;
      value = 0;
    }
  }
  return bytes;
}

/// OpenFFBoard (open-source direct-drive force-feedback firmware), two-axis FFB descriptor.
/// Source: github.com/Ultrawipf/OpenFFBoard, Firmware/FFBoard/UserExtensions/Src/
/// usb_hid_2ffb_desc.c (commit 02da947797e8ecb5e9202e4ef635af2b57337541), macros resolved with
/// Firmware/FFBoard/Inc/ffb_defs.h (FFB_ID_OFFSET 0, MAX_EFFECTS 40, HID_ID_HIDCMD 0xA1).
/// Layout traits: report IDs 1..0x13, 16-bit signed magnitude (-32768..32767), 16-bit direction
/// 0..36000, Device Control as an 8-bit *bit field* inside 0x95/0x96 collections, 64-bit vendor
/// fields, Create New Effect 0x11 / Block Load 0x12 / Pool 0x13 features.
inline const char* kOpenFfboard2Axis =
  // Joystick input, report 1: 64 buttons, 8 axes of 16 bits
  "05 01 09 04 A1 01 A1 00 85 01 05 09 19 01 29 40 15 00 25 01 95 40 75 01 81 02"
  " 05 01 09 30 09 31 09 32 09 33 09 34 09 35 09 37 09 36 16 01 80 26 FF 7F 75 10 95 08 81 02 C0"
  // Vendor command reports (0xA1)
  " 06 00 FF 09 00 A1 01"
  " 85 A1 09 01 15 00 26 04 00 75 08 95 01 91 02 09 02 75 10 95 01 91 02 09 03 75 08 95 01 91 02"
  " 09 04 75 20 95 01 91 02 09 05 75 40 95 01 91 02 09 06 75 40 95 01 91 02"
  " 85 A1 09 01 15 00 26 04 00 75 08 95 01 81 02 09 02 75 10 95 01 81 02 09 03 75 08 95 01 81 02"
  " 09 04 75 20 95 01 81 02 09 05 75 40 95 01 81 02 09 06 75 40 95 01 81 02 C0"
  // PID State (input 2)
  " 05 0F 09 92 A1 02 85 02 09 9F 09 A0 09 A4 09 A6 09 94 15 00 25 01 35 00 45 01 75 01 95 05 81 02"
  " 95 03 81 03 C0"
  // Set Effect (output 1)
  " 09 21 A1 02 85 01 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 25 A1 02 09 26 09 27 09 30 09 31 09 32 09 33 09 34 09 40 09 41 09 42 09 43"
  " 25 0B 15 01 35 01 45 0B 75 08 95 01 91 00 C0"
  " 09 50 09 54 09 51 09 A7 15 00 26 FF 7F 35 00 46 FF 7F 66 03 10 55 FD 75 10 95 04 91 02"
  " 55 00 66 00 00"
  " 09 52 15 00 26 FF 00 35 00 46 10 27 75 08 95 01 91 02"
  " 09 53 15 01 25 08 35 01 45 08 75 08 95 01 91 02"
  " 09 55 A1 02 05 01 09 30 09 31 15 00 25 01 75 01 95 02 91 02 C0"
  " 05 0F 09 56 95 01 91 02 95 05 91 03"
  " 09 57 A1 02 0B 01 00 0A 00 0B 02 00 0A 00 66 14 00 15 00 27 A0 8C 00 00 35 00"
  " 47 A0 8C 00 00 66 00 00 75 10 95 02 91 02 55 00 66 00 00 C0"
  " 05 0F 09 58 A1 02 0B 01 00 0A 00 0B 02 00 0A 00 26 FD 7F 75 10 95 02 91 02 C0"
  " C0"
  // Set Envelope (output 2)
  " 09 5A A1 02 85 02 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 5B 09 5D 16 00 00 26 FF 7F 36 00 00 46 FF 7F 75 10 95 02 91 02"
  " 09 5C 09 5E 66 03 10 55 FD 27 FF 7F 00 00 47 FF 7F 00 00 75 20 91 02"
  " 45 00 66 00 00 55 00 C0"
  // Set Condition (output 3)
  " 09 5F A1 02 85 03 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 23 15 00 25 03 35 00 45 03 75 04 95 01 91 02"
  " 09 58 A1 02 0B 01 00 0A 00 0B 02 00 0A 00 75 02 95 02 91 02 C0"
  " 16 00 80 26 FF 7F 36 00 80 46 FF 7F 09 60 75 10 95 01 91 02"
  " 36 00 80 46 FF 7F 09 61 09 62 95 02 91 02"
  " 16 00 00 26 FF 7F 36 00 00 46 FF 7F 09 63 09 64 75 10 95 02 91 02"
  " 09 65 46 FF 7F 95 01 91 02 C0"
  // Set Periodic (output 4)
  " 09 6E A1 02 85 04 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 70 16 00 00 26 FF 7F 36 00 00 26 FF 7F 75 10 95 01 91 02"
  " 09 6F 16 00 80 26 FF 7F 36 00 80 46 FF 7F 95 01 75 10 91 02"
  " 09 71 66 14 00 55 FE 15 00 27 9F 8C 00 00 35 00 47 9F 8C 00 00 75 10 95 01 91 02"
  " 09 72 15 01 27 FF 7F 00 00 35 01 47 FF 7F 00 00 66 03 10 55 FD 75 20 95 01 91 02"
  " 66 00 00 55 00 C0"
  // Set Constant Force (output 5)
  " 09 73 A1 02 85 05 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 70 16 00 80 26 FF 7F 36 00 80 46 FF 7F 75 10 95 01 91 02 C0"
  // Set Ramp Force (output 6)
  " 09 74 A1 02 85 06 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 75 09 76 16 00 80 26 FF 7F 36 00 80 46 FF 7F 75 10 95 02 91 02 C0"
  // Effect Operation (output 0x0A)
  " 05 0F 09 77 A1 02 85 0A 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 78 A1 02 09 79 09 7A 09 7B 15 01 25 03 75 08 95 01 91 00 C0"
  " 09 7C 15 00 26 FF 00 35 00 46 FF 00 91 02 C0"
  // Block Free (output 0x0B)
  " 09 90 A1 02 85 0B 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02 C0"
  // Device Control (output 0x0C): bit field
  " 09 95 A1 02 85 0C 09 96 A1 02 09 97 09 98 09 99 09 9A 09 9B 09 9C 15 01 25 06 75 01 95 08"
  " 91 02 C0 C0"
  // Device Gain (output 0x0D)
  " 09 7D A1 02 85 0D 09 7E 15 00 26 FF 00 35 00 46 10 27 75 08 95 01 91 02 C0"
  // Create New Effect (feature 0x11)
  " 09 AB A1 02 85 11 09 25 A1 02 09 26 09 27 09 30 09 31 09 32 09 33 09 34 09 40 09 41 09 42"
  " 09 43 25 0B 15 01 35 01 45 0B 75 08 95 01 B1 00 C0"
  " 05 01 09 3B 15 00 26 FF 01 35 00 46 FF 01 75 0A 95 01 B1 02 75 06 B1 01 C0"
  // Block Load (feature 0x12)
  " 05 0F 09 89 A1 02 85 12 09 22 25 28 15 01 35 01 45 28 75 08 95 01 B1 02"
  " 09 8B A1 02 09 8C 09 8D 09 8E 15 01 25 03 35 01 45 03 75 08 95 01 B1 00 C0"
  " 09 AC 15 00 27 FF FF 00 00 35 00 47 FF FF 00 00 75 10 95 01 B1 00 C0"
  // PID Pool (feature 0x13)
  " 09 7F A1 02 85 13 09 80 75 10 95 01 15 00 35 00 27 FF FF 00 00 47 FF FF 00 00 B1 02"
  " 09 83 26 FF 00 46 FF 00 75 08 95 01 B1 02"
  " 09 A9 09 AA 75 01 95 02 15 00 25 01 35 00 45 01 B1 02 75 06 95 01 B1 03 C0"
  " C0";

/// The PID segment of the NVIDIA SHIELD controller's force-feedback descriptor, the classic
/// layout that descends from the Microsoft SideWinder Force Feedback 2 (8-bit magnitudes and
/// directions, Device Control as a selector *array*, report IDs 0x21 Set Effect, 0x20 Block Load).
/// Source: github.com/Syniurge/ShieldControllerWinDriver sys/hid.c (commit b5c2bfa7), as
/// republished byte for byte in github.com/nefarius/DsHidMini docs/FFB_PID_2.c
/// (FFB_DESCRIPTOR_SEGMENT). The segment is spliced inside a game-pad Application collection and
/// ends with that collection's End Collection; the six-item game-pad header before it (report 1:
/// X/Y 8 bits, 8 buttons) is ours, so that the device has a position to read.
inline const char* kShieldPidSegmentGamepad =
  // Our header: Generic Desktop Game Pad, report 1 with X, Y and 8 buttons
  "05 01 09 05 A1 01 85 01 09 30 09 31 15 00 26 FF 00 75 08 95 02 81 02"
  " 05 09 19 01 29 08 15 00 25 01 75 01 95 08 81 02"
  // Published segment: PID State (input 0x20)
  " 05 0F 09 92 A1 02 85 20 09 9F 09 A0 09 A4 09 A5 09 A6 15 00 25 01 35 00 45 01 75 01 95 05"
  " 81 02 95 03 75 01 81 03 09 94 15 00 25 01 35 00 45 01 75 01 95 01 81 02"
  " 09 22 15 01 25 28 35 01 45 28 75 07 95 01 81 02 C0"
  // Set Effect (output 0x21)
  " 09 21 A1 02 85 21 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 25 A1 02 09 26 09 27 09 30 09 31 09 32 09 33 09 34 09 40 09 41 09 42 09 43 09 28"
  " 25 0C 15 01 35 01 45 0C 75 08 95 01 91 00 C0"
  " 09 50 09 54 09 51 15 00 26 FF 7F 35 00 46 FF 7F 66 03 10 55 FD 75 10 95 03 91 02"
  " 55 00 66 00 00"
  " 09 52 15 00 26 FF 00 35 00 46 10 27 75 08 95 01 91 02"
  " 09 53 15 01 25 08 35 01 45 08 75 08 95 01 91 02"
  " 09 55 A1 02 05 01 09 30 09 31 15 00 25 01 75 01 95 02 91 02 C0"
  " 05 0F 09 56 95 01 91 02 95 05 91 03"
  " 09 57 A1 02 0B 01 00 0A 00 0B 02 00 0A 00 66 14 00 55 FE 15 00 26 FF 00 35 00"
  " 47 A0 8C 00 00 66 00 00 75 08 95 02 91 02 55 00 66 00 00 C0"
  " 05 0F 09 A7 66 03 10 55 FD 15 00 26 FF 7F 35 00 46 FF 7F 75 10 95 01 91 02"
  " 66 00 00 55 00 C0"
  // Set Envelope (output 0x20)
  " 05 0F 09 5A A1 02 85 20 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 5B 09 5D 15 00 26 FF 00 35 00 46 10 27 95 02 91 02"
  " 09 5C 09 5E 66 03 10 55 FD 26 FF 7F 46 FF 7F 75 10 91 02 45 00 66 00 00 55 00 C0"
  // Set Condition (output 3)
  " 09 5F A1 02 85 03 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 23 15 00 25 01 35 00 45 01 75 04 95 01 91 02"
  " 09 58 A1 02 0B 01 00 0A 00 0B 02 00 0A 00 75 02 95 02 91 02 C0"
  " 15 80 25 7F 36 F0 D8 46 10 27 09 60 75 08 95 01 91 02"
  " 36 F0 D8 46 10 27 09 61 09 62 95 02 91 02"
  " 15 00 26 FF 00 35 00 46 10 27 09 63 09 64 75 08 95 02 91 02"
  " 09 65 46 10 27 95 01 91 02 C0"
  // Set Periodic (output 4)
  " 09 6E A1 02 85 04 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 70 15 00 26 FF 00 35 00 46 10 27 75 08 95 01 91 02"
  " 09 6F 15 80 25 7F 36 F0 D8 46 10 27 95 01 91 02"
  " 09 71 66 14 00 55 FE 15 00 26 FF 00 35 00 47 A0 8C 00 00 91 02"
  " 09 72 26 FF 7F 46 FF 7F 66 03 10 55 FD 75 10 95 01 91 02 66 00 00 55 00 C0"
  // Set Constant Force (output 5): 16-bit magnitude -255..255
  " 09 73 A1 02 85 05 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 70 16 01 FF 26 FF 00 36 F0 D8 46 10 27 75 10 95 01 91 02 C0"
  // Set Ramp Force (output 6)
  " 09 74 A1 02 85 06 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 75 09 76 15 80 25 7F 36 F0 D8 46 10 27 75 08 95 02 91 02 C0"
  // Custom Force Data (output 7), with a buffered-bytes Output item
  " 09 68 A1 02 85 07 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 6C 15 00 26 10 27 35 00 46 10 27 75 10 95 01 91 02"
  " 09 69 15 81 25 7F 35 00 46 FF 00 75 08 95 0C 92 02 01 C0"
  // Download Force Sample (output 8)
  " 09 66 A1 02 85 08 05 01 09 30 09 31 15 81 25 7F 35 00 46 FF 00 75 08 95 02 91 02 C0"
  // Effect Operation (output 0x0A)
  " 05 0F 09 77 A1 02 85 0A 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 78 A1 02 09 79 09 7A 09 7B 15 01 25 03 75 08 95 01 91 00 C0"
  " 09 7C 15 00 26 FF 00 35 00 46 FF 00 91 02 C0"
  // Block Free (output 0x0B)
  " 09 90 A1 02 85 0B 09 22 25 28 15 01 35 01 45 28 75 08 95 01 91 02 C0"
  // Device Control (output 0x0C): selector array
  " 09 96 A1 02 85 0C 09 97 09 98 09 99 09 9A 09 9B 09 9C 15 01 25 06 75 08 95 01 91 00 C0"
  // Device Gain (output 0x0D)
  " 09 7D A1 02 85 0D 09 7E 15 00 26 FF 00 35 00 46 10 27 75 08 95 01 91 02 C0"
  // Set Custom Force (output 0x0E)
  " 09 6B A1 02 85 0E 09 22 15 01 25 28 35 01 45 28 75 08 95 01 91 02"
  " 09 6D 15 00 26 FF 00 35 00 46 FF 00 75 08 95 01 91 02"
  " 09 51 66 03 10 55 FD 15 00 26 FF 7F 35 00 46 FF 7F 75 10 95 01 91 02 55 00 66 00 00 C0"
  // Create New Effect (feature 9)
  " 09 AB A1 02 85 09 09 25 A1 02 09 26 09 27 09 30 09 31 09 32 09 33 09 34 09 40 09 41 09 42"
  " 09 43 09 28 25 0C 15 01 35 01 45 0C 75 08 95 01 B1 00 C0"
  " 05 01 09 3B 15 00 26 FF 01 35 00 46 FF 01 75 0A 95 01 B1 02 75 06 B1 01 C0"
  // Block Load (feature 0x20)
  " 05 0F 09 89 A1 02 85 20 09 22 25 28 15 01 35 01 45 28 75 08 95 01 B1 02"
  " 09 8B A1 02 09 8C 09 8D 09 8E 25 03 15 01 35 01 45 03 75 08 95 01 B1 00 C0"
  " 09 AC 15 00 27 FF FF 00 00 35 00 47 FF FF 00 00 75 10 95 01 B1 00 C0"
  // PID Pool (feature 3)
  " 09 7F A1 02 85 03 09 80 75 10 95 01 15 00 35 00 27 FF FF 00 00 47 FF FF 00 00 B1 02"
  " 09 83 26 FF 00 46 FF 00 75 08 95 01 B1 02"
  " 09 A9 09 AA 75 01 95 02 15 00 25 01 35 00 45 01 B1 02 75 06 95 01 B1 03 C0"
  // End of the enclosing game-pad collection (part of the published segment)
  " C0";

/// A device with no PID reports: the mouse of the HID specification, Device Class Definition for
/// HID 1.11, Appendix E.10 "Report Descriptor (Mouse)": 3 buttons, relative 8-bit X/Y, no report
/// ID.
inline const char* kHidSpecMouse =
  "05 01 09 02 A1 01 09 01 A1 00 05 09 19 01 29 03 15 00 25 01 95 03 75 01 81 02"
  " 95 01 75 05 81 01 05 01 09 30 09 31 15 81 25 7F 75 08 95 02 81 06 C0 C0";

/// A pen digitizer with physical units: Microsoft's sample "Integrated Windows Pen TLC" report
/// descriptor (Windows hardware documentation, "Sample report descriptors"; republished in
/// MicrosoftDocs/windows-driver-docs), report ID 1. X: logical 0..21240 over physical 0..8250 at
/// Unit 0x13 (English Linear, inch) and Unit Exponent -3, i.e. 8.250 in; Y: 0..15980 over
/// 6.188 in (PUSH/POP around them); tip pressure 0..255, X/Y tilt. No PID reports.
inline const char* kMicrosoftSamplePen =
  "05 0D 09 02 A1 01 85 01 09 20 A1 00 09 42 09 44 09 3C 09 45 15 00 25 01 75 01 95 04 81 02"
  " 95 01 81 03 09 32 81 02 95 02 81 03"
  " 05 01 09 30 75 10 95 01 A4 55 0D 65 13 35 00 46 3A 20 26 F8 52 81 02"
  " 09 31 46 2C 18 26 6C 3E 81 02 B4"
  " 05 0D 09 30 26 FF 00 81 02 75 08 09 3D 15 81 25 7F 81 02 09 3E 15 81 25 7F 81 02 C0 C0";

} // namespace test
} // namespace vtouch
