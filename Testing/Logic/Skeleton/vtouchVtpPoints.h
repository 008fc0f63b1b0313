// Minimal reader for the points of a VTK XML PolyData file (.vtp) as VMTK writes them: inline
// "binary" (base64) arrays, optionally zlib-compressed (vtkZLibDataCompressor), UInt32 or UInt64
// headers, Float32 or Float64 points. Enough for a reference centerline in a test.
#pragma once

#include "vtouchVector.h"

#include <string>
#include <vector>

namespace vtouch
{
namespace test
{

/// Reads the "Points" array. Returns false and sets `error` when the file is not understood.
bool readVtpPoints(const std::string& fileName, std::vector<Vec3>& points, std::string& error);

} // namespace test
} // namespace vtouch
