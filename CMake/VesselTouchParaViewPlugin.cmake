# Builds the plugin in Modules/ParaView the way ParaView expects (paraview_plugin_scan/build).
# Build tree:  lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so
#              lib/paraview-5.11/plugins/VesselTouch.xml   (the plugin configuration file)
set(VESSELTOUCH_PLUGIN_SUBDIR "paraview-${ParaView_VERSION_MAJOR}.${ParaView_VERSION_MINOR}/plugins")

# ParaView loads plugins as shared libraries; the project's own libraries above stay static
# (position-independent) and are linked into the plugin.
set(BUILD_SHARED_LIBS ON)

paraview_plugin_scan(
  PLUGIN_FILES "${PROJECT_SOURCE_DIR}/Modules/ParaView/paraview.plugin"
  PROVIDES_PLUGINS _vtouch_plugins
  ENABLE_BY_DEFAULT ON
  HIDE_PLUGINS_FROM_CACHE ON)

paraview_plugin_build(
  PLUGINS ${_vtouch_plugins}
  TARGET VesselTouchPlugins
  RUNTIME_DESTINATION "${CMAKE_INSTALL_BINDIR}"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  LIBRARY_SUBDIRECTORY "${VESSELTOUCH_PLUGIN_SUBDIR}"
  PLUGINS_FILE_NAME "VesselTouch.xml"
  INSTALL_HEADERS OFF
  ADD_INSTALL_RPATHS ON)

# The extension download also carries an install note, the README (its scripting example is what
# the package test runs) and, for reading, the Python, XML and Qt Designer (.ui) sources that are
# embedded into the plugin. The device presets (share/VesselTouch/Presets) are installed by
# HapticDevice/CMakeLists.txt.
install(FILES "${PROJECT_SOURCE_DIR}/Docs/INSTALL-EXTENSION.md" DESTINATION . RENAME INSTALL.md)
install(FILES "${PROJECT_SOURCE_DIR}/README.md" DESTINATION .)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/Resources/UI/"
  DESTINATION "${CMAKE_INSTALL_DATADIR}/VesselTouch/UI" FILES_MATCHING PATTERN "*.ui")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/Modules/ParaView/vesseltouch"
  DESTINATION "${CMAKE_INSTALL_DATADIR}/VesselTouch/python" FILES_MATCHING PATTERN "*.py")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/Modules/ParaView/ServerManager/"
  DESTINATION "${CMAKE_INSTALL_DATADIR}/VesselTouch/ServerManager" FILES_MATCHING PATTERN "*.xml")
install(FILES "${VESSELTOUCH_SESSION_XML}"
  DESTINATION "${CMAKE_INSTALL_DATADIR}/VesselTouch/ServerManager")

set(VESSELTOUCH_PLUGIN_DIR
  "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}/${VESSELTOUCH_PLUGIN_SUBDIR}/VesselTouch"
  CACHE INTERNAL "Folder of the built plugin")
set(VESSELTOUCH_PLUGIN_CONFIG
  "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}/${VESSELTOUCH_PLUGIN_SUBDIR}/VesselTouch.xml"
  CACHE INTERNAL "The built tree's plugin configuration file")
