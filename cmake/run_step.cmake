# snh_run_step(COMMAND WORDS...): runs one step of a package test, failing
# the test with the step's words and exit status when it fails.
function(snh_run_step)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGV}")
  endif()
endfunction()
