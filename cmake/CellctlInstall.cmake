# cellctl installed like a service: `cmake --install` and the Debian package (CPack, DEB).
#
#   cmake --install build/demo --prefix /usr/local        the binary, the unit, the user, the examples
#   cpack --config build/demo/CPackConfig.cmake -B build/demo/package   cellctl_<version>_<arch>.deb
#
# What goes where (under the prefix; the package's prefix is /usr):
#   bin/cellctl                                  the controller
#   lib/systemd/system/cellctl.service           `cellctl serve` as a service (packaging/cellctl.service.in)
#   lib/sysusers.d/cellctl.conf                  its user (packaging/cellctl.sysusers)
#   share/cellctl/examples/                      the default cell, config/examples/ and recipes/
#   share/doc/cellctl/README.md
# The unit names the binary by the prefix given at install time (so a DESTDIR or CPack staging folder
# never shows in it); the cell's own files are in /etc/cellctl and /var/lib/cellctl, made by the
# package's postinst and the unit (StateDirectory), never installed over.
include(GNUInstallDirs)
# Installing (and cpack, which installs first) takes what is built and builds nothing: the package's
# test runs in a tree whose other targets need not be built.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

install(TARGETS cellctl RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# The unit, written at install time with the prefix then in force (`--prefix`, CPack's /usr).
set(cellctl_unit_in ${PROJECT_SOURCE_DIR}/packaging/cellctl.service.in)
set(cellctl_unit ${PROJECT_BINARY_DIR}/packaging/cellctl.service)
install(CODE "
  set(CELLCTL_BINARY \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}/cellctl\")
  set(CELLCTL_DOCDIR \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DOCDIR}\")
  configure_file(\"${cellctl_unit_in}\" \"${cellctl_unit}\" @ONLY)
")
install(FILES ${cellctl_unit} DESTINATION lib/systemd/system)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/cellctl.sysusers DESTINATION lib/sysusers.d RENAME cellctl.conf)

install(FILES ${PROJECT_SOURCE_DIR}/config/cell.yaml DESTINATION ${CMAKE_INSTALL_DATADIR}/cellctl/examples)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/examples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/cellctl/examples)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/recipes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/cellctl/examples/recipes)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The Debian package. CPACK_SET_DESTDIR: CPack installs with the package's prefix and a staging
# DESTDIR, so the unit written at install time names /usr/bin/cellctl.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME cellctl)
set(CPACK_PACKAGE_VENDOR "cellctl")
set(CPACK_PACKAGE_CONTACT "cellctl maintainers <cellctl@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "controller of one motion cell (Ewellix SCU, SycoTec spindle, Scancon encoder)")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
       "Runs YAML recipes on the cell with a 1 ms control loop and a safety monitor, dry-runs them on\n"
       "emulators of every device, and stands by as a service (cellctl serve) for the plant's MQTT\n"
       "broker and an operator page. The service is not enabled on installation: configure the cell in\n"
       "/etc/cellctl first (/usr/share/doc/cellctl/README.md, section Installing on the cell PC).")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_SET_DESTDIR ON)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# systemd: the unit and systemd-sysusers, which the postinst runs.
set(CPACK_DEBIAN_PACKAGE_DEPENDS systemd)
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "mosquitto, prometheus")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/postinst ${PROJECT_SOURCE_DIR}/packaging/prerm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
