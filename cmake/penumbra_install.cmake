# Install the library, its public headers and a CMake package so that another
# project can say find_package(penumbra CONFIG) and link penumbra::penumbra.
#
# Three install components (docs/architecture.md, "Install layout"):
#   penumbra   libpenumbra, include/penumbra/*.h, the package files and
#              penumbraTargets.cmake (penumbra::penumbra);
#   reference  libpenumbra_reference, include/penumbra/reference{.h,/}, and
#              penumbraReferenceTargets.cmake (penumbra::reference), loaded
#              only by find_package(penumbra CONFIG COMPONENTS reference);
#   tool       bin/penumbra (it needs both libraries);
#   python     the Python module, when built (PENUMBRA_PYTHON).
# `cmake --install build` installs all three; `--component penumbra` alone
# is a complete package for a renderer (tests/install_test.cmake checks it).
include(CMakePackageConfigHelpers)
set(PENUMBRA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/penumbra)

install(TARGETS penumbra EXPORT penumbraTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT penumbra
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT penumbra
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT penumbra)
install(DIRECTORY host/include/penumbra DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT penumbra)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/generated/penumbra/config.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/penumbra COMPONENT penumbra)
install(EXPORT penumbraTargets NAMESPACE penumbra:: DESTINATION ${PENUMBRA_CMAKE_DIR} COMPONENT penumbra)

install(TARGETS penumbra_reference EXPORT penumbraReferenceTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT reference
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT reference
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT reference)
install(DIRECTORY reference/include/penumbra DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT reference)
install(EXPORT penumbraReferenceTargets NAMESPACE penumbra:: DESTINATION ${PENUMBRA_CMAKE_DIR}
        COMPONENT reference)

install(TARGETS penumbra_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tool)

# The Python module (python/), component `python`: into Debian's
# dist-packages under the prefix (/usr/lib/python3/dist-packages for /usr, on
# Debian's sys.path), finding libpenumbra by a RUNPATH relative to itself.
if(TARGET penumbra_python)  # PENUMBRA_PYTHON_DIR: python/CMakeLists.txt
  file(RELATIVE_PATH _penumbra_python_to_lib /${PENUMBRA_PYTHON_DIR} /${CMAKE_INSTALL_LIBDIR})
  set_target_properties(penumbra_python PROPERTIES INSTALL_RPATH "$ORIGIN/${_penumbra_python_to_lib}")
  install(TARGETS penumbra_python LIBRARY DESTINATION ${PENUMBRA_PYTHON_DIR} COMPONENT python)
endif()

configure_package_config_file(cmake/penumbraConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfig.cmake
  INSTALL_DESTINATION ${PENUMBRA_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/penumbraConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfigVersion.cmake
        DESTINATION ${PENUMBRA_CMAKE_DIR} COMPONENT penumbra)
