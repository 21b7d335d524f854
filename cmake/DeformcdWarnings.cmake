# deformcd_set_warnings(target): the warnings every deformcd target is compiled with.
function(deformcd_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>)
  # GCC 12 at -O3 warns -Wrestrict inside libstdc++'s std::string (GCC bug 105651, a false
  # positive in system headers that -Werror would turn into a build failure).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(DEFORMCD_WERROR)
    target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-Werror>)
  endif()
  if(DEFORMCD_VALIDATE)
    target_compile_definitions(${target} PRIVATE DEFORMCD_VALIDATE=1)
  endif()
endfunction()
