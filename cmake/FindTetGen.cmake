# Finds TetGen's library (Debian's libtet, AGPL-3) and gives the imported target TetGen::tet.
# Installed with deformcd's package for deformcd::tetgen's link interface.
find_path(TetGen_INCLUDE_DIR tetgen.h)
find_library(TetGen_LIBRARY tet)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(TetGen REQUIRED_VARS TetGen_LIBRARY TetGen_INCLUDE_DIR)
if(TetGen_FOUND AND NOT TARGET TetGen::tet)
  add_library(TetGen::tet UNKNOWN IMPORTED)
  set_target_properties(TetGen::tet PROPERTIES IMPORTED_LOCATION "${TetGen_LIBRARY}"
                                               INTERFACE_INCLUDE_DIRECTORIES "${TetGen_INCLUDE_DIR}"
                                               # libtet throws an int instead of calling exit()
                                               INTERFACE_COMPILE_DEFINITIONS TETLIBRARY)
endif()
mark_as_advanced(TetGen_INCLUDE_DIR TetGen_LIBRARY)
