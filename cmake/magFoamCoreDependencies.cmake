# The libraries libmagCore's readers and headers use (Debian 12 versions),
# found alike by the project and by the standalone fuzz build (tests/fuzz):
# Eigen, yaml-cpp (its target in MAG_YAML_TARGET), spdlog, assimp.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(spdlog REQUIRED)
find_package(assimp REQUIRED)
# yaml-cpp 0.7 exports the target `yaml-cpp`; newer releases `yaml-cpp::yaml-cpp`.
if(TARGET yaml-cpp::yaml-cpp)
  set(MAG_YAML_TARGET yaml-cpp::yaml-cpp)
else()
  set(MAG_YAML_TARGET yaml-cpp)
endif()
