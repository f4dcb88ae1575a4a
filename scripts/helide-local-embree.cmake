# Build the ANARI-SDK's helide device from a local Embree 4 source tree instead of the archive its
# configure step downloads (the SDK itself is left unmodified). Pass to the SDK's configure step:
#
#   -DCMAKE_PROJECT_local_embree_INCLUDE=<ripple>/scripts/helide-local-embree.cmake
#   -DHELIDE_EMBREE_SOURCE=<embree-4.3.3 source tree>
#
# CMake includes this file right after helide's `project(local_embree)`, which then calls
# anari_sdk_fetch_project(NAME anari_helide_embree URL .../v4.3.3.zip MD5 ... ADD_SUBDIR). The function
# below replaces the SDK's for that one call: it adds the local tree as the SDK's would add the unpacked
# archive (same options, set by helide just before: static, internal tasking, namespace embree_for_helide),
# and sets anari_helide_embree_LOCATION, whose common/ folder helide includes. Embree 4.3.3 is what the
# SDK 0.16 pins; Debian's trixie source package (embree_4.3.3+dfsg.orig.tar.xz) and the upstream v4.3.3
# tag both carry the tree.
if (NOT HELIDE_EMBREE_SOURCE)
  message(FATAL_ERROR "helide-local-embree.cmake: set -DHELIDE_EMBREE_SOURCE=<embree 4 source tree>")
endif()
get_filename_component(HELIDE_EMBREE_SOURCE "${HELIDE_EMBREE_SOURCE}" ABSOLUTE)
if (NOT EXISTS "${HELIDE_EMBREE_SOURCE}/include/embree4/rtcore.h"
    OR NOT EXISTS "${HELIDE_EMBREE_SOURCE}/common/tasking")
  message(FATAL_ERROR "helide-local-embree.cmake: ${HELIDE_EMBREE_SOURCE} is not an Embree 4 source tree")
endif()
file(STRINGS "${HELIDE_EMBREE_SOURCE}/CMakeLists.txt" _helide_embree_version
     REGEX "^SET\\(EMBREE_VERSION_(MAJOR|MINOR|PATCH) [0-9]+\\)")
string(REGEX REPLACE "SET\\(EMBREE_VERSION_[A-Z]+ ([0-9]+)\\)" "\\1" _helide_embree_version "${_helide_embree_version}")
string(REPLACE ";" "." _helide_embree_version "${_helide_embree_version}")
if (NOT _helide_embree_version VERSION_EQUAL 4.3.3)
  message(WARNING "helide-local-embree.cmake: Embree ${_helide_embree_version}; the SDK 0.16 pins 4.3.3")
endif()
message(STATUS "helide: Embree ${_helide_embree_version} from ${HELIDE_EMBREE_SOURCE}")

function(anari_sdk_fetch_project)
  cmake_parse_arguments(FETCH_SOURCE "ADD_SUBDIR" "NAME;URL;MD5" "" ${ARGN})
  if (NOT FETCH_SOURCE_NAME STREQUAL "anari_helide_embree")
    message(FATAL_ERROR "helide-local-embree.cmake: unexpected fetch of ${FETCH_SOURCE_NAME}")
  endif()
  set(${FETCH_SOURCE_NAME}_LOCATION "${HELIDE_EMBREE_SOURCE}" PARENT_SCOPE)
  if (FETCH_SOURCE_ADD_SUBDIR)
    add_subdirectory("${HELIDE_EMBREE_SOURCE}" "${CMAKE_BINARY_DIR}/deps/build/${FETCH_SOURCE_NAME}")
  endif()
endfunction()
