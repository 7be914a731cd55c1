# Debian's libnova-dev ships neither a CMake config nor a pkg-config file:
# find the header and the library, and wrap them in an imported target.
find_path(LibNova_INCLUDE_DIR libnova/solar.h)
find_library(LibNova_LIBRARY NAMES nova)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LibNova REQUIRED_VARS LibNova_LIBRARY LibNova_INCLUDE_DIR)
if(LibNova_FOUND AND NOT TARGET LibNova::LibNova)
  add_library(LibNova::LibNova UNKNOWN IMPORTED)
  set_target_properties(LibNova::LibNova PROPERTIES
    IMPORTED_LOCATION "${LibNova_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LibNova_INCLUDE_DIR}")
endif()
mark_as_advanced(LibNova_INCLUDE_DIR LibNova_LIBRARY)
