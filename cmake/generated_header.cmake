# A header written at build time from the repository's data (an aircraft's YAML, a message), and
# the targets that include it. One pattern for every generator:
#   generated_header(<name> <header path> COMMAND ... DEPENDS ... COMMENT "...")
#     the rule that writes the header and a target <name> that makes it;
#   uses_generated_header(<target> <name>)
#     <target> is built after the header and finds it on its include path (a target that only
#     includes it must say so: nothing else orders the generator before the compiler).
# A function is global, so a component uses a header another component's folder generates.

function(generated_header name header)
  cmake_parse_arguments(GH "" "COMMENT" "COMMAND;DEPENDS" ${ARGN})
  get_filename_component(dir ${header} DIRECTORY)
  add_custom_command(
    OUTPUT ${header}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${dir}
    COMMAND ${GH_COMMAND}
    DEPENDS ${GH_DEPENDS}
    COMMENT "${GH_COMMENT}"
    VERBATIM)
  add_custom_target(${name} DEPENDS ${header})
  set_property(TARGET ${name} PROPERTY GENERATED_HEADER_DIR ${dir})
endfunction()

function(uses_generated_header target name)
  add_dependencies(${target} ${name})
  get_property(dir TARGET ${name} PROPERTY GENERATED_HEADER_DIR)
  target_include_directories(${target} PRIVATE ${dir})
endfunction()
