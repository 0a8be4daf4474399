# Installs the built project into a scratch prefix with `cmake --install`, builds the program in
# tests/install_package/ against it through find_package(voxremesh), and runs it on the sample
# part: the install must hold the CLI, the library, the headers and a working package config.
# Run by ctest as: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCXX=... -P this file
foreach(variable BUILD_DIR SOURCE_DIR WORK_DIR CXX)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "install_package_test: ${variable} is not set")
  endif()
endforeach()

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run_step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

include(GNUInstallDirs)
foreach(installed ${CMAKE_INSTALL_BINDIR}/voxremesh ${CMAKE_INSTALL_LIBDIR}/libvoxremesh_core.a
        ${CMAKE_INSTALL_INCLUDEDIR}/voxremesh/io.h
        ${CMAKE_INSTALL_LIBDIR}/cmake/voxremesh/voxremeshConfig.cmake
        ${CMAKE_INSTALL_LIBDIR}/cmake/voxremesh/voxremeshConfigVersion.cmake)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "cmake --install did not install ${installed}")
  endif()
endforeach()

run_step("configuring the consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install_package
         -B ${WORK_DIR}/consumer -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX}
         -DCMAKE_BUILD_TYPE=Release)
run_step("building the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
run_step("running the consumer" ${WORK_DIR}/consumer/remesh_one_deck
         ${SOURCE_DIR}/tools/samples/hat_rail.k)
if(NOT step_output MATCHES "part [0-9]+ (remeshed|retried)\n" OR NOT step_output MATCHES "shells [1-9]")
  message(FATAL_ERROR "the consumer did not remesh the sample part:\n${step_output}")
endif()

set(consumer_output "${step_output}")
run_step("the installed CLI" ${prefix}/${CMAKE_INSTALL_BINDIR}/voxremesh --version)
message(STATUS "installed package works:\n${consumer_output}${step_output}")
