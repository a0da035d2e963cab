# Install rules (bin/vots, lib/vots, share/vots/web), the build tree's matching web link, and CPack's Debian
# package.
install(TARGETS vots RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET vots_webm)
  # FFmpeg's encoder, which vots loads from bin/../lib/vots when it writes a WebM (render/CMakeLists.txt).
  install(TARGETS vots_webm LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/vots)
endif()
if(TARGET vots_server)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/web/ DESTINATION ${CMAKE_INSTALL_DATADIR}/vots/web)
  # A build-tree `vots serve` looks where an installed one does (server/src/Server.cpp, defaultWebDir);
  # a link there to the source's web/ makes that the same rule, and edits to web/ show without a rebuild.
  get_target_property(VOTS_CLI_BINARY_DIR vots BINARY_DIR)
  set(VOTS_BUILD_TREE_WEB ${VOTS_CLI_BINARY_DIR}/${VOTS_WEB_DIR_FROM_BIN})
  cmake_path(GET VOTS_BUILD_TREE_WEB PARENT_PATH VOTS_BUILD_TREE_WEB_PARENT)
  file(MAKE_DIRECTORY ${VOTS_BUILD_TREE_WEB_PARENT})
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/web ${VOTS_BUILD_TREE_WEB} SYMBOLIC)
endif()

if(TARGET vots_server)
  # The system service (packaging/): the unit, its user and folders, the default configuration (a conffile,
  # kept on upgrades when edited) and the maintainer scripts that make the user and set /etc/vots's modes.
  set(VOTS_PACKAGING ${PROJECT_SOURCE_DIR}/packaging)
  install(FILES ${VOTS_PACKAGING}/systemd/vots.service DESTINATION lib/systemd/system)
  install(FILES ${VOTS_PACKAGING}/sysusers.d/vots.conf DESTINATION lib/sysusers.d)
  install(FILES ${VOTS_PACKAGING}/tmpfiles.d/vots.conf DESTINATION lib/tmpfiles.d)
  # GNUInstallDirs' rule for the configuration folder, applied at install time when the prefix is known:
  # /etc for the prefix /usr (the .deb, where the unit reads it), else <prefix>/etc (`--prefix ~/.local`);
  # file(INSTALL) puts DESTDIR (cpack's staging folder) before it.
  install(CODE "
    set(vots_etc \"\${CMAKE_INSTALL_PREFIX}/etc\")
    if(CMAKE_INSTALL_PREFIX STREQUAL \"/usr\")
      set(vots_etc /etc)
    endif()
    file(INSTALL DESTINATION \"\${vots_etc}/vots\" TYPE FILE FILES \"${VOTS_PACKAGING}/etc/vots.conf\")")
  file(WRITE ${PROJECT_BINARY_DIR}/packaging/conffiles "/etc/vots/vots.conf\n")
  set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${VOTS_PACKAGING}/debian/postinst ${VOTS_PACKAGING}/debian/prerm
                                         ${VOTS_PACKAGING}/debian/postrm ${PROJECT_BINARY_DIR}/packaging/conffiles)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME vots)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Fits volumes into Vot-Spaces, renders them as MIP, serves them over HTTP")
set(CPACK_STRIP_FILES ON)
set(VOTS_PACKAGE_MAINTAINER "Vots maintainers <vots@localhost>" CACHE STRING "The .deb's Maintainer field")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${VOTS_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# libEGL (glvnd) alone has no driver: a vendor must be installed (Mesa: llvmpipe without a GPU).
# adduser: the postinst's way to make the vots user where systemd-sysusers is missing.
set(VOTS_DEB_DEPENDS "libegl-mesa0 | libegl-vendor, libgl1-mesa-dri, adduser")
find_program(VOTS_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(VOTS_DPKG_SHLIBDEPS)
  # The libraries the binary links, with versions, from dpkg-shlibdeps (package dpkg-dev).
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
else()
  # Debian 12's packages of what `ldd vots` lists (a build without dpkg-dev).
  string(PREPEND VOTS_DEB_DEPENDS "libc6, libstdc++6, libgcc-s1, libdeflate0, zlib1g, libabsl20220623, "
                                  "libepoxy0, libegl1, libcpp-httplib0.11, libavcodec59, libavformat59, libswscale6, libavutil57, libopenmpi3, ")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${VOTS_DEB_DEPENDS}")
include(CPack)
