# Finds Debian's OpenFOAM v1912: libraries from the package libopenfoam, headers from the flat
# include directories bin/installOpenFOAM builds from Debian's source package of the same version.
# Defines the imported target OpenFOAM::finiteVolume (finiteVolume, meshTools, OpenFOAM; the
# compile flags and link options of docs/architecture.md), OpenFOAM_PROJECT_DIR (the
# WM_PROJECT_DIR applications need at run time) and OpenFOAM_BIN_DIR (blockMesh, decomposePar).
set(OpenFOAM_INCLUDE_ROOT "/opt/iceRidgeSim/openfoam-v1912/include"
    CACHE PATH "Flat per-library OpenFOAM include directories (bin/installOpenFOAM)")
set(OpenFOAM_PROJECT_DIR "/usr/share/openfoam" CACHE PATH "OpenFOAM's WM_PROJECT_DIR")

find_path(OpenFOAM_CORE_INCLUDE_DIR NAMES fvCFD.H PATHS ${OpenFOAM_INCLUDE_ROOT}/finiteVolume NO_DEFAULT_PATH)
find_library(OpenFOAM_LIBRARY NAMES OpenFOAM)
find_library(OpenFOAM_finiteVolume_LIBRARY NAMES finiteVolume)
find_library(OpenFOAM_meshTools_LIBRARY NAMES meshTools)
find_program(OpenFOAM_BLOCKMESH NAMES blockMesh)
if(OpenFOAM_BLOCKMESH)
  get_filename_component(OpenFOAM_BIN_DIR ${OpenFOAM_BLOCKMESH} DIRECTORY)
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenFOAM
  REQUIRED_VARS OpenFOAM_LIBRARY OpenFOAM_finiteVolume_LIBRARY OpenFOAM_meshTools_LIBRARY
                OpenFOAM_CORE_INCLUDE_DIR OpenFOAM_BLOCKMESH
  REASON_FAILURE_MESSAGE "run bin/installOpenFOAM (Debian packages and headers)")

if(OpenFOAM_FOUND AND NOT TARGET OpenFOAM::finiteVolume)
  add_library(OpenFOAM::finiteVolume INTERFACE IMPORTED)
  set(_of_includes "")
  foreach(lib finiteVolume meshTools OpenFOAM OSspecific/POSIX)
    list(APPEND _of_includes ${OpenFOAM_INCLUDE_ROOT}/${lib})
  endforeach()
  set_target_properties(OpenFOAM::finiteVolume PROPERTIES
    # SYSTEM: OpenFOAM's own headers warn under -Wall -Wextra; ours should not be drowned.
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_of_includes}"
    INTERFACE_INCLUDE_DIRECTORIES "${_of_includes}"
    INTERFACE_COMPILE_DEFINITIONS "OPENFOAM=1912;WM_DP;WM_LABEL_SIZE=32;NoRepository"
    INTERFACE_COMPILE_OPTIONS "-m64;-fPIC;-ftemplate-depth-100"
    INTERFACE_COMPILE_FEATURES cxx_std_17
    # --no-as-needed: run-time selection tables fill from static constructors of libraries
    # no symbol of which the application names directly.
    INTERFACE_LINK_OPTIONS "LINKER:--add-needed;LINKER:--no-as-needed"
    INTERFACE_LINK_LIBRARIES
      "${OpenFOAM_finiteVolume_LIBRARY};${OpenFOAM_meshTools_LIBRARY};${OpenFOAM_LIBRARY};dl")
  unset(_of_includes)
endif()
mark_as_advanced(OpenFOAM_CORE_INCLUDE_DIR OpenFOAM_LIBRARY OpenFOAM_finiteVolume_LIBRARY
                 OpenFOAM_meshTools_LIBRARY OpenFOAM_BLOCKMESH)
