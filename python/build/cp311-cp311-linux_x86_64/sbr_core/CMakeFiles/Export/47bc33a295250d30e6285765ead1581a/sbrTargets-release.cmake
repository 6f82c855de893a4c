#----------------------------------------------------------------
# Generated CMake target import file for configuration "Release".
#----------------------------------------------------------------

# Commands may need to know the format version.
set(CMAKE_IMPORT_FILE_VERSION 1)

# Import target "sbr::sbr" for configuration "Release"
set_property(TARGET sbr::sbr APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(sbr::sbr PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "C"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libsbr.a"
  )

list(APPEND _cmake_import_check_targets sbr::sbr )
list(APPEND _cmake_import_check_files_for_sbr::sbr "${_IMPORT_PREFIX}/lib/libsbr.a" )

# Commands beyond this point should not need to know the version.
set(CMAKE_IMPORT_FILE_VERSION)
