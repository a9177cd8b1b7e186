# ncpost_engine_library(<stage> SOURCES ... [DEPS ...])
# Declares one pipeline stage as a static library `ncpost_<stage>` with the alias
# `ncpost::<stage>`. Public headers live in engine/<stage>/include/ncpost/<stage>/.
function(ncpost_engine_library stage)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(ncpost_${stage} STATIC ${ARG_SOURCES})
  add_library(ncpost::${stage} ALIAS ncpost_${stage})
  target_include_directories(ncpost_${stage} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
                                             PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(ncpost_${stage} PUBLIC ${ARG_DEPS} PRIVATE ncpost_warnings ${ARG_PRIVATE_DEPS})
endfunction()

# ncpost_add_gtest(<name> SOURCES ... DEPS ...)
# One GoogleTest executable, registered test by test with ctest so that counts are visible.
function(ncpost_add_gtest name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main ncpost_warnings)
  target_compile_definitions(${name} PRIVATE
    NCPOST_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    NCPOST_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
    PROPERTIES ENVIRONMENT "NCPOST_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
