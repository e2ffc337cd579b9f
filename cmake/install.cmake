# Installs the client library (with the generated API and the core it uses)
# and a CMake package config, so another service can write
#   find_package(freeform CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE freeform::client)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(freeform_client PROPERTIES EXPORT_NAME client)
set_target_properties(freeform_proto PROPERTIES EXPORT_NAME proto)
set_target_properties(freeform_core PROPERTIES EXPORT_NAME core)
set_target_properties(freeform_file PROPERTIES EXPORT_NAME file)

install(TARGETS freeform_client freeform_proto freeform_core freeform_file
  freeform_warnings
  EXPORT freeformTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY client/include/ core/include/ io/include/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${CMAKE_BINARY_DIR}/proto/gen/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")
# The .proto files with their two include roots: proto/ and third_party/.
install(DIRECTORY proto/freeform proto/third_party
  DESTINATION ${CMAKE_INSTALL_DATADIR}/freeform/proto)

install(EXPORT freeformTargets NAMESPACE freeform::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/freeform)
configure_package_config_file(cmake/freeformConfig.cmake.in
  ${CMAKE_BINARY_DIR}/freeformConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/freeform)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/freeformConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/freeformConfig.cmake
  ${CMAKE_BINARY_DIR}/freeformConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/freeform)
