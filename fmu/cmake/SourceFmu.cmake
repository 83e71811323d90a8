# Run at build time (cmake -P): assembles the source FMU ${OUT} (build/dist/PlateImpact-source.fmu):
# the FMI 3.0 FMU's modelDescription.xml, documentation/ (with the licence texts of what the
# sources contain), terminalsAndIcons/ and extra/ (the reference experiments) from its packaging
# stage ${STAGE}, no binaries, and sources/:
#   sources/buildDescription.xml       FMI 3.0 build description (one configuration)
#   sources/CMakeLists.txt             fmu/source/CMakeLists.txt: a plain CMake build into binaries/
#   sources/plateimpact/solver/        the solver's sources (solver/ without its tests and bench)
#   sources/plateimpact/fmu/           the FMI 3.0 layer and the PlateImpact binding, fmi2/ and fmi3/ headers
#   sources/plateimpact/generated/     PlateImpactGuid.h (the instantiation token of this build)
#   sources/suitesparse/               CHOLMOD Core + Cholesky, AMD, COLAMD, SuiteSparse_config (pinned 5.12.0)
#   sources/eigen3/Eigen/              Eigen's headers (MPL-2.0), sources/xxhash/xxhash.h (BSD-2-Clause)
#   sources/spectra/Spectra/           Spectra's headers (MPL-2.0)
# Inputs (-D): REPO, STAGE, GUID_HEADER, SUITESPARSE, EIGEN, SPECTRA, XXHASH, OUT, LICENSES (entries <name>:<SPDX>:<path>).
foreach(var REPO STAGE GUID_HEADER SUITESPARSE EIGEN SPECTRA XXHASH OUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "SourceFmu.cmake: ${var} is not set")
  endif()
endforeach()
set(dir "${OUT}.d")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}/sources")
foreach(part modelDescription.xml documentation terminalsAndIcons extra)
  if(EXISTS "${STAGE}/${part}")
    file(COPY "${STAGE}/${part}" DESTINATION "${dir}")
  endif()
endforeach()
foreach(license IN LISTS LICENSES)
  string(REGEX MATCH "^([^:]+):([^:]+):(.+)$" parsed "${license}")
  configure_file("${CMAKE_MATCH_3}" "${dir}/documentation/licenses/${CMAKE_MATCH_1}.txt" COPYONLY)
endforeach()

set(src "${dir}/sources")
configure_file("${REPO}/fmu/source/CMakeLists.txt" "${src}/CMakeLists.txt" COPYONLY)
# The solver's folders as they are (includes name them from solver/) with every file at its top
# (globbed: a new one cannot be forgotten), and of fmu/ the version-neutral core, the FMI 3.0 front
# end, the binding and the vendored FMI headers.
file(GLOB solver_top "${REPO}/solver/*.h" "${REPO}/solver/*.cpp")
foreach(part base fe plate schemes)
  file(COPY "${REPO}/solver/${part}" DESTINATION "${src}/plateimpact/solver")
endforeach()
file(COPY ${solver_top} DESTINATION "${src}/plateimpact/solver")
foreach(part core fmi3 binding headers)
  file(COPY "${REPO}/fmu/${part}" DESTINATION "${src}/plateimpact/fmu")
endforeach()
file(REMOVE "${src}/plateimpact/fmu/core/RuntimeRelease.cpp" "${src}/plateimpact/fmu/fmi3/exports.map")
configure_file("${REPO}/fmu/core/RuntimeRelease.cpp" "${src}/plateimpact/fmu/gcc/RuntimeRelease.cpp" COPYONLY)
configure_file("${GUID_HEADER}" "${src}/plateimpact/generated/PlateImpactGuid.h" COPYONLY)
foreach(part CHOLMOD/Core CHOLMOD/Cholesky CHOLMOD/Include AMD/Source AMD/Include AMD/Doc/License.txt
             COLAMD/Source COLAMD/Include COLAMD/Doc/License.txt SuiteSparse_config/SuiteSparse_config.c
             SuiteSparse_config/SuiteSparse_config.h CHOLMOD/Core/lesser.txt)
  get_filename_component(parent "${src}/suitesparse/${part}" DIRECTORY)
  file(COPY "${SUITESPARSE}/${part}" DESTINATION "${parent}")
endforeach()
file(COPY "${EIGEN}/Eigen" DESTINATION "${src}/eigen3")
file(COPY "${SPECTRA}" DESTINATION "${src}/spectra")
configure_file("${XXHASH}" "${src}/xxhash/xxhash.h" COPYONLY)

# buildDescription.xml: every compiled file, the include directories and definitions, as the
# CMakeLists.txt beside it compiles them. One SourceFileSet (C and C++ files, each compiled by its
# extension), no language attribute: fmpy's build_platform_binary (0.3.32) reads only the first set
# (and would take its language for every file), so a second set of C files would be left out.
# fmpy also ignores IncludeDirectory and puts only sources/ on the include path: the forwarding
# headers at sources/ (sources/<name> includes <include directory>/<name>, and sources/Eigen/<Module>
# the Eigen module) make every include resolve from there too. plateimpact/fmu/gcc/RuntimeRelease.cpp
# is left out: it belongs to a build that links libstdc++ statically (sources/CMakeLists.txt).
file(GLOB_RECURSE c_files RELATIVE "${src}" "${src}/suitesparse/*.c")
list(FILTER c_files INCLUDE REGEX "/(cholmod_[^/]*|amd_[^/]*|colamd|SuiteSparse_config)\\.c$")
file(GLOB_RECURSE cpp_files RELATIVE "${src}" "${src}/plateimpact/*.cpp")
list(FILTER cpp_files EXCLUDE REGEX "/gcc/")
list(SORT c_files)
list(SORT cpp_files)
set(includes suitesparse/CHOLMOD/Include suitesparse/SuiteSparse_config suitesparse/AMD/Include
             suitesparse/COLAMD/Include plateimpact/solver plateimpact/fmu plateimpact/fmu/headers/fmi2
             plateimpact/fmu/headers/fmi3 plateimpact/generated xxhash)
set(forwarded "")
foreach(i IN LISTS includes)
  # Recursive: the solver's and the FMU layer's includes name their folder (fe/Mesh.h, core/Model.h).
  file(GLOB_RECURSE headers RELATIVE "${src}/${i}" "${src}/${i}/*.h")
  list(FILTER headers EXCLUDE REGEX "^headers/")
  foreach(h IN LISTS headers)
    list(FIND forwarded "${h}" seen)
    if(NOT seen EQUAL -1)
      message(FATAL_ERROR "SourceFmu.cmake: two headers named ${h} (${i} and another include directory)")
    endif()
    list(APPEND forwarded "${h}")
    file(WRITE "${src}/${h}" "/* Forwards to ${i}/${h}: for builders that put only sources/ on the include path. */\n#include \"${i}/${h}\"\n")
  endforeach()
endforeach()
file(GLOB eigen_modules RELATIVE "${src}/eigen3/Eigen" "${src}/eigen3/Eigen/*")
foreach(m IN LISTS eigen_modules)
  if(NOT IS_DIRECTORY "${src}/eigen3/Eigen/${m}")
    file(WRITE "${src}/Eigen/${m}" "/* Forwards to eigen3/Eigen/${m}: for builders that put only sources/ on the include path. */\n#include \"../eigen3/Eigen/${m}\"\n")
  endif()
endforeach()
file(GLOB spectra_headers RELATIVE "${src}/spectra/Spectra" "${src}/spectra/Spectra/*.h")
foreach(h IN LISTS spectra_headers)
  file(WRITE "${src}/Spectra/${h}" "/* Forwards to spectra/Spectra/${h}: for builders that put only sources/ on the include path. */\n#include \"../spectra/Spectra/${h}\"\n")
endforeach()
set(xml "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiBuildDescription fmiVersion=\"3.0\">\n")
string(APPEND xml "  <BuildConfiguration modelIdentifier=\"PlateImpact\" description=\"The FMI 3.0 binary from these sources: the .c files are C99, the .cpp files C++17 (one set, each file compiled by its extension). Or with CMake: cmake -S sources -B build &amp;&amp; cmake --build build (sources/CMakeLists.txt, which also links libstdc++ statically with plateimpact/fmu/gcc/RuntimeRelease.cpp).\">\n")
string(APPEND xml "    <SourceFileSet name=\"plateimpact\">\n")
foreach(f IN LISTS c_files cpp_files)
  string(APPEND xml "      <SourceFile name=\"${f}\"/>\n")
endforeach()
foreach(d NGPL NPARTITION NCHECK NDEBUG)
  string(APPEND xml "      <PreprocessorDefinition name=\"${d}\" value=\"1\"/>\n")
endforeach()
foreach(i IN LISTS includes ITEMS eigen3 spectra)
  string(APPEND xml "      <IncludeDirectory name=\"${i}\"/>\n")
endforeach()
string(APPEND xml "    </SourceFileSet>\n    <Library name=\"m\" external=\"true\" description=\"the C maths library (Unix)\"/>\n")
string(APPEND xml "    <Library name=\"dl\" external=\"true\" description=\"dladdr and dlopen (Linux with glibc before 2.34; later glibc has them in libc)\"/>\n")
string(APPEND xml "  </BuildConfiguration>\n</fmiBuildDescription>\n")
file(WRITE "${src}/buildDescription.xml" "${xml}")

file(GLOB contents RELATIVE "${dir}" "${dir}/*")
file(REMOVE "${OUT}")
get_filename_component(out_dir "${OUT}" DIRECTORY)
file(MAKE_DIRECTORY "${out_dir}")
execute_process(COMMAND "${CMAKE_COMMAND}" -E tar cf "${OUT}" --format=zip ${contents}
                WORKING_DIRECTORY "${dir}" RESULT_VARIABLE zip_result)
if(NOT zip_result EQUAL 0)
  message(FATAL_ERROR "SourceFmu.cmake: zipping ${OUT} failed")
endif()
file(SIZE "${OUT}" size)
math(EXPR kib "${size} / 1024")
message(STATUS "Wrote ${OUT} (${kib} KiB)")
