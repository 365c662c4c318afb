# One place for the flags every cellctl target gets: warnings are errors, per target.
function(cellctl_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Werror)
endfunction()

# cellctl_library(<name> SOURCES ... DEPS ...): a static library cellctl_<name> with the alias
# cellctl::<name>, its folder's parent as the include root (so includes read "scu/codec.hpp").
function(cellctl_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(cellctl_${name} STATIC ${ARG_SOURCES})
  add_library(cellctl::${name} ALIAS cellctl_${name})
  get_filename_component(include_root ${CMAKE_CURRENT_SOURCE_DIR} DIRECTORY)
  target_include_directories(cellctl_${name} PUBLIC ${include_root})
  target_link_libraries(cellctl_${name} PUBLIC ${ARG_DEPS})
  cellctl_warnings(cellctl_${name})
endfunction()

# cellctl_test(<name> SOURCES ... DEPS ...): a GoogleTest executable registered with CTest.
function(cellctl_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  cellctl_warnings(${name})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${CELLCTL_TEST_TIMEOUT})
endfunction()
