# SPDX-License-Identifier: BSD-3-Clause
# Debian packages, one per install component (CPack DEB), as Debian splits VTK's. Included by
# the module's build (CMakeLists.txt: the library, -dev, python3- and programs packages) and by
# the ParaView plugin's (ParaView/CMakeLists.txt: the plugin package), each configured for
# /usr; scripts/package.sh builds them all and scripts/package-test.sh installs and checks them.
#
#   csm_debian_package(<component> <package> <section> <description>
#     [DEPENDS <Debian relations>] [COMPONENTS <component>...] [SUGGESTS <Debian relations>])
#
# <description>: the synopsis, a newline, then the extended description. Every package gets
# /usr/share/doc/<package>/copyright (from LICENSE) and changelog.gz (Packaging/changelog), and
# Packaging/lintian/<package> when that file exists (only in the packages: EXCLUDE_FROM_ALL
# keeps them out of a plain cmake --install). Dependencies on shared libraries come from
# dpkg-shlibdeps; DEPENDS adds those the binaries do not show, COMPONENTS the packages of other
# components of the same build (at this exact version).
# Then include(CPack) with CPACK_COMPONENTS_ALL set to the components.

set(CSM_DEB_MAINTAINER "CascadedShadows maintainers <maintainers@example.org>" CACHE STRING
  "The Maintainer field of the Debian packages")
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGING_INSTALL_PREFIX "${CMAKE_INSTALL_PREFIX}")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${CSM_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The libraries of this build, found where they were built; their packages come from COMPONENTS.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}")
set(CPACK_STRIP_FILES ON)
set(CPACK_RESOURCE_FILE_LICENSE "${CMAKE_CURRENT_LIST_DIR}/../LICENSE")
if(NOT CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  message(STATUS "Debian packages: configure with -DCMAKE_INSTALL_PREFIX=/usr to build them "
    "(scripts/package.sh does)")
endif()

# The changelog's newest entry names the version the build makes.
file(STRINGS "${CMAKE_CURRENT_LIST_DIR}/changelog" csm_deb_changelog_head LIMIT_COUNT 1)
if(NOT csm_deb_changelog_head MATCHES "^[a-z0-9.+-]+ \\(${PROJECT_VERSION}\\) ")
  message(WARNING "Packaging/changelog: the newest entry must be version ${PROJECT_VERSION} "
    "(the project's) for the Debian packages, not: ${csm_deb_changelog_head}")
endif()
set(csm_deb_dir "${CMAKE_CURRENT_LIST_DIR}")
set(csm_deb_files "${CMAKE_BINARY_DIR}/debian-files")
file(MAKE_DIRECTORY "${csm_deb_files}")
find_program(CSM_GZIP gzip REQUIRED)
execute_process(COMMAND "${CSM_GZIP}" -9nc "${CMAKE_CURRENT_LIST_DIR}/changelog"
  OUTPUT_FILE "${csm_deb_files}/changelog.gz" RESULT_VARIABLE csm_deb_gzip)
if(NOT csm_deb_gzip EQUAL 0)
  message(FATAL_ERROR "Packaging: could not compress Packaging/changelog")
endif()
# debian/copyright (machine-readable format) with the license text of LICENSE.
file(STRINGS "${CMAKE_CURRENT_LIST_DIR}/../LICENSE" csm_deb_license)
list(FILTER csm_deb_license INCLUDE REGEX "^Copyright \\(c\\) ")
string(REGEX REPLACE "^Copyright \\(c\\) " "" csm_deb_copyright "${csm_deb_license}")
string(REPLACE "," "" csm_deb_copyright "${csm_deb_copyright}")
file(READ "${CMAKE_CURRENT_LIST_DIR}/../LICENSE" csm_deb_license)
string(REGEX REPLACE "^[^\n]*\n\n" "" csm_deb_license "${csm_deb_license}") # the title line
string(REGEX REPLACE "\n+$" "" csm_deb_license "${csm_deb_license}")
string(REGEX REPLACE "\n\n" "\n.\n" csm_deb_license "${csm_deb_license}")
string(REGEX REPLACE "\n" "\n " csm_deb_license "${csm_deb_license}")
file(WRITE "${csm_deb_files}/copyright"
  "Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/\n"
  "Upstream-Name: CascadedShadows\n\n"
  "Files: *\nCopyright: ${csm_deb_copyright}\nLicense: BSD-3-Clause\n\n"
  "License: BSD-3-Clause\n ${csm_deb_license}\n")

macro(csm_debian_package component package section description)
  cmake_parse_arguments(csm_deb "" "" "DEPENDS;COMPONENTS;SUGGESTS" ${ARGN})
  string(TOUPPER "${component}" csm_deb_c)
  set(CPACK_DEBIAN_${csm_deb_c}_PACKAGE_NAME "${package}")
  set(CPACK_DEBIAN_${csm_deb_c}_PACKAGE_SECTION "${section}")
  set(CPACK_DEBIAN_${csm_deb_c}_DESCRIPTION "${description}")
  list(JOIN csm_deb_DEPENDS ", " CPACK_DEBIAN_${csm_deb_c}_PACKAGE_DEPENDS)
  list(JOIN csm_deb_SUGGESTS ", " CPACK_DEBIAN_${csm_deb_c}_PACKAGE_SUGGESTS)
  set(CPACK_COMPONENT_${csm_deb_c}_DEPENDS ${csm_deb_COMPONENTS})
  install(FILES "${csm_deb_files}/copyright" "${csm_deb_files}/changelog.gz"
    DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/${package}" COMPONENT "${component}"
    EXCLUDE_FROM_ALL)
  if(EXISTS "${csm_deb_dir}/lintian/${package}")
    install(FILES "${csm_deb_dir}/lintian/${package}"
      DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/lintian/overrides" COMPONENT "${component}"
      EXCLUDE_FROM_ALL)
  endif()
  list(APPEND CPACK_COMPONENTS_ALL "${component}")
endmacro()
