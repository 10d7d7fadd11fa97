# What `cmake --install` puts under the prefix, and the CMake package that lets a project write
#   find_package(Tessera REQUIRED)                        # or COMPONENTS test_support
#   target_link_libraries(app PRIVATE Tessera::tessera)   # the renderer and the scene model
#   target_link_libraries(app_tests PRIVATE Tessera::test_support)  # EXPECT_IMAGES_NEAR
# Headers keep the paths used inside Tessera (#include "compute/renderer.h") under
# include/tessera/. examples/render_spheres is built against the installed package in CI
# (scripts/check-package.sh), which checks that this list of headers is complete.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(include_dir ${CMAKE_INSTALL_INCLUDEDIR}/tessera)
set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/Tessera)

# Tessera::tessera: everything a program that renders needs.
add_library(tessera_library INTERFACE)
target_link_libraries(tessera_library INTERFACE tessera_compute)
# The public headers use C++20 (designated initializers, std::span).
target_compile_features(tessera_library INTERFACE cxx_std_20)
add_library(Tessera::tessera ALIAS tessera_library)
set_target_properties(tessera_library PROPERTIES EXPORT_NAME tessera)
set_target_properties(tessera_core PROPERTIES EXPORT_NAME core)
set_target_properties(tessera_shaders PROPERTIES EXPORT_NAME shaders)
set_target_properties(tessera_compute PROPERTIES EXPORT_NAME compute)

install(TARGETS tessera_core tessera_shaders tessera_compute tessera_library
        EXPORT TesseraTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${include_dir})
install(TARGETS tessera RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/ DESTINATION ${include_dir}/core
        FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/shared/ DESTINATION ${include_dir}/shaders/shared
        FILES_MATCHING PATTERN "*.h")
# The public compute headers: context.h and renderer.h and what they include.
install(FILES
          ${PROJECT_SOURCE_DIR}/compute/context.h
          ${PROJECT_SOURCE_DIR}/compute/environment_gpu.h
          ${PROJECT_SOURCE_DIR}/compute/gpu_memory.h
          ${PROJECT_SOURCE_DIR}/compute/passes.h
          ${PROJECT_SOURCE_DIR}/compute/pipelines.h
          ${PROJECT_SOURCE_DIR}/compute/renderer.h
          ${PROJECT_SOURCE_DIR}/compute/vk_check.h
        DESTINATION ${include_dir}/compute)
install(EXPORT TesseraTargets NAMESPACE Tessera:: DESTINATION ${config_dir})

# Tessera::test_support, in its own file: only a project that finds GoogleTest loads it.
if(TARGET tessera_test_support)
  add_library(Tessera::test_support ALIAS tessera_test_support)
  set_target_properties(tessera_test_support PROPERTIES EXPORT_NAME test_support)
  target_compile_features(tessera_test_support INTERFACE cxx_std_20)
  install(TARGETS tessera_test_support
          EXPORT TesseraTestSupportTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${include_dir})
  install(FILES ${PROJECT_SOURCE_DIR}/tests/support/image_assertions.h
          DESTINATION ${include_dir}/tests/support)
  install(EXPORT TesseraTestSupportTargets NAMESPACE Tessera:: DESTINATION ${config_dir})
endif()

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/TesseraConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/TesseraConfig.cmake
                              INSTALL_DESTINATION ${config_dir})
# 0.x: a new minor version may change the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/TesseraConfig.cmake
              ${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake
        DESTINATION ${config_dir})
