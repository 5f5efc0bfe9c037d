# Warnings every conform target compiles with; CONFORM_WERROR turns them into errors (CI does).
add_library(conform_warnings INTERFACE)
target_compile_options(conform_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                                  -Wconversion -Wno-sign-conversion)
# Same input, same bytes out: no fused multiply-adds, which some targets (aarch64, -march with FMA) would
# otherwise introduce and which change the last bits of generated data.
target_compile_options(conform_warnings INTERFACE -ffp-contract=off)
if(CONFORM_WERROR)
  target_compile_options(conform_warnings INTERFACE -Werror)
endif()
if(CONFORM_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "CONFORM_BUILD_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++-14")
  endif()
  target_compile_options(conform_warnings INTERFACE -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                                                    -fno-sanitize-recover=undefined)
  target_link_options(conform_warnings INTERFACE -fsanitize=address,undefined)
  target_compile_definitions(conform_warnings INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=1)  # see CONFORM_SANITIZE
endif()
if(CONFORM_SANITIZE)
  target_compile_options(conform_warnings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                    -fno-sanitize-recover=undefined)
  target_link_options(conform_warnings INTERFACE -fsanitize=address,undefined)
  # Under ASan, Eigen stops trusting malloc's alignment and switches to its own aligned allocator, while the
  # uninstrumented PCL libraries free the same objects (FPFH, registration) with plain free(): a mismatch ASan reports
  # as a bad free. glibc's malloc is 16-byte aligned on x86-64, all Eigen needs here, so tell Eigen so.
  target_compile_definitions(conform_warnings INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=1)
endif()

# conform_add_library(<module> DEPS <targets...>)
# One library per module folder: include/conform/<module>/*.h is the public API, src/*.cpp the implementation.
# New source files are picked up without editing CMake (CONFIGURE_DEPENDS), so a new file touches nothing else.
function(conform_add_library module)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(conform_${module} STATIC ${sources})
  add_library(conform::${module} ALIAS conform_${module})
  target_include_directories(conform_${module} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  target_link_libraries(conform_${module} PUBLIC ${ARG_DEPS} PRIVATE conform_warnings ${ARG_PRIVATE_DEPS})
  set_target_properties(conform_${module} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  install(TARGETS conform_${module} ARCHIVE DESTINATION lib)
  install(DIRECTORY include/conform DESTINATION include)
endfunction()

# conform_add_tests(<module> DEPS <targets...>)
# One GoogleTest executable per tests/<module>/<name>_test.cpp (one test file per unit), so a unit builds and runs
# on its own; ctest labels them with the module.
function(conform_add_tests module)
  cmake_parse_arguments(ARG "" "" "DEPS;DEFINITIONS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cpp)
  foreach(source ${sources})
    get_filename_component(name ${source} NAME_WE)
    set(target ${module}_${name})
    add_executable(${target} ${source})
    target_link_libraries(${target} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main conform_warnings
                                            conform_test_support conform_pcl_all)
    target_compile_definitions(${target} PRIVATE ${ARG_DEFINITIONS})
    gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${module})
  endforeach()
endfunction()
