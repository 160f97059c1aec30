# What `cmake --install` lays out (the folders are set in the top-level CMakeLists.txt): a 3D Slicer
# extension's tree, runnable from any prefix, and a CMake package through which a C++ project
# finds the logic: find_package(VesselProximity) and link VesselProximity::VesselProximityLogic.
include(CMakePackageConfigHelpers)

# Each program finds our library beside itself or one folder over; the system's libraries by the
# linker's own search, HDF5's serial folder through CMAKE_INSTALL_RPATH_USE_LINK_PATH.
set_target_properties(VesselProximityCommands VesselProximityWidgets VesselProximityPhantom PROPERTIES INSTALL_RPATH "$ORIGIN")
set_target_properties(VesselProximityModule VesselProximityDemoModule PROPERTIES INSTALL_RPATH "$ORIGIN/../qt-loadable-modules")
set_target_properties(VesselProximityModels VesselProximityDistance VesselProximityTrack PROPERTIES
  INSTALL_RPATH "$ORIGIN/../qt-loadable-modules")

install(TARGETS VesselProximityLogic EXPORT VesselProximityTargets
  LIBRARY DESTINATION ${VP_INSTALL_LIBRARY_DIR}
  INCLUDES DESTINATION ${VP_INSTALL_INCLUDE_DIR})
# The module with the libraries it links beside it, as Slicer keeps a module's logic and widgets.
install(TARGETS VesselProximityCommands VesselProximityWidgets VesselProximityPhantom LIBRARY DESTINATION ${VP_INSTALL_LIBRARY_DIR})
install(TARGETS VesselProximityModule VesselProximityDemoModule LIBRARY DESTINATION ${VP_INSTALL_MODULE_DIR})
# The extension's description, as Slicer's extension index reads it.
install(FILES ${PROJECT_SOURCE_DIR}/Resources/VesselProximity.s4ext DESTINATION ${VP_INSTALL_SLICER_DIR})
install(TARGETS VesselProximityModels VesselProximityDistance VesselProximityTrack RUNTIME DESTINATION ${VP_INSTALL_CLI_DIR})
install(TARGETS vesselproximity RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# The public headers (Logic/PublicHeaders.txt) and every header of ours they include, found by
# following their #include "..." lines through the logic's folders.
set(_vp_logic ${PROJECT_SOURCE_DIR}/Logic)
file(GLOB_RECURSE _vp_all_headers ${_vp_logic}/*.h)
file(STRINGS ${_vp_logic}/PublicHeaders.txt _vp_pending REGEX "^[^#].*\\.h$")
set(_vp_installed_headers "")
while(_vp_pending)
  list(POP_FRONT _vp_pending _vp_name)
  set(_vp_path "")
  foreach(_vp_candidate IN LISTS _vp_all_headers)
    get_filename_component(_vp_base ${_vp_candidate} NAME)
    if(_vp_base STREQUAL _vp_name)
      set(_vp_path ${_vp_candidate})
    endif()
  endforeach()
  if(NOT _vp_path OR _vp_path IN_LIST _vp_installed_headers)
    continue() # a system header in quotes, or one already taken
  endif()
  list(APPEND _vp_installed_headers ${_vp_path})
  file(STRINGS ${_vp_path} _vp_includes REGEX "^#include \"[^\"]+\"")
  foreach(_vp_line IN LISTS _vp_includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" _vp_included "${_vp_line}")
    list(APPEND _vp_pending ${_vp_included})
  endforeach()
endwhile()
install(FILES ${_vp_installed_headers} DESTINATION ${VP_INSTALL_INCLUDE_DIR})

# The package: the logic's target, and the packages its public interface needs.
set(VP_VTK_COMPONENTS "")
foreach(_vp_vtk IN LISTS VP_VTK_LOGIC_LIBRARIES)
  string(REPLACE "VTK::" "" _vp_vtk ${_vp_vtk})
  list(APPEND VP_VTK_COMPONENTS ${_vp_vtk})
endforeach()
string(REPLACE ";" " " VP_VTK_COMPONENTS "${VP_VTK_COMPONENTS}")
install(EXPORT VesselProximityTargets NAMESPACE VesselProximity:: DESTINATION ${VP_INSTALL_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/CMake/VesselProximityConfig.cmake.in
  ${CMAKE_BINARY_DIR}/VesselProximityConfig.cmake INSTALL_DESTINATION ${VP_INSTALL_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/VesselProximityConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/VesselProximityConfig.cmake ${CMAKE_BINARY_DIR}/VesselProximityConfigVersion.cmake
  DESTINATION ${VP_INSTALL_CMAKE_DIR})

# What the CLIs' documentation-url points at once installed (the README, and the guides and
# pictures it links to, in the same places relative to it), and the licence.
set(VP_INSTALL_DOC_DIR ${CMAKE_INSTALL_DATADIR}/doc/VesselProximity)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${VP_INSTALL_DOC_DIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/Documentation DESTINATION ${VP_INSTALL_DOC_DIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/Resources/Documentation DESTINATION ${VP_INSTALL_DOC_DIR}/Resources)
