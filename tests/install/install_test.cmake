# The steps of the install tests, run as `cmake -DSTEP=<step> ... -P install_test.cmake` (see CMakeLists.txt).
#   install             cmake --install BUILD_DIR into a fresh PREFIX, and check that the package files are there
#   cmake_consumer      configure, build and run consumer/ with find_package(geotri), finding it in PREFIX only
#   pkgconfig_consumer  compile consumer/main.cpp with the flags of PREFIX's geotri.pc (through PKG_CONFIG), run it
#   embed_example       configure and build examples/embed (EMBED_SOURCE_DIR) against PREFIX as cmake_consumer does,
#                       run it on MESH, check what it prints, and that its .gtri is the installed tools' one
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

# Configures and builds the CMake project in `source_dir` into `build` against PREFIX only, and sets `exe_var` to
# its executable `exe_name`.
function(build_against_prefix source_dir exe_name exe_var)
  file(REMOVE_RECURSE "${build}")
  set(generator_args -G "${GENERATOR}")
  if(MAKE_PROGRAM)
    list(APPEND generator_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
  endif()
  run("${CMAKE_COMMAND}" -S "${source_dir}" -B "${build}" ${generator_args}
      "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -DCMAKE_BUILD_TYPE=Release
      "-DCMAKE_PREFIX_PATH=${PREFIX}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  # The package must come from PREFIX, not from a geotri installed elsewhere on the machine.
  file(STRINGS "${build}/CMakeCache.txt" found REGEX "^geotri_DIR:")
  get_filename_component(prefix_real "${PREFIX}" REALPATH)
  if(NOT found MATCHES "=${PREFIX}/" AND NOT found MATCHES "=${prefix_real}/")
    message(FATAL_ERROR "${source_dir} found geotri outside ${PREFIX}: ${found}")
  endif()
  run("${CMAKE_COMMAND}" --build "${build}" --config Release)
  set(exe "${build}/${exe_name}")
  if(EXISTS "${build}/Release/${exe_name}${CMAKE_EXECUTABLE_SUFFIX}")
    set(exe "${build}/Release/${exe_name}")
  endif()
  set(${exe_var} "${exe}" PARENT_SCOPE)
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
  build_against_prefix("${CONSUMER_SOURCE_DIR}" geotri_consumer exe)
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

elseif(STEP STREQUAL "embed_example")
  build_against_prefix("${EMBED_SOURCE_DIR}" embed exe)

  # Without a mesh it prints its usage and exits 2.
  execute_process(COMMAND "${exe}" RESULT_VARIABLE result OUTPUT_QUIET ERROR_VARIABLE usage)
  if(NOT result EQUAL 2 OR NOT usage MATCHES "usage: embed MESH")
    message(FATAL_ERROR "embed without arguments: exit ${result}, not 2 with its usage:\n${usage}")
  endif()

  set(gtri "${build}/example.gtri")
  execute_process(COMMAND "${exe}" "${MESH}" 100 "${gtri}"
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
  message(STATUS "embed ${MESH} 100 ${gtri}:\n${output}${errors}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "embed failed (${result})")
  endif()
  # The path length agrees with the distance of the farthest vertex (embed.cpp checks it, and says so), G was built
  # and checked, and the program got to its last line.
  foreach(expected
      "distance field from vertex 0: farthest vertex [0-9]+ at distance [0-9]"
      "shortest path to vertex [0-9]+: [0-9]+ points, length [0-9.e+-]+ \\(agrees with the distance"
      "\nG: [0-9]+ faces, (valid|INVALID)"
      "\ndone\n$")
    if(NOT output MATCHES "${expected}")
      message(FATAL_ERROR "embed's output does not match '${expected}'")
    endif()
  endforeach()
  if(NOT EXISTS "${gtri}")
    message(FATAL_ERROR "embed did not write ${gtri}")
  endif()

  # build_geodesic_triangulation() is geotri-decimate --paths, geotri-trace --paths and geotri-flip in one call:
  # the installed tools, run one after another on the same mesh, write the same .gtri, byte for byte.
  set(tools "${PREFIX}/bin")
  run("${tools}/geotri-decimate" "${MESH}" -o "${build}/tools.off" --faces 100 --paths "${build}/tools.paths" --quiet)
  run("${tools}/geotri-trace" "${MESH}" "${build}/tools.off" --paths "${build}/tools.paths" -o "${build}/tools.gtri"
      --quiet)
  execute_process(COMMAND "${tools}/geotri-flip" "${build}/tools.gtri" -o "${build}/tools.flip.gtri" --quiet
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0 AND NOT result EQUAL 3)  # 3: written, but still invalid
    message(FATAL_ERROR "geotri-flip failed (${result})")
  endif()
  file(SHA256 "${gtri}" embedded)
  file(SHA256 "${build}/tools.flip.gtri" piped)
  if(NOT embedded STREQUAL piped)
    message(FATAL_ERROR "embed's ${gtri} differs from what geotri-decimate, geotri-trace and geotri-flip write")
  endif()

else()
  message(FATAL_ERROR "unknown STEP '${STEP}'")
endif()
