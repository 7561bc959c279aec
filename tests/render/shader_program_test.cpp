// Shader loading: include expansion, defines, and compile errors reported as file:line.
#include "gl_fixture.h"

#include "hexlod/render/render_shaders.h"
#include "hexlod/render/shader_program.h"

namespace hexlod::render {
namespace {

TEST(ShaderLibraryTest, IncludesExpandOnceWithLineDirectives) {
    ShaderLibrary library;
    library.add("common.h", "float twice(float x) { return 2.0 * x; }\n");
    library.add("a.vert",
                "#version 450 core\n#include \"common.h\"\n#include \"common.h\"\nvoid main() {}\n");
    ExpandedShader out;
    std::string error;
    ASSERT_TRUE(library.expand("a.vert", "#define LOD 3", out, error)) << error;
    ASSERT_EQ(out.sourceNames.size(), 2u);
    EXPECT_EQ(out.sourceNames[0], "a.vert");
    EXPECT_EQ(out.sourceNames[1], "common.h");
    EXPECT_EQ(out.text.rfind("#version 450 core\n#define LOD 3\n", 0), 0u) << out.text;
    // The included text appears once, introduced as source 1 and followed by a return to source 0.
    EXPECT_EQ(out.text.find("twice"), out.text.rfind("twice"));
    EXPECT_NE(out.text.find("#line 1 1\nfloat twice"), std::string::npos) << out.text;
    EXPECT_NE(out.text.find("#line 3 0\n"), std::string::npos) << out.text;
}

TEST(ShaderLibraryTest, MissingIncludesCyclesAndVersionsAreErrorsWithLocations) {
    ShaderLibrary library;
    library.add("missing.vert", "#version 450 core\n\n#include \"nowhere.h\"\n");
    library.add("noversion.vert", "void main() {}\n");
    library.add("loop.h", "#include \"loop2.h\"\n");
    library.add("loop2.h", "#include \"loop.h\"\n");
    library.add("loop.vert", "#version 450 core\n#include \"loop.h\"\n");
    ExpandedShader out;
    std::string error;
    EXPECT_FALSE(library.expand("missing.vert", "", out, error));
    EXPECT_EQ(error, "missing.vert:3: cannot include \"nowhere.h\": no such shader");
    EXPECT_FALSE(library.expand("noversion.vert", "", out, error));
    EXPECT_EQ(error, "noversion.vert:1: the first line must be #version");
    EXPECT_FALSE(library.expand("absent.frag", "", out, error));
    EXPECT_EQ(error, "absent.frag: no such shader");
    // Each file is included at most once, so a cycle ends instead of recursing forever.
    EXPECT_TRUE(library.expand("loop.vert", "", out, error)) << error;
}

TEST(ShaderLibraryTest, DriverLogsMapToFileAndLine) {
    ExpandedShader shader;
    shader.sourceNames = {"terminal.vert", "gpu_types.h"};
    EXPECT_EQ(ShaderLibrary::mapLog("1:7(12): error: syntax error, unexpected '}'\n", shader),
              "gpu_types.h:7: error: syntax error, unexpected '}'\n");
    EXPECT_EQ(ShaderLibrary::mapLog("0(21) : error C1008: undefined variable \"x\"", shader),
              "terminal.vert:21: error C1008: undefined variable \"x\"\n");
}

class ShaderProgramTest : public GlTest {};

TEST_F(ShaderProgramTest, ACompileErrorNamesTheIncludedFileAndLine) {
    ShaderLibrary library;
    library.add("broken.h", "// a header\nfloat broken( { return 1.0; }\n");
    library.add("uses.vert",
                "#version 450 core\n#include \"broken.h\"\nvoid main() { gl_Position = vec4(0); }\n");
    std::string error;
    ShaderProgram program = ShaderProgram::build(library, {{ShaderStage::Vertex, "uses.vert"}}, "", error);
    EXPECT_FALSE(program.valid());
    EXPECT_EQ(error.rfind("broken.h:2: error:", 0), 0u) << error;
}

TEST_F(ShaderProgramTest, AnErrorInTheMainFileKeepsItsLineAfterDefinesAndIncludes) {
    ShaderLibrary library;
    library.add("ok.h", "float one() { return 1.0; }\n");
    library.add("bad.frag",
                "#version 450 core\n#include \"ok.h\"\nout vec4 c;\nvoid main() { c = vec4(undeclared); }\n");
    std::string error;
    ShaderProgram program = ShaderProgram::build(library, {{ShaderStage::Fragment, "bad.frag"}},
                                                 "#define A 1\n#define B 2", error);
    EXPECT_FALSE(program.valid());
    EXPECT_EQ(error.rfind("bad.frag:4: error:", 0), 0u) << error;
}

TEST_F(ShaderProgramTest, EveryShippedRenderShaderCompiles) {
    ShaderLibrary library = renderShaderLibrary();
    std::string error;
    ShaderProgram program = ShaderProgram::build(
        library, {{ShaderStage::Vertex, "shape_view.vert"}, {ShaderStage::Fragment, "shape_view.frag"}}, "",
        error);
    EXPECT_TRUE(program.valid()) << error;
}

} // namespace
} // namespace hexlod::render
