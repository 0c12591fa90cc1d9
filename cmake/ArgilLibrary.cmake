# argil_add_library(<name> <sources>...): the library argil_<name>, exported and
# aliased as argil::<name>, requiring C++20 of its users, with its headers from
# the calling folder (installed under include/) and argil's warnings on its own
# sources. Dependencies are linked by the caller.
function(argil_add_library name)
  add_library(argil_${name} ${ARGN})
  add_library(argil::${name} ALIAS argil_${name})
  set_target_properties(argil_${name} PROPERTIES EXPORT_NAME ${name})
  target_compile_features(argil_${name} PUBLIC cxx_std_20)
  target_include_directories(argil_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(argil_${name} PRIVATE $<BUILD_INTERFACE:argil_warnings>)
endfunction()
