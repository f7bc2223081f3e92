# yaml-cpp 0.7 (Debian 12) exports the target `yaml-cpp`; newer releases export
# `yaml-cpp::yaml-cpp`. Alias whichever exists to iga::yaml-cpp.
find_package(yaml-cpp REQUIRED)
if(TARGET yaml-cpp::yaml-cpp)
  add_library(iga::yaml-cpp ALIAS yaml-cpp::yaml-cpp)
else()
  add_library(iga_yaml_cpp INTERFACE)
  target_link_libraries(iga_yaml_cpp INTERFACE yaml-cpp)
  add_library(iga::yaml-cpp ALIAS iga_yaml_cpp)
endif()
