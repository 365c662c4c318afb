# cmake -P include_probe.cmake: compiles a one-line source, `#include "<header>"`, with one library's
# own include directories, definitions and options, once for each header in `allowed` (each must
# compile) and once for each header in `forbidden` (each must be not found). Run by the layers.* tests
# (CMakeLists.txt beside this file); a missing compiler or a broken flag fails the allowed headers, so
# no case passes without having compiled.
#
#   -D library=cellctl_X  -D compiler=...  -D flags=a|b  -D includes=a|b  -D implicit=a|b  -D definitions=a|b
#   -D options=a|b  -D source_dir=<repository>
#   -D binary_dir=<build tree>  -D work=<folder for the probes>
#   -D allowed=h1|h2  -D forbidden=glob1|glob2   (globs in the repository)
cmake_minimum_required(VERSION 3.25)

foreach(list IN ITEMS flags includes implicit definitions options allowed forbidden)
  string(REPLACE "|" ";" ${list} "${${list}}")
endforeach()
set(args ${flags} ${options})
list(REMOVE_ITEM includes ${implicit})  # the compiler's own (/usr/include), left out as CMake does
foreach(dir IN LISTS includes)
  # Outside the repository and its build tree (Eigen, yaml-cpp, ...): a system header, as CMake has it.
  string(FIND "${dir}" "${source_dir}/" in_source)
  string(FIND "${dir}" "${binary_dir}/" in_build)
  if(in_source EQUAL 0 OR in_build EQUAL 0)
    list(APPEND args -I${dir})
  else()
    list(APPEND args -isystem ${dir})
  endif()
endforeach()
foreach(definition IN LISTS definitions)
  list(APPEND args -D${definition})
endforeach()
file(MAKE_DIRECTORY ${work})

# Compiles `#include "<header>"`; sets probe_failed and probe_output in the caller.
function(probe header)
  string(MAKE_C_IDENTIFIER ${header} name)
  set(file ${work}/${name}.cpp)
  file(WRITE ${file} "#include \"${header}\"\n")
  execute_process(COMMAND ${compiler} ${args} -fsyntax-only ${file}
                  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  set(probe_failed ${result} PARENT_SCOPE)
  set(probe_output "${output}" PARENT_SCOPE)
endfunction()

if(NOT allowed OR NOT forbidden)
  message(FATAL_ERROR "${library}: a case needs allowed and forbidden headers")
endif()
foreach(header IN LISTS allowed)
  probe(${header})
  if(probe_failed)
    message(FATAL_ERROR "${library} may include ${header}, but it does not compile with its flags:\n${probe_output}")
  endif()
endforeach()

set(headers)
foreach(pattern IN LISTS forbidden)
  file(GLOB_RECURSE found ${source_dir}/${pattern})
  if(NOT found)
    message(FATAL_ERROR "${library}: no header matches ${pattern} (moved? the case must follow it)")
  endif()
  foreach(path IN LISTS found)
    string(REGEX REPLACE "^.*/([^/]+/[^/]+)$" "\\1" header ${path})  # as included: folder/file
    list(APPEND headers ${header})
  endforeach()
endforeach()
list(REMOVE_DUPLICATES headers)
list(REMOVE_ITEM headers ${allowed})
set(open)
foreach(header IN LISTS headers)
  probe(${header})
  if(NOT probe_failed)
    list(APPEND open ${header})
  elseif(NOT probe_output MATCHES "${header}: No such file or directory")
    message(FATAL_ERROR "${library}: ${header} failed to compile, but not as a header out of reach:\n${probe_output}")
  endif()
endforeach()
if(open)
  list(JOIN open "\n  " open)
  message(FATAL_ERROR "${library} reaches headers it must not include:\n  ${open}")
endif()
list(LENGTH headers count)
message(STATUS "${library}: ${count} forbidden headers out of reach; ${allowed} compiles")
