# `cmake --install` puts the program, the static library, the public headers (include/skyspec/
# only) and a CMake package in the prefix, so that another project can write
#   find_package(skyspec REQUIRED)
#   target_link_libraries(app PRIVATE skyspec::skyspec)
# tests/consumer/ is such a project; scripts/test.sh builds it against an installed copy.
# The library is static: its private dependencies (OpenEXR, OpenColorIO, TBB, libpng, toml++,
# nlohmann_json) are found again by skyspecConfig.cmake for the link. -march is never exported;
# a package meant for other machines is built with -DSKYSPEC_ARCH= (the compiler's default).
include(CMakePackageConfigHelpers)

install(TARGETS skyspec_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The Python module's run_job runs this program for the tasks of a job: `--component python`
# installs it too (PREFIX/bin: a virtual environment's bin, beside its python).
install(TARGETS skyspec_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT python)
install(TARGETS skyspec EXPORT skyspecTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/skyspec DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The OpenColorIO config the program embeds, as a file for other tools (docs/other-tools.md);
# `skyspec render --list-displays` prints its installed path.
install(FILES ${PROJECT_SOURCE_DIR}/data/ocio/config.ocio DESTINATION ${CMAKE_INSTALL_DATADIR}/skyspec/ocio)
install(EXPORT skyspecTargets NAMESPACE skyspec:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/skyspec)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/skyspecConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/skyspecConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/skyspec)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/skyspecConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/skyspecConfig.cmake ${PROJECT_BINARY_DIR}/skyspecConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/skyspec)
if(SKYSPEC_ARCH)
  install(CODE "message(STATUS \"skyspec: this build is compiled with -march=${SKYSPEC_ARCH}; for a package that other machines use, configure with -DSKYSPEC_ARCH=\")")
endif()
