# Builds examples/host_app with find_package(snh) pointed at the build tree
# (no install) and runs it: the build tree works as a package.
include(${CMAKE_CURRENT_LIST_DIR}/run_step.cmake)
set(app_build ${BINARY_DIR}/host-app-build-tree)
file(REMOVE_RECURSE ${app_build})
foreach(step
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/examples/host_app;-B;${app_build};-DCMAKE_PREFIX_PATH=${BINARY_DIR};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${app_build}"
    "${app_build}/host_app")
  snh_run_step(${step})
endforeach()
