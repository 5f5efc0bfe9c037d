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
  # GCC 12 at -O1 with ASan reports -Wmaybe-uninitialized inside libstdc++'s std::regex and std::function (its
  # instrumentation hides the initialisation from the flow analysis; the release build, which has the warning, is
  # clean). Only the sanitizer build turns it off.
  target_compile_options(conform_warnings INTERFACE -Wno-maybe-uninitialized)
endif()

# conform_add_library(<module> DEPS <targets...> [PRIVATE_DEPS <targets...>] [EXCLUDE <src/ file names...>])
# One library per module folder: include/conform/<module>/*.h is the public API, src/*.cpp the implementation.
# New source files are picked up without editing CMake (CONFIGURE_DEPENDS), so a new file touches nothing else.
# EXCLUDE leaves files of src/ to a plugin module (conform_add_plugin).
function(conform_add_library module)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS;EXCLUDE" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  foreach(excluded ${ARG_EXCLUDE})
    list(REMOVE_ITEM sources ${CMAKE_CURRENT_SOURCE_DIR}/src/${excluded})
  endforeach()
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

# conform_add_plugin(<name> SOURCES <files...> DEPS <targets...>)
# A shared module lib<name>.so that conform opens on first use (core/include/conform/core/plugin.h), so that a heavy
# library linked only into it costs start-up time only in the runs that call it. Written beside the `conform`
# executable and installed in lib/; `conform` and every test depend on it (CONFORM_PLUGINS), so building them builds
# it. conform's static libraries linked in stay private to it: only its extern "C" entry points are exported.
function(conform_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} MODULE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} conform_warnings)
  set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}
                                           CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  target_link_options(${name} PRIVATE -Wl,--exclude-libs,ALL -Wl,--as-needed)
  install(TARGETS ${name} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  set_property(GLOBAL APPEND PROPERTY CONFORM_PLUGINS ${name})
endfunction()

# conform_depend_on_plugins(<targets...>): building a target builds every plugin it may open at run time.
function(conform_depend_on_plugins)
  get_property(plugins GLOBAL PROPERTY CONFORM_PLUGINS)
  if(plugins)
    foreach(target ${ARGN})
      add_dependencies(${target} ${plugins})
    endforeach()
  endif()
endfunction()

# conform_add_tests(<module> DEPS <targets...>)
# One GoogleTest executable per tests/<module>/<name>_test.cpp (one test file per unit), so a unit builds and runs
# on its own; ctest labels them with the module, and the target <module>_tests builds all of them.
function(conform_add_tests module)
  cmake_parse_arguments(ARG "" "" "DEPS;DEFINITIONS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cpp)
  foreach(source ${sources})
    get_filename_component(name ${source} NAME_WE)
    # The sanitizer build skips the realistic-variation sweeps (ctest -E Matrix in .ci/run): files that hold only
    # *Matrix* suites are not even compiled there.
    if(CONFORM_SANITIZE AND name MATCHES "(_matrix|_perturbation|_browser)_test$")
      continue()
    endif()
    set(target ${module}_${name})
    add_executable(${target} ${source})
    target_link_libraries(${target} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main conform_warnings
                                            conform_test_support conform_pcl_all)
    target_compile_definitions(${target} PRIVATE ${ARG_DEFINITIONS})
    conform_depend_on_plugins(${target})
    gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${module})
    if(NOT TARGET ${module}_tests)
      add_custom_target(${module}_tests)
    endif()
    add_dependencies(${module}_tests ${target})
  endforeach()
endfunction()
