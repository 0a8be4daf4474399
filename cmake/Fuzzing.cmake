# -DVOXREMESH_FUZZ=ON builds the libFuzzer harnesses of tests/fuzz (clang only). Everything is
# compiled with coverage instrumentation plus AddressSanitizer and UBSan (UB aborts, so libFuzzer
# reports it), so the library code the harnesses reach is instrumented too.
option(VOXREMESH_FUZZ "Build the libFuzzer harnesses (clang only)" OFF)
if(VOXREMESH_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "VOXREMESH_FUZZ needs clang (libFuzzer); configure with "
                        "CC=clang CXX=clang++ (compiler here: ${CMAKE_CXX_COMPILER_ID})")
  endif()
  # oneTBB's concurrent_hash_map (used by OpenVDB's tree accessor registry) downcasts a tagged
  # pointer (0x3) in its iterator: UB inside TBB's headers that aborted `voxremesh voxelize` under
  # -fno-sanitize-recover (oneTBB issue #908, fixed upstream by oneTBB PR #959). UBSan therefore
  # skips TBB's headers; ASan still covers them.
  set(VOXREMESH_FUZZ_IGNORELIST ${CMAKE_BINARY_DIR}/fuzz_ubsan_ignorelist.txt)
  # CONFIGURE rewrites the file only when its content changes (every object depends on it).
  file(CONFIGURE OUTPUT ${VOXREMESH_FUZZ_IGNORELIST} CONTENT "[undefined]\nsrc:*/tbb/*\n")
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fsanitize-ignorelist=${VOXREMESH_FUZZ_IGNORELIST}
                      -fno-omit-frame-pointer -gline-tables-only)
  # The non-fuzzer programs (the CLI, benchmarks) link the sanitizer runtimes, which also provide
  # the coverage callbacks the instrumented library calls.
  add_link_options(-fsanitize=address,undefined)
  set(VOXREMESH_SANITIZER_LINK_OPTIONS -fsanitize=address,undefined)
  # voxremesh_core is defined after this include; target names are resolved at generate time.
  add_subdirectory(tests/fuzz)
endif()
