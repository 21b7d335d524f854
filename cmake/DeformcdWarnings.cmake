# deformcd_set_warnings(target): the warnings every deformcd target is compiled with.
function(deformcd_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>)
  if(DEFORMCD_WERROR)
    target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-Werror>)
  endif()
  if(DEFORMCD_VALIDATE)
    target_compile_definitions(${target} PRIVATE DEFORMCD_VALIDATE=1)
  endif()
endfunction()
