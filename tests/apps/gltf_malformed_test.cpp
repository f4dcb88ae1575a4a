// Malformed and hostile glTF files, made by the test from a valid one-triangle file with one element
// broken each: every one must end in a GltfError whose message names the file and the broken element.
#include "apps/common/GltfScene.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

using ripple::apps::GltfError;
using ripple::apps::loadGltf;
using namespace ripple::test;

namespace {

// The message of the GltfError loading `file` throws; fails the test when it loads or throws anything else.
std::string loadError(const std::filesystem::path& file) {
    try {
        loadGltf(file);
    } catch (const GltfError& e) {
        const std::string message = e.what();
        CHECK_MESSAGE(message.find(file.filename().string()) != std::string::npos, "message does not name the file: " << message);
        return message;
    } catch (const std::exception& e) {
        FAIL("not a GltfError: " << e.what());
    }
    FAIL("loaded without an error: " << file);
    return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("the unbroken triangle loads (the base every malformed case starts from)") {
    TempFolder dir;
    const auto scene = loadGltf(writeGlb(dir / "triangle.glb", triangleSource()));
    CHECK(scene.trianglesStored() == 1);
    CHECK(scene.trianglesDrawn() == 1);
    CHECK(scene.warnings.empty());
}

TEST_CASE("GLB container errors") {
    TempFolder dir;
    const std::vector<uint8_t> good = glbBytes(triangleSource());

    SUBCASE("missing file") { CHECK(contains(loadError(dir / "absent.glb"), "no such file")); }
    SUBCASE("empty file") {
        CHECK(contains(loadError(writeBytes(dir / "empty.glb", {})), "too short for a GLB header"));
    }
    SUBCASE("truncated in the middle") {
        const std::vector<uint8_t> half(good.begin(), good.begin() + long(good.size() / 2));
        const std::string message = loadError(writeBytes(dir / "truncated.glb", half));
        CHECK(contains(message, "declares " + std::to_string(good.size()) + " bytes but the file has " +
                                    std::to_string(half.size()) + " (truncated?)"));
    }
    SUBCASE("bad magic") {
        std::vector<uint8_t> bytes = good;
        bytes[0] = 'x';
        CHECK(contains(loadError(writeBytes(dir / "magic.glb", bytes)), "bad magic"));
    }
    SUBCASE("chunk length past the end") {
        std::vector<uint8_t> bytes = good;
        bytes[12] = 0xff;  // the JSON chunk's length, little-endian
        bytes[13] = 0xff;
        CHECK(contains(loadError(writeBytes(dir / "chunk.glb", bytes)), "GLB chunk 0"));
    }
}

TEST_CASE("JSON syntax error") {
    TempFolder dir;
    const std::string message = loadError(writeText(dir / "syntax.gltf", R"({"asset":{"version":"2.0"},"nodes":[)"));
    CHECK_MESSAGE(contains(message, "parse error at line 1, column 37"), message);
}

TEST_CASE("buffers that are missing or too short") {
    TempFolder dir;
    SUBCASE("external buffer file missing") {
        GltfSource s = triangleSource();
        s.replace(R"("buffers":[{"byteLength":48}])", R"("buffers":[{"byteLength":48,"uri":"missing.bin"}])");
        const std::string message = loadError(writeText(dir / "external.gltf", s.json));
        CHECK_MESSAGE(contains(message, "File not found : missing.bin"), message);
    }
    SUBCASE("buffer without uri in a .gltf") {
        const std::string message = loadError(writeText(dir / "nouri.gltf", triangleSource().json));
        CHECK(contains(message, "'uri' is missing"));
    }
    SUBCASE("buffer longer than the BIN chunk") {
        GltfSource s = triangleSource();
        s.replace(R"("byteLength":48})", R"("byteLength":480})");
        CHECK(contains(loadError(writeGlb(dir / "short.glb", s)), "byteLength"));
    }
    SUBCASE("buffer view past its buffer") {
        GltfSource s = triangleSource();
        s.replace(R"("byteOffset":36,"byteLength":12)", R"("byteOffset":36,"byteLength":16)");
        CHECK(contains(loadError(writeGlb(dir / "view.glb", s)),
                       "accessor 1 (indices): buffer view 1 (offset 36, length 16) runs past buffer 0 (48 bytes)"));
    }
}

TEST_CASE("accessors that do not fit or have the wrong type") {
    TempFolder dir;
    GltfSource s = triangleSource();
    std::string expected;
    SUBCASE("accessor past its buffer view") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":4,"type":"VEC3")");
        expected = "accessor 0 (POSITION): 4 elements of 12 bytes at offset 0 run past buffer view 0 (36 bytes)";
    }
    SUBCASE("byte offset past its buffer view") {
        s.replace(R"("bufferView":1,"componentType":5125)", R"("bufferView":1,"byteOffset":4,"componentType":5125)");
        expected = "accessor 1 (indices): 3 elements of 4 bytes at offset 4 run past buffer view 1 (12 bytes)";
    }
    SUBCASE("absurd count") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":4000000000,"type":"VEC3")");
        expected = "accessor 0 (POSITION): count 4000000000 is absurd";
    }
    SUBCASE("large count past the buffer") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":100000000,"type":"VEC3")");
        expected = "accessor 0 (POSITION): 100000000 elements of 12 bytes at offset 0 run past buffer view 0";
    }
    SUBCASE("stride below the element size") {
        s.replace(R"({"buffer":0,"byteOffset":0,"byteLength":36})", R"({"buffer":0,"byteOffset":0,"byteLength":36,"byteStride":4})");
        expected = "byte stride 4 of buffer view 0 is below the element size 12";
    }
    SUBCASE("wrong component type for POSITION") {
        s.replace(R"("componentType":5126,"count":3,"type":"VEC3")", R"("componentType":5123,"count":3,"type":"VEC3")");
        expected = "accessor 0 (POSITION) has component type uint16, which glTF does not allow here";
    }
    SUBCASE("wrong type for POSITION") {
        s.replace(R"("count":3,"type":"VEC3")", R"("count":3,"type":"VEC2")");
        expected = "accessor 0 (POSITION) has 2 components, expected 3";
    }
    SUBCASE("float indices") {
        s.replace(R"("componentType":5125,"count":3,"type":"SCALAR")", R"("componentType":5126,"count":3,"type":"SCALAR")");
        expected = "accessor 1 (indices) has component type float32, expected uint8, uint16 or uint32";
    }
    SUBCASE("accessor that does not exist") {
        s.replace(R"({"POSITION":0})", R"({"POSITION":0,"TEXCOORD_0":9})");
        expected = "accessor 9 (TEXCOORD_0) does not exist (the file has 2 accessors)";
    }
    SUBCASE("attribute count differs from POSITION") {
        s.replace(R"({"POSITION":0})", R"({"POSITION":0,"NORMAL":2})");
        s.replace(R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}])",
                  R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"},{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"}])");
        expected = "accessor 2 (NORMAL) has 2 elements but POSITION has 3";
    }
    const std::string message = loadError(writeGlb(dir / "accessor.glb", s));
    CHECK_MESSAGE(contains(message, expected), message);
    CHECK(contains(message, "mesh 0 primitive 0"));
}

TEST_CASE("indices and positions with bad values") {
    TempFolder dir;
    GltfSource s = triangleSource();
    std::string expected;
    SUBCASE("index out of range") {
        s.poke(36 + 4, uint32_t(12034));
        expected = "accessor 1 (indices): index 12034 out of range for 3 vertices (element 1)";
    }
    SUBCASE("index count not a multiple of 3") {
        s.replace(R"("componentType":5125,"count":3)", R"("componentType":5125,"count":2)");
        expected = "accessor 1 (indices): count 2 is not a multiple of 3";
    }
    SUBCASE("NaN position") {
        s.poke(4 * 4, std::numeric_limits<float>::quiet_NaN());  // vertex 1, y
        expected = "accessor 0 (POSITION): vertex 1 is not finite";
    }
    SUBCASE("infinite position") {
        s.poke(8 * 4, std::numeric_limits<float>::infinity());  // vertex 2, z
        expected = "accessor 0 (POSITION): vertex 2 is not finite";
    }
    const std::string message = loadError(writeGlb(dir / "values.glb", s));
    CHECK_MESSAGE(contains(message, expected), message);
}

TEST_CASE("node graphs that are not trees, and dangling references") {
    TempFolder dir;
    GltfSource s = triangleSource();
    std::string expected;
    SUBCASE("cycle") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[1]},{"children":[0]}])");
        expected = "node 0: cycle in the node hierarchy";
    }
    SUBCASE("node that is its own child") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[0]}])");
        expected = "node 0: cycle in the node hierarchy";
    }
    SUBCASE("two parents") {
        s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[1,2]}])");
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0},{"children":[0]},{"children":[0]}])");
        expected = "node 0 is reached twice (it has more than one parent)";
    }
    SUBCASE("over-deep hierarchy") {
        std::string chain;
        for (int i = 0; i < 2000; ++i) chain += R"({"children":[)" + std::to_string(i + 1) + "]},";
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[)" + chain + R"({"mesh":0}])");
        expected = "node hierarchy deeper than 1024 levels";
    }
    SUBCASE("child that does not exist") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[7]}])");
        expected = "node 7 does not exist (the file has 1 nodes)";
    }
    SUBCASE("mesh that does not exist") {
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":5}])");
        expected = "node 0: mesh 5 does not exist";
    }
    SUBCASE("material that does not exist") {
        s.replace(R"("indices":1})", R"("indices":1,"material":3})");
        expected = "mesh 0 primitive 0: material 3 does not exist";
    }
    SUBCASE("required extension the importer lacks") {
        s.replace(R"("scene":0,)", R"("extensionsRequired":["KHR_draco_mesh_compression"],"extensionsUsed":["KHR_draco_mesh_compression"],"scene":0,)");
        expected = "requires extension KHR_draco_mesh_compression, which this importer does not support";
    }
    SUBCASE("scene that does not exist") {
        s.replace(R"("scene":0)", R"("scene":4)");
        expected = "scene 4 does not exist";
    }
    SUBCASE("world transform beyond single precision") {
        s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[1]}])");
        s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"scale":[1e30,1,1]},{"scale":[1e30,1,1],"children":[0]}])");
        expected = "node 0: world transform is not finite in single precision";
    }
    SUBCASE("indices accessor index out of range (tinygltf's own check)") {
        s.replace(R"("indices":1)", R"("indices":9)");
        expected = "primitive indices accessor out of bounds";
    }
    const std::string message = loadError(writeGlb(dir / "nodes.glb", s));
    CHECK_MESSAGE(contains(message, expected), message);
}

TEST_CASE("random corruption never crashes: each of 400 seeded mutations loads or throws GltfError") {
    TempFolder dir;
    GltfSource s = triangleSource();
    s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[1]},{"camera":0,"translation":[0,0,3]}],
        "cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}}])");
    const std::vector<uint8_t> good = glbBytes(s);
    std::mt19937 random(1234);  // fixed seed: the same 400 files on every run
    int loaded = 0, rejected = 0;
    for (int i = 0; i < 400; ++i) {
        std::vector<uint8_t> bytes = good;
        for (int k = 0, n = 1 + int(random() % 6); k < n && !bytes.empty(); ++k) {
            const size_t at = random() % bytes.size();
            switch (random() % 3) {
                case 0: bytes[at] = uint8_t(random()); break;                       // any byte
                case 1: bytes[at] = uint8_t("0123456789-e.,:{}[]\""[random() % 20]); break;  // JSON-ish
                default: bytes.resize(at); break;                                   // truncation
            }
        }
        try {
            loadGltf(writeBytes(dir / "mutant.glb", bytes));
            ++loaded;
        } catch (const GltfError&) {
            ++rejected;
        }  // any other exception escapes and fails the test
    }
    CHECK(loaded + rejected == 400);
    CHECK(rejected > 0);
}
