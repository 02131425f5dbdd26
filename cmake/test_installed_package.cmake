# Installs snh into a scratch prefix, builds examples/host_app,
# examples/flex_frames, examples/arm_rig and examples/scene_file against it
# with find_package(snh), and runs them: the install tree works for a host
# application.
include(${CMAKE_CURRENT_LIST_DIR}/run_step.cmake)
set(prefix ${BINARY_DIR}/install-test)
set(app_build ${BINARY_DIR}/host-app-build)
set(frames_build ${BINARY_DIR}/flex-frames-build)
set(rig_build ${BINARY_DIR}/arm-rig-build)
set(scene_build ${BINARY_DIR}/scene-file-build)
file(REMOVE_RECURSE ${prefix} ${app_build} ${frames_build} ${rig_build} ${scene_build})
foreach(step
    "${CMAKE_COMMAND};--install;${BINARY_DIR};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/examples/host_app;-B;${app_build};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${app_build}"
    "${app_build}/host_app"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/examples/arm_rig;-B;${rig_build};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${rig_build}"
    "${rig_build}/arm_rig;${SOURCE_DIR}/data/arm;6;${rig_build}/out"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/examples/flex_frames;-B;${frames_build};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${frames_build}"
    "${frames_build}/flex_frames;${frames_build}/out"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/examples/scene_file;-B;${scene_build};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${scene_build}"
    "${scene_build}/scene_file;${SOURCE_DIR}/data/scenes/soft_stiff_bar.json;${scene_build}/summary.json")
  snh_run_step(${step})
endforeach()
