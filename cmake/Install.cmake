# `cmake --install build [--prefix DIR]`: the voxremesh command line tool, the library
# (voxremesh::core), its public headers, the default quality criteria file and a CMake package,
# so that another project can use
#   find_package(voxremesh REQUIRED)
#   target_link_libraries(my_tool PRIVATE voxremesh::core)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# An instrumented library (VOXREMESH_SANITIZE, VOXREMESH_FUZZ) needs the sanitizer runtimes in
# every program that links it.
if(VOXREMESH_SANITIZER_LINK_OPTIONS)
  target_link_options(voxremesh_core INTERFACE
                      $<INSTALL_INTERFACE:${VOXREMESH_SANITIZER_LINK_OPTIONS}>)
endif()

set(VOXREMESH_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/voxremesh)

install(TARGETS voxremesh RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS voxremesh_core EXPORT voxremeshTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/voxremesh DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The default quality criteria, a starting point for a user's own (criteria_file.h).
install(FILES ${PROJECT_SOURCE_DIR}/share/criteria/default.txt
        DESTINATION ${CMAKE_INSTALL_DATADIR}/voxremesh/criteria)
install(EXPORT voxremeshTargets NAMESPACE voxremesh:: DESTINATION ${VOXREMESH_CMAKE_DIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/voxremeshConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/voxremeshConfig.cmake INSTALL_DESTINATION ${VOXREMESH_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/voxremeshConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/voxremeshConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/voxremeshConfigVersion.cmake
        DESTINATION ${VOXREMESH_CMAKE_DIR})
