# The licence and the citation file: BSD-3-Clause, the CITATION.cff's version is the project's,
# and it cites the paper the method follows. Run with -DSOURCE_DIR=... -DVERSION=...
file(READ "${SOURCE_DIR}/LICENSE" license)
if (NOT license MATCHES "^BSD 3-Clause License" OR NOT license MATCHES "Neither the name of the copyright holder")
  message(FATAL_ERROR "LICENSE is not the BSD 3-Clause licence")
endif ()
file(READ "${SOURCE_DIR}/CITATION.cff" cff)
foreach (needed
    "cff-version: 1.2.0"
    "version: \"${VERSION}\""
    "license: BSD-3-Clause"
    "title: \"A Framework for Augmented Reality using Non-Central Catadioptric Cameras\"")
  string(FIND "${cff}" "${needed}" at)
  if (at LESS 0)
    message(FATAL_ERROR "CITATION.cff lacks: ${needed}")
  endif ()
endforeach ()
message(STATUS "LICENSE and CITATION.cff: 1 passed, 0 failed")
