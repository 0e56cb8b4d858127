# Installs the library, its public headers, the sysid program and a CMake package so that a
# downstream project can write find_package(Sysid) + target_link_libraries(app sysid::sysid)
# (and sysid::report for plots and the pipeline report).
include(CMakePackageConfigHelpers)

install(TARGETS sysid sysid_report EXPORT SysidTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY libsysid/include/sysid DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Component "cli": scripts/setup.sh installs the program alone (with the Python package), so
# that `sysid` is on the PATH after the README's commands.
install(TARGETS sysid_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)

set(SYSID_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Sysid)
install(EXPORT SysidTargets NAMESPACE sysid:: DESTINATION ${SYSID_CMAKE_DIR})
configure_package_config_file(cmake/SysidConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/SysidConfig.cmake
                              INSTALL_DESTINATION ${SYSID_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/SysidConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/SysidConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/SysidConfigVersion.cmake
        DESTINATION ${SYSID_CMAKE_DIR})
