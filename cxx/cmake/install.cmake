# cmake --install <build> --prefix P: the headers, both libraries and the CMake package
# P/lib/cmake/hypercontact, so that a C++ program finds them with find_package(hypercontact).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(HYPERCONTACT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/hypercontact)

install(DIRECTORY include/hypercontact DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(part kernels assembly)
  install(TARGETS hypercontact_${part} EXPORT hypercontact_${part}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT hypercontact_${part} NAMESPACE hypercontact::
          FILE hypercontact_${part}_targets.cmake DESTINATION ${HYPERCONTACT_CMAKE_DIR})
endforeach()

configure_package_config_file(cmake/hypercontactConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/hypercontactConfig.cmake INSTALL_DESTINATION ${HYPERCONTACT_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/hypercontactConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/hypercontactConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/hypercontactConfigVersion.cmake
        DESTINATION ${HYPERCONTACT_CMAKE_DIR})
