# All dependencies come from Debian packages; nothing is downloaded at configure time.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
# PCL's io component pulls VTK, whose config needs MPI's C component found first.
find_package(MPI COMPONENTS C QUIET)
find_package(PCL 1.12 REQUIRED COMPONENTS common io kdtree search features filters registration sample_consensus
                                          segmentation)
find_package(Ceres 2.0 REQUIRED)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.9 REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_path(NANOFLANN_INCLUDE_DIR nanoflann.hpp REQUIRED)
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
target_link_libraries(conform_pcl INTERFACE ${PCL_LIBRARIES})
target_compile_definitions(conform_pcl INTERFACE ${PCL_DEFINITIONS})
