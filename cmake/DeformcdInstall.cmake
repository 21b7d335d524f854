# Install rules and the exported package, by component:
#   find_package(deformcd 0.2 REQUIRED COMPONENTS collision)   # the Detector alone
#   collision: deformcd::core, deformcd::cpu, deformcd::collision (+ deformcd::gl when built)
#   io:        deformcd::io (mesh files)                  needs collision's core
#   scene:     deformcd::scene (scene files)              needs io
#   world:     deformcd::world (simulation + detector)    needs collision
#   render:    deformcd::render (when built)              needs world
#   tetgen:    deformcd::tetgen (AGPL-3, when built)      needs io
# Each component is its own export set, loaded only when asked for (or needed by one asked
# for), with its dependencies found again through their own packages or the Find modules
# installed beside the config: the exported targets name imported targets, never a path of the
# machine they were built on. Also installed: the tool, and share/deformcd with the shipped
# scenes and the paper's models (the scenes' relative model paths resolve there) and LICENSE.
include(CMakePackageConfigHelpers)

set(_deformcd_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/deformcd)
set(DEFORMCD_CONFIG_COMPONENTS collision io scene world)

function(deformcd_install_component component)
  install(TARGETS ${ARGN} EXPORT deformcd-${component}-targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT deformcd-${component}-targets NAMESPACE deformcd::
          FILE deformcd-${component}-targets.cmake DESTINATION ${_deformcd_cmake_dir})
endfunction()

set(_deformcd_collision_targets deformcd_core deformcd_cpu deformcd_collision)
if(TARGET deformcd_gl)
  list(APPEND _deformcd_collision_targets deformcd_gl)
endif()
deformcd_install_component(collision ${_deformcd_collision_targets})
deformcd_install_component(io deformcd_io)
deformcd_install_component(scene deformcd_scene)
deformcd_install_component(world deformcd_world)
if(TARGET deformcd_render)
  deformcd_install_component(render deformcd_render)
  list(APPEND DEFORMCD_CONFIG_COMPONENTS render)
endif()
if(TARGET deformcd_tetgen)
  deformcd_install_component(tetgen deformcd_tetgen)
  list(APPEND DEFORMCD_CONFIG_COMPONENTS tetgen)
endif()

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/deformcd DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(TARGET deformcd)
  install(TARGETS deformcd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes DESTINATION ${CMAKE_INSTALL_DATADIR}/deformcd
        FILES_MATCHING PATTERN "*.json" PATTERN "*.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/models
        DESTINATION ${CMAKE_INSTALL_DATADIR}/deformcd/assets
        FILES_MATCHING PATTERN "*.node" PATTERN "*.ele" PATTERN "*.face" PATTERN "*.off"
                       PATTERN "*.md")
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/deformcd)

set(DEFORMCD_CONFIG_WITH_GL ${DEFORMCD_WITH_GL})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/deformcdConfig.cmake.in
  ${PROJECT_BINARY_DIR}/deformcdConfig.cmake
  INSTALL_DESTINATION ${_deformcd_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/deformcdConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/deformcdConfig.cmake
              ${PROJECT_BINARY_DIR}/deformcdConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FindStb.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FindTetGen.cmake
        DESTINATION ${_deformcd_cmake_dir})
