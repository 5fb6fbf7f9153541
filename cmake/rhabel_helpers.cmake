# rhabel_module(NAME [DEPENDS targets...]): a header-only module rhabel::NAME whose
# headers live in NAME/include/rhabel/.
function(rhabel_header_module name)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  add_library(rhabel_${name} INTERFACE)
  add_library(rhabel::${name} ALIAS rhabel_${name})
  set_target_properties(rhabel_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(rhabel_${name} INTERFACE
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(rhabel_${name} INTERFACE cxx_std_20)
  target_link_libraries(rhabel_${name} INTERFACE ${ARG_DEPENDS})
endfunction()

# Warnings for rhabel's own compiled code (never pushed onto consumers of the headers).
function(rhabel_warnings target)
  if(RHABEL_WARNINGS)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  endif()
  if(RHABEL_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
