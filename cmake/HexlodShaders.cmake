# hexlod_embed_shaders(TARGET SYMBOL FILE...): compiles the shader files into TARGET as the
# function `std::span<const hexlod::render::ShaderFile> SYMBOL()` (declare it in a header).
set(HEXLOD_EMBED_SHADERS_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/EmbedShaders.cmake")
function(hexlod_embed_shaders target symbol)
    set(files "")
    foreach(file IN LISTS ARGN)
        get_filename_component(path "${file}" ABSOLUTE)
        list(APPEND files "${path}")
    endforeach()
    set(output "${CMAKE_CURRENT_BINARY_DIR}/${symbol}.cpp")
    # A ;-list inside one argument would be split into several by add_custom_command.
    string(REPLACE ";" "$<SEMICOLON>" files_argument "${files}")
    add_custom_command(OUTPUT "${output}"
        COMMAND ${CMAKE_COMMAND} "-DOUTPUT=${output}" "-DSYMBOL=${symbol}" "-DFILES=${files_argument}"
            -P "${HEXLOD_EMBED_SHADERS_SCRIPT}"
        DEPENDS ${files} "${HEXLOD_EMBED_SHADERS_SCRIPT}"
        COMMENT "Embedding shaders for ${target}" VERBATIM)
    target_sources(${target} PRIVATE "${output}")
endfunction()
