# One place for the flags every cellctl target gets: warnings are errors, per target.
function(cellctl_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Werror)
endfunction()

# Layers the compiler keeps (docs/architecture.md). A library sees its own headers and those of the
# libraries it links, nothing else: each gets an include root of its own in the build tree,
# build/<tree>/include/<target>/, holding one entry named after its source folder, so that includes
# keep reading "scu/session.hpp":
#   - a library that has its folder to itself: a symbolic link to the folder;
#   - a library that shares its folder and names its HEADERS (an emulator beside its device's session,
#     the DP slave beside the master, the clock in link/): a folder of links to those headers;
#   - the folder's main library (the one without HEADERS) then gets links to every other header there.
# The root is PUBLIC (INTERFACE for a header-only library): what links the library sees the folder,
# and through the library's DEPS (its headers include them) the folders below it; PRIVATE_DEPS are
# what only its sources include, invisible to what links it.
set(CELLCTL_INCLUDE_ROOTS ${PROJECT_BINARY_DIR}/include)

# The include root of `target` for the headers `headers` of folder `dir` (all of it without headers).
function(_cellctl_link_headers target dir)
  get_filename_component(folder ${dir} NAME)
  set(root ${CELLCTL_INCLUDE_ROOTS}/${target})
  file(REMOVE_RECURSE ${root})  # removes links, never what they point at
  if(ARGN)
    file(MAKE_DIRECTORY ${root}/${folder})
    foreach(header IN LISTS ARGN)
      file(CREATE_LINK ${dir}/${header} ${root}/${folder}/${header} SYMBOLIC)
    endforeach()
  else()
    file(MAKE_DIRECTORY ${root})
    file(CREATE_LINK ${dir} ${root}/${folder} SYMBOLIC)
  endif()
endfunction()

# Deferred to the end of the folder's CMakeLists: the main library's headers are what the folder's
# other libraries did not claim. A new header makes the build re-run CMake (CONFIGURE_DEPENDS).
function(_cellctl_link_folder_rest target dir)
  get_property(claimed DIRECTORY ${dir} PROPERTY CELLCTL_CLAIMED_HEADERS)
  if(NOT claimed)
    _cellctl_link_headers(${target} ${dir})
    return()
  endif()
  file(GLOB headers CONFIGURE_DEPENDS RELATIVE ${dir} ${dir}/*.hpp)
  list(REMOVE_ITEM headers ${claimed})
  _cellctl_link_headers(${target} ${dir} ${headers})
endfunction()

# Gives `target` the include root of the folder it is declared in (see above); `scope` is PUBLIC,
# INTERFACE or PRIVATE (an executable's own folder).
function(cellctl_include_root target scope)
  cmake_parse_arguments(ARG "" "" "HEADERS" ${ARGN})
  set(dir ${CMAKE_CURRENT_SOURCE_DIR})
  if(ARG_HEADERS)
    foreach(header IN LISTS ARG_HEADERS)
      if(NOT EXISTS ${dir}/${header})
        message(FATAL_ERROR "${target}: HEADERS names ${header}, which is not in ${dir}")
      endif()
    endforeach()
    set_property(DIRECTORY APPEND PROPERTY CELLCTL_CLAIMED_HEADERS ${ARG_HEADERS})
    _cellctl_link_headers(${target} ${dir} ${ARG_HEADERS})
  else()
    get_property(main DIRECTORY PROPERTY CELLCTL_MAIN_TARGET)
    if(main)
      message(FATAL_ERROR "${target} and ${main} both take the rest of ${dir}: give one of them HEADERS")
    endif()
    set_property(DIRECTORY PROPERTY CELLCTL_MAIN_TARGET ${target})
    # (EVAL: a deferred call's arguments would otherwise be read when it runs, in the folder's scope)
    cmake_language(EVAL CODE "cmake_language(DEFER CALL _cellctl_link_folder_rest [[${target}]] [[${dir}]])")
  endif()
  target_include_directories(${target} ${scope} ${CELLCTL_INCLUDE_ROOTS}/${target})
endfunction()

# cellctl_library(<name> [SOURCES ...] [HEADERS ...] [DEPS ...] [PRIVATE_DEPS ...]): a static library
# cellctl_<name> with the alias cellctl::<name> (header-only, an INTERFACE library, without SOURCES).
# HEADERS: the headers it owns when it shares its folder (see above). DEPS: what its headers include
# (PUBLIC); PRIVATE_DEPS: what only its sources include.
function(cellctl_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;HEADERS;DEPS;PRIVATE_DEPS" ${ARGN})
  if(ARG_SOURCES)
    add_library(cellctl_${name} STATIC ${ARG_SOURCES})
    set(scope PUBLIC)
    cellctl_warnings(cellctl_${name})
    target_link_libraries(cellctl_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  else()
    if(ARG_PRIVATE_DEPS)
      message(FATAL_ERROR "cellctl_${name} is header-only: it has no PRIVATE_DEPS")
    endif()
    add_library(cellctl_${name} INTERFACE)
    set(scope INTERFACE)
    target_link_libraries(cellctl_${name} INTERFACE ${ARG_DEPS})
  endif()
  add_library(cellctl::${name} ALIAS cellctl_${name})
  if(ARG_HEADERS)
    cellctl_include_root(cellctl_${name} ${scope} HEADERS ${ARG_HEADERS})
  else()
    cellctl_include_root(cellctl_${name} ${scope})
  endif()
endfunction()

# cellctl_test(<name> SOURCES ... DEPS ...): a GoogleTest executable registered with CTest. It sees the
# headers of what it links in DEPS, and tests/ (support/, fixtures).
function(cellctl_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  # The allocation counter replaces the global operator new and delete: compiled alone, as in one unity
  # file with the tests it counts, the replacements would be seen (and inlined) where they are called.
  foreach(source IN LISTS ARG_SOURCES)
    if(source MATCHES "allocation_counter\\.cpp$")
      set_source_files_properties(${source} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
    endif()
  endforeach()
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  cellctl_warnings(${name})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${CELLCTL_TEST_TIMEOUT})
endfunction()
