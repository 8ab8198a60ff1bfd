# Debian packages through CPack (docs/packaging.md): `lfcam` (the command and its viewer, man
# page, docs) from the full build, `lfcam-node` (the capture agent, its systemd unit and
# maintainer scripts) from a node-only build (-DLFCAM_NODE_ONLY=ON), the one the Pis get.
#   cmake --build build/release && (cd build/release && cpack)      -> lfcam_VERSION_amd64.deb
#   cmake -B build/node -DLFCAM_NODE_ONLY=ON ... && (cd build/node && cpack) -> lfcam-node_...deb
# scripts/package.sh does both, checks them with lintian and tries them.
include(GNUInstallDirs)
set(LFCAM_PACKAGING ${CMAKE_SOURCE_DIR}/packaging)

# The package's changelog (a native package: changelog.gz), compressed reproducibly.
function(lfcam_package_docs component package)
  set(out ${CMAKE_BINARY_DIR}/package-docs/${package})
  file(MAKE_DIRECTORY ${out})
  add_custom_command(OUTPUT ${out}/changelog.gz
    COMMAND gzip -9n -c ${LFCAM_PACKAGING}/debian/changelog > ${out}/changelog.gz
    DEPENDS ${LFCAM_PACKAGING}/debian/changelog)
  add_custom_target(${package}-changelog ALL DEPENDS ${out}/changelog.gz)
  install(FILES ${out}/changelog.gz ${LFCAM_PACKAGING}/debian/copyright
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${package} COMPONENT ${component})
endfunction()

# A man page from the program's own help (packaging/make-manpage.sh, help2man).
function(lfcam_man_page target component name_line)
  set(page ${CMAKE_BINARY_DIR}/man/${target}.1.gz)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/man)
  add_custom_command(OUTPUT ${page}
    COMMAND ${LFCAM_PACKAGING}/make-manpage.sh $<TARGET_FILE:${target}> "${name_line}" ${page}
            ${CMAKE_CROSSCOMPILING_EMULATOR}
    DEPENDS ${target} ${LFCAM_PACKAGING}/make-manpage.sh
    COMMENT "Writing the man page of ${target}")
  add_custom_target(${target}-manpage DEPENDS ${page})
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT ${component}
          OPTIONAL)
  set_property(GLOBAL APPEND PROPERTY LFCAM_MAN_PAGES ${target}-manpage)
endfunction()

set(CPACK_PACKAGE_NAME lfcam)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "the lfcam developers")
set(CPACK_PACKAGE_CONTACT "lfcam developers <lfcam@users.noreply.github.com>")
set(CPACK_PACKAGE_HOMEPAGE_URL "https://github.com/lfcam/lfcam")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE ${CPACK_PACKAGE_HOMEPAGE_URL})
set(CPACK_OUTPUT_FILE_PREFIX packages)

if(LFCAM_NODE_ONLY)
  install(TARGETS lfcam-node RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT node)
  install(FILES ${CMAKE_SOURCE_DIR}/deploy/lfcam-node.service
          DESTINATION lib/systemd/system COMPONENT node)
  lfcam_package_docs(node lfcam-node)
  lfcam_man_page(lfcam-node node "the capture agent of an lfcam camera array")
  set(CPACK_COMPONENTS_ALL node)
  set(CPACK_DEBIAN_NODE_PACKAGE_NAME lfcam-node)
  set(CPACK_DEBIAN_NODE_PACKAGE_SECTION net)
  set(CPACK_DEBIAN_NODE_PACKAGE_DEPENDS "adduser")
  set(CPACK_DEBIAN_NODE_PACKAGE_RECOMMENDS "rpicam-apps | libcamera-apps, chrony")
  string(CONCAT CPACK_DEBIAN_NODE_DESCRIPTION
      "capture agent of an lfcam light field camera array\n"
      "lfcam-node runs on each Raspberry Pi of an lfcam camera array (one Pi per\n"
      "camera module). It takes the photographs and video that the host's\n"
      "`lfcam capture` asks for, at the time it asks, with the settings it locks,\n"
      "and serves them back verified over a signed HTTP API. The package installs\n"
      "the agent, its systemd unit and the lfcam system user; the agent starts once\n"
      "the array's key is in /etc/lfcam/array.key.")
  set(CPACK_DEBIAN_NODE_PACKAGE_CONTROL_EXTRA
      ${LFCAM_PACKAGING}/debian/lfcam-node/postinst ${LFCAM_PACKAGING}/debian/lfcam-node/prerm
      ${LFCAM_PACKAGING}/debian/lfcam-node/postrm)
else()
  install(TARGETS lfcam RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT host)
  install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/lfcam
          COMPONENT host)
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/lfcam/docs
          COMPONENT host)
  lfcam_package_docs(host lfcam)
  lfcam_man_page(lfcam host "capture, calibrate and render 4D light fields")
  set(CPACK_COMPONENTS_ALL host)
  # FFmpeg is opened when a video is written (share/ffmpeg_library.h), not linked, so
  # dpkg-shlibdeps cannot see it: its packages by the headers' major versions (libavformat59
  # brings libavcodec59 and libavutil57).
  string(REGEX MATCH "^[0-9]+" lfcam_avformat_major "${LIBAV_libavformat_VERSION}")
  string(REGEX MATCH "^[0-9]+" lfcam_swscale_major "${LIBAV_libswscale_VERSION}")
  set(lfcam_ffmpeg_packages "libavformat${lfcam_avformat_major}, libswscale${lfcam_swscale_major}")
  # python3-lfcam: `import lfcam` for Debian's python3 (docs/python.md).
  if(TARGET lfcam_python)
    install(TARGETS lfcam_python LIBRARY DESTINATION lib/python3/dist-packages COMPONENT python)
    lfcam_package_docs(python python3-lfcam)
    list(APPEND CPACK_COMPONENTS_ALL python)
    set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-lfcam)
    set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
    string(REGEX MATCH "^[0-9]+\\.[0-9]+" lfcam_python_version "${Python_VERSION}")
    string(REGEX REPLACE "\\.([0-9]+)$" "" lfcam_python_major "${lfcam_python_version}")
    math(EXPR lfcam_python_next "${CMAKE_MATCH_1} + 1")
    set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS
        "python3 (>= ${lfcam_python_version}), python3 (<< ${lfcam_python_major}.${lfcam_python_next}), python3-numpy, ${lfcam_ffmpeg_packages}")
    string(CONCAT CPACK_DEBIAN_PYTHON_DESCRIPTION
        "Python module of lfcam, the 4D light field camera system\n"
        "import lfcam: open a light field (its views as NumPy arrays over the\n"
        "file's own mapping, no copy), its geometry and cameras; render a view\n"
        "through the paper's virtual camera with every flag of `lfcam render` as a\n"
        "keyword argument; estimate depth; import folders of views; export for\n"
        "NeRF and COLMAP; read capture sessions. Errors are Python exceptions with\n"
        "lfcam's messages.")
  endif()
  set(CPACK_DEBIAN_HOST_PACKAGE_NAME lfcam)
  set(CPACK_DEBIAN_HOST_PACKAGE_DEPENDS "${lfcam_ffmpeg_packages}")
  set(CPACK_DEBIAN_HOST_PACKAGE_SECTION graphics)
  string(CONCAT CPACK_DEBIAN_HOST_DESCRIPTION
      "do-it-yourself 4D light field camera system\n"
      "lfcam drives an array of Raspberry Pi camera modules (lfcam-node on each),\n"
      "calibrates it into a two-plane light field L(u, v, s, t) and renders that\n"
      "light field through a virtual camera that zooms, pans, refocuses and controls\n"
      "depth of field, on the CPU or a GPU, offline and in an interactive viewer.\n"
      "It records light field video, imports light fields made elsewhere, estimates\n"
      "depth, and shares a light field as MP4 videos, a web page or Looking Glass\n"
      "quilts. A simulator plays the array without hardware.")
endif()
# Not part of every build (help2man is a packaging tool): scripts/package.sh builds `man-pages`
# before cpack.
get_property(lfcam_man_pages GLOBAL PROPERTY LFCAM_MAN_PAGES)
add_custom_target(man-pages DEPENDS ${lfcam_man_pages})
include(CPack)
