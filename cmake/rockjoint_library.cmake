# SPDX-License-Identifier: MIT
# rockjoint_add_library(<name> [PUBLIC_LINK <targets...>])
# One library per source folder: every .cpp of the calling folder, target rockjoint_<name>,
# exported as rockjoint::<name>; headers installed under <prefix>/include/rockjoint/<name>/ so
# that users (and the project itself) write #include <rockjoint/<name>/header.hpp>.
function(rockjoint_add_library name)
  cmake_parse_arguments(ARG "" "" "PUBLIC_LINK" ${ARGN})
  file(GLOB _sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  file(GLOB _headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.hpp)
  add_library(rockjoint_${name} ${_sources})
  add_library(rockjoint::${name} ALIAS rockjoint_${name})
  set_target_properties(rockjoint_${name} PROPERTIES EXPORT_NAME ${name})
  target_compile_features(rockjoint_${name} PUBLIC cxx_std_20)
  # The headers are copied into <build>/include/rockjoint/<name>/ (configure_file re-copies a
  # header when it changes), so the same <rockjoint/...> paths resolve before and after
  # installation, and only headers are visible under the include root.
  foreach(_header ${_headers})
    get_filename_component(_file ${_header} NAME)
    configure_file(${_header} ${ROCKJOINT_BUILD_INCLUDE_DIR}/rockjoint/${name}/${_file} COPYONLY)
  endforeach()
  target_include_directories(rockjoint_${name} PUBLIC
    $<BUILD_INTERFACE:${ROCKJOINT_BUILD_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(rockjoint_${name} PUBLIC ${ARG_PUBLIC_LINK})
  install(TARGETS rockjoint_${name} EXPORT rockjointTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(FILES ${_headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rockjoint/${name})
endfunction()
