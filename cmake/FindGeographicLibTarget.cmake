# Debian ships GeographicLib with only a Find module (no CMake config package):
# use it, then wrap its variables in an imported target so the rest of the
# build links GeographicLib::GeographicLib like any other dependency.
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib QUIET)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(GeographicLibTarget
  REQUIRED_VARS GeographicLib_LIBRARIES GeographicLib_INCLUDE_DIRS)
if(GeographicLibTarget_FOUND AND NOT TARGET GeographicLib::GeographicLib)
  add_library(GeographicLib::GeographicLib UNKNOWN IMPORTED)
  set_target_properties(GeographicLib::GeographicLib PROPERTIES
    IMPORTED_LOCATION "${GeographicLib_LIBRARIES}"
    INTERFACE_INCLUDE_DIRECTORIES "${GeographicLib_INCLUDE_DIRS}")
endif()
