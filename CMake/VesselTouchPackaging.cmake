# CPack: the extension download (a .tar.gz with the plugin, its XML/config, Python files and notes).
set(CPACK_PACKAGE_NAME "VesselTouch")
set(CPACK_PACKAGE_VENDOR "VesselTouch")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Feel the 3D shape of vessel networks over a MIP (ParaView plugin)")
set(CPACK_GENERATOR "TGZ")
set(CPACK_PACKAGE_FILE_NAME "VesselTouch-${PROJECT_VERSION}-ParaView-5.11-${CMAKE_SYSTEM_NAME}-${CMAKE_SYSTEM_PROCESSOR}")
set(CPACK_INCLUDE_TOPLEVEL_DIRECTORY ON)
include(CPack)
