# Install rules: the two libraries and their public headers, an exported CMake package (`find_package(geotri)`
# gives geotri::geodesic and geotri::geotri), a pkg-config file, and the geotri-* tools.
#
# Included at the end of the top-level CMakeLists.txt, once every target exists.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(GEOTRI_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/geotri"
    CACHE STRING "Where geotriConfig.cmake is installed, relative to the prefix")
mark_as_advanced(GEOTRI_INSTALL_CMAKEDIR)

# Libraries and headers.
install(TARGETS geodesic geotri
  EXPORT geotriTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY
    ${PROJECT_SOURCE_DIR}/libgeodesic/include/geodesic
    ${PROJECT_SOURCE_DIR}/libgeotri/include/geotri
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")

# CMake package. The config looks for OpenMP only when libgeotri was built with it.
if(OpenMP_CXX_FOUND)
  set(GEOTRI_NEEDS_OPENMP ON)
else()
  set(GEOTRI_NEEDS_OPENMP OFF)
endif()
install(EXPORT geotriTargets
  NAMESPACE geotri::
  FILE geotriTargets.cmake
  DESTINATION ${GEOTRI_INSTALL_CMAKEDIR})
configure_package_config_file(
  ${CMAKE_CURRENT_LIST_DIR}/geotriConfig.cmake.in
  ${PROJECT_BINARY_DIR}/geotriConfig.cmake
  INSTALL_DESTINATION ${GEOTRI_INSTALL_CMAKEDIR})
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/geotriConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMajorVersion)
install(FILES
    ${PROJECT_BINARY_DIR}/geotriConfig.cmake
    ${PROJECT_BINARY_DIR}/geotriConfigVersion.cmake
  DESTINATION ${GEOTRI_INSTALL_CMAKEDIR})

# pkg-config. Paths are relative to the .pc file, so that `cmake --install --prefix` anywhere gives a working file.
function(_geotri_pc_dir var dir)
  if(IS_ABSOLUTE "${dir}")
    set(${var} "${dir}" PARENT_SCOPE)
  else()
    set(${var} "\${prefix}/${dir}" PARENT_SCOPE)
  endif()
endfunction()
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(GEOTRI_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _geotri_up "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
  string(REGEX REPLACE "/$" "" _geotri_up "${_geotri_up}")
  set(GEOTRI_PC_PREFIX "\${pcfiledir}/${_geotri_up}")
endif()
_geotri_pc_dir(GEOTRI_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
_geotri_pc_dir(GEOTRI_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
set(GEOTRI_PC_OPENMP "")
if(GEOTRI_NEEDS_OPENMP)
  set(GEOTRI_PC_OPENMP "${OpenMP_CXX_FLAGS}")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/geotri.pc.in ${PROJECT_BINARY_DIR}/geotri.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/geotri.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# Tools. geotri_install_tool(<target>) installs one executable into bin/, once. This file is included after
# add_subdirectory(tools), so tools/CMakeLists.txt cannot call it; instead, every executable target named geotri-*
# that it creates is installed below.
function(geotri_install_tool target)
  if(NOT TARGET ${target})
    message(FATAL_ERROR "geotri_install_tool: no target named '${target}'")
  endif()
  get_property(_installed GLOBAL PROPERTY GEOTRI_INSTALLED_TOOLS)
  if(target IN_LIST _installed)
    return()
  endif()
  set_property(GLOBAL APPEND PROPERTY GEOTRI_INSTALLED_TOOLS ${target})
  if(BUILD_SHARED_LIBS AND NOT IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
    file(RELATIVE_PATH _lib "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${CMAKE_INSTALL_LIBDIR}")
    set_target_properties(${target} PROPERTIES INSTALL_RPATH "$ORIGIN/${_lib}")
  endif()
  install(TARGETS ${target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # Its man page, made from docs/tools.md and its --help by scripts/update-docs.sh.
  if(EXISTS ${PROJECT_SOURCE_DIR}/docs/man/${target}.1)
    install(FILES ${PROJECT_SOURCE_DIR}/docs/man/${target}.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
  endif()
endfunction()

if(GEOTRI_BUILD_TOOLS)
  get_property(_geotri_tool_targets DIRECTORY ${PROJECT_SOURCE_DIR}/tools PROPERTY BUILDSYSTEM_TARGETS)
  foreach(_tool IN LISTS _geotri_tool_targets)
    get_target_property(_type ${_tool} TYPE)
    if(_tool MATCHES "^geotri-" AND _type STREQUAL "EXECUTABLE")
      geotri_install_tool(${_tool})
    endif()
  endforeach()
endif()
