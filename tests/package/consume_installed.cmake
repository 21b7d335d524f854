# CTest script: installs the build tree into a fresh prefix, checks that no exported target names
# a path of this machine's libraries, then builds and runs a consumer project against it.
# -D BUILD_DIR=... -D SOURCE_DIR=... -D WORK_DIR=... [-D CXX_FLAGS=... -D LINKER_FLAGS=...]
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
file(GLOB exports "${WORK_DIR}/prefix/lib*/cmake/deformcd/deformcd-*-targets*.cmake")
if(NOT exports)
  message(FATAL_ERROR "no exported targets installed")
endif()
foreach(f IN LISTS exports)
  file(READ "${f}" text)
  if(text MATCHES "/usr/lib[^\"]*\\.(so|a)")
    message(FATAL_ERROR "${f} names a library path of the build machine: ${CMAKE_MATCH_0}")
  endif()
  if(text MATCHES "${BUILD_DIR}" OR text MATCHES "${SOURCE_DIR}")
    message(FATAL_ERROR "${f} names the build or source tree")
  endif()
endforeach()
foreach(scene phase1.json fold.json)
  if(NOT EXISTS "${WORK_DIR}/prefix/share/deformcd/scenes/${scene}")
    message(FATAL_ERROR "share/deformcd/scenes/${scene} not installed")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/package/consumer"
                        -B "${WORK_DIR}/build" -G Ninja "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix"
                        "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the consumer against the installed package failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK_DIR}/build" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer failed")
endif()
execute_process(COMMAND "${WORK_DIR}/build/consumer" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the consumer failed (${rc})")
endif()
# A version this package does not satisfy, and a component it does not have, must fail.
file(WRITE "${WORK_DIR}/old/CMakeLists.txt"
     "cmake_minimum_required(VERSION 3.25)\nproject(old NONE)\nfind_package(deformcd 0.1 REQUIRED)\n")
execute_process(COMMAND ${CMAKE_COMMAND} -S "${WORK_DIR}/old" -B "${WORK_DIR}/old/build"
                        "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "find_package(deformcd 0.1) accepted version 0.2")
endif()
file(WRITE "${WORK_DIR}/bogus/CMakeLists.txt"
     "cmake_minimum_required(VERSION 3.25)\nproject(bogus NONE)\nfind_package(deformcd 0.2 REQUIRED COMPONENTS nonsense)\n")
execute_process(COMMAND ${CMAKE_COMMAND} -S "${WORK_DIR}/bogus" -B "${WORK_DIR}/bogus/build"
                        "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "find_package(deformcd COMPONENTS nonsense) succeeded")
endif()
# ... naming the component and the valid ones (CMake wraps the message: spaces may be newlines).
string(REGEX REPLACE "[ \t\r\n]+" " " err "${err}")
if(NOT err MATCHES "unknown component 'nonsense' \\(valid: collision, io, scene, world, render, tetgen")
  message(FATAL_ERROR "find_package(deformcd COMPONENTS nonsense) did not name the component "
                      "and the valid ones:\n${err}")
endif()
message(STATUS "installed package: consumer built and ran, versions and components checked")
