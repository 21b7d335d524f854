# Install rules and the exported package: find_package(deformcd) gives deformcd::core,
# deformcd::io, and (when built) deformcd::gl, deformcd::render and deformcd::tetgen.
include(CMakePackageConfigHelpers)

set(_deformcd_targets deformcd_core deformcd_io deformcd_cpu deformcd_scene deformcd_world)
if(TARGET deformcd_gl)
  list(APPEND _deformcd_targets deformcd_gl)
endif()
if(TARGET deformcd_render)
  list(APPEND _deformcd_targets deformcd_render)
endif()
if(TARGET deformcd_tetgen)
  list(APPEND _deformcd_targets deformcd_tetgen)
endif()

install(TARGETS ${_deformcd_targets} EXPORT deformcdTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/deformcd DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(TARGET deformcd)
  install(TARGETS deformcd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(DEFORMCD_CONFIG_WITH_GL ${DEFORMCD_WITH_GL})
set(DEFORMCD_CONFIG_WITH_TETGEN ${DEFORMCD_WITH_TETGEN})
install(EXPORT deformcdTargets NAMESPACE deformcd::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/deformcd)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/deformcdConfig.cmake.in
  ${PROJECT_BINARY_DIR}/deformcdConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/deformcd)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/deformcdConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/deformcdConfig.cmake
              ${PROJECT_BINARY_DIR}/deformcdConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/deformcd)
