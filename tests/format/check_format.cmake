# The tree is clang-format clean (the repository's .clang-format, Debian 12's
# clang-format 14). Run as a test: cmake -DSOURCE_DIR=... -P check_format.cmake.
# A machine without clang-format fails with what to install; never skipped.
find_program(CLANG_FORMAT NAMES clang-format-14 clang-format)
if(NOT CLANG_FORMAT)
  message(FATAL_ERROR "clang-format not found: install Debian's clang-format (bash .ci/setup does)")
endif()
set(files)
foreach(folder mesh io voronoi remesh quality pipeline tests bench examples python)
  file(GLOB_RECURSE found RELATIVE ${SOURCE_DIR}
       ${SOURCE_DIR}/${folder}/*.cpp ${SOURCE_DIR}/${folder}/*.hpp ${SOURCE_DIR}/${folder}/*.h)
  list(APPEND files ${found})
endforeach()
list(LENGTH files count)
if(count LESS 50)
  message(FATAL_ERROR "found only ${count} C++ files under ${SOURCE_DIR}")
endif()
execute_process(COMMAND ${CLANG_FORMAT} --dry-run -Werror ${files}
                WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc ERROR_VARIABLE report)
if(NOT rc EQUAL 0)
  execute_process(COMMAND ${CLANG_FORMAT} --version OUTPUT_VARIABLE version)
  message(FATAL_ERROR "not clang-format clean (${version}); run clang-format -i on the files named:\n${report}")
endif()
message(STATUS "${count} files clang-format clean")
