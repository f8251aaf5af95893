# `cmake --install` rules: the geodual libraries (static by default), their
# public headers, the `geodual` command line tool and a relocatable CMake
# package, so that an installed geodual is used as
#
#   find_package(geodual 0.1 REQUIRED)      # optionally COMPONENTS io voronoi remesh pipeline
#   target_link_libraries(app PRIVATE geodual::pipeline)
#
# Imported targets (the same names as the build tree's ALIAS targets, so code
# written against one works with the other):
#   geodual::mesh      TriangleMesh, SurfacePoint, errors, MeshTopology, mesh analysis (Eigen)
#   geodual::io        readers and writers
#   geodual::voronoi   exact geodesics and the geodesic Voronoi diagram
#   geodual::remesh    site sampling, Lloyd, dual Delaunay, quality statistics
#   geodual::texture   the remesh's texture atlas and baking (headers in include/geodual/remesh)
#   geodual::pipeline  stage orchestration (what the CLI calls)
#   geodual::geodual   the command line tool (an imported executable)
#
# Layout under the prefix: bin/geodual, <libdir>/libgeodual_*.a,
# include/geodual/..., <libdir>/cmake/geodual/{geodual-config,
# geodual-config-version,geodual-targets*}.cmake. Static libraries keep their
# private dependencies (tinygltf, nlohmann_json, TBB, CGAL with GMP/MPFR) on
# their link line, so geodual-config.cmake finds those packages again.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(GEODUAL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/geodual CACHE STRING
    "Where the geodual CMake package files are installed, relative to the prefix")
mark_as_advanced(GEODUAL_INSTALL_CMAKEDIR)

# Library targets and their exported names.
set(GEODUAL_INSTALLED_COMPONENTS mesh io voronoi remesh texture quality pipeline)
set(_geodual_installed_libraries)
foreach(component IN LISTS GEODUAL_INSTALLED_COMPONENTS)
  set_target_properties(geodual_${component} PROPERTIES EXPORT_NAME ${component})
  list(APPEND _geodual_installed_libraries geodual_${component})
endforeach()

install(TARGETS ${_geodual_installed_libraries} geodual
  EXPORT geodual-targets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# Public headers only: each module's include/geodual/<module>/ folder becomes
# include/geodual/<module>/. Private headers (a module's src/, mesh/detail/)
# stay in the source tree.
foreach(module IN ITEMS mesh io voronoi remesh quality pipeline)  # texture's headers are remesh's
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/geodual/${module}
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/geodual
    COMPONENT development
    FILES_MATCHING PATTERN "*.hpp")
endforeach()

install(EXPORT geodual-targets
  NAMESPACE geodual::
  DESTINATION ${GEODUAL_INSTALL_CMAKEDIR}
  COMPONENT development)

# Which third-party packages the config file must find again: those the
# installed targets link, publicly or (static libraries) privately.
set(GEODUAL_NEEDS_CGAL ON)
configure_package_config_file(
  ${CMAKE_CURRENT_LIST_DIR}/geodual-config.cmake.in
  ${PROJECT_BINARY_DIR}/geodual-package/geodual-config.cmake
  INSTALL_DESTINATION ${GEODUAL_INSTALL_CMAKEDIR}
  NO_SET_AND_CHECK_MACRO)
# 0.x: a minor version may break the API, so only the same MAJOR.MINOR matches.
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/geodual-package/geodual-config-version.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/geodual-package/geodual-config.cmake
  ${PROJECT_BINARY_DIR}/geodual-package/geodual-config-version.cmake
  DESTINATION ${GEODUAL_INSTALL_CMAKEDIR}
  COMPONENT development)
