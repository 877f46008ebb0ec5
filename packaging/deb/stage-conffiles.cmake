# CPack's pre-build script (CPACK_PRE_BUILD_SCRIPTS): files only the package carries, placed in
# its staging tree after the install and before the archive is made. The rig's config is the
# package's conffile /etc/glarecam/glarecam.toml (dpkg keeps the operator's edits and asks before
# replacing them); `make install` instead installs it as an example and never over /etc.
set(root "${CPACK_TEMPORARY_INSTALL_DIRECTORY}")
if(NOT IS_DIRECTORY "${root}")
  message(FATAL_ERROR "stage-conffiles: no staging directory ${root}")
endif()
# file(COPY), not file(INSTALL): the latter would put DESTDIR (CPack's staging) in front again.
file(COPY "${CPACK_GLARECAM_SOURCE_DIR}/firmware-config/glarecam.toml"
     DESTINATION "${root}/etc/glarecam" FILE_PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ
     WORLD_READ)
