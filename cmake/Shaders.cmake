# bl_add_shaders(TARGET <name> SOURCES <file.stage.glsl>...)
#
# Compiles each GLSL file to SPIR-V with glslangValidator, embedded as a C++ header
# `<build>/shaders/spv/<dir>/<file>.spv.h` that defines `static const uint32_t kSpv_<dir>_<file>_<stage>[]`.
# SPIR-V 1.5 (--target-env vulkan1.2): Vulkan 1.3 devices take it, and it keeps gl_HelperInvocation
# the plain built-in (SPIR-V 1.6 turns it into OpIsHelperInvocationEXT, which lavapipe 22.3 lacks).
# Dependencies on included headers come from glslangValidator's --depfile, so editing
# shaders/shared/*.h recompiles exactly the shaders that include it. SPIR-V never leaves the build tree.
function(bl_add_shaders)
    cmake_parse_arguments(ARG "" "TARGET" "SOURCES" ${ARGN})
    set(spv_root "${CMAKE_BINARY_DIR}/shaders/spv")
    set(outputs "")
    foreach(src IN LISTS ARG_SOURCES)
        get_filename_component(abs "${src}" ABSOLUTE)
        file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}/shaders" "${abs}")
        # name.stage.glsl -> stage
        string(REGEX MATCH "\\.([a-z]+)\\.glsl$" _ "${rel}")
        set(stage "${CMAKE_MATCH_1}")
        if(NOT stage MATCHES "^(vert|frag|comp|geom|tesc|tese)$")
            message(FATAL_ERROR "shader ${src}: name must end in .<vert|frag|comp|...>.glsl")
        endif()
        string(REGEX REPLACE "\\.glsl$" ".spv.h" out_rel "${rel}")
        string(REGEX REPLACE "[^A-Za-z0-9]" "_" var "${rel}")
        string(REGEX REPLACE "_glsl$" "" var "${var}")
        set(out "${spv_root}/${out_rel}")
        get_filename_component(out_dir "${out}" DIRECTORY)
        add_custom_command(
            OUTPUT "${out}"
            COMMAND ${CMAKE_COMMAND} -E make_directory "${out_dir}"
            COMMAND ${BL_GLSLANG} -S ${stage} --target-env vulkan1.2 -g0 --quiet
                    -I${PROJECT_SOURCE_DIR}/shaders --vn kSpv_${var}
                    --depfile "${out}.d" -o "${out}" "${abs}"
            DEPENDS "${abs}"
            DEPFILE "${out}.d"
            COMMENT "GLSL ${rel}"
            VERBATIM)
        list(APPEND outputs "${out}")
    endforeach()
    add_custom_target(${ARG_TARGET}_spv DEPENDS ${outputs})
    add_library(${ARG_TARGET} INTERFACE)
    target_include_directories(${ARG_TARGET} INTERFACE "${spv_root}")
    add_dependencies(${ARG_TARGET} ${ARG_TARGET}_spv)
endfunction()
