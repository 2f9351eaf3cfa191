# ctest install_puts_topple_on_a_prefix (tests/CMakeLists.txt): `cmake --install BUILD --prefix PREFIX`, as the README
# tells users to put `topple` on their PATH, must install PREFIX/bin/topple, and that copy must run from another
# folder (no path into the build or source tree) and report the project's version.
# Arguments: -DBUILD_DIR=... -DPREFIX=... -DEXPECTED_VERSION=...
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${out}${err}")
endif()
set(exe "${PREFIX}/bin/topple")
if(NOT EXISTS "${exe}")
  message(FATAL_ERROR "cmake --install did not install ${exe}:\n${out}")
endif()
execute_process(COMMAND "${exe}" --version WORKING_DIRECTORY "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE version ERROR_VARIABLE err)
string(STRIP "${version}" version)
if(NOT rc EQUAL 0 OR NOT version STREQUAL "topple ${EXPECTED_VERSION}")
  message(FATAL_ERROR "installed topple --version: status ${rc}, output '${version}' (expected "
                      "'topple ${EXPECTED_VERSION}'): ${err}")
endif()
file(REMOVE_RECURSE "${PREFIX}")
