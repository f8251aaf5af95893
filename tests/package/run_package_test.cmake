# cmake -P driver of the package_install_and_consume test (see CMakeLists.txt
# here): -DBUILD_DIR -DCONFIG -DWORK_DIR -DCONSUMER_DIR -DGENERATOR
# -DCXX_COMPILER -DCXX_FLAGS -DVERSION. Any failed step is a FATAL_ERROR
# (non-zero exit) that prints the step's output.
cmake_minimum_required(VERSION 3.25)

foreach(var BUILD_DIR WORK_DIR CONSUMER_DIR GENERATOR CXX_COMPILER VERSION)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_package_test.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run_or_fail what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(JOIN " " command ${ARGN})
    message(FATAL_ERROR "package test: ${what} failed (exit ${rc}):\n${command}\n${out}${err}")
  endif()
  set(run_output "${out}${err}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(stage ${WORK_DIR}/stage)
set(prefix ${WORK_DIR}/prefix)

# 1. Install, then move the tree: the package must not remember where it was
#    installed (nor point back into the build or source tree).
set(config_args)
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()
run_or_fail("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${stage} ${config_args})
file(RENAME ${stage} ${prefix})

file(GLOB_RECURSE config_files ${prefix}/*/geodual-config.cmake)
list(LENGTH config_files config_count)
if(NOT config_count EQUAL 1)
  message(FATAL_ERROR "package test: expected one geodual-config.cmake under ${prefix}, found: ${config_files}")
endif()
get_filename_component(package_dir ${config_files} DIRECTORY)
foreach(file
    bin/geodual
    include/geodual/triangle_mesh.hpp include/geodual/error.hpp
    include/geodual/io/gltf.hpp include/geodual/voronoi/geodesic_field.hpp
    include/geodual/remesh/remesh.hpp include/geodual/pipeline/version.hpp)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "package test: ${file} was not installed under ${prefix}")
  endif()
endforeach()
foreach(file geodual-config-version.cmake geodual-targets.cmake)
  if(NOT EXISTS ${package_dir}/${file})
    message(FATAL_ERROR "package test: ${package_dir}/${file} was not installed")
  endif()
endforeach()
file(GLOB package_files ${package_dir}/*.cmake)
foreach(file IN LISTS package_files)
  file(READ ${file} text)
  foreach(forbidden ${BUILD_DIR} ${stage})
    string(FIND "${text}" "${forbidden}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "package test: ${file} refers to ${forbidden}: the package is not relocatable")
    endif()
  endforeach()
endforeach()

# 2. The installed CLI runs and knows its version.
run_or_fail("the installed geodual --version" ${prefix}/bin/geodual --version)
if(NOT run_output MATCHES "${VERSION}")
  message(FATAL_ERROR "package test: `geodual --version` printed '${run_output}', expected ${VERSION}")
endif()

# 3. A separate project finds the package (and nothing else: no package
#    registry, no build tree), builds and runs.
set(consumer_build ${WORK_DIR}/consumer-build)
run_or_fail("configuring the consumer project with find_package(geodual)"
  ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${consumer_build} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
message("${run_output}")
string(FIND "${run_output}" "geodual ${VERSION} from ${package_dir}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "package test: the consumer did not find geodual ${VERSION} in ${package_dir}")
endif()
run_or_fail("building the consumer" ${CMAKE_COMMAND} --build ${consumer_build} --config Release)

set(consumer ${consumer_build}/geodual_consumer)
if(NOT EXISTS ${consumer})
  set(consumer ${consumer_build}/Release/geodual_consumer)  # multi-config generators
endif()
execute_process(COMMAND ${consumer}
  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "geodual consumer: all checks passed")
  message(FATAL_ERROR "package test: the consumer failed (exit ${rc})")
endif()
