# cmake -P driver of the package_install_and_consume test (see CMakeLists.txt
# here): -DBUILD_DIR -DCONFIG -DWORK_DIR -DCONSUMER_DIR -DEXAMPLES_DIR
# -DGENERATOR -DCXX_COMPILER -DCXX_FLAGS -DVERSION. Any failed step is a FATAL_ERROR
# (non-zero exit) that prints the step's output.
cmake_minimum_required(VERSION 3.25)

foreach(var BUILD_DIR WORK_DIR CONSUMER_DIR EXAMPLES_DIR GENERATOR CXX_COMPILER VERSION)
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
    include/geodual/mesh/triangle_mesh.hpp include/geodual/mesh/error.hpp
    include/geodual/mesh/surface_point.hpp include/geodual/mesh/mesh_topology.hpp
    include/geodual/mesh/union_find.hpp include/geodual/mesh/random.hpp
    include/geodual/io/gltf.hpp include/geodual/voronoi/geodesic_field.hpp
    include/geodual/remesh/remesh.hpp include/geodual/quality/quality_stats.hpp
    include/geodual/pipeline/version.hpp)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "package test: ${file} was not installed under ${prefix}")
  endif()
endforeach()
# Only public headers are installed: no module's private headers, no detail/.
file(GLOB_RECURSE installed_headers RELATIVE ${prefix}/include ${prefix}/include/*)
foreach(header IN LISTS installed_headers)
  if(header MATCHES "/detail/" OR NOT header MATCHES "^geodual/(mesh|io|voronoi|remesh|quality|pipeline)/[a-z0-9_]+\\.hpp$")
    message(FATAL_ERROR "package test: include/${header} is installed but is not a public header")
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
#    registry, no build tree), builds and runs; it also builds one of
#    geodual's examples (step 4).
set(consumer_build ${WORK_DIR}/consumer-build)
run_or_fail("configuring the consumer project with find_package(geodual)"
  ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${consumer_build} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    -DCMAKE_PREFIX_PATH=${prefix}
    -DGEODUAL_EXAMPLES_DIR=${EXAMPLES_DIR}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
message("${run_output}")
string(FIND "${run_output}" "geodual ${VERSION} from ${package_dir}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "package test: the consumer did not find geodual ${VERSION} in ${package_dir}")
endif()
run_or_fail("building the consumer" ${CMAKE_COMMAND} --build ${consumer_build} --config Release)

# The built program, for single- and multi-config generators.
function(consumer_program name out)
  set(program ${consumer_build}/${name})
  if(NOT EXISTS ${program})
    set(program ${consumer_build}/Release/${name})
  endif()
  set(${out} ${program} PARENT_SCOPE)
endfunction()

consumer_program(geodual_consumer consumer)
execute_process(COMMAND ${consumer}
  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "geodual consumer: all checks passed")
  message(FATAL_ERROR "package test: the consumer failed (exit ${rc})")
endif()

# 4. examples/remesh_file.cpp, built against the installed package, remeshes
#    the bundled scan (few sites, so that it takes seconds).
consumer_program(remesh_file example)
set(example_output ${WORK_DIR}/bunny-remeshed.ply)
execute_process(COMMAND ${example} ${EXAMPLES_DIR}/data/bunny.ply ${example_output} 300
  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "vertices  3[0-9][0-9]\nfaces     [0-9]+\nQavg      0\\.[0-9]+\nHausdorff")
  message(FATAL_ERROR "package test: examples/remesh_file built against the package failed (exit ${rc})")
endif()
if(NOT EXISTS ${example_output})
  message(FATAL_ERROR "package test: examples/remesh_file wrote no ${example_output}")
endif()
