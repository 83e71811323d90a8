# Run at BUILD time (cmake -P) after PlateImpact.so is linked: assembles the FMU.
#   STAGING_DIR/modelDescription.xml
#   STAGING_DIR/binaries/linux64/PlateImpact.so
#   STAGING_DIR/binaries/linux64/<every shared library ldd resolves for PlateImpact.so that is
#                                  not part of glibc> (CHOLMOD and its dependencies)
# and zips them into FMU_FILE. PlateImpact.so carries RPATH=$ORIGIN (DT_RPATH, which glibc also
# applies to the dependencies of its dependencies), so the shipped copies are the ones loaded.
#
# Inputs (-D): LIBRARY, MODEL_DESCRIPTION, STAGING_DIR, FMU_FILE; MODEL_IDENTIFIER (default
# PlateImpact) names the shipped shared object.
if(NOT DEFINED MODEL_IDENTIFIER)
  set(MODEL_IDENTIFIER PlateImpact)
endif()
foreach(var LIBRARY MODEL_DESCRIPTION STAGING_DIR FMU_FILE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "PackageFmu.cmake: ${var} is not set")
  endif()
endforeach()

# PLATFORM: the binaries/ folder (linux64 for FMI 2.0, x86_64-linux for FMI 3.0).
if(NOT DEFINED PLATFORM)
  set(PLATFORM linux64)
endif()
set(bin_dir "${STAGING_DIR}/binaries/${PLATFORM}")
file(REMOVE_RECURSE "${STAGING_DIR}")
file(MAKE_DIRECTORY "${bin_dir}")
configure_file("${MODEL_DESCRIPTION}" "${STAGING_DIR}/modelDescription.xml" COPYONLY)
configure_file("${LIBRARY}" "${bin_dir}/${MODEL_IDENTIFIER}.so" COPYONLY)

find_program(LDD ldd REQUIRED)
execute_process(COMMAND "${LDD}" "${LIBRARY}" OUTPUT_VARIABLE ldd_output ERROR_VARIABLE ldd_error
                RESULT_VARIABLE ldd_result)
if(NOT ldd_result EQUAL 0)
  message(FATAL_ERROR "ldd ${LIBRARY} failed: ${ldd_error}")
endif()

# glibc's own libraries: present on every target system, never shipped.
set(glibc_regex "^(ld-linux.*|linux-vdso.*|linux-gate.*|libc|libm|libmvec|libpthread|libdl|librt|libutil|libresolv|libanl|libnsl|libBrokenLocale)(\\.so.*)?$")

string(REPLACE "\n" ";" ldd_lines "${ldd_output}")
set(shipped "")
foreach(line IN LISTS ldd_lines)
  string(STRIP "${line}" line)
  if(line STREQUAL "")
    continue()
  endif()
  if(line MATCHES "^([^ ]+) => not found")
    message(FATAL_ERROR "PackageFmu.cmake: ldd cannot resolve ${CMAKE_MATCH_1} for ${LIBRARY}")
  endif()
  if(NOT line MATCHES "^([^ ]+) => ([^ ]+) \\(0x")
    continue()  # linux-vdso.so.1 (0x...), /lib64/ld-linux-x86-64.so.2 (0x...)
  endif()
  set(name "${CMAKE_MATCH_1}")
  set(path "${CMAKE_MATCH_2}")
  if(name MATCHES "${glibc_regex}")
    continue()
  endif()
  # configure_file(COPYONLY) copies the content behind symlinks (Debian's BLAS/LAPACK are
  # alternatives symlinks), under the name the loader asks for.
  configure_file("${path}" "${bin_dir}/${name}" COPYONLY)
  list(APPEND shipped "${name}")
endforeach()
list(JOIN shipped ", " shipped_text)
message(STATUS "${MODEL_IDENTIFIER}.fmu ships: ${shipped_text}")

# documentation/index.html (the model's page, written from its table) and the licence texts of
# what the binary links statically (documentation/licenses/).
set(contents modelDescription.xml binaries)
if(DEFINED DOCUMENTATION AND EXISTS "${DOCUMENTATION}")
  configure_file("${DOCUMENTATION}" "${STAGING_DIR}/documentation/index.html" COPYONLY)
  # LICENSES: entries <file name>:<SPDX expression>:<path> (fmu/CMakeLists.txt).
  foreach(license IN LISTS LICENSES)
    string(REGEX MATCH "^([^:]+):([^:]+):(.+)$" parsed "${license}")
    if(NOT parsed)
      message(FATAL_ERROR "PackageFmu.cmake: licence entry \"${license}\" is not <name>:<SPDX>:<path>")
    endif()
    configure_file("${CMAKE_MATCH_3}" "${STAGING_DIR}/documentation/licenses/${CMAKE_MATCH_1}.txt" COPYONLY)
  endforeach()
  list(APPEND contents documentation)
endif()

# TERMINALS (FMI 3.0): terminalsAndIcons/terminalsAndIcons.xml when the model wrote one.
if(DEFINED TERMINALS AND EXISTS "${TERMINALS}")
  configure_file("${TERMINALS}" "${STAGING_DIR}/terminalsAndIcons/terminalsAndIcons.xml" COPYONLY)
  list(APPEND contents terminalsAndIcons)
endif()

file(REMOVE "${FMU_FILE}")
execute_process(COMMAND "${CMAKE_COMMAND}" -E tar cf "${FMU_FILE}" --format=zip ${contents}
                WORKING_DIRECTORY "${STAGING_DIR}" RESULT_VARIABLE zip_result)
if(NOT zip_result EQUAL 0)
  message(FATAL_ERROR "PackageFmu.cmake: zipping ${FMU_FILE} failed")
endif()
message(STATUS "Wrote ${FMU_FILE}")
