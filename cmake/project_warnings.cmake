# Project code builds with warnings as errors; third-party and generated headers are included
# as SYSTEM so their warnings stay theirs.
function(strict_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
endfunction()

# Generated message headers of this package, for targets that use them.
function(uses_package_messages target)
  add_dependencies(${target} ${PROJECT_NAME}_generate_messages_cpp)
  target_include_directories(${target} SYSTEM PRIVATE ${catkin_INCLUDE_DIRS}
    ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
  target_link_libraries(${target} ${catkin_LIBRARIES})
endfunction()
