# tinyxml2 (Debian 12: libtinyxml2-dev 9.0) ships a CMake config exporting
# tinyxml2::tinyxml2; older packagings have only a pkg-config file. Use the config
# when present, else pkg-config, and define tinyxml2::tinyxml2 either way.
find_package(tinyxml2 CONFIG QUIET)
if(NOT TARGET tinyxml2::tinyxml2)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(TINYXML2 REQUIRED IMPORTED_TARGET GLOBAL tinyxml2)
  add_library(tinyxml2::tinyxml2 ALIAS PkgConfig::TINYXML2)
endif()
