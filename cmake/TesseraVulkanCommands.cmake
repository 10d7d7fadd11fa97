# tessera_vulkan_commands(<target> <list file>): adds to <target> a generated source that defines
# each Vulkan command named in <list file> as a function forwarding to the loader opened at run
# time (compute/vulkan_loader.h), and the Vulkan headers without the loader library, so no
# binary has libvulkan.so.1 as DT_NEEDED.
function(tessera_vulkan_commands target list_file)
  get_filename_component(list_file ${list_file} ABSOLUTE)
  set(header ${Vulkan_INCLUDE_DIR}/vulkan/vulkan_core.h)
  set(script ${PROJECT_SOURCE_DIR}/cmake/generate_vulkan_commands.cmake)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/vulkan_commands.cpp)
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DHEADER=${header} -DCOMMANDS=${list_file} -DOUTPUT=${out} -P ${script}
    DEPENDS ${header} ${list_file} ${script}
    COMMENT "Generating Vulkan command forwarders from ${list_file}"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
  target_link_libraries(${target} PUBLIC Vulkan::Headers ${CMAKE_DL_LIBS})
endfunction()
