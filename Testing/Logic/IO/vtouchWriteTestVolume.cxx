// Writes the reader test volumes with ITK for the pvpython integration tests and the benchmark,
// and prints the geometry written as one JSON line.
//   vtouchWriteTestVolume volume <file> [axial|oblique] [pixel] [nx ny nz]
//   vtouchWriteTestVolume dicom <folder> <seriesUID> [axial|oblique] [skipSlice] [prefix] [nx ny
//   nz] vtouchWriteTestVolume bad2d|bad4d|badvector <file>
#include "vtouchTestVolumes.h"

#include <itkMacro.h>

#include <cstdlib>
#include <iostream>

namespace
{
void printGeometry(const vtouch::test::TestGeometry& g)
{
  std::cout.precision(17);
  std::cout << "{\"size\": [" << g.size[0] << ", " << g.size[1] << ", " << g.size[2]
            << "], \"spacing\": [" << g.spacing_mm[0] << ", " << g.spacing_mm[1] << ", "
            << g.spacing_mm[2] << "], \"origin\": [" << g.origin_LPS_mm[0] << ", "
            << g.origin_LPS_mm[1] << ", " << g.origin_LPS_mm[2] << "], \"direction\": [";
  for (int i = 0; i < 9; ++i)
  {
    std::cout << (i ? ", " : "") << g.direction[i];
  }
  std::cout << "]}" << std::endl;
}

vtouch::test::TestGeometry geometry(int argc, char** argv, int orientationArg, int sizeArg)
{
  vtouch::test::TestGeometry g;
  if (argc > orientationArg && std::string(argv[orientationArg]) == "oblique")
  {
    g = vtouch::test::obliqueGeometry();
  }
  if (argc > sizeArg + 2)
  {
    for (int a = 0; a < 3; ++a)
    {
      g.size[a] = static_cast<unsigned>(std::atoi(argv[sizeArg + a]));
    }
  }
  return g;
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 3)
  {
    std::cerr << "usage: " << argv[0] << " volume|dicom|bad2d|bad4d|badvector <path> ...\n";
    return 2;
  }
  const std::string what = argv[1];
  const std::string path = argv[2];
  try
  {
    if (what == "volume")
    {
      const auto g = geometry(argc, argv, 3, 5);
      vtouch::test::writeVolume(path, g, argc > 4 ? argv[4] : "int16");
      printGeometry(g);
    }
    else if (what == "dicom" && argc > 3)
    {
      const auto g = geometry(argc, argv, 4, 7);
      vtouch::test::writeDicomSeries(path,
        g,
        argv[3],
        argc > 5 ? std::atoi(argv[5]) : -1,
        argc > 6 ? argv[6] : "IM",
        argc > 10 ? argv[10] : "");
      printGeometry(g);
    }
    else if (what == "bad2d")
    {
      vtouch::test::write2D(path);
    }
    else if (what == "bad4d")
    {
      vtouch::test::write4D(path);
    }
    else if (what == "badvector")
    {
      vtouch::test::writeVector(path);
    }
    else
    {
      std::cerr << "unknown command " << what << "\n";
      return 2;
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "vtouchWriteTestVolume: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
