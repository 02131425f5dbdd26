# Installs snh into a scratch prefix, builds examples/host_app against it with
# find_package(snh), and runs it: the install tree works for a host application.
set(prefix ${BINARY_DIR}/install-test)
set(app_build ${BINARY_DIR}/host-app-build)
file(REMOVE_RECURSE ${prefix} ${app_build})
foreach(step
    "${CMAKE_COMMAND};--install;${BINARY_DIR};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/examples/host_app;-B;${app_build};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${app_build}"
    "${app_build}/host_app")
  execute_process(COMMAND ${step} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${step}")
  endif()
endforeach()
