# The FMI 3.0 co-simulation FMUs, from the same model bindings as the FMI 2.0 ones (included by
# fmu/CMakeLists.txt after add_fmu): the version-neutral core with fmi3Functions.cpp instead of
# fmi2Functions.cpp (fmu_layer3), the same object files of the core and the binding, and the
# FMI 3.0 modelDescription.xml written from the same table by the same writer
# (modelDescription/WriteModelDescription.cpp). Lands in ${CMAKE_BINARY_DIR}/fmi3/<Model>.fmu
# with binaries/x86_64-linux/<Model>.so; ${CMAKE_BINARY_DIR}/<Model>.fmu stays the FMI 2.0 one.
# Cross builds (win64, aarch64) make only the shared object (target <Model>3); the scripts
# add it to the FMU (scripts/build-win64.sh, scripts/build-aarch64.sh).

add_library(fmu_layer3 OBJECT fmi3/fmi3Functions.cpp fmi3/fmi3Unsupported.cpp fmi3/Fmi3Values.cpp fmi3/fmi3Exports.cpp)
target_include_directories(fmu_layer3 PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}/headers/fmi3")
target_link_libraries(fmu_layer3 PUBLIC fmu_core)
target_compile_options(fmu_layer3 PRIVATE -Wall -Wextra)

# add_fmu3(<Model> [LIBRARIES <libs>]): after add_fmu(<Model> ...), whose writer and licence list it uses.
file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/fmi3")

function(add_fmu3 model)
  cmake_parse_arguments(ARG "" "" "LIBRARIES" ${ARGN})
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/fmi3")
  add_library(${model}3 SHARED $<TARGET_OBJECTS:fmu_core> $<TARGET_OBJECTS:fmu_layer3> $<TARGET_OBJECTS:${model}Binding>)
  target_link_libraries(${model}3 PRIVATE ${ARG_LIBRARIES})
  fmu_primary_copy_link_options(${model}3)
  set_target_properties(${model}3 PROPERTIES PREFIX "" OUTPUT_NAME ${model}
    LIBRARY_OUTPUT_DIRECTORY "${out_dir}" RUNTIME_OUTPUT_DIRECTORY "${out_dir}")
  if(WIN32)
    # As the FMI 2.0 DLL: runtimes linked in, only the fmi3* functions exported (FMI3_Export).
    target_link_options(${model}3 PRIVATE -static -static-libstdc++ -static-libgcc -Wl,--exclude-all-symbols)
    return()
  endif()
  set_target_properties(${model}3 PROPERTIES BUILD_WITH_INSTALL_RPATH ON INSTALL_RPATH "$ORIGIN"
    LINK_DEPENDS "${PLATEIMPACT_FMU_DIR}/fmi3/exports.map")
  target_link_options(${model}3 PRIVATE -static-libstdc++ -static-libgcc -Wl,--disable-new-dtags
    -Wl,--exclude-libs,ALL "-Wl,--version-script=${PLATEIMPACT_FMU_DIR}/fmi3/exports.map" -Wl,-z,defs)
  target_sources(${model}3 PRIVATE "${PLATEIMPACT_FMU_DIR}/core/RuntimeRelease.cpp")
  if(CMAKE_CROSSCOMPILING)
    return()
  endif()

  # The FMI 3.0 modelDescription.xml and its own documentation/index.html, from the same writer
  # and table as the FMI 2.0 ones (modelDescription/WriteModelDescription.cpp, its FMI 3.0
  # emitter); the licence texts are those of the FMI 2.0 FMU (the same objects are linked).
  set(licenses ${${model}_LICENSES})
  set(model_description "${out_dir}/${model}.modelDescription.xml")
  set(documentation "${out_dir}/${model}.index.html")
  # terminalsAndIcons.xml: written only by a model with terminals (fmu::Model::terminals).
  set(terminals "${out_dir}/${model}.terminalsAndIcons.xml")
  add_custom_command(
    OUTPUT "${model_description}" "${documentation}"
    BYPRODUCTS "${terminals}"
    COMMAND write_${model}_description 3 "${model_description}" "${documentation}" "--terminals=${terminals}"
            ${licenses}
    DEPENDS write_${model}_description
    COMMENT "Writing the ${model} FMI 3.0 modelDescription.xml from its table of variables"
    VERBATIM)

  set(fmu_file "${CMAKE_BINARY_DIR}/fmi3/${model}.fmu")
  add_custom_command(
    OUTPUT "${fmu_file}"
    COMMAND "${CMAKE_COMMAND}" "-DLIBRARY=$<TARGET_FILE:${model}3>" "-DMODEL_IDENTIFIER=${model}"
            "-DMODEL_DESCRIPTION=${model_description}" "-DSTAGING_DIR=${out_dir}/${model}.fmu.d"
            "-DFMU_FILE=${fmu_file}" "-DDOCUMENTATION=${documentation}" "-DLICENSES=${licenses}"
            "-DPLATFORM=x86_64-linux" "-DTERMINALS=${terminals}" -P "${PLATEIMPACT_FMU_DIR}/cmake/PackageFmu.cmake"
    DEPENDS ${model}3 "${model_description}" "${documentation}" "${PLATEIMPACT_FMU_DIR}/cmake/PackageFmu.cmake"
    COMMENT "Packaging ${fmu_file}"
    VERBATIM)
  add_custom_target(${model}Fmu3 ALL DEPENDS "${fmu_file}")
endfunction()


