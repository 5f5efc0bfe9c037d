# All dependencies come from Debian packages; nothing is downloaded at configure time.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
# Not PCL's io component: it pulls VTK and ~100 shared libraries into every start of `conform` (0.2 s); conform reads
# and writes PCD itself. Tests that write files with pcl::io find it on their own (tests/core/CMakeLists.txt).
find_package(PCL 1.12 REQUIRED COMPONENTS common kdtree search features filters registration sample_consensus
                                          segmentation)
find_package(Ceres 2.0 REQUIRED)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs)  # imgcodecs: tests decode the PNG
find_package(ZLIB REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.9 REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_path(NANOFLANN_INCLUDE_DIR nanoflann.hpp REQUIRED)
include(GNUInstallDirs)
# OpenCASCADE (Debian's libocct-*-dev), for the cad plugin only (cad/CMakeLists.txt) and the tests that make CAD.
# Found library by library: its CMake config also wants the visualization toolkits, which conform does not install.
find_path(OCCT_INCLUDE_DIR Standard.hxx PATH_SUFFIXES opencascade REQUIRED)
set(OCCT_LIBRARIES)
foreach(toolkit TKSTEP TKSTEPBase TKXSBase TKIGES TKMesh TKTopAlgo TKBRep TKGeomBase TKG3d TKG2d TKMath TKernel)
  find_library(OCCT_${toolkit} ${toolkit} REQUIRED)
  list(APPEND OCCT_LIBRARIES ${OCCT_${toolkit}})
endforeach()
# What the tests need beyond the reader to build and write shapes (primitives, booleans, fillets, classification).
set(OCCT_TEST_LIBRARIES)
foreach(toolkit TKPrim TKBO TKBool TKFillet)
  find_library(OCCT_${toolkit} ${toolkit} REQUIRED)
  list(APPEND OCCT_TEST_LIBRARIES ${OCCT_${toolkit}})
endforeach()
list(APPEND OCCT_TEST_LIBRARIES ${OCCT_LIBRARIES})
if(CONFORM_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(CONFORM_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# PCL's config exports its flags and definitions as plain variables; wrap them in one interface target
# so that only the modules that use PCL see them.
add_library(conform_pcl INTERFACE)
target_include_directories(conform_pcl SYSTEM INTERFACE ${PCL_INCLUDE_DIRS})
# Only the PCL libraries conform's code calls: with --as-needed (apps/CMakeLists.txt) `conform` then does not load
# pcl_segmentation (45k relocations at start-up; it also exports search::OrganizedNeighbor, which would bind there).
# Only pcl_common for conform's libraries (its point types); conform's FPFH is its own (registration/src/
# fpfh_features.h): pcl_features alone had 116k relocations, most of the loader's work at start-up.
target_link_libraries(conform_pcl INTERFACE ${PCL_COMMON_LIBRARIES})
# Every PCL component found, for the tests and benchmarks that use PCL as a peer (ICP, FPFH, SAC segmentation).
add_library(conform_pcl_all INTERFACE)
target_link_libraries(conform_pcl_all INTERFACE conform_pcl ${PCL_LIBRARIES})
target_compile_definitions(conform_pcl INTERFACE ${PCL_DEFINITIONS})
# conform_find_pcl_io(<target>...): PCL's io component (and VTK behind it) for the tests and benchmarks that write or
# read files with pcl::io as a peer; conform itself does not link it. VTK's config needs MPI's C component found first.
# The targets VTK's config imports are local to the calling directory, hence a call per directory.
macro(conform_find_pcl_io)
  find_package(MPI COMPONENTS C QUIET)
  find_package(PCL 1.12 REQUIRED COMPONENTS common io)
  foreach(target ${ARGN})
    target_include_directories(${target} SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
    target_link_libraries(${target} PRIVATE ${PCL_LIBRARIES})
  endforeach()
endmacro()
