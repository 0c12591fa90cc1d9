# `cmake --install` gives a package that `find_package(argil)` finds: the three
# libraries, their public headers (detail/ folders are private and stay out) and
# argilConfig.cmake with its version file.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(ARGIL_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/argil")

install(TARGETS argil_core argil_io argil_sculpt argil_occt EXPORT argilTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS argil RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

foreach(_tree src/argil io/argil sculpt/argil)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_tree}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/argil
    FILES_MATCHING PATTERN "*.hpp" PATTERN "detail" EXCLUDE)
endforeach()

install(EXPORT argilTargets NAMESPACE argil:: DESTINATION ${ARGIL_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/argilConfig.cmake.in
  ${PROJECT_BINARY_DIR}/argilConfig.cmake INSTALL_DESTINATION ${ARGIL_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/argilConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/argilConfig.cmake ${PROJECT_BINARY_DIR}/argilConfigVersion.cmake
  DESTINATION ${ARGIL_INSTALL_CMAKEDIR})
