# Manifest of the `drape` library for the Unity source plug-in (.ci/unity-source.py): its sources
# in target order, include directories (its own and its header-only libraries') and compile definitions, written to
# <build>/drape-source-manifest.txt at generate time, plus a target that builds only the generated
# sources (embedded shaders). Runs deferred, at the end of plugin-native/, so it sees every source
# added to the target.
include_guard(GLOBAL)

function(drape_write_source_manifest)
  get_target_property(_srcs drape SOURCES)
  set(_cpp "")
  set(_generated "")
  foreach(_s IN LISTS _srcs)
    cmake_path(ABSOLUTE_PATH _s BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" NORMALIZE OUTPUT_VARIABLE _abs)
    get_source_file_property(_gen "${_abs}" GENERATED)
    if(_gen)
      list(APPEND _generated "${_abs}")
    elseif(_abs MATCHES "\\.(c|cc|cpp)$")
      list(APPEND _cpp "${_abs}")
    endif()
  endforeach()
  # Include directories of the header-only libraries linked to drape (glm, Eigen).
  get_target_property(_libs drape LINK_LIBRARIES)
  set(_dep_dirs "")
  foreach(_l IN LISTS _libs)
    if(TARGET "${_l}")
      string(APPEND _dep_dirs "$<TARGET_PROPERTY:${_l},INTERFACE_INCLUDE_DIRECTORIES>;")
    endif()
  endforeach()
  file(GENERATE OUTPUT "${CMAKE_BINARY_DIR}/drape-source-manifest.txt" CONTENT
"sources=${_cpp}
generated=${_generated}
include_dirs=$<TARGET_PROPERTY:drape,INCLUDE_DIRECTORIES>
dep_include_dirs=${_dep_dirs}
definitions=$<TARGET_PROPERTY:drape,COMPILE_DEFINITIONS>
")
  add_custom_target(drape_generated_sources DEPENDS ${_generated})
endfunction()

cmake_language(DEFER DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" CALL drape_write_source_manifest)
