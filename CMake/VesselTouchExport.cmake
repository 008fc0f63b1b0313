# The development install: the plain C++ libraries (Core, HapticDevice, Model, Phantom, Skeleton,
# IO, Haptics, View) and the Qt widgets, their headers and a CMake package, so that another host
# adapter (a 3D Slicer loadable module: qSlicer*Module over the same Logic and Widgets) builds
# against them with
#
#   find_package(VesselTouch REQUIRED)
#   target_link_libraries(MyAdapter PRIVATE VesselTouch::Haptics VesselTouch::Widgets)
#
# Installed only when asked for, as the component "Development" (`cmake --install build
# --component Development`): EXCLUDE_FROM_ALL keeps it out of a plain install and of the extension
# download (CPack, VesselTouchPackaging.cmake). The VTK facade
# (VesselTouch::Logic) is a VTK module of ParaView's VTK and ships inside the plugin; a Slicer
# adapter builds its own facade against Slicer's VTK.
include(CMakePackageConfigHelpers)

set(_vtouch_export_targets VesselTouchCore VesselTouchHapticDevice VesselTouchModel)
foreach(_component Phantom Skeleton IO Haptics View Widgets)
  if(TARGET VesselTouch${_component})
    list(APPEND _vtouch_export_targets VesselTouch${_component})
  endif()
endforeach()
foreach(_target IN LISTS _vtouch_export_targets)
  # VesselTouch::Haptics rather than VesselTouch::VesselTouchHaptics for consumers too.
  string(REGEX REPLACE "^VesselTouch" "" _export_name "${_target}")
  set_target_properties(${_target} PROPERTIES EXPORT_NAME ${_export_name})
endforeach()

set(VESSELTOUCH_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/VesselTouch")
install(TARGETS ${_vtouch_export_targets}
  EXPORT VesselTouchTargets
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT Development EXCLUDE_FROM_ALL
  LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT Development EXCLUDE_FROM_ALL
  INCLUDES DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/VesselTouch")
install(EXPORT VesselTouchTargets
  NAMESPACE VesselTouch::
  DESTINATION "${VESSELTOUCH_INSTALL_CMAKEDIR}"
  COMPONENT Development
  EXCLUDE_FROM_ALL)

# Every public header of those libraries, flat in include/VesselTouch (names are unique: the
# vtouch/qVesselTouch prefixes).
set(_vtouch_header_dirs Logic/Core HapticDevice Logic/Model Logic/Phantom Logic/Skeleton Logic/IO
  Logic/Haptics Logic/View Widgets)
foreach(_dir IN LISTS _vtouch_header_dirs)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/${_dir}/"
    DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/VesselTouch"
    COMPONENT Development
    EXCLUDE_FROM_ALL
    FILES_MATCHING PATTERN "*.h" PATTERN "*.hxx" PATTERN "*.def"
    PATTERN "Fuzz" EXCLUDE PATTERN "Tools" EXCLUDE)
endforeach()

string(REPLACE ";" " " VESSELTOUCH_ITK_COMPONENTS_SPACED "${VESSELTOUCH_ITK_COMPONENTS}")
if(TARGET VesselTouchWidgets)
  set(VESSELTOUCH_EXPORTS_WIDGETS TRUE)
else()
  set(VESSELTOUCH_EXPORTS_WIDGETS FALSE)
endif()
configure_package_config_file("${PROJECT_SOURCE_DIR}/CMake/VesselTouchConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/VesselTouchConfig.cmake"
  INSTALL_DESTINATION "${VESSELTOUCH_INSTALL_CMAKEDIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/VesselTouchConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/VesselTouchConfig.cmake"
  "${PROJECT_BINARY_DIR}/VesselTouchConfigVersion.cmake"
  DESTINATION "${VESSELTOUCH_INSTALL_CMAKEDIR}"
  COMPONENT Development
  EXCLUDE_FROM_ALL)
