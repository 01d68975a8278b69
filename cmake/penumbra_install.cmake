# Install the library, its public headers and a CMake package so that another
# project can say find_package(penumbra CONFIG) and link penumbra::penumbra.
include(CMakePackageConfigHelpers)
install(TARGETS penumbra penumbra_cli EXPORT penumbraTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY host/include/penumbra DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/generated/penumbra/config.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/penumbra)
install(EXPORT penumbraTargets NAMESPACE penumbra::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/penumbra)
configure_package_config_file(cmake/penumbraConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/penumbra)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/penumbraConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/penumbra)
