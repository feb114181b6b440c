# Installation: headers, the libraries, a CMake package (find_package(vraster): vraster::vraster, vraster::svg,
# vraster::text) and pkg-config files (vraster.pc, vraster-svg.pc, vraster-text.pc). docs/design.md, "Packaging",
# says why the libraries are static archives by default and how the pkg-config files account for that.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(vraster_install_targets vraster vraster_svg)
if(VRASTER_BUILD_TEXT)
  list(APPEND vraster_install_targets vraster_text)
endif()
install(TARGETS ${vraster_install_targets} EXPORT vrasterTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS vraster_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY include/ svg_subset/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(VRASTER_BUILD_TEXT)
  install(DIRECTORY text/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()

set(vraster_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/vraster)
install(EXPORT vrasterTargets NAMESPACE vraster:: DESTINATION ${vraster_cmake_dir})
configure_package_config_file(cmake/vrasterConfig.cmake.in ${PROJECT_BINARY_DIR}/vrasterConfig.cmake
                              INSTALL_DESTINATION ${vraster_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/vrasterConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/vrasterConfig.cmake ${PROJECT_BINARY_DIR}/vrasterConfigVersion.cmake
        DESTINATION ${vraster_cmake_dir})

# pkg-config. The prefix is found from the .pc file's own place (${pcfiledir}), so an installed tree can move.
# A static archive carries none of its dependencies: a C program linking libvraster.a needs libpng and the C++
# runtime on its link line, so for static builds they go in Requires / Libs; shared libraries record them
# themselves (DT_NEEDED), so there they are only Requires.private / Libs.private (for pkg-config --static).
set(vraster_pc_dir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH VRASTER_PC_TO_PREFIX /prefix/${vraster_pc_dir} /prefix)
string(REGEX REPLACE "/$" "" VRASTER_PC_TO_PREFIX "${VRASTER_PC_TO_PREFIX}")
set(vraster_cxx_runtime "-lstdc++ -lm -pthread")
if(BUILD_SHARED_LIBS)
  set(VRASTER_PC_REQUIRES "Requires.private")
  set(VRASTER_PC_CXX_LIBS_PUBLIC "")
  set(VRASTER_PC_CXX_LIBS_PRIVATE "${vraster_cxx_runtime}")
else()
  set(VRASTER_PC_REQUIRES "Requires")
  set(VRASTER_PC_CXX_LIBS_PUBLIC "${vraster_cxx_runtime}")
  set(VRASTER_PC_CXX_LIBS_PRIVATE "")
endif()
# SVG text needs the text library (core <- text <- svg).
set(VRASTER_SVG_PC_TEXT "")
if(VRASTER_BUILD_TEXT)
  set(VRASTER_SVG_PC_TEXT "vraster-text")
endif()
set(vraster_pc_files vraster vraster-svg)
if(VRASTER_BUILD_TEXT)
  list(APPEND vraster_pc_files vraster-text)
endif()
foreach(pc ${vraster_pc_files})
  configure_file(cmake/${pc}.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/${pc}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/pkgconfig/${pc}.pc DESTINATION ${vraster_pc_dir})
endforeach()
