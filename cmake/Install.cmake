# install() and export rules: `cmake --install` puts the hpsf command, the libraries, their headers and the shader
# interface under a prefix, with a CMake package a team's project finds by find_package(hpsf COMPONENTS ...).
# Headers keep their paths below include/hpsf (core/key_batch.h, verifier/checker/table_checker.h), and the GLSL
# interface sits beside them (vulkan/shaders/table_interface.glsl includes ../../core/shared/*.h), so one include
# directory serves C++ and glslangValidator alike.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(HPSF_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/hpsf)
set(HPSF_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/hpsf)

# Components and their targets. core is always there; the others are what a consumer asks for.
set(HPSF_COMPONENT_core core simt emulated reference checker theory gate generators)
set(HPSF_COMPONENT_vulkan vulkan contract fuzzing)
set(HPSF_COMPONENT_tracer tracer)
set(HPSF_COMPONENT_reports metrics)
set(HPSF_COMPONENTS core vulkan tracer reports)

foreach(component IN LISTS HPSF_COMPONENTS)
  set(targets)
  foreach(name IN LISTS HPSF_COMPONENT_${component})
    list(APPEND targets hpsf_${name})
    set_target_properties(hpsf_${name} PROPERTIES EXPORT_NAME ${name})
    target_include_directories(hpsf_${name} PUBLIC $<INSTALL_INTERFACE:${HPSF_INSTALL_INCLUDEDIR}>)
  endforeach()
  install(TARGETS ${targets} EXPORT hpsf-${component}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
  install(EXPORT hpsf-${component} NAMESPACE hpsf:: FILE hpsf-${component}-targets.cmake
    DESTINATION ${HPSF_INSTALL_CMAKEDIR} COMPONENT development)
endforeach()

install(TARGETS hpsf RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)

# The headers of every installed library and the shader interface, tests left out.
foreach(folder core emulated reference tracer vulkan verifier)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/ DESTINATION ${HPSF_INSTALL_INCLUDEDIR}/${folder}
    COMPONENT development
    FILES_MATCHING PATTERN "*.h" PATTERN "*.glsl" PATTERN "*.comp" PATTERN "*_test.h" EXCLUDE)
endforeach()

# The gate file's and the table declaration's JSON Schemas, for editors and CI linters (hpsf check --schema prints
# the gate's), the reports', and the example table declarations.
install(FILES ${PROJECT_SOURCE_DIR}/verifier/gate/gate_schema.json ${PROJECT_SOURCE_DIR}/verifier/gate/table_schema.json
  DESTINATION ${CMAKE_INSTALL_DATADIR}/hpsf COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/tables/ DESTINATION ${CMAKE_INSTALL_DATADIR}/hpsf/tables
  COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/reference/schemas/ DESTINATION ${CMAKE_INSTALL_DATADIR}/hpsf/schemas
  COMPONENT runtime)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/hpsfConfig.cmake.in
  ${PROJECT_BINARY_DIR}/hpsfConfig.cmake INSTALL_DESTINATION ${HPSF_INSTALL_CMAKEDIR} PATH_VARS HPSF_INSTALL_INCLUDEDIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hpsfConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hpsfConfig.cmake ${PROJECT_BINARY_DIR}/hpsfConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/FindOpenCVQuality.cmake DESTINATION ${HPSF_INSTALL_CMAKEDIR} COMPONENT development)

# A Debian package of all of it (cpack -G DEB in the build folder): the command, the libraries, their headers and
# the CMake package, under /usr. Its dependencies are the shared libraries the command links, found by
# dpkg-shlibdeps, the Vulkan loader (which Vulkan-Hpp opens at run time, so dpkg-shlibdeps cannot see it), and the
# -dev packages a consumer's find_package(hpsf) needs for the core component.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME hpsf)
set(CPACK_PACKAGE_VENDOR "hpsf")
set(CPACK_PACKAGE_CONTACT "hpsf maintainers <hpsf@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Makes GPU hash tables for hashed path space filtering trustworthy")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION devel)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libvulkan1, libglm-dev, nlohmann-json3-dev, libtbb-dev, libnanoflann-dev")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "mesa-vulkan-drivers")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libvulkan-dev, libspirv-cross-c-shared-dev, libembree-dev, libtinyobjloader-dev, \
libopencv-contrib-dev, glslang-tools")
include(CPack)
