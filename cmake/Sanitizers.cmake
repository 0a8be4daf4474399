# -DVOXREMESH_SANITIZE=ON builds everything with AddressSanitizer and UBSan.
option(VOXREMESH_SANITIZE "Build with address and undefined-behaviour sanitizers" OFF)
if(VOXREMESH_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
  set(VOXREMESH_SANITIZER_LINK_OPTIONS -fsanitize=address,undefined)
endif()
