# Every external dependency is found here, once, with its components named explicitly.

find_package(Threads REQUIRED)

# ITK 5.2 from Debian: name the components (the HDF5 IO modules are left out on purpose).
set(VESSELTOUCH_ITK_COMPONENTS
  ITKCommon
  ITKImageFilterBase
  ITKImageIntensity
  ITKThresholding
  ITKDistanceMap
  ITKImageFeature
  ITKRegionGrowing
  ITKSmoothing
  ITKConnectedComponents
  ITKIOImageBase
  ITKIOMeta
  ITKIONRRD
  ITKIONIFTI
  ITKIOGDCM
  ITKGDCM
)
find_package(ITK 5.2 REQUIRED COMPONENTS ${VESSELTOUCH_ITK_COMPONENTS})
# ITK's use file pollutes global include dirs; use the targets/variables explicitly instead.
set(VESSELTOUCH_ITK_LIBRARIES ${ITK_LIBRARIES})
set(VESSELTOUCH_ITK_INCLUDE_DIRS ${ITK_INCLUDE_DIRS})

# hidapi: the hidraw back end talks to /dev/hidraw* (no libusb detach dance).
find_package(PkgConfig REQUIRED)
pkg_check_modules(HIDAPI REQUIRED IMPORTED_TARGET hidapi-hidraw)

if(VESSELTOUCH_BUILD_TESTING)
  find_package(GTest REQUIRED)
endif()
if(VESSELTOUCH_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

if(VESSELTOUCH_BUILD_PLUGIN)
  find_package(ParaView 5.11 REQUIRED)
  find_package(Qt5 REQUIRED COMPONENTS Core Gui Widgets)
endif()
