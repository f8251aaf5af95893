# Every dependency comes from a Debian 12 package; nothing is downloaded.
#
# Order matters: find_package(CGAL) puts CGAL's own FindOpenMesh.cmake and
# FindEigen3.cmake on CMAKE_MODULE_PATH, and those define no imported targets.
# Eigen and OpenMesh are therefore found first, in CONFIG mode.
find_package(Threads REQUIRED)
find_package(Eigen3 3.4 CONFIG REQUIRED)          # libeigen3-dev      -> Eigen3::Eigen
find_package(OpenMesh CONFIG REQUIRED)            # libopenmesh-dev    -> OpenMeshCore
find_package(TBB CONFIG REQUIRED)                 # libtbb-dev         -> TBB::tbb
find_package(TinyGLTF CONFIG REQUIRED)            # libtinygltf-dev    -> tinygltf
find_package(nlohmann_json 3.10 CONFIG REQUIRED)  # nlohmann-json3-dev -> nlohmann_json::nlohmann_json
find_package(CLI11 CONFIG REQUIRED)               # libcli11-dev       -> CLI11::CLI11
find_package(meshoptimizer 0.18 CONFIG REQUIRED)  # libmeshoptimizer-dev -> meshoptimizer::meshoptimizer
find_package(draco 1.5 CONFIG REQUIRED)           # libdraco-dev       -> draco::draco
find_package(CGAL CONFIG REQUIRED)                # libcgal-dev        -> CGAL::CGAL
if(GEODUAL_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)             # libgtest-dev       -> GTest::gtest_main
endif()
