# Fails when a C++/OpenCL source of the project differs from .clang-format.
file(GLOB_RECURSE sources ${SOURCE_DIR}/kernels/*.h ${SOURCE_DIR}/kernels/*.cl ${SOURCE_DIR}/host/*.h
     ${SOURCE_DIR}/host/*.cpp ${SOURCE_DIR}/host/*.inc ${SOURCE_DIR}/include/*.h ${SOURCE_DIR}/bench/*.h
     ${SOURCE_DIR}/bench/*.cpp ${SOURCE_DIR}/bench/*.cl ${SOURCE_DIR}/tests/*.h ${SOURCE_DIR}/tests/*.cpp ${SOURCE_DIR}/tests/*.inc
     ${SOURCE_DIR}/cli/*.h ${SOURCE_DIR}/cli/*.cpp ${SOURCE_DIR}/examples/*.cpp ${SOURCE_DIR}/python/src/*.h
     ${SOURCE_DIR}/python/src/*.cpp)
# Vendored sources keep their upstream formatting.
list(FILTER sources EXCLUDE REGEX "/host/third_party/")
execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${sources} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "clang-format: sources are not formatted (run clang-format -i on them)")
endif()
