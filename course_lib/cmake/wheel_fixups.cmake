# Included by the course's workspace build (CMAKE_PROJECT_INCLUDE) into every CMake package.
#
# The ros-jazzy-* wheels were built in a manylinux container, and each of their
# share/<pkg>/cmake/export_<pkg>__rosidl_generator_pyExport.cmake files names that container's
# Python and numpy include folders (/opt/python/cp3XX-.../include/...). Those folders do not
# exist here, so CMake refuses to generate a package that links a message package's Python
# type support. The wheels' files stay untouched: once the package's own CMakeLists.txt has
# run, every imported `<pkg>::<pkg>__rosidl_generator_py` target is pointed at this
# virtualenv's include folders (COURSE_PYTHON_INCLUDE_DIRS, given by the build step).
include_guard(GLOBAL)

function(_course_point_py_targets_at_venv)
  get_property(_targets DIRECTORY "${CMAKE_SOURCE_DIR}" PROPERTY IMPORTED_TARGETS)
  foreach(_target IN LISTS _targets)
    if(_target MATCHES "::.*__rosidl_generator_py$")
      get_target_property(_dirs "${_target}" INTERFACE_INCLUDE_DIRECTORIES)
      if(_dirs AND NOT _dirs STREQUAL "${COURSE_PYTHON_INCLUDE_DIRS}")
        set_target_properties("${_target}" PROPERTIES
          INTERFACE_INCLUDE_DIRECTORIES "${COURSE_PYTHON_INCLUDE_DIRS}")
      endif()
    endif()
  endforeach()
endfunction()

if(COURSE_PYTHON_INCLUDE_DIRS)
  cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL _course_point_py_targets_at_venv)
endif()
