# voxremesh_set_warnings(target): the warning flags every voxremesh target is built with.
option(VOXREMESH_WERROR "Treat compiler warnings as errors" OFF)

function(voxremesh_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wcast-align -Woverloaded-virtual -Wnull-dereference)
  if(VOXREMESH_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
