# Finds the libraries voxremesh builds on, all from Debian's packages (tools/install_dependencies.sh).
find_package(Threads REQUIRED)
find_package(TBB REQUIRED)

# Debian ships FindOpenVDB.cmake outside CMake's default module path; it needs boost-iostreams.
# The installed package config (cmake/voxremeshConfig.cmake.in) looks in the same folders.
set(VOXREMESH_OPENVDB_MODULE_DIRS /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB)
list(APPEND CMAKE_MODULE_PATH ${VOXREMESH_OPENVDB_MODULE_DIRS})
find_package(OpenVDB REQUIRED)

# zlib (a dependency of OpenVDB anyway) compresses the PNG images of `voxremesh slice`.
find_package(ZLIB REQUIRED)
# With Blosc (OpenVDB's other codec; FindBlosc.cmake ships beside FindOpenVDB.cmake), zlib also
# decompresses each block of a .vdb file's trees in its layout check (vdb_tree_layout.cpp).
find_package(Blosc REQUIRED)

find_package(OpenMesh REQUIRED)
if(NOT TARGET OpenMeshCore)
  message(FATAL_ERROR "OpenMesh was found but defines no OpenMeshCore target")
endif()

if(VOXREMESH_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()

find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
endif()
