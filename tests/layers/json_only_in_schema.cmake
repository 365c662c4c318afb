# cmake -D source_dir=<repository> -P json_only_in_schema.cmake: JSON is made and read in one part,
# controller/schema (docs/architecture.md). A header-only JSON library in /usr/include is reachable from
# every include path, so the build cannot hide it; this scan names every source under controller/ and
# devices/ outside schema/ that includes it (fuzz targets and tests are outside both: they may read
# JSON to check what the schema wrote).
cmake_minimum_required(VERSION 3.25)

file(GLOB_RECURSE sources ${source_dir}/controller/*.cpp ${source_dir}/controller/*.hpp
     ${source_dir}/devices/*.cpp ${source_dir}/devices/*.hpp)
list(LENGTH sources scanned)
if(scanned LESS 100)
  message(FATAL_ERROR "only ${scanned} sources under ${source_dir}/controller and devices: wrong folder?")
endif()
set(offenders)
foreach(source IN LISTS sources)
  if(source MATCHES "/controller/schema/")
    continue()
  endif()
  file(STRINGS ${source} includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"](nlohmann|json)[/.]")
  if(includes)
    file(RELATIVE_PATH name ${source_dir} ${source})
    list(APPEND offenders "${name}")
  endif()
endforeach()
if(offenders)
  list(JOIN offenders "\n  " named)
  message(FATAL_ERROR "JSON outside controller/schema/ (make it a typed record there):\n  ${named}")
endif()
message(STATUS "${scanned} sources scanned: JSON only in controller/schema/")
