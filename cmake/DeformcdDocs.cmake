# The API reference (Doxygen, docs/Doxyfile.in) as the target `docs`, only when Doxygen is
# installed (Debian's `doxygen`, scripts/install_deps.sh). Not part of `all`: build it with
# `cmake --build build/release --target docs`; the HTML lands in build/release/docs/api/html.
# Warnings are errors (WARN_AS_ERROR in the Doxyfile), so CI fails on an undocumented symbol.
# The target always reruns Doxygen (about 2 s for the public headers): no list of headers to
# keep in step.
find_package(Doxygen QUIET)
if(NOT DOXYGEN_FOUND)
  message(STATUS "Doxygen not found: no `docs` target (apt-get install doxygen)")
  return()
endif()

set(DEFORMCD_DOCS_OUTPUT "${PROJECT_BINARY_DIR}/docs/api")
configure_file(${PROJECT_SOURCE_DIR}/docs/Doxyfile.in ${PROJECT_BINARY_DIR}/docs/Doxyfile @ONLY)
add_custom_target(docs
  COMMAND ${CMAKE_COMMAND} -E rm -rf ${DEFORMCD_DOCS_OUTPUT}
  COMMAND Doxygen::doxygen ${PROJECT_BINARY_DIR}/docs/Doxyfile
  COMMENT "Doxygen: the API reference of include/deformcd (warnings are errors)"
  VERBATIM)
