# Finds Debian's LIGGGHTS 3.8 library (packages liggghts, libliggghts-dev).
# Defines the imported target LIGGGHTS::LIGGGHTS and LIGGGHTS_EXECUTABLE.
find_path(LIGGGHTS_INCLUDE_DIR NAMES lammps.h fix_external.h PATH_SUFFIXES liggghts)
find_library(LIGGGHTS_LIBRARY NAMES liggghts)
find_program(LIGGGHTS_EXECUTABLE NAMES liggghts)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LIGGGHTS
  REQUIRED_VARS LIGGGHTS_LIBRARY LIGGGHTS_INCLUDE_DIR)

if(LIGGGHTS_FOUND AND NOT TARGET LIGGGHTS::LIGGGHTS)
  add_library(LIGGGHTS::LIGGGHTS UNKNOWN IMPORTED)
  set_target_properties(LIGGGHTS::LIGGGHTS PROPERTIES
    IMPORTED_LOCATION "${LIGGGHTS_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LIGGGHTS_INCLUDE_DIR}")
endif()
mark_as_advanced(LIGGGHTS_INCLUDE_DIR LIGGGHTS_LIBRARY LIGGGHTS_EXECUTABLE)
