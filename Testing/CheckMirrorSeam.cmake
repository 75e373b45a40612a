# House rule (the mirror seam): the sphere's names appear only in the sphere's own files
# (Module/Mirror/SphereMirror.*, and the fit of a sphere to its outline,
# Module/Vision/MirrorOutline.cxx) and in the catalogue that lists the mirror types
# (Module/Mirror/MirrorTypes.cxx): its classes, the old field-data names, and member access to a
# centre or radius (a calibration key such as "mirror.radius" in a message of the quadric family
# is not code that knows a shape).
# Everything else reaches the mirror through Module/Mirror/Mirror.h.
# Run: cmake -DSOURCE_DIR=... -P this.
set(names "SphereMirror|SphereSurface|SphereReflectionPoint|MirrorFrame|MirrorSphere|MirrorCenter|MirrorRadius|[A-Za-z0-9_)]\\.mirror\\.center|[A-Za-z0-9_)]\\.mirror\\.radius")
set(offenders "")
foreach (folder Module Filters Rendering Applications ParaView Wrapping Examples)
  file(GLOB_RECURSE files "${SOURCE_DIR}/${folder}/*.h" "${SOURCE_DIR}/${folder}/*.cxx"
    "${SOURCE_DIR}/${folder}/*.in" "${SOURCE_DIR}/${folder}/*.py" "${SOURCE_DIR}/${folder}/*.xml")
  foreach (f IN LISTS files)
    file(RELATIVE_PATH rel "${SOURCE_DIR}" "${f}")
    if (rel MATCHES "^Module/Mirror/SphereMirror\\.(h|cxx)$" OR rel STREQUAL "Module/Mirror/MirrorTypes.cxx"
        OR rel STREQUAL "Module/Vision/MirrorOutline.cxx")
      continue()
    endif ()
    file(STRINGS "${f}" hits REGEX "${names}")
    if (hits)
      list(APPEND offenders "${rel}: ${hits}")
    endif ()
  endforeach ()
endforeach ()
if (offenders)
  list(JOIN offenders "\n" text)
  message(FATAL_ERROR "the sphere's names outside its own files:\n${text}")
endif ()
message(STATUS "the sphere's names appear only in Module/Mirror/SphereMirror.*, Module/Vision/MirrorOutline.cxx and Module/Mirror/MirrorTypes.cxx")
