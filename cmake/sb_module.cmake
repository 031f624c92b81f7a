# sb_module(NAME SOURCES a.cc b.cc DEPS sb_base ... TEST_DEPS ...)
# Creates the static library sb_NAME (part of libstrangebeta) from SOURCES and,
# when tests are on, the test binary sb_NAME_test from every *_test.cc in the
# module folder. Modules may only depend on modules below them.
#
# The tests of the modules in SB_DATABASE_TEST_MODULES are written once
# against a database and registered twice: on SQLite and, with the suffix
# "/postgresql" and SB_TEST_BACKEND=postgresql, on the throw-away PostgreSQL
# server of the ctest fixture `pg` (scripts/pg_server.sh; store/store_test_util.h).
set(SB_DATABASE_TEST_MODULES app web)
# Test sources compile without optimisation: the work they check runs in the
# (optimised) libraries, and -O0 halves the compile time of GoogleTest-heavy
# files (20.8 s -> 9.7 s for web/api_test.cc), which is most of `make test`'s
# two builds (DEVELOPERS.md, "make test stays under 45 minutes"). Floating point is unchanged:
# x86-64 SSE and -ffp-contract=off give the same results at every level.
set(SB_TEST_COMPILE_OPTIONS -O0)
function(sb_module name)
  cmake_parse_arguments(M "" "" "SOURCES;DEPS;TEST_DEPS" ${ARGN})
  add_library(sb_${name} STATIC ${M_SOURCES})
  target_include_directories(sb_${name} PUBLIC ${CMAKE_SOURCE_DIR}/src)
  target_link_libraries(sb_${name} PUBLIC ${M_DEPS})
  target_compile_definitions(sb_${name} PRIVATE SB_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  if(SB_BUILD_TESTS)
    file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cc)
    if(tests)
      add_executable(sb_${name}_test ${tests})
      target_link_libraries(sb_${name}_test PRIVATE sb_${name} ${M_TEST_DEPS} GTest::gtest_main GTest::gmock)
      target_compile_options(sb_${name}_test PRIVATE ${SB_TEST_COMPILE_OPTIONS})
      target_compile_definitions(sb_${name}_test PRIVATE
        SB_SHARED_DIR="${SB_SHARED_DIR}" SB_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
        SB_BINARY_DIR="${CMAKE_BINARY_DIR}")
      if(name STREQUAL "store")  # parameterised over both backends itself
        gtest_discover_tests(sb_${name}_test DISCOVERY_TIMEOUT 60
          PROPERTIES ENVIRONMENT "SB_SHARED=${SB_SHARED_DIR}" FIXTURES_REQUIRED pg)
      else()
        gtest_discover_tests(sb_${name}_test DISCOVERY_TIMEOUT 60
          PROPERTIES ENVIRONMENT "SB_SHARED=${SB_SHARED_DIR}")
      endif()
      if(name IN_LIST SB_DATABASE_TEST_MODULES)
        gtest_discover_tests(sb_${name}_test DISCOVERY_TIMEOUT 60 TEST_SUFFIX /postgresql
          PROPERTIES ENVIRONMENT "SB_SHARED=${SB_SHARED_DIR}\\;SB_TEST_BACKEND=postgresql"
                     FIXTURES_REQUIRED pg)
      endif()
    endif()
  endif()
endfunction()
