# CPack: the extension download (a .tar.gz with the plugin, its XML/config, Python files and notes).
set(CPACK_PACKAGE_NAME "VesselTouch")
set(CPACK_PACKAGE_VENDOR "VesselTouch")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Feel the 3D shape of vessel networks over a MIP (ParaView plugin)")
set(CPACK_GENERATOR "TGZ")
set(CPACK_PACKAGE_FILE_NAME "VesselTouch-${PROJECT_VERSION}-ParaView-5.11-${CMAKE_SYSTEM_NAME}-${CMAKE_SYSTEM_PROCESSOR}")
set(CPACK_INCLUDE_TOPLEVEL_DIRECTORY ON)

# The download is the product's install components only (issue 18, item 4): not the GUI tests'
# VesselTouchTestDriver plugin (component VesselTouchTesting, Testing/ParaView/CMakeLists.txt) and
# not the development files (component Development, VesselTouchExport.cmake: EXCLUDE_FROM_ALL only
# keeps them out of a whole-project install, not out of a per-component one). Every other
# component, known at this point (the last file of the configure), goes in.
get_cmake_property(_vtouch_components COMPONENTS)
list(REMOVE_ITEM _vtouch_components VesselTouchTesting Development)
set(CPACK_INSTALL_CMAKE_PROJECTS "")
foreach(_component IN LISTS _vtouch_components)
  list(APPEND CPACK_INSTALL_CMAKE_PROJECTS "${CMAKE_BINARY_DIR}" "${PROJECT_NAME}" "${_component}" "/")
endforeach()
include(CPack)
