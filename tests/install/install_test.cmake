# The steps of the install tests, run as `cmake -DSTEP=<step> ... -P install_test.cmake` (see CMakeLists.txt).
#   install             cmake --install BUILD_DIR into a fresh PREFIX, and check that the package files are there
#   cmake_consumer      configure, build and run consumer/ with find_package(geotri), finding it in PREFIX only
#   pkgconfig_consumer  compile consumer/main.cpp with the flags of PREFIX's geotri.pc (through PKG_CONFIG), run it
cmake_minimum_required(VERSION 3.16)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "failed (${result}): ${command}")
  endif()
endfunction()

# The one installed file under PREFIX/<libdir>/<subpath>, whatever the libdir (lib, lib64, lib/<multiarch>).
function(find_installed var subpath)
  file(GLOB found "${PREFIX}/lib*/${subpath}" "${PREFIX}/lib/*/${subpath}")
  if(NOT found)
    message(FATAL_ERROR "the install has no <libdir>/${subpath}")
  endif()
  list(GET found 0 found)
  set(${var} "${found}" PARENT_SCOPE)
endfunction()

set(build "${WORK_DIR}/${STEP}")

if(STEP STREQUAL "install")
  file(REMOVE_RECURSE "${PREFIX}")
  set(config_args "")
  if(CONFIG)
    set(config_args --config "${CONFIG}")
  endif()
  run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}" ${config_args})
  find_installed(config_file cmake/geotri/geotriConfig.cmake)
  find_installed(version_file cmake/geotri/geotriConfigVersion.cmake)
  find_installed(pc_file pkgconfig/geotri.pc)
  foreach(header geodesic/errors.h geodesic/exact_geodesic.h geodesic/mesh.h geodesic/surface_point.h
                 geotri/mesh_io.h)
    if(NOT EXISTS "${PREFIX}/include/${header}")
      message(FATAL_ERROR "the install has no include/${header}")
    endif()
  endforeach()

elseif(STEP STREQUAL "cmake_consumer")
  file(REMOVE_RECURSE "${build}")
  set(generator_args -G "${GENERATOR}")
  if(MAKE_PROGRAM)
    list(APPEND generator_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
  endif()
  run("${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${build}" ${generator_args}
      "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -DCMAKE_BUILD_TYPE=Release
      "-DCMAKE_PREFIX_PATH=${PREFIX}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  # The package must come from PREFIX, not from a geotri installed elsewhere on the machine.
  file(STRINGS "${build}/CMakeCache.txt" found REGEX "^geotri_DIR:")
  get_filename_component(prefix_real "${PREFIX}" REALPATH)
  if(NOT found MATCHES "=${PREFIX}/" AND NOT found MATCHES "=${prefix_real}/")
    message(FATAL_ERROR "the consumer found geotri outside ${PREFIX}: ${found}")
  endif()
  run("${CMAKE_COMMAND}" --build "${build}" --config Release)
  set(exe "${build}/geotri_consumer")
  if(EXISTS "${build}/Release/geotri_consumer${CMAKE_EXECUTABLE_SUFFIX}")
    set(exe "${build}/Release/geotri_consumer")
  endif()
  run("${exe}" "${build}")

elseif(STEP STREQUAL "pkgconfig_consumer")
  find_installed(pc_file pkgconfig/geotri.pc)
  get_filename_component(pc_dir "${pc_file}" DIRECTORY)
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -E env "PKG_CONFIG_PATH=${pc_dir}" "${PKG_CONFIG}" --cflags --libs geotri
    OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "pkg-config cannot resolve ${pc_file}")
  endif()
  message(STATUS "pkg-config --cflags --libs geotri: ${flags}")
  separate_arguments(flags UNIX_COMMAND "${flags}")
  file(REMOVE_RECURSE "${build}")
  file(MAKE_DIRECTORY "${build}")
  run("${CXX_COMPILER}" -std=c++17 -O1 "${CONSUMER_SOURCE_DIR}/main.cpp" -o "${build}/geotri_consumer" ${flags})
  run("${build}/geotri_consumer" "${build}")

else()
  message(FATAL_ERROR "unknown STEP '${STEP}'")
endif()
