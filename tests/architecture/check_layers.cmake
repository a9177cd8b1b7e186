cmake_minimum_required(VERSION 3.25)
# The one road (docs/architecture.md): the command line and the server reach the engine through
# ncpost::pipeline only. Run by ctest with
#   -DTARGET=<name> -DLINKS=<the target's LINK_LIBRARIES> -DSOURCES=<its folder> -DALLOWED=<list>
# Fails when the target links a stage library other than those ALLOWED, or when a file of its
# folder includes an engine header that is not a pipeline header.
set(failures "")
foreach(link IN LISTS LINKS)
  if(link MATCHES "^ncpost::" OR link MATCHES "^ncpost_[a-z0-9]+$")
    if(NOT link IN_LIST ALLOWED AND NOT link STREQUAL "ncpost_warnings")
      list(APPEND failures "${TARGET} links ${link} directly; only ${ALLOWED}")
    endif()
  endif()
endforeach()
file(GLOB files "${SOURCES}/*.cpp" "${SOURCES}/*.hpp")
foreach(file IN LISTS files)
  file(STRINGS "${file}" includes REGEX "^#include \"ncpost/")
  foreach(line IN LISTS includes)
    if(NOT line MATCHES "^#include \"ncpost/pipeline/")
      list(APPEND failures "${file}: ${line} (include ncpost/pipeline/ headers only)")
    endif()
  endforeach()
endforeach()
if(failures)
  list(JOIN failures "\n" message)
  message(FATAL_ERROR "${message}")
endif()
message(STATUS "${TARGET}: links and includes go through ncpost::pipeline only")
