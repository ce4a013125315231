# The DG808 GNC as a library target `${GNC_TARGET}`, included by drone_ros/controller with
# GNC_DIR set to this folder. Another aircraft provides the same file (and gnc_binding.h) in its
# own aircraft/<name>/gnc/.
find_package(Eigen3 REQUIRED NO_MODULE)
add_library(${GNC_TARGET} STATIC
  ${GNC_DIR}/airdata_ekf.cpp
  ${GNC_DIR}/dg808_gnc.cpp
  ${GNC_DIR}/guidance.cpp
  ${GNC_DIR}/inner_loops.cpp)
target_include_directories(${GNC_TARGET} PUBLIC ${GNC_DIR})
# geo_wgs84 (arduino_ha/src/core): the stack's one latitude/longitude <-> north/east conversion.
target_link_libraries(${GNC_TARGET} PUBLIC Eigen3::Eigen geo_wgs84)
set_target_properties(${GNC_TARGET} PROPERTIES POSITION_INDEPENDENT_CODE ON)
strict_warnings(${GNC_TARGET})
# The gains header design/design_gains.py writes; the controller's test reruns the script and
# compares, so each aircraft names its own.
set(GNC_GENERATED_HEADER ${GNC_DIR}/dg808_gnc_data.h)
